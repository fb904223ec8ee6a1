"""Slack cables: Irvine–Caughey theory and a converged lumped-mass solver.

Griffin & Rosenthal (1985), "The Dynamics of Slack Marine Cables", NRL MR 5559.

scene (``SlackScene``, ``load_scene``) -> statics (``solve_equilibrium`` -> :class:`Equilibrium`)
-> modes (``compute_modes`` -> :class:`ModeSet`; ``analyze`` does both) -> element-count
convergence (``converge`` -> :class:`Convergence`); the flat-sag theory in ``irvine_modes``.
"""

from ..lazy import lazy_exports

# public name -> module that defines it, imported on first use (cablesys.lazy)
_EXPORTS = {
    "IrvineMode": ".irvine",
    "irvine_modes": ".irvine",
    "lambda_squared": ".irvine",
    "analyze": ".modes",
    "compute_modes": ".modes",
    "converge": ".modes",
    "plot_equilibrium": ".plots",
    "plot_mode_shapes": ".plots",
    "Convergence": ".results",
    "Equilibrium": ".results",
    "ModeSet": ".results",
    "Cable": ".scene",
    "PointMass": ".scene",
    "SlackScene": ".scene",
    "load_scene": ".scene",
    "solve_equilibrium": ".statics",
}

__all__ = ["Cable", "Convergence", "Equilibrium", "IrvineMode", "ModeSet", "PointMass", "SlackScene",
           "analyze", "compute_modes", "converge", "irvine_modes", "lambda_squared", "load_scene",
           "plot_equilibrium", "plot_mode_shapes", "solve_equilibrium"]

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, __all__)
