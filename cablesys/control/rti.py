"""The MPC's real-time iteration: one Gauss-Newton quadratic program per sample on the winch problem's horizon
(:func:`.payout.payout_nlp`), its kernels compiled once per structure (:func:`.kernels.gauss_newton_kernel`)."""

from __future__ import annotations

import math

import casadi as ca
import numpy as np

from ..errors import ParameterError
from .kernels import gauss_newton_kernel
from .payout import payout_nlp


class GaussNewtonMPC:
    """The receding-horizon problem of ``payout_nlp(problem, N, constrain_first=False)`` solved by
    Gauss-Newton sequential quadratic programming in the real-time iteration scheme (Diehl, Bock &
    Schloeder 2005, "A real-time iteration scheme for nonlinear optimization in optimal feedback
    control", SIAM J. Control Optim. 43(5), 1714-1736): per sample, ``iterations`` (1: the real-time
    iteration) full Gauss-Newton steps from the previous plan shifted by one interval, each one
    convex quadratic program.

    Each step linearizes at the roll-out of the plan from the measured state (single shooting:
    node states x_k(U), so the condensed problem has the N controls alone as variables; the
    sensitivities S_k = dx_k/dU follow S_{k+1} = A_k S_k + B_k e_k^T from the kernel's A, B),
    takes the objective's Gauss-Newton model 1/2 dU^T J^T J dU + (J^T r)^T dU (the objective is
    r^T r, :func:`.kernels.gauss_newton_function`; Bock 1983) and the linearized path
    constraints (winch power, no slack, working load at nodes 1..N-1), the speed bound at nodes
    1..N and |alpha| <= a_max, and solves that dense QP with DAQP (a dual active-set method: Arnstroem,
    Bemporad & Axehill 2022, IEEE Trans. Autom. Control 67(8), 4362-4369; ``qpsol``: any CasADi ``conic``
    plugin that takes dense matrices, e.g. "qpoases"). The per-interval linearization is
    one compiled kernel (:func:`.kernels.gauss_newton_kernel`) mapped over the horizon; the QP has
    a fixed structure (N, the model's size, which limits are finite), built once. The scheme's
    preparation phase (the linearization) and feedback phase (the QP) both run after the measurement
    here, so a step's time is the whole iteration, not the feedback delay alone.

    ``step(x0, E, U) -> (U_new, ok)``: E (N+1, ne) the horizon's exogenous rows, U (N,) the guess.
    """

    def __init__(self, problem, N: int, *, iterations: int = 1, qpsol: str = "daqp"):
        if not (isinstance(iterations, int) and iterations >= 1):
            raise ParameterError("mpc_iterations", iterations, "must be an integer >= 1")
        self.problem, self.N, self.iterations = problem, N, iterations
        nx, ne = problem.model.nx, problem.step.size1_in(2)
        kernel = gauss_newton_kernel(problem)
        w = ca.DM([problem.heave_rest, problem.static_tension, problem.tension_weight, problem.control_weight,
                   problem.dt])
        x0, U, E = ca.MX.sym("x0", nx), ca.MX.sym("U", 1, N), ca.MX.sym("E", ne, N + 1)
        p, c = ca.DM(problem.p), ca.DM(problem.c)
        out = kernel.mapaccum("gn_horizon", N, [0], [0])(x0, U, E[:, :N], p, c, w)
        rN, RxN = kernel(out[0][:, N - 1], 0.0, E[:, N], p, c, w)[3:5]
        self.horizon = ca.Function("gn_horizon", [x0, U, E], [*out, rN, RxN])
        # constraint rows: speed at nodes 1..N, then each finite path constraint at nodes 1..N-1
        lim = problem.limits
        self.speed = float(lim.speed)
        self.path = [(c.rows[0], c.lb / c.scale, c.ub / c.scale, c.scale) for c in problem.constraints()
                     if np.isfinite(c.lb) or np.isfinite(c.ub)]
        self.n_rows = (N if math.isfinite(self.speed) else 0) + len(self.path) * (N - 1)
        qp = {"h": ca.Sparsity.dense(N, N), "a": ca.Sparsity.dense(max(self.n_rows, 1), N)}
        opts = {"printLevel": "none", "error_on_fail": False} if qpsol == "qpoases" else {"error_on_fail": False}
        self.qp = ca.conic("gn_qp", qpsol, qp, opts)
        self.a_max = float(lim.acceleration)
        self.qp_failures = 0

    def linearization(self, x0, E, U):
        """(H, grad, Acon, lba, uba, X) of the condensed Gauss-Newton QP at the plan U from x0."""
        N, nx = self.N, self.problem.model.nx
        X, A, B, r, Rx, Ru, g, Gx, Gu, rN, RxN = (np.array(v) for v in self.horizon(x0, U[None, :], E.T))
        A = A.reshape(nx, N, nx).transpose(1, 0, 2)
        S = np.zeros((N + 1, nx, N))
        for k in range(N):
            S[k + 1] = A[k] @ S[k]
            S[k + 1][:, k] += B[:, k]
        nr = r.shape[0]
        Jr = np.einsum("kij,kjn->kin", Rx.reshape(nr, N, nx).transpose(1, 0, 2), S[:N])
        Jr[np.arange(N), :, np.arange(N)] += Ru.T
        J = np.vstack([Jr.reshape(nr * N, N), RxN @ S[N]])
        res = np.concatenate([r.T.ravel(), rN.ravel()])
        rows, lo, hi = [], [], []
        if math.isfinite(self.speed):
            rows.append(S[1:, -1, :])
            lo.append(-self.speed - X[-1])
            hi.append(self.speed - X[-1])
        if self.path:
            ng = g.shape[0]
            Jg = np.einsum("kij,kjn->kin", Gx.reshape(ng, N, nx).transpose(1, 0, 2), S[:N])
            Jg[np.arange(N), :, np.arange(N)] += Gu.T
            for row, lb, ub, scale in self.path:
                rows.append(Jg[1:, row, :] / scale)
                lo.append(lb - g[row, 1:] / scale)
                hi.append(ub - g[row, 1:] / scale)
        if not rows:
            rows, lo, hi = [np.zeros((1, N))], [np.array([-np.inf])], [np.array([np.inf])]
        return J.T @ J, J.T @ res, np.vstack(rows), np.concatenate(lo), np.concatenate(hi), X

    def step(self, x0, E, U):
        """``iterations`` Gauss-Newton steps from the plan U (N,): (the new plan, whether every QP was solved)."""
        U = np.asarray(U, float).copy()
        for _ in range(self.iterations):
            H, grad, Acon, lba, uba, _ = self.linearization(x0, E, U)
            if not (np.isfinite(H).all() and np.isfinite(grad).all() and np.isfinite(Acon).all()):
                self.qp_failures += 1          # the roll-out left the model's domain: keep the plan
                return U, False
            sol = self.qp(h=H, g=grad, a=Acon, lba=lba, uba=uba, lbx=-self.a_max - U, ubx=self.a_max - U)
            if not self.qp.stats()["success"]:
                self.qp_failures += 1
                return U, False
            U = U + np.array(sol["x"]).ravel()
        return U, True
