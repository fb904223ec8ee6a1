"""Solve the isolation design NLP with IPOPT (``casadi.nlpsol``): several starts, drag fixed point.

The problem is not convex (resonances move through the sea spectrum as AE changes), so the
first solve runs from ``n_starts`` points: the scene's own design and a Latin hypercube in
the log-scaled box. The equivalent linearization (the Jacobian shift dJ) is then updated from the Gaussian
equivalent linearization at the optimum (:mod:`cablesys.linear.stochastic`) and the NLP is
warm-started from the best point (primal and dual, small barrier parameter), until the
objective changes by less than ``outer_tol`` (see :mod:`.objective` for why dJ is held during
a solve). The multistart pass uses a looser tolerance (``SCOUT_TOL``) when later passes
polish the optimum. IPOPT uses a limited-memory
quasi-Newton Hessian; its gradients and constraint Jacobians are exact (CasADi AD).

IPOPT's status is translated: infeasibility names the constraint (or bound) that cannot be
met, with the best value reached, and raises :class:`DesignInfeasible`.
"""

from __future__ import annotations

import logging
import time

import casadi as ca
import numpy as np
from scipy.stats import qmc

from ..errors import SolverError
from ..linear.linearization import linearize, residual_jacobian, xi_blocks
from ..linear.spectra import jonswap
from ..linear.steady import steady_state
from ..linear.stochastic import stochastic_response
from ..model import build_model
from .objective import constraint_names, nlp_functions
from .problem import DesignSettings, current_values, variables
from .results import DesignResult, describe_constraint

log = logging.getLogger(__name__)
OK_STATUS = ("Solve_Succeeded", "Solved_To_Acceptable_Level")
FEASIBILITY_TOL = 1e-6
SCOUT_TOL = 1e-3       # IPOPT tolerance of the multistart pass when later passes polish the optimum


ACTIVE_TOL = 1e-4      # a constraint is active when its normalized margin -g is within this of 0 (g = 0: just met)


class DesignFailed(SolverError):
    """IPOPT could not evaluate the design problem from any start (a failed computation: exit 1)."""

    exit_code = 1


class DesignInfeasible(SolverError):
    """No design within the bounds meets the constraints: a failed computation (the ``cablesys`` command
    exits 1), not bad input. ``constraint`` names the most violated constraint, ``violation`` its g > 0
    (normalized: relative to its limit), ``best`` the point IPOPT reached (variable name -> value in the
    variable's unit) and ``margins`` every constraint's margin -g there (>= 0 met)."""

    exit_code = 1

    def __init__(self, message: str, constraint: str, violation: float, best: dict | None = None,
                 margins: dict | None = None):
        super().__init__(message)
        self.constraint, self.violation = constraint, violation
        self.best, self.margins = dict(best or {}), dict(margins or {})


def active_set(vars_, x_normalized, names, g) -> list:
    """The constraints at their bound: variables within ``ACTIVE_TOL`` of a bound of their normalized
    (0-1) box, and constraints whose margin -g is within ``ACTIVE_TOL`` of 0 (met or just violated),
    so the list agrees with the printed margins (IPOPT's interior-point multipliers are not used:
    they are small but nonzero off the bound)."""
    active = [f"{v.name} at {'lower' if a < 0.5 else 'upper'} bound" for v, a in zip(vars_, x_normalized)
              if min(a, 1 - a) < ACTIVE_TOL]
    return active + [n for n, gk in zip(names, g) if abs(gk) <= ACTIVE_TOL]


def equivalent_jacobian_shift(model, p, settings: DesignSettings, *, n_log2: int | None = None, start=None):
    """dJ = E[dr/dxi] - dr/dxi(q_0): what the Gaussian equivalent linearization adds (mostly drag).

    ``start``: the stochastic response at a neighbouring design (warm start of its iteration)."""
    omega = settings.omega
    st = stochastic_response(model, p, omega, jonswap(omega, settings.hs, settings.tp, settings.gamma),
                             n_log2=n_log2 or settings.quadrature_log2, tol=settings.equivalent_tol, start=start)
    return (residual_jacobian(st.linear) - residual_jacobian(linearize(model, p))).real, st


