"""Optimal heave compensation by the winch: open-loop optimum, MPC, and the strategies it replaces.

``heave_problem(scene, WinchLimits(...), model=...)`` sets the problem up on a winch model: by default
(``model="auto"``) the winch form of the ladder's a priori choice for the scene (where ``cablesys run`` starts,
before the a posteriori checks that may grow its N), with its reason (:mod:`.model_choice`: ``resolve_model``, the one place every door of the control takes it from);
explicitly Wang's 2-DOF cable with the unstretched length driven by the payout rate (:mod:`cablesys.model.winch`,
``model="wang"``) or the segmented node model's winch (:mod:`cablesys.model.segmented_winch_control`,
``model="segmented"``, ``segments=N``); ``optimal_payout(problem, horizon)`` solves it by direct multiple shooting with
IPOPT, exact AD derivatives and the objective's Gauss-Newton Hessian (or the exact one); ``resimulate`` checks an
optimum with CVODES between the grid points; ``compare_compensation`` runs no compensation, a passive compensator,
a PI/feed-forward AHC, MPC with preview and the open-loop optimum in closed loop, every one on the same plant, which
may be finer than the controller's model (a node-model plant with a Wang or coarser node controller: the model
mismatch). :mod:`.design` tunes the line's AE and C_I through the nonlinear time domain on either model (by
default the ladder's). Every problem and result says which model ran and why (``model_reason``).
"""

from .limits import WinchLimits
from .model_choice import ModelChoice, resolve_model
from .mpc import STRATEGIES, Comparison, compare_compensation
from .payout import HeaveProblem, PayoutResult, heave_problem, optimal_payout
from .plant import resimulate

__all__ = ["STRATEGIES", "Comparison", "HeaveProblem", "ModelChoice", "PayoutResult", "WinchLimits",
           "compare_compensation", "heave_problem", "optimal_payout", "resimulate", "resolve_model"]
