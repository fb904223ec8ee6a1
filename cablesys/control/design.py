"""Design through the nonlinear time domain: the line's AE and C_I (each section's, and an intermediate body's mass)
tuned on realised seas.

The plant is the design's winch model at zero payout (:mod:`.design_problem`: Wang's 2-DOF cable, Wang 1971 eq.
47-48 with the drag of eq. 32-45, or the segmented node model; by default, in the API as in ``cablesys control
--design``, the winch form of the model the ladder chooses for the scene, :mod:`.model_choice`), rolled out by the classical RK4 from the rest state of each candidate design, in
each of ``seeds`` realisations of the scene's sea (:mod:`.design_rollout`). The NLP over theta (one section:
(AE, C_I); a chain: each section's, a soft insert's among them, and the intermediate body's mass,
:mod:`.design_problem`), normalized to z in [0, 1]^n on the log of the ``[design]`` bounds:

    minimize   (1 / S) sum_s var_s(y_b)                        (mean over the seeds; y_b the lowest body's)
    subject to KS_rho(T_top,i / WL_i) <= 1                     (each section's top tension <= its working load)
               KS_rho(-T_f / mean T_f) <= -slack_fraction      (no slack: least / static tension, DNV-RP-H103)
               KS_rho(|y_b - mean y_b|, |x_b - mean x_b|) / e_max <= 1   (body excursion)
               u_0,i / l_0,i <= strain_limit_i                 (each section's static stretch at rest)

for every seed s separately (so each constraint holds in the worst seed), over the statistics window
[``limits.statistics_start``, T] of the record. var is the variance about the window mean; T_f the tension the
no-slack floor bounds (Wang's model: the spring force of the uniform stretch F_bc, Wang 1971 eq. 54; the node
model: the least element tension, where slack starts), T_top the pull on the sheave. KS_rho(g) = m + log(sum_k
exp(rho (g_k - m))) / rho with m = max_k g_k is the Kreisselmeier-Steinhauser envelope (Kreisselmeier &
Steinhauser 1979, "Systematic control design by optimizing a vector performance index", IFAC Proc. 12(7)): smooth,
max_k g_k <= KS_rho <= max_k g_k + ln(N) / rho, so a met KS constraint is conservative by at most ln(N) / rho of the
normalized limit (rho = 200: 3.5 % at N = 1200, in practice far less: only samples within ~1/rho of the peak
count). The shift m cancels in exact arithmetic (d KS / d m = 0), so AD through it is exact.

Derivatives: exact, by forward sensitivities of the roll-out (:mod:`.design_rollout`). IPOPT (``nlpsol``) sees the
roll-out as one function with that Jacobian (a ``casadi.Callback``) and a limited-memory Hessian (a few variables),
from the two starts of a scan (:func:`scan_starts`). The design re-run by the plain time domain:
:mod:`.design_check`.
"""

from __future__ import annotations

import dataclasses
import math
import time
from typing import ClassVar

import casadi as ca
import numpy as np
from scipy.stats import qmc

from ..results import ResultBase, timed
from .design_check import resimulate_design
from .design_problem import SERIES, TimeDesignProblem, describe_theta, time_design_problem, unit
from .design_rollout import DesignFunctions, design_functions, design_kernels, ks_max

# constraint kinds (per seed, then the static one)
CONSTRAINTS = ("peak_tension", "slack", "excursion", "static_strain")
# importable from here too: the problem (.design_problem), the roll-out (.design_rollout), the re-run (.design_check)
__all__ = ["CONSTRAINTS", "SERIES", "DesignFunctions", "TimeDesignProblem", "TimeDesignResult", "design_functions",
           "design_kernels", "evaluate_design", "ks_max", "resimulate_design", "scan_starts", "time_design_problem",
           "time_domain_design"]


