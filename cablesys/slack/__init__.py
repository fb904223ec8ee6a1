"""Slack cables: Irvine–Caughey theory and a converged lumped-mass solver.

Griffin & Rosenthal (1985), "The Dynamics of Slack Marine Cables", NRL MR 5559.

scene (``SlackScene``, ``load_scene``) -> statics (``solve_equilibrium`` -> :class:`Equilibrium`)
-> modes (``compute_modes`` -> :class:`ModeSet`; ``analyze`` does both) -> element-count
convergence (``converge`` -> :class:`Convergence`); the flat-sag theory in ``irvine_modes``.
"""

from .irvine import IrvineMode, irvine_modes, lambda_squared
from .modes import analyze, compute_modes, converge
from .plots import plot_equilibrium, plot_mode_shapes
from .results import Convergence, Equilibrium, ModeSet
from .scene import Cable, PointMass, SlackScene, load_scene
from .statics import solve_equilibrium

__all__ = ["Cable", "Convergence", "Equilibrium", "IrvineMode", "ModeSet", "PointMass", "SlackScene",
           "analyze", "compute_modes", "converge", "irvine_modes", "lambda_squared", "load_scene",
           "plot_equilibrium", "plot_mode_shapes", "solve_equilibrium"]
