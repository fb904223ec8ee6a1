"""The multiple-shooting transcription of cablesys.control against the discrete Riccati solution.

For a linear spring-mass plant x' = A x + B u (exactly discretized with the matrix exponential)
and the cost sum x'Qx + u'Ru with terminal cost x_N' P x_N, P the solution of the discrete
algebraic Riccati equation, the finite-horizon optimum is the stationary LQR law u_k = -K x_k
with K = (R + B'PB)^-1 B'PA (Bellman: the cost-to-go is x'Px at every stage). A wrong sign,
a shifted index or a dropped continuity constraint in the transcription breaks the equality.
"""

import casadi as ca
import numpy as np
import pytest
from scipy.linalg import expm, solve_discrete_are

from cablesys.control.shooting import PathConstraint, solve_shooting


def _plant(dt=0.1, m=2.0, k=8.0, c=0.3):
    Ac = np.array([[0.0, 1.0], [-k / m, -c / m]])
    Bc = np.array([[0.0], [1.0 / m]])
    E = expm(np.block([[Ac, Bc], [np.zeros((1, 3))]]) * dt)
    return E[:2, :2], E[:2, 2:]


def _functions(A, B, Q, R):
    x, u, r = ca.SX.sym("x", 2), ca.SX.sym("u", 1), ca.SX.sym("r", 1)
    step = ca.Function("step", [x, u, r], [ca.mtimes(ca.DM(A), x) + ca.mtimes(ca.DM(B), u)])
    cost = ca.bilin(ca.DM(Q), x, x) + ca.bilin(ca.DM(R), u, u)
    stage = ca.Function("stage", [x, u, r], [cost, ca.vertcat(u, x[0])])
    return step, stage, x


def test_shooting_equals_discrete_riccati_lqr():
    A, B = _plant()
    Q, R = np.diag([1.0, 0.1]), np.array([[0.05]])
    P = solve_discrete_are(A, B, Q, R)
    K = np.linalg.solve(R + B.T @ P @ B, B.T @ P @ A)
    step, stage, x = _functions(A, B, Q, R)
    terminal = ca.Function("term", [x], [ca.bilin(ca.DM(P), x, x)])
    x0 = np.array([1.0, -0.5])
    sol = solve_shooting(step, stage, x0, 60, terminal=terminal, ipopt={"tol": 1e-12})
    assert sol.success, sol.status
    u_lqr = -(K @ sol.X[:-1].T).ravel()
    rel = np.max(np.abs(sol.U.ravel() - u_lqr)) / np.max(np.abs(u_lqr))
    assert rel < 1e-6
    # and the optimal cost is x0' P x0
    assert sol.objective == pytest.approx(float(x0 @ P @ x0), rel=1e-8)


def test_long_horizon_without_terminal_cost_converges_to_lqr():
    """Receding-horizon view: the first move of the horizon-N problem tends to -K x0 as N grows."""
    A, B = _plant()
    Q, R = np.diag([1.0, 0.1]), np.array([[0.05]])
    P = solve_discrete_are(A, B, Q, R)
    K = np.linalg.solve(R + B.T @ P @ B, B.T @ P @ A)
    step, stage, _ = _functions(A, B, Q, R)
    x0 = np.array([1.0, -0.5])
    u_star = float(-(K @ x0)[0])
    errs = [abs(solve_shooting(step, stage, x0, n, ipopt={"tol": 1e-12}).U[0, 0] - u_star) for n in (5, 20, 120)]
    assert errs[0] > errs[1] > errs[2] and errs[2] < 1e-6 * abs(u_star)


def test_infeasible_bound_is_named():
    """|u| <= 1e-3 cannot steer x_0 ... with x[0] >= 0.9 on every node: the status names that constraint."""
    A, B = _plant()
    step, stage, _ = _functions(A, B, np.eye(2), np.eye(1))
    sol = solve_shooting(step, stage, [1.0, 0.0], 30,
                         constraints=[PathConstraint("position floor", (1,), 0.9, np.inf)],
                         u_bounds=([-1e-3], [1e-3]), ipopt={"max_iter": 200})
    assert not sol.success
    assert sol.worst == "position floor" and sol.violations["position floor"] > 0.1