class _NLP(ca.Callback):
    """z -> (f, g) for ``nlpsol`` with the Jacobian from the forward sensitivities (:class:`DesignFunctions`)."""

    def __init__(self, fns: DesignFunctions, scale: float, n: int):
        ca.Callback.__init__(self)
        self.fns, self.scale, self.n = fns, scale, n
        self.construct("time_design_nlp", {"enable_fd": False})

    def get_n_in(self):
        return 1

    def get_n_out(self):
        return 2

    def get_sparsity_in(self, i):
        return ca.Sparsity.dense(self.n, 1)

    def get_sparsity_out(self, i):
        return ca.Sparsity.dense(1, 1) if i == 0 else ca.Sparsity.dense(len(self.fns.rows), 1)

    def eval(self, arg):
        f, g = self.fns.fg(arg[0])
        return [self.scale * f, g]

    def has_jacobian(self):
        return True

    def get_jacobian(self, name, inames, onames, opts):
        z = ca.MX.sym("z", self.n)
        out = [ca.MX.sym("f"), ca.MX.sym("g", len(self.fns.rows))]
        jf, jg = self.fns.jac(z)
        return ca.Function(name, [z, *out], [self.scale * jf, jg], inames, onames, opts)


@dataclasses.dataclass(frozen=True)
class TimeDesignResult(ResultBase):
    """A time-domain design (module docstring): the optimum ``theta`` (the variables ``names``, one section: (AE N,
    C_I N s)), the baseline (the scene's values) and both responses per seed on the roll-out grid (``times`` s; ``tension_top``,
    ``tension_floor`` N, ``heave`` m from the window mean, per seed: arrays (seeds, N)); ``constraints``
    {row: (value, upper bound)} at the optimum and at the baseline; ``history`` IPOPT's per-iteration
    objective and primal infeasibility; ``model`` the design's model
    (:meth:`.design_problem.TimeDesignProblem.describe`), ``model_reason`` why it runs
    (:attr:`.design_problem.TimeDesignProblem.model_reason`) and ``floor_output`` the model's output ``tension_floor`` is (Wang's ``tension_mid``, F_bc; the node model's
    ``tension_least``)."""

    theta: tuple
    theta_baseline: tuple
    objective: float                    # mean over seeds of var(y_b), m^2
    objective_baseline: float
    constraints: dict
    constraints_baseline: dict
    seeds: tuple
    times: np.ndarray
    heave: np.ndarray
    heave_baseline: np.ndarray
    tension_top: np.ndarray
    tension_top_baseline: np.ndarray
    tension_floor: np.ndarray
    tension_floor_baseline: np.ndarray
    history: dict
    limits: dict
    status: str
    success: bool = True
    message: str = ""
    stats: dict = dataclasses.field(default_factory=dict)
    model: str = ""
    floor_output: str = "tension_mid"
    model_reason: str = ""
    names: tuple = ("ae_1", "internal_damping_1")

    VARIABLES: ClassVar[dict] = {
        "heave": ("m", "body heave from its window mean (down +), design"),
        "heave_baseline": ("m", "body heave from its window mean, the scene's line"),
        "tension_top": ("N", "tension at the top, design"), "tension_top_baseline": ("N", "tension at the top, baseline"),
        "tension_floor": ("N", "the tension the no-slack floor bounds (Wang's F_bc, eq. 54; the node model's least "
                               "element tension), design"),
        "tension_floor_baseline": ("N", "the tension the no-slack floor bounds, baseline")}

    @property
    def heave_std_m(self) -> float:
        return math.sqrt(self.objective)

    def to_xarray(self):
        """The per-seed histories on dimensions (seed, time)."""
        import xarray as xr
        names = ("heave", "heave_baseline", "tension_top", "tension_top_baseline", "tension_floor",
                 "tension_floor_baseline")
        ds = xr.Dataset({n: (("seed", "time"), getattr(self, n)) for n in names},
                        coords={"seed": list(self.seeds), "time": self.times})
        for n in names:
            ds[n].attrs.update(units=self.VARIABLES[n][0], long_name=self.VARIABLES[n][1])
        ds["time"].attrs.update(units="s", long_name="time")
        ds.attrs.update(**{_key(n): v for n, v in zip(self.names, self.theta)}, model=self.model,
                        model_reason=self.model_reason, floor_output=self.floor_output)
        return ds

    def summary(self) -> dict:
        single = {}
        if tuple(self.names) == ("ae_1", "internal_damping_1"):      # one section: its (AE, C_I) by their names
            single = {"ae_n": self.theta[0], "internal_damping_n_s": self.theta[1],
                      "baseline_ae_n": self.theta_baseline[0], "baseline_internal_damping_n_s": self.theta_baseline[1]}
        return {"success": self.success, "message": self.message, "status": self.status, **single,
                "design": {_key(n): v for n, v in zip(self.names, self.theta)},
                "baseline": {_key(n): v for n, v in zip(self.names, self.theta_baseline)},
                "described": describe_theta(self.names, self.theta),
                "objective_heave_variance_m2": self.objective, "baseline_heave_variance_m2": self.objective_baseline,
                "heave_std_m": self.heave_std_m, "baseline_heave_std_m": math.sqrt(self.objective_baseline),
                "heave_reduction_db": 10 * math.log10(self.objective / self.objective_baseline),
                "constraints": {k: {"value": v, "bound": b} for k, (v, b) in self.constraints.items()},
                "constraints_baseline": {k: {"value": v, "bound": b} for k, (v, b) in self.constraints_baseline.items()},
                "seeds": list(self.seeds), "limits": self.limits, "stats": self.stats, "model": self.model,
                "model_reason": self.model_reason, "floor_output": self.floor_output}


