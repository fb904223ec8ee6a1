"""Slack cables: Irvine–Caughey theory and a converged lumped-mass solver.

Griffin & Rosenthal (1985), "The Dynamics of Slack Marine Cables", NRL MR 5559.

scene (``SlackScene``, ``SlackCable``, ``load_slack_scene``) -> ``analyze`` -> :class:`SlackAnalysis`
(equilibrium and natural modes, omega in rad/s) -> element-count convergence (``converge`` ->
:class:`Convergence`). ``analyze`` and ``converge`` run on the shared cable: the span is a scene of
the segmented node model (:mod:`.shared`: support A the top, B the anchor, the point masses the
sections' bodies), its equilibrium the node model's statics and its modes the model's own mass
matrix and the AD Jacobian of its forces. The lumped chain of :mod:`.statics` and :mod:`.vibration`
(``solve_equilibrium`` -> :class:`Equilibrium`, ``modes(eq)`` -> :class:`ModeSet`: the energy NLP and
its Hessian, and the shooting route) solves the same discrete equations another way and is kept as
their independent check. The flat-sag theory is in ``irvine_modes``. The old names ``Cable`` and ``load_scene`` still resolve, with a DeprecationWarning.
"""

import warnings


from ..lazy import lazy_exports

# public name -> module that defines it, imported on first use (cablesys.lazy)
_EXPORTS = {
    "IrvineMode": ".results",
    "IrvineModes": ".results",
    "irvine_modes": ".irvine",
    "lambda_squared": ".irvine",
    "analyze": ".vibration",
    "converge": ".vibration",
    "modes": ".vibration",
    "plot_equilibrium": ".plots",
    "plot_mode_shapes": ".plots",
    "Convergence": ".results",
    "Equilibrium": ".results",
    "ModeSet": ".results",
    "SlackAnalysis": ".results",
    "SlackCable": ".scene",
    "PointMass": ".scene",
    "SlackScene": ".scene",
    "load_slack_scene": ".scene",
    "solve_equilibrium": ".statics",
}

__all__ = ["Convergence", "Equilibrium", "IrvineMode", "IrvineModes", "ModeSet", "PointMass", "SlackAnalysis",
           "SlackCable", "SlackScene", "analyze", "converge", "irvine_modes", "lambda_squared", "load_slack_scene",
           "modes", "plot_equilibrium", "plot_mode_shapes", "solve_equilibrium"]

# old name -> new name: they clashed with cablesys.Cable / cablesys.load_scene (the Wang scene's)
DEPRECATED = {"Cable": "SlackCable", "load_scene": "load_slack_scene"}

_lazy_getattr, __dir__ = lazy_exports(__name__, _EXPORTS, __all__)


def __getattr__(name):
    if name in DEPRECATED:
        warnings.warn(f"cablesys.slack.{name} is deprecated: use cablesys.slack.{DEPRECATED[name]}",
                      DeprecationWarning, stacklevel=2)
        return _lazy_getattr(DEPRECATED[name])
    return _lazy_getattr(name)
