"""Direct multiple shooting (Bock & Plitt 1984) with CasADi ``Opti`` and IPOPT, exact derivatives.

The discrete dynamics x_{k+1} = F(x_k, u_k, r_k) are a CasADi function (an RK4 step of an ODE,
or an exact linear map); the NLP has every node state and every control as variables, the
continuity conditions as equality constraints, and named path constraints lb <= g(x_k, u_k,
r_k) <= ub. Hessians come from CasADi's AD of the whole transcription. The variables are
scaled (x = x_ref + S z) so that IPOPT sees O(1) numbers. After the solve every named group of
constraints is evaluated at the returned point, and a failed or infeasible solve names the
most violated one.
"""

from __future__ import annotations

import dataclasses
import time

import casadi as ca
import numpy as np

from ..errors import ParameterError

# the Hessian of the Lagrangian IPOPT is given: CasADi's exact AD one, or the objective's Gauss-Newton matrix
HESSIANS = ("exact", "gauss-newton")

@dataclasses.dataclass(frozen=True)
class PathConstraint:
    """Rows ``rows`` of the stage function's ``g`` bounded by [lb, ub] (``scale``: its unit size)."""

    name: str
    rows: tuple
    lb: float
    ub: float
    scale: float = 1.0


@dataclasses.dataclass(frozen=True)
class ShootingSolution:
    """Node states X (N+1, nx), controls U (N, nu), stage outputs G (N, ng) and the solver's verdict."""

    X: np.ndarray
    U: np.ndarray
    G: np.ndarray
    objective: float
    status: str                 # IPOPT return_status
    success: bool
    iterations: int
    solve_s: float
    violations: dict            # name -> largest violation / scale (0 when met)
    worst: str                  # the most violated constraint ("" when all hold to 1e-6)
    # IPOPT's own timing (s): t_proc_/t_wall_ total and per NLP function (nlp_hess_l, nlp_jac_g, ...)
    timing: dict = dataclasses.field(default_factory=dict)


def solve_shooting(step: ca.Function, stage: ca.Function, x0, N: int, *, params=None, constraints=(),
                   u_bounds=None, x_bounds=None, terminal: ca.Function | None = None,
                   x_ref=None, x_scale=None, u_scale=None, guess=None, ipopt=None,
                   elastic=False) -> ShootingSolution:
    """Solve min sum_k stage(x_k, u_k, r_k)[0] + terminal(x_N) over a multiple-shooting grid.

    Parameters
    ----------
    step : casadi.Function
        (x, u, r) -> x_next.
    stage : casadi.Function
        (x, u, r) -> (cost, g): the stage cost (already weighted by the step) and the path outputs.
    x0 : array
        Fixed initial state.
    N : int
        Number of intervals.
    params : array (N, nr) or (N+1, nr), optional
        The per-interval parameters r_k (e.g. the interval's start time); row N is the terminal's.
    constraints : sequence of PathConstraint
    u_bounds, x_bounds : (lb, ub) arrays, optional
        Simple bounds on every control / node state (inf: none).
    terminal : casadi.Function, optional
        x_N -> cost, or (x_N, r_N) -> cost with r_N the last row of ``params`` (N+1 rows).
    x_ref, x_scale, u_scale : arrays, optional
        Scaling: x = x_ref + x_scale z, u = u_scale v.
    guess : (X, U), optional
        Warm start (node states (N+1, nx), controls (N, nu)).
    ipopt : dict, optional
        IPOPT options (``tol``, ``max_iter``, ...).
    elastic : bool
        Phase-one problem: every path-constraint group gets a slack s >= 0 (lb - s <= g <= ub + s,
        in its scale), the dynamics and simple bounds stay hard, and the sum of the slacks is
        minimized. A failed solve runs it to find which constraint cannot be met
        (``worst``, ``violations``: the slack each group needs).

    Returns
    -------
    ShootingSolution
    """
    nlp = ShootingNLP(step, stage, N, constraints=constraints, u_bounds=u_bounds, x_bounds=x_bounds,
                      terminal=terminal, x_ref=np.asarray(x0, float) if x_ref is None else x_ref,
                      x_scale=x_scale, u_scale=u_scale, ipopt=ipopt, elastic=elastic)
    return nlp.solve(x0, params, guess)