def _key(name: str) -> str:
    """A variable's key with its unit (``ae_1_n``, ``internal_damping_1_n_s``, ``intermediate_mass_kg``)."""
    return f"{name}_{unit(name).lower().replace(' ', '_')}"


def _evaluate(problem, fns, z):
    """(objective, {row: (value, bound)}, series per seed (S, 4, N)) at z."""
    th = np.array(fns.theta(z)).ravel()
    Ys = np.array([np.array(fns.series(th, T)[0]) for T in fns.tables])
    f, g = fns.fg(z)
    g = np.array(g).ravel()
    return float(f), {r: (float(v), float(b)) for r, v, b in zip(fns.rows, g, fns.ub)}, Ys


def scan_starts(problem, fns, n_ae: int = 17, n_ci: int = 3, n_points: int = 32) -> list:
    """IPOPT's starts from a scan of designs: the feasible design of least objective and the best one at least a
    quarter of the log-AE range away from it in some section's AE (the heave variance has a local optimum on each
    side of the axial resonance's passage through the sea band: a soft insert below it, a stiff line above). One
    section: n_ae x n_ci log-spaced (AE, C_I); more variables: ``n_points`` scrambled Sobol points of the
    normalized box (``scipy.stats.qmc``, seed 0). Without a feasible design: the least violations."""
    nv = len(problem.variables)
    if nv == 2:
        pts = [(a, b) for a in np.linspace(0.0, 1.0, n_ae) for b in np.linspace(0.1, 0.9, n_ci)]
    else:
        pts = [tuple(p) for p in qmc.Sobol(nv, scramble=True, seed=0).random(n_points)]
    ae = [j for j, n in enumerate(problem.names) if n.startswith("ae_")]
    scored = []
    for zz in pts:
        f, g = fns.fg(zz)
        viol = float(np.max(np.maximum(np.array(g).ravel() - fns.ub, 0.0))) if fns.ub.size else 0.0
        scored.append((viol > 0, viol if viol > 0 else float(f), zz))
    scored.sort(key=lambda t: (t[0], t[1]))
    first = scored[0]
    other = next((t for t in scored[1:] if max(abs(t[2][j] - first[2][j]) for j in ae) >= 0.25
                  and t[0] == first[0]), None)
    return [tuple(problem.theta(t[2])) for t in (first, other) if t is not None]


