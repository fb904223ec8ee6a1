"""Optimal heave compensation by the winch: open-loop optimum, MPC, and the winch model's limits.

``heave_problem(scene, WinchLimits(...))`` sets the problem up on the winch model
(:mod:`cablesys.model.winch`); ``optimal_payout(problem, horizon)`` solves it by direct multiple
shooting with IPOPT; ``resimulate`` checks the optimum with CVODES between the grid points.
"""

from .limits import WinchLimits
from .payout import HeaveProblem, PayoutResult, heave_problem, optimal_payout
from .resimulate import resimulate

__all__ = ["HeaveProblem", "PayoutResult", "WinchLimits", "heave_problem", "optimal_payout", "resimulate"]