class ShootingNLP:
    """The transcription of :func:`solve_shooting` built once; ``solve(x0, params, guess)`` re-solves
    it for a new initial state and interval parameters (the receding horizon of MPC: IPOPT and
    its derivative functions are reused, only the numbers change).

    ``hessian``: "exact" (CasADi's AD Hessian of the Lagrangian) or "gauss-newton" (the objective's
    Gauss-Newton matrix, :meth:`_gauss_newton_hessian`, for a stage cost r^T r: ``residual(x, u, r_k)`` gives
    r, ``terminal_residual`` the terminal cost's, as ``terminal``'s inputs)."""

    def __init__(self, step, stage, N, *, constraints=(), u_bounds=None, x_bounds=None, terminal=None,
                 x_ref=None, x_scale=None, u_scale=None, ipopt=None, elastic=False, expand=False,
                 warm_duals=False, constrain_first=True, residual=None, terminal_residual=None,
                 hessian: str = "exact"):
        if hessian not in HESSIANS:
            raise ParameterError("hessian", hessian, f"allowed: {', '.join(HESSIANS)}")
        if hessian == "gauss-newton" and (residual is None or (terminal is not None and terminal_residual is None)):
            raise ParameterError("hessian", hessian, "needs the stage cost's residuals (residual, and "
                                                     "terminal_residual with a terminal cost)")
        nx, nu = step.size1_in(0), step.size1_in(1)
        self.N, self.nx, self.nu, self.elastic = N, nx, nu, elastic
        self.args = dict(step=step, stage=stage, N=N, constraints=constraints, u_bounds=u_bounds,
                         x_bounds=x_bounds, x_scale=x_scale, u_scale=u_scale, ipopt=ipopt,
                         constrain_first=constrain_first)
        self.x_ref = np.zeros(nx) if x_ref is None else np.asarray(x_ref, float)
        self.xs = np.ones(nx) if x_scale is None else np.asarray(x_scale, float)
        self.us = np.ones(nu) if u_scale is None else np.asarray(u_scale, float)
        self.constraints, self.u_bounds, self.x_bounds = constraints, u_bounds, x_bounds
        nr = max(step.size1_in(2), 1)
        opti = self.opti = ca.Opti()
        self.Z, self.V = opti.variable(nx, N + 1), opti.variable(nu, N)
        self.X0, self.R = opti.parameter(nx), opti.parameter(nr, N + 1)   # column N: the terminal's
        x_ref, xs = ca.DM(self.x_ref), ca.DM(self.xs)
        self.Xe = ca.repmat(x_ref, 1, N + 1) + ca.mtimes(ca.diag(xs), self.Z)
        self.Ue = ca.mtimes(ca.diag(ca.DM(self.us)), self.V)
        self.Xn = step.map(N)(self.Xe[:, :N], self.Ue, self.R[:, :N])
        cost, self.G = stage.map(N)(self.Xe[:, :N], self.Ue, self.R[:, :N])
        opti.subject_to(ca.vec(self.Z[:, 1:]) == ca.vec(ca.mtimes(ca.diag(1 / xs), self.Xn - ca.repmat(x_ref, 1, N))))
        opti.subject_to(self.Z[:, 0] == (self.X0 - x_ref) / xs)
        if terminal is None:
            self.J = ca.sum2(cost)
        else:
            self.J = ca.sum2(cost) + terminal(*([self.Xe[:, N], self.R[:, N]][: terminal.n_in()]))
        # constrain_first=False: no path constraint at node 0, whose state is given (a measured state
        # just outside a limit must not make the whole horizon infeasible)
        self.slacks = _path_constraints(opti, self.G if constrain_first else self.G[:, 1:], constraints, elastic)
        opti.minimize(self.J if not elastic else ca.sum1(ca.vertcat(*self.slacks.values())))
        for bounds, var, ref, sc in ((u_bounds, self.V, np.zeros(nu), self.us), (x_bounds, self.Z[:, 1:], self.x_ref, self.xs)):
            if bounds is None:
                continue
            for i, (lo, hi) in enumerate(zip(*bounds)):
                if np.isfinite(lo):
                    opti.subject_to(var[i, :] >= (lo - ref[i]) / sc[i])
                if np.isfinite(hi):
                    opti.subject_to(var[i, :] <= (hi - ref[i]) / sc[i])
        opts = {"tol": 1e-8, "max_iter": 500, "print_level": 0, "sb": "yes", **(ipopt or {})}
        self.warm_duals, self.lam_g = warm_duals, None
        if warm_duals:     # IPOPT restarted near the previous solution: small barrier, previous multipliers
            opts = {"warm_start_init_point": "yes", "mu_init": 1e-5, "warm_start_bound_push": 1e-6,
                    "warm_start_mult_bound_push": 1e-6, **opts}
        plugin = {"print_time": False, "record_time": True, "expand": expand}
        if hessian == "gauss-newton" and not elastic:     # the phase-one problem's objective is linear
            plugin["hess_lag"] = self._gauss_newton_hessian(residual, terminal_residual)
        opti.solver("ipopt", plugin, opts)

    def _gauss_newton_hessian(self, residual, terminal_residual) -> ca.Function:
        """The Hessian of the Lagrangian as IPOPT's ``hess_lag``: 2 lam_f J^T J with J the Jacobian of every
        stage's (and the terminal's) residuals r (cost = r^T r) in the NLP's variables (Bock 1983, "Recent
        advances in parameter identification techniques for ODE", in Numerical Treatment of Inverse Problems,
        Birkhaeuser, 95-121): the objective's Gauss-Newton matrix, no second derivatives of the dynamics or of
        the path constraints (their multipliers' terms are dropped). The NLP is the same, so is its KKT point;
        only the steps toward it differ (superlinear near a small-residual optimum with inactive curvature)."""
        opti, N = self.opti, self.N
        r = ca.vec(residual.map(N)(self.Xe[:, :N], self.Ue, self.R[:, :N]))
        if terminal_residual is not None:
            r = ca.vertcat(r, terminal_residual(*([self.Xe[:, N], self.R[:, N]][: terminal_residual.n_in()])))
        J = ca.jacobian(r, opti.x)
        lam_f, lam_g = ca.MX.sym("lam_f"), ca.MX.sym("lam_g", opti.ng)
        H = ca.triu(2 * lam_f * ca.mtimes(J.T, J))
        return ca.Function("gauss_newton_hess", [opti.x, opti.p, lam_f, lam_g], [H],
                           ["x", "p", "lam_f", "lam_g"], ["triu_hess_gamma_x_x"])

    def solve(self, x0, params=None, guess=None) -> ShootingSolution:
        """Solve from ``x0`` with interval parameters ``params`` (N, nr) and warm start ``guess`` (X, U)."""
        opti, N, nx, nu = self.opti, self.N, self.nx, self.nu
        x0 = np.asarray(x0, float).ravel()
        nr = self.R.shape[0]
        R = np.zeros((N + 1, nr)) if params is None else np.asarray(params, float).reshape(-1, nr)
        if len(R) == N:                  # no terminal parameters given: repeat the last interval's
            R = np.vstack([R, R[-1:]])
        opti.set_value(self.X0, x0)
        opti.set_value(self.R, R.T)
        if guess is not None:
            Xg, Ug = (np.asarray(a, float) for a in guess)
            opti.set_initial(self.Z, ((Xg - self.x_ref) / self.xs).T)
            opti.set_initial(self.V, (Ug.reshape(N, nu) / self.us).T)
        else:
            opti.set_initial(self.Z, np.tile(((x0 - self.x_ref) / self.xs)[:, None], (1, N + 1)))
            opti.set_initial(self.V, np.zeros((nu, N)))
        if self.warm_duals and self.lam_g is not None:
            opti.set_initial(opti.lam_g, self.lam_g)
        t0 = time.perf_counter()
        try:
            val = opti.solve().value
        except RuntimeError:
            val = opti.debug.value
        solve_s = time.perf_counter() - t0
        stats = opti.stats()
        if self.warm_duals:
            self.lam_g = np.array(val(opti.lam_g)).ravel()
        Xv, Uv = np.array(val(self.Xe)).reshape(nx, N + 1).T, np.array(val(self.Ue)).reshape(nu, N).T
        Gv = np.array(val(self.G)).reshape(-1, N).T
        if not self.args["constrain_first"]:
            Gv = Gv[1:]
        violations = {}
        for c in self.constraints:
            g = Gv[:, list(c.rows)]
            v = np.max(np.maximum(np.maximum(c.lb - g, g - c.ub), 0.0)) / c.scale
            violations[c.name] = max(violations.get(c.name, 0.0), float(v))
        for name, bounds, A, sc in (("control bounds", self.u_bounds, Uv, self.us),
                                    ("state bounds", self.x_bounds, Xv[1:], self.xs)):
            if bounds is not None:
                lo, hi = (np.asarray(b, float) for b in bounds)
                violations[name] = float(np.max(np.maximum(np.maximum(lo - A, A - hi), 0.0) / sc))
        Xs = np.array(val(self.Xn)).reshape(nx, N).T          # each interval's end, integrated from its start
        violations["dynamics (continuity)"] = float(np.max(np.abs((Xs - Xv[1:]) / self.xs)))
        worst = max(violations, key=violations.get)
        worst = worst if violations[worst] > 1e-6 else ""
        status = str(stats.get("return_status", "unknown"))
        ok = bool(stats.get("success", False)) and not worst
        if self.elastic:
            violations = {name: float(val(sv)) for name, sv in self.slacks.items()}
            worst = max(violations, key=violations.get) if violations else ""
            worst = worst if violations.get(worst, 0.0) > 1e-6 else ""
        elif not ok and self.constraints:
            phase1 = ShootingNLP(**self.args, x_ref=self.x_ref, elastic=True).solve(x0, R, (Xv, Uv))
            if phase1.worst:            # a path constraint no control within the bounds can meet
                violations, worst = phase1.violations, phase1.worst
        return ShootingSolution(X=Xv, U=Uv, G=Gv, objective=float(val(self.J)), status=status,
                                success=ok, iterations=int(stats.get("iter_count", -1)),
                                solve_s=solve_s, violations=violations, worst=worst,
                                timing={k: float(v) for k, v in stats.items() if k.startswith(("t_proc_", "t_wall_"))
                                        and isinstance(v, (int, float))})

def _path_constraints(opti, G, constraints, elastic: bool) -> dict:
    """Impose lb <= g <= ub (scaled) for every constraint row; with ``elastic`` one slack per group."""
    slacks = {}
    for c in constraints:
        s = 0.0
        if elastic:
            s = slacks.setdefault(c.name, opti.variable())
            opti.subject_to(s >= 0)
            opti.set_initial(s, 1.0)
        for r in c.rows:
            g = G[r, :] / c.scale
            if np.isfinite(c.lb):
                opti.subject_to(g >= c.lb / c.scale - s)
            if np.isfinite(c.ub):
                opti.subject_to(g <= c.ub / c.scale + s)
    return slacks