@timed
def time_domain_design(problem: TimeDesignProblem, *, starts=None, max_iter: int = 50,
                       tol: float = 1e-6) -> TimeDesignResult:
    """The design of least mean heave variance meeting every constraint in every seed (module docstring).

    Parameters
    ----------
    problem : TimeDesignProblem
        From :func:`time_design_problem`.
    starts : sequence of theta, optional
        IPOPT's starting designs (the variables' values, ``problem.names``; default: the two of a scan,
        :func:`scan_starts`); the feasible optimum of least objective is kept.
    max_iter, tol : int, float
        IPOPT's iteration limit and tolerance per start.
    """
    fns = design_functions(problem)
    nv = len(problem.variables)
    z = ca.MX.sym("z", nv)
    t0 = time.perf_counter()
    f0 = float(fns.fg(problem.z(problem.theta_nominal))[0])
    scale = 1.0 / f0 if f0 > 0 else 1.0
    cb = _NLP(fns, scale, nv)
    f, g = cb(z)
    opts = {"ipopt": {"max_iter": max_iter, "tol": tol, "hessian_approximation": "limited-memory",
                      "print_level": 0, "sb": "yes", "acceptable_tol": 1e-4, "acceptable_iter": 5},
            "print_time": False}
    solver = ca.nlpsol("time_design", "ipopt", {"x": z, "f": f, "g": g}, opts)
    if starts is None:
        starts = scan_starts(problem, fns)
    scan_s = time.perf_counter() - t0
    runs = []
    for th in starts:
        z0 = np.clip(problem.z(th), 0.0, 1.0)
        sol = solver(x0=z0, lbx=0.0, ubx=1.0, lbg=-np.inf, ubg=fns.ub)
        st = solver.stats()
        g = np.array(sol["g"]).ravel()
        viol = float(np.max(np.maximum(g - fns.ub, 0.0))) if g.size else 0.0
        it = st.get("iterations", {})
        runs.append({"start": [float(v) for v in th], "z": np.array(sol["x"]).ravel(), "f": float(sol["f"]) / scale,
                     "status": st["return_status"], "success": bool(st["success"]), "violation": viol,
                     "iterations": int(st["iter_count"]),
                     "history": {"objective": [float(v) / scale for v in it.get("obj", [])],
                                 "infeasibility": [float(v) for v in it.get("inf_pr", [])]}})
    solve_s = time.perf_counter() - t0
    ok = [r for r in runs if r["violation"] <= 1e-6]
    best = min(ok or runs, key=lambda r: (r["f"] if ok else r["violation"]))
    zb = problem.z(problem.theta_nominal)
    f_opt, c_opt, Y = _evaluate(problem, fns, best["z"])
    f_base, c_base, Yb = _evaluate(problem, fns, zb)
    success = bool(ok) and best["success"]
    if not ok:
        worst = max(c_opt, key=lambda k: c_opt[k][0] - c_opt[k][1])
        message = f"infeasible: '{worst}' cannot be met within the design bounds ({c_opt[worst][0]:.4g} > {c_opt[worst][1]:.4g})"
    elif not best["success"]:
        message = f"IPOPT stopped with {best['status']}: a feasible design, not proven optimal; try more iterations"
    else:
        message = ""
    k0 = problem.window_start
    times = problem.dt * np.arange(problem.N)
    centre = lambda h: h - np.mean(h[:, k0:], axis=1, keepdims=True)
    limits = {"working_load_n": problem.working_load, "slack_fraction": problem.slack_fraction,
              "max_excursion_m": problem.max_excursion, "strain_limit": problem.strain_limit,
              "statistics_start_s": k0 * problem.dt, "ks_rho": problem.rho,
              "bounds": {_key(v.name): [v.lower, v.upper] for v in problem.variables}}
    stats = {"iterations": sum(r["iterations"] for r in runs), "solve_s": solve_s, "starts": len(runs),
             "setup_and_scan_s": scan_s,
             "runs": [{k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in r.items() if k != "history"}
                      for r in runs], "intervals": problem.N, "dt_s": problem.dt, "seeds": list(problem.seeds),
             "rk4_steps_per_interval": problem.heave.substeps, "fastest_mode_rad_s": problem.fastest_mode}
    return TimeDesignResult(theta=tuple(float(v) for v in problem.theta(best["z"])),
                            theta_baseline=problem.theta_nominal, objective=f_opt, objective_baseline=f_base,
                            constraints=c_opt, constraints_baseline=c_base, seeds=problem.seeds, times=times,
                            heave=centre(Y[:, 0]), heave_baseline=centre(Yb[:, 0]), tension_top=Y[:, 3],
                            tension_top_baseline=Yb[:, 3], tension_floor=Y[:, 2], tension_floor_baseline=Yb[:, 2],
                            history=best["history"], limits=limits, status=best["status"], success=success,
                            message=message, stats=stats, model=problem.describe(), floor_output=problem.floor_output,
                            model_reason=problem.model_reason, names=problem.names)


def evaluate_design(problem: TimeDesignProblem, theta) -> dict:
    """The roll-out's objective and constraint values (row -> (value, bound)) at ``theta`` (the variables' values,
    ``problem.names``): e.g. the frequency-domain optimum seen by the nonlinear time domain."""
    fns = design_functions(problem)
    f, c, _ = _evaluate(problem, fns, problem.z(theta))
    return {"objective_heave_variance_m2": f, "constraints": c}