def _starts(x_scene: np.ndarray, n: int) -> list:
    pts = [np.clip(x_scene, 0.02, 0.98)]
    if n > 1:
        pts += list(0.05 + 0.9 * qmc.LatinHypercube(d=len(x_scene), seed=1).random(n - 1))
    return pts


def _infeasibility(g: np.ndarray, names: tuple, settings: DesignSettings, report_row, vars_=(), x=()) -> DesignInfeasible:
    k = int(np.argmax(g))
    text = describe_constraint(names[k], settings)
    best = {v.name: float(v.value(a)) for v, a in zip(vars_, x)}
    point = ", ".join(f"{n} {val:.5g}" for n, val in best.items())
    return DesignInfeasible(
        f"design infeasible: the constraint '{names[k]}' ({text}) cannot be met within the bounds; the best point "
        f"IPOPT reached ({point or 'no variables'}) still violates it by {g[k]:.3g} (relative; 0 = just met). "
        f"{report_row}Relax that limit, widen the bounds of the variables it depends on, or change the sea state.",
        names[k], float(g[k]), best, {n: float(-gk) for n, gk in zip(names, g)})


def design(scene, settings: DesignSettings, *, model=None) -> DesignResult:
    """Optimize ``scene``'s AE and C_I per section (and optionally the intermediate body) for ``settings``.

    Parameters
    ----------
    scene : Scene
        The Wang (1971) scene whose AE and C_I are designed (its values are the first start).
    settings : DesignSettings
        Sea state, objective, bounds, constraints and solver settings.
    model : CableModel, optional
        A model already built for ``scene`` (its structure must match).

    Returns
    -------
    DesignResult
        Optimal values, margins, active set; ``success`` False if IPOPT or the outer
        drag iteration did not converge.

    Raises
    ------
    DesignInfeasible
        If no design within the bounds meets the constraints (names the constraint, keeps the best point).
    DesignFailed
        If the objective or constraints are not finite at every start.
    """
    t_start = time.perf_counter()
    model = model or build_model(scene)
    vars_ = variables(scene, settings)
    p_base = model.parameters(scene)
    x_sym, par, f, g, report = nlp_functions(model, settings, vars_, p_base)
    nlp = {"x": x_sym, "p": par, "f": f, "g": g}
    base = {"print_level": 0, "sb": "yes", "max_iter": settings.max_iter, "tol": settings.tol,
            "hessian_approximation": "limited-memory", "acceptable_tol": 1e-6}
    # the first pass only has to find the basin (dJ is still the scene's, not the optimum's):
    # scout with a looser tolerance when later passes polish the result
    scout_tol = settings.tol if settings.outer_iterations == 1 else max(settings.tol, SCOUT_TOL)
    scout = ca.nlpsol("isolation_design_scout", "ipopt", nlp, {"print_time": False, "ipopt": {**base, "tol": scout_tol}})
    # later passes move the optimum a little (dJ changes by a few %): warm start from the previous
    # primal-dual point with a small barrier parameter
    warm = ca.nlpsol("isolation_design_warm", "ipopt", nlp, {"print_time": False, "ipopt": {
        **base, "warm_start_init_point": "yes", "mu_init": 1e-6, "warm_start_bound_push": 1e-9,
        "warm_start_bound_frac": 1e-9, "warm_start_slack_bound_push": 1e-9, "warm_start_slack_bound_frac": 1e-9,
        "warm_start_mult_bound_push": 1e-9}})
    names = constraint_names(model.n_sections)
    x_scene = np.array([v.normalized(np.clip(val, v.lower, v.upper)) for v, val in zip(vars_, current_values(scene, vars_))])
    q_guess = steady_state(model, p_base).q
    n_xi = xi_blocks(model)["n"]

    def p_of(xv):
        return np.array(report(xv, np.r_[np.zeros(model.nq * n_xi), q_guess])[6]).ravel()

    dJ, st = equivalent_jacobian_shift(model, p_of(x_scene), settings)
    starts = _starts(x_scene, settings.n_starts)
    runs, history = [], []
    best, f_prev = None, None
    for outer in range(settings.outer_iterations):
        par_val = np.r_[dJ.ravel(order="F"), q_guess]
        candidates = []
        solver = scout if outer == 0 else warm
        for x0 in starts:
            t0 = time.perf_counter()
            duals = {} if outer == 0 else {"lam_x0": best[3], "lam_g0": best[4]}
            sol = solver(x0=x0, lbx=0.0, ubx=1.0, lbg=-np.inf, ubg=0.0, p=par_val, **duals)
            wall = time.perf_counter() - t0
            s = solver.stats()
            xv = np.array(sol["x"]).ravel()
            gv = np.array(sol["g"]).ravel()
            run = {"outer": outer, "start": [float(a) for a in x0], "status": s["return_status"],
                   "iterations": int(s["iter_count"]), "wall_s": wall,
                   "objective": float(sol["f"]), "max_violation": float(max(gv.max(), 0.0))}
            runs.append(run)
            candidates.append((run, xv, gv, np.array(sol["lam_x"]).ravel(), np.array(sol["lam_g"]).ravel()))
        feasible = [c for c in candidates if c[0]["max_violation"] <= FEASIBILITY_TOL and np.isfinite(c[0]["objective"])]
        if not feasible and not any(np.all(np.isfinite(c[2])) for c in candidates):
            raise DesignFailed(f"isolation design: IPOPT failed from every start ({candidates[0][0]['status']}): the "
                              "objective or constraints are not finite (check that the bounds keep AE above the "
                              "reference tension and that the scene has a taut steady state)")
        if not feasible:
            c = min(candidates, key=lambda c: c[0]["max_violation"])
            raise _infeasibility(c[2], names, settings,
                                 f"(IPOPT status {c[0]['status']}, {c[0]['iterations']} iterations.) ", vars_, c[1])
        best = min(feasible, key=lambda c: c[0]["objective"])
        f_now = best[0]["objective"]
        # update the equivalent drag damping at the optimum (the outer fixed point)
        C_new, st = equivalent_jacobian_shift(model, p_of(best[1]), settings, start=st)
        change = float(np.max(np.abs(C_new - dJ)) / max(np.max(np.abs(C_new)), 1e-30))
        history.append({"outer": outer, "objective": f_now, "dJ_change": change})
        dJ = C_new
        starts = [best[1]]
        if f_prev is not None and abs(f_now - f_prev) <= settings.outer_tol * abs(f_now):
            break
        f_prev = f_now
    run, xv = best[0], best[1]
    rep = report(xv, np.r_[dJ.ravel(order="F"), q_guess])
    obj, gv_final, sigma, mean_t, strain, q0, p = (np.array(a).ravel() for a in rep)
    values = np.array([v.value(a) for v, a in zip(vars_, xv)])
    active = active_set(vars_, xv, names, gv_final)
    outer_converged = len(history) >= 2 and (
        abs(history[-1]["objective"] - history[-2]["objective"]) <= settings.outer_tol * abs(history[-1]["objective"]))
    converged = run["status"] in OK_STATUS and (outer_converged or settings.outer_iterations == 1)
    if not converged:
        log.warning("isolation design: outer drag iteration or IPOPT did not converge (%s)", run["status"])
    return DesignResult(
        variable_names=tuple(v.name for v in vars_), values=values, lower=np.array([v.lower for v in vars_]),
        upper=np.array([v.upper for v in vars_]), objective=float(obj[0]), objective_kind=settings.objective,
        constraint_names=names, constraint_values=gv_final, active=tuple(active), sigma_y_b=float(sigma[0]),
        sigma_tension=sigma[1:], mean_tension=mean_t, static_strain=strain, q0=q0, parameters=p,
        jacobian_shift=dJ, status=run["status"], success=bool(converged), runs=tuple(runs), outer_history=tuple(history),
        nlp_iterations=int(sum(r["iterations"] for r in runs)), nlp_wall_s=float(sum(r["wall_s"] for r in runs)),
        total_wall_s=time.perf_counter() - t_start, stochastic_sig_y_b=st.significant_amplitude(
            model.label("y_b", model.n_sections - 1)),
        message="" if converged else (f"IPOPT status {run['status']}" if run["status"] not in OK_STATUS else
                                      f"the outer drag iteration did not settle in {settings.outer_iterations} passes"),
        stats={"wall_time_s": time.perf_counter() - t_start, "iterations": int(sum(r["iterations"] for r in runs)),
               "nlp_wall_s": float(sum(r["wall_s"] for r in runs)), "solves": len(runs)})
