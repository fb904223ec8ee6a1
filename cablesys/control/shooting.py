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


def solve_shooting(step: ca.Function, stage: ca.Function, x0, N: int, *, params=None, constraints=(),
                   u_bounds=None, x_bounds=None, terminal: ca.Function | None = None,
                   x_ref=None, x_scale=None, u_scale=None, guess=None, ipopt=None, elastic=False) -> ShootingSolution:
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
    params : array (N, nr), optional
        The per-interval parameters r_k (e.g. the interval's start time).
    constraints : sequence of PathConstraint
    u_bounds, x_bounds : (lb, ub) arrays, optional
        Simple bounds on every control / node state (inf: none).
    terminal : casadi.Function, optional
        x_N -> cost.
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
    nx, nu = step.size1_in(0), step.size1_in(1)
    x0 = np.asarray(x0, float).ravel()
    x_ref = x0 if x_ref is None else np.asarray(x_ref, float)
    xs = np.ones(nx) if x_scale is None else np.asarray(x_scale, float)
    us = np.ones(nu) if u_scale is None else np.asarray(u_scale, float)
    R = np.zeros((N, max(step.size1_in(2), 1))) if params is None else np.asarray(params, float).reshape(N, -1)
    opti = ca.Opti()
    Z, V = opti.variable(nx, N + 1), opti.variable(nu, N)
    X = ca.repmat(ca.DM(x_ref), 1, N + 1) + ca.mtimes(ca.diag(ca.DM(xs)), Z)
    U = ca.mtimes(ca.diag(ca.DM(us)), V)
    Rm = ca.DM(R.T)
    Xn = step.map(N)(X[:, :N], U, Rm)
    cost, G = stage.map(N)(X[:, :N], U, Rm)
    opti.subject_to(ca.vec(Z[:, 1:]) == ca.vec(ca.mtimes(ca.diag(ca.DM(1 / xs)), Xn - ca.repmat(ca.DM(x_ref), 1, N))))
    opti.subject_to(Z[:, 0] == (x0 - x_ref) / xs)
    J = ca.sum2(cost)
    if terminal is not None:
        J = J + terminal(X[:, N])
    slacks = _path_constraints(opti, G, constraints, elastic)
    opti.minimize(J if not elastic else ca.sum1(ca.vertcat(*slacks.values())))
    for bounds, var, ref, sc in ((u_bounds, V, np.zeros(nu), us), (x_bounds, Z[:, 1:], x_ref, xs)):
        if bounds is None:
            continue
        for i, (lo, hi) in enumerate(zip(*bounds)):
            if np.isfinite(lo):
                opti.subject_to(var[i, :] >= (lo - ref[i]) / sc[i])
            if np.isfinite(hi):
                opti.subject_to(var[i, :] <= (hi - ref[i]) / sc[i])
    if guess is not None:
        Xg, Ug = (np.asarray(a, float) for a in guess)
        opti.set_initial(Z, ((Xg - x_ref) / xs).T)
        opti.set_initial(V, (Ug / us).T)
    else:
        opti.set_initial(Z, np.zeros((nx, N + 1)))
    opts = {"tol": 1e-8, "max_iter": 500, "print_level": 0, "sb": "yes", **(ipopt or {})}
    opti.solver("ipopt", {"print_time": False, "expand": False}, opts)
    t0 = time.perf_counter()
    try:
        sol = opti.solve()
        val = sol.value
    except RuntimeError:
        val = opti.debug.value
    solve_s = time.perf_counter() - t0
    stats = opti.stats()
    Xv, Uv = np.array(val(X)).reshape(nx, N + 1).T, np.array(val(U)).reshape(nu, N).T
    Gv = np.array(val(G)).reshape(-1, N).T
    violations = {}
    for c in constraints:
        g = Gv[:, list(c.rows)]
        v = np.max(np.maximum(np.maximum(c.lb - g, g - c.ub), 0.0)) / c.scale
        violations[c.name] = max(violations.get(c.name, 0.0), float(v))
    for name, bounds, A in (("control bounds", u_bounds, Uv), ("state bounds", x_bounds, Xv[1:])):
        if bounds is not None:
            lo, hi = (np.asarray(b, float) for b in bounds)
            sc = us if A is Uv else xs
            violations[name] = float(np.max(np.maximum(np.maximum(lo - A, A - hi), 0.0) / sc))
    Xs = np.array(val(Xn)).reshape(nx, N).T          # each interval's end, integrated from its start
    defect = float(np.max(np.abs((Xs - Xv[1:]) / xs)))
    violations["dynamics (continuity)"] = defect
    worst = max(violations, key=violations.get) if violations else ""
    worst = worst if violations.get(worst, 0.0) > 1e-6 else ""
    status = str(stats.get("return_status", "unknown"))
    if elastic:
        violations = {name: float(val(sv)) for name, sv in slacks.items()}
        worst = max(violations, key=violations.get) if violations else ""
        worst = worst if violations.get(worst, 0.0) > 1e-6 else ""
    elif not (stats.get("success", False) and not worst) and constraints:
        phase1 = solve_shooting(step, stage, x0, N, params=params, constraints=constraints, u_bounds=u_bounds,
                                x_bounds=x_bounds, x_ref=x_ref, x_scale=x_scale, u_scale=u_scale,
                                guess=(Xv, Uv), ipopt=ipopt, elastic=True)
        if phase1.worst:            # a path constraint no control within the bounds can meet
            violations, worst = phase1.violations, phase1.worst
    return ShootingSolution(X=Xv, U=Uv, G=Gv, objective=float(val(J)), status=status,
                            success=bool(stats.get("success", False)) and not worst,
                            iterations=int(stats.get("iter_count", -1)), solve_s=solve_s,
                            violations=violations, worst=worst)


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
