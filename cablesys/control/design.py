"""Design through the nonlinear time domain: the line's AE and C_I tuned on realised seas.

The plant is the winch model of :mod:`cablesys.model.winch` held at zero payout (w = alpha = 0,
L = l_0: Wang's 2-DOF model exactly, Wang 1971 eq. 47-48 with the drag of eq. 32-45), rolled out
by the fixed-step classical RK4 of :func:`cablesys.control.payout.heave_problem` (``substeps`` steps
per ``dt``) from the rest state of each candidate design, in each of ``seeds`` realisations of the
scene's sea (:mod:`cablesys.scene.sea`: same spectrum, phases from ``default_rng(seed)``). The NLP
over theta = (AE, C_I), normalized to z in [0, 1]^2 on the log of the ``[design]`` bounds:

    minimize   (1 / S) sum_s var_s(y_b)                        (mean over the seeds)
    subject to KS_rho(T_top / WL) <= 1                         (peak tension <= working load)
               KS_rho(-F_bc / mean F_bc) <= -slack_fraction    (no slack: least / static tension, DNV-RP-H103)
               KS_rho(|y_b - mean y_b|, |x_b - mean x_b|) / e_max <= 1   (body excursion)
               u_0 / l_0 <= strain_limit                       (static stretch of the rest state)

for every seed s separately (so each constraint holds in the worst seed), over the statistics window
[``limits.statistics_start``, T] of the record. var is the variance about the window mean; F_bc the
spring force of the uniform stretch (Wang 1971 eq. 54, ``tension_mid``), T_top the pull on the
sheave. KS_rho(g) = m + log(sum_k exp(rho (g_k - m))) / rho with m = max_k g_k is the
Kreisselmeier-Steinhauser envelope (Kreisselmeier & Steinhauser 1979, "Systematic control design by
optimizing a vector performance index", IFAC Proc. 12(7)): smooth, max_k g_k <= KS_rho <=
max_k g_k + ln(N) / rho, so a met KS constraint is conservative by at most ln(N) / rho of the
normalized limit (rho = 200: 3.5 % at N = 1200, in practice far less: only samples within ~1/rho of
the peak count). The shift m cancels in exact arithmetic (d KS / d m = 0), so AD through it is exact.

Derivatives: exact, by forward sensitivities of the roll-out (S_{k+1} = F_x S_k + F_theta, the
variational equation of the discrete map, Hairer, Norsett & Wanner, *Solving ODEs I*, sec. I.14; two
directions in one sweep per seed, the step and its sensitivity step compiled once per model structure),
the rest state's by the implicit-function theorem (``rootfinder``), then the objective's and every
constraint's gradient by forward mode through the (cheap) KS and variance post-processing. IPOPT
(``nlpsol``) sees the roll-out as one function with that Jacobian (a ``casadi.Callback``) and a
limited-memory Hessian (2 variables), from the two starts of a scan (:func:`scan_starts`).
"""

from __future__ import annotations

import dataclasses
import math
import time
from typing import ClassVar

import casadi as ca
import numpy as np

from ..errors import ParameterError, require_positive
from ..model.params import ParameterLayout
from ..model.top_motion import top_motion_function
from ..model.winch import WINCH_OUTPUTS
from ..results import ResultBase, timed
from .gradient import compiled_kernels
from .payout import heave_problem

# the rolled-out series (rows of the roll-out's output), from WINCH_OUTPUTS
SERIES = ("heave", "x_b", "tension_mid", "tension_top")
# constraint kinds (per seed, then the static one)
CONSTRAINTS = ("peak_tension", "slack", "excursion", "static_strain")


def ks_max(v, rho: float):
    """Kreisselmeier-Steinhauser envelope of the entries of ``v`` (module docstring): >= max v."""
    m = ca.mmax(v)
    return m + ca.log(ca.sum2(ca.exp(rho * (v - m)))) / rho


def _bounds(design: dict, name: str, default) -> tuple:
    """(lo, hi) of one section from the ``[design]`` table's ``name`` ([[lo, hi]] or [lo, hi])."""
    v = design.get(name, default)
    v = np.asarray(v, float).ravel()
    if v.size != 2 or not (0 < v[0] < v[1]) or not np.all(np.isfinite(v)):
        raise ParameterError(f"design.{name}", design.get(name, default), "one pair [lo, hi] with 0 < lo < hi")
    return float(v[0]), float(v[1])


@dataclasses.dataclass(frozen=True)
class TimeDesignProblem:
    """The time-domain design problem of a scene (module docstring; SI units).

    ``exogenous`` holds, per seed, the top motion at the RK4 stage times of every interval
    (:meth:`cablesys.control.payout.HeaveProblem.exogenous`, shape (N, 7 (2 substeps + 1))).
    """

    scene: object
    heave: object                       # the HeaveProblem (model, p, c, interval) of the nominal scene
    seeds: tuple
    exogenous: tuple
    dt: float
    N: int
    window_start: int                   # first interval of the statistics window
    ae_bounds: tuple                    # N
    damping_bounds: tuple               # N s
    working_load: float                 # N (inf: none)
    slack_fraction: float | None
    max_excursion: float | None         # m
    strain_limit: float | None          # static u_0 / l_0
    rho: float
    theta_nominal: tuple                # the scene's (AE, C_I)

    @property
    def duration(self) -> float:
        return self.N * self.dt

    def theta(self, z) -> np.ndarray:
        """(AE, C_I) of the normalized design z in [0, 1]^2 (log scale between the bounds)."""
        z = np.asarray(z, float)
        lo = np.log([self.ae_bounds[0], self.damping_bounds[0]])
        hi = np.log([self.ae_bounds[1], self.damping_bounds[1]])
        return np.exp(lo + z * (hi - lo))

    def z(self, theta) -> np.ndarray:
        lo = np.log([self.ae_bounds[0], self.damping_bounds[0]])
        hi = np.log([self.ae_bounds[1], self.damping_bounds[1]])
        return (np.log(np.asarray(theta, float)) - lo) / (hi - lo)

    def designed_scene(self, theta):
        """The scene with the cable's AE and C_I set to ``theta``."""
        return self.scene.replace_section(0, cable={"ae": float(theta[0]), "internal_damping": float(theta[1])})


def time_design_problem(scene, *, seeds=(1, 2, 3), duration: float | None = None, dt: float = 0.5,
                        substeps: int = 2, rho: float = 200.0) -> TimeDesignProblem:
    """Set the time-domain design of ``scene`` up (module docstring).

    Parameters
    ----------
    scene : Scene
        One section, a ``[top_motion.spectrum]`` sea, a ``[design]`` table (``ae_bounds``,
        ``damping_bounds``, optionally ``strain_limit`` and ``working_load``) and ``[limits]``.
    seeds : sequence of int
        Seeds of the sea's random phases; each is one realised record.
    duration : float, optional
        Record length (s; default ``numerics.duration``).
    dt, substeps : float, int
        RK4 interval (s) and steps per interval.
    rho : float
        KS parameter on the normalized constraints (the envelope is within ln(N)/rho of the max).
    """
    if not scene.design:
        raise ParameterError("design", None, "the scene needs a [design] table (ae_bounds, damping_bounds)")
    if scene.top_motion.spectrum is None:
        raise ParameterError("top_motion.spectrum", None, "a realised sea is needed: give [top_motion.spectrum]")
    seeds = tuple(seeds)
    if not seeds or not all(isinstance(s, (int, np.integer)) and s >= 0 for s in seeds) or len(set(seeds)) < len(seeds):
        raise ParameterError("seeds", seeds, "one or more distinct integers >= 0")
    require_positive("rho", rho, "")
    duration = float(scene.numerics.duration if duration is None else duration)
    require_positive("duration", duration, "s")
    lim = scene.limits
    start = float(lim.statistics_start) if lim is not None and lim.statistics_start is not None else 0.2 * duration
    if start >= duration - 10 * dt:
        raise ParameterError("duration", duration, f"must exceed the statistics start {start:g} s by 10 intervals")
    design = scene.design
    ae_b, ci_b = _bounds(design, "ae_bounds", None), _bounds(design, "damping_bounds", None)
    t_ref = scene.sections[0].cable.tension_ref
    if ae_b[0] <= t_ref:
        raise ParameterError("design.ae_bounds lower", ae_b[0], f"must exceed the reference tension {t_ref:g} N")
    wl = design.get("working_load")
    wl = float(np.ravel(wl)[0]) if wl is not None else (lim.working_load if lim is not None else None)
    strain = design.get("strain_limit")
    strain = None if strain is None else float(np.ravel(strain)[0])
    scene = scene.with_numerics(duration=duration)
    hp = heave_problem(scene, dt=dt, substeps=substeps, tension_weight=0.0, control_weight=0.0)
    if wl is not None and not wl > hp.static_tension:
        raise ParameterError("design.working_load", wl, f"must exceed the static top tension {hp.static_tension:.6g} N")
    N = int(round(duration / dt))
    exo = []
    for s in seeds:
        sea = dataclasses.replace(scene.top_motion.spectrum, seed=int(s))
        sc = scene.replace(top_motion=dataclasses.replace(scene.top_motion, spectrum=sea))
        exo.append(_exogenous(sc, hp, N))
    cable = scene.sections[0].cable
    return TimeDesignProblem(scene=scene, heave=hp, seeds=seeds, exogenous=tuple(exo), dt=float(dt), N=N,
                             window_start=int(math.ceil(start / dt - 1e-9)), ae_bounds=ae_b, damping_bounds=ci_b,
                             working_load=math.inf if wl is None else float(wl),
                             slack_fraction=None if lim is None else lim.slack_fraction,
                             max_excursion=None if lim is None else lim.max_excursion, strain_limit=strain,
                             rho=float(rho), theta_nominal=(float(cable.ae), float(cable.internal_damping)))


def _exogenous(scene, hp, N: int) -> np.ndarray:
    """The interval table E (N, 7 (2 substeps + 1)) of ``scene``'s top motion on ``hp``'s grid
    (:meth:`cablesys.control.payout.HeaveProblem.exogenous`); a seed's own top-motion function, since
    another seed may realise a different number of sinusoids (another structure of the model)."""
    layout = ParameterLayout.from_scene(scene)
    top = top_motion_function(scene, layout)
    return dataclasses.replace(hp, model=dataclasses.replace(hp.model, top=top),
                               p=layout.values(scene)).exogenous(hp.dt * np.arange(N))


def _selection(problem: TimeDesignProblem):
    """(base, B): p(theta) = base + B theta, the nominal parameters with AE and C_I replaced."""
    hp = problem.heave
    lay = hp.model.layout
    idx = [lay.index("cable.ae"), lay.index("cable.internal_damping")]
    base = np.array(hp.p, float)
    base[idx] = 0.0
    B = np.zeros((len(base), 2))
    B[idx[0], 0] = B[idx[1], 1] = 1.0
    return base, B


def _rest_state(problem: TimeDesignProblem, theta):
    """(x_0, static strain u_0 / l_0) of the design theta (MX): (phi, l) solving q'' = 0 at L = l_0
    (eq. 1: l_0 = l_r - T_r l_r / AE) by Newton (``rootfinder``; its derivative by the implicit-function
    theorem)."""
    hp = problem.heave
    model, lay = hp.model, hp.model.layout
    nq = model.nq
    base, B = _selection(problem)
    l_r, t_r = (float(hp.p[lay.index(f"cable.{n}")]) for n in ("length", "tension_ref"))
    qs, ts = ca.SX.sym("q", nq), ca.SX.sym("theta", 2)
    res = model.accel(qs, ca.DM.zeros(nq), ca.DM.zeros(7), ca.vertcat(l_r - t_r * l_r / ts[0], 0, 0, 0),
                      ca.DM(base) + ca.mtimes(ca.DM(B), ts), ca.DM(hp.c))
    solve = ca.rootfinder("rest_design", "newton", ca.Function("r", [qs, ts], [res]), {"abstol": 1e-10})
    L0 = l_r - t_r * l_r / theta[0]
    q0 = solve(ca.DM(hp.x_rest[:nq]), theta)
    return ca.vertcat(q0, ca.MX.zeros(nq), L0, 0), (q0[1] - L0) / L0


def _step_functions(problem: TimeDesignProblem):
    """(step, sens): one RK4 interval at zero payout, ``step(x, E_k, theta, p0, c, w) -> (x_{k+1}, y_k)``
    with y the :data:`SERIES` at the interval start, and ``sens(x, S, E_k, theta, p0, c, w) -> (x_{k+1},
    S_{k+1}, y_k, dy_k)`` with the sensitivities S = dx/dtheta (nx, 2): S_{k+1} = F_x S_k + F_theta,
    dy_k = y_x S_k + y_theta (the variational equation of the discrete map; Hairer, Norsett & Wanner,
    *Solving ODEs I*, sec. I.14), both columns as forward directional derivatives of the step. The
    scene's numbers are inputs (p0 the parameters with AE and C_I zeroed, p = p0 + B theta, B from the
    layout; c the compensator's; w of :func:`cablesys.control.kernels.interval_functions`): the functions
    depend on the model's structure only."""
    hp = problem.heave
    model = hp.model
    nq = model.nq
    _, B = _selection(problem)
    x, e, th = ca.SX.sym("x", model.nx), ca.SX.sym("E", hp.step.size1_in(2)), ca.SX.sym("theta", 2)
    p0, c, w = ca.SX.sym("p0", len(hp.p)), ca.SX.sym("c", len(hp.c)), ca.SX.sym("w", 5)
    S = ca.SX.sym("S", model.nx, 2)
    p = p0 + ca.mtimes(ca.DM(B), th)
    xn = hp.interval(x, 0.0, e, p, c, w)[0]
    y = model.outputs_e(x[:nq], x[nq:2 * nq], e[:7], ca.vertcat(x[2 * nq], x[2 * nq + 1], 0, 0), p, c)
    ys = ca.vertcat(*(y[WINCH_OUTPUTS.index(n)] for n in SERIES))
    z, seeds = ca.vertcat(x, th), ca.vertcat(S, ca.DM.eye(2))
    names = ["x", "E", "theta", "p0", "c", "w"]
    step = ca.Function("design_step", [x, e, th, p0, c, w], [xn, ys], names, ["xn", "y"])
    sens = ca.Function("design_sens", [x, S, e, th, p0, c, w],
                       [xn, ca.jtimes(xn, z, seeds), ys, ca.jtimes(ys, z, seeds)],
                       names[:1] + ["S"] + names[1:], ["xn", "Sn", "y", "dy"])
    return step, sens


def design_kernels(problem: TimeDesignProblem):
    """(step, sens, compiled): :func:`_step_functions` compiled once per model structure
    (:func:`cablesys.control.gradient.compiled_kernels`), or the SX functions in CasADi's virtual machine
    (``CABLESYS_COMPILE=0``, no compiler, a failed build)."""
    return compiled_kernels(*_step_functions(problem))


def series_functions(problem: TimeDesignProblem):
    """(series, sensitivities) of the roll-out from the design's rest state, each a function of
    theta (2) and E (7 (2 substeps + 1), N): ``series -> (Y, strain)`` with Y (len(SERIES), N) at the
    interval starts, ``sensitivities -> (Y, dY/dAE, dY/dC_I, strain, dstrain/dtheta (1, 2))``."""
    hp = problem.heave
    step, sens, _ = design_kernels(problem)
    base, _ = _selection(problem)
    nums = (ca.DM(base), ca.DM(hp.c), ca.DM([hp.heave_rest, hp.static_tension, 0.0, 0.0, hp.dt]))
    theta, E = ca.MX.sym("theta", 2), ca.MX.sym("E", problem.exogenous[0].shape[1], problem.N)
    x0, strain = _rest_state(problem, theta)
    _, Y = step.mapaccum("design_roll", problem.N, [0], [0])(x0, E, theta, *nums)
    series = ca.Function("design_series", [theta, E], [Y, strain], ["theta", "E"], ["Y", "strain"])
    S0 = ca.jacobian(x0, theta)                        # the rest state's own dependence (implicit function)
    _, _, Y2, dY = sens.mapaccum("design_roll_sens", problem.N, [0, 1], [0, 1])(x0, S0, E, theta, *nums)
    n = Y2.size1()
    dY = ca.reshape(dY, n * 2, problem.N)              # columns [dy/dAE; dy/dC_I] per step
    sensitivities = ca.Function("design_sensitivities", [theta, E],
                                [Y2, dY[:n, :], dY[n:, :], strain, ca.jacobian(strain, theta)],
                                ["theta", "E"], ["Y", "dY_ae", "dY_ci", "strain", "dstrain"])
    return series, sensitivities


def _seed_terms(problem: TimeDesignProblem, Y):
    """(variance of y_b, [(constraint, value, bound)]) of one seed's series Y (MX)."""
    k0, rho = problem.window_start, problem.rho
    W = Y[:, k0:]
    n = W.size2()
    mean = ca.sum2(W) / n
    h = W[0, :] - mean[0]
    var = ca.sum2(h ** 2) / n
    g = []
    if math.isfinite(problem.working_load):
        g.append(("peak_tension", ks_max(W[3, :] / problem.working_load, rho), 1.0))
    if problem.slack_fraction is not None:
        g.append(("slack", ks_max(-W[2, :] / mean[2], rho), -problem.slack_fraction))
    if problem.max_excursion is not None:
        dev = ca.horzcat(h, -h, W[1, :] - mean[1], mean[1] - W[1, :]) / problem.max_excursion
        g.append(("excursion", ks_max(dev, rho), 1.0))
    return var, g


@dataclasses.dataclass(frozen=True)
class DesignFunctions:
    """The NLP's functions of the normalized design z: ``fg(z) -> (f, g)`` the objective (mean heave
    variance over the seeds, m^2) and the constraints (rows ``rows``, upper bounds ``ub``), and
    ``jac(z) -> (df/dz, dg/dz)`` by the forward sensitivities (exact, no AD through the roll-out's graph)."""

    fg: ca.Function
    jac: ca.Function
    rows: tuple
    ub: np.ndarray
    theta: ca.Function
    series: ca.Function


def design_functions(problem: TimeDesignProblem) -> DesignFunctions:
    """The objective and constraints of ``problem`` as CasADi functions of z (module docstring)."""
    z = ca.MX.sym("z", 2)
    lo = np.log([problem.ae_bounds[0], problem.damping_bounds[0]])
    hi = np.log([problem.ae_bounds[1], problem.damping_bounds[1]])
    theta = ca.exp(ca.DM(lo) + z * ca.DM(hi - lo))
    dtheta_dz = theta * ca.DM(hi - lo)                  # diagonal
    series, sens = series_functions(problem)
    # post-processing of the series (cheap): (f, g) of the per-seed Y and the strain
    Ys = [ca.MX.sym(f"Y{s}", len(SERIES), problem.N) for s in problem.seeds]
    strain = ca.MX.sym("strain")
    total, rows, gs, ub = 0, [], [], []
    for s, Y in zip(problem.seeds, Ys):
        var, g = _seed_terms(problem, Y)
        total = total + var
        for name, expr, bound in g:
            rows.append(f"{name} (seed {s})")
            gs.append(expr)
            ub.append(bound)
    if problem.strain_limit is not None:
        rows.append("static_strain")
        gs.append(strain)
        ub.append(problem.strain_limit)
    fo, go = total / len(problem.seeds), ca.vertcat(*gs) if gs else ca.MX(0, 1)
    post = ca.Function("design_post", [*Ys, strain], [fo, go])
    # forward mode of the post-processing, seeded by the sensitivities of each theta direction
    dYs = [ca.MX.sym(f"dY{s}", len(SERIES), problem.N) for s in problem.seeds]
    dstrain = ca.MX.sym("dstrain")
    vars_, seeds_ = ca.vertcat(*[ca.vec(Y) for Y in Ys], strain), ca.vertcat(*[ca.vec(d) for d in dYs], dstrain)
    post_fwd = ca.Function("design_post_fwd", [*Ys, strain, *dYs, dstrain],
                           [ca.jtimes(fo, vars_, seeds_), ca.jtimes(go, vars_, seeds_)])
    outs = [series(theta, ca.DM(E.T)) for E in problem.exogenous]
    fg = ca.Function("design_fg", [z], post(*[o[0] for o in outs], outs[0][1]))
    sol = [sens(theta, ca.DM(E.T)) for E in problem.exogenous]
    Yv, st = [o[0] for o in sol], sol[0][3]
    cols_f, cols_g = [], []
    for j in range(2):
        df, dg = post_fwd(*Yv, st, *[o[1 + j] for o in sol], sol[0][4][j])
        cols_f.append(df * dtheta_dz[j])
        cols_g.append(dg * dtheta_dz[j])
    jac = ca.Function("design_jac", [z], [ca.horzcat(*cols_f), ca.horzcat(*cols_g)])
    return DesignFunctions(fg=fg, jac=jac, rows=tuple(rows), ub=np.array(ub, float),
                           theta=ca.Function("theta", [z], [theta]), series=series)


class _NLP(ca.Callback):
    """z -> (f, g) for ``nlpsol`` with the Jacobian from the forward sensitivities (:class:`DesignFunctions`)."""

    def __init__(self, fns: DesignFunctions, scale: float):
        ca.Callback.__init__(self)
        self.fns, self.scale = fns, scale
        self.construct("time_design_nlp", {"enable_fd": False})

    def get_n_in(self):
        return 1

    def get_n_out(self):
        return 2

    def get_sparsity_in(self, i):
        return ca.Sparsity.dense(2, 1)

    def get_sparsity_out(self, i):
        return ca.Sparsity.dense(1, 1) if i == 0 else ca.Sparsity.dense(len(self.fns.rows), 1)

    def eval(self, arg):
        f, g = self.fns.fg(arg[0])
        return [self.scale * f, g]

    def has_jacobian(self):
        return True

    def get_jacobian(self, name, inames, onames, opts):
        z = ca.MX.sym("z", 2)
        out = [ca.MX.sym("f"), ca.MX.sym("g", len(self.fns.rows))]
        jf, jg = self.fns.jac(z)
        return ca.Function(name, [z, *out], [self.scale * jf, jg], inames, onames, opts)


@dataclasses.dataclass(frozen=True)
class TimeDesignResult(ResultBase):
    """A time-domain design (module docstring): the optimum ``theta`` = (AE N, C_I N s), the baseline
    (the scene's values) and both responses per seed on the roll-out grid (``times`` s; ``tension_top``,
    ``tension_mid`` N, ``heave`` m from the window mean, per seed: arrays (seeds, N)); ``constraints``
    {row: (value, upper bound)} at the optimum and at the baseline; ``history`` IPOPT's per-iteration
    objective and primal infeasibility."""

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
    tension_mid: np.ndarray
    tension_mid_baseline: np.ndarray
    history: dict
    limits: dict
    status: str
    success: bool = True
    message: str = ""
    stats: dict = dataclasses.field(default_factory=dict)

    VARIABLES: ClassVar[dict] = {
        "heave": ("m", "body heave from its window mean (down +), design"),
        "heave_baseline": ("m", "body heave from its window mean, the scene's line"),
        "tension_top": ("N", "tension at the top, design"), "tension_top_baseline": ("N", "tension at the top, baseline"),
        "tension_mid": ("N", "spring force F_bc (Wang 1971 eq. 54), design"),
        "tension_mid_baseline": ("N", "spring force F_bc, baseline")}

    @property
    def heave_std_m(self) -> float:
        return math.sqrt(self.objective)

    def to_xarray(self):
        """The per-seed histories on dimensions (seed, time)."""
        import xarray as xr
        names = ("heave", "heave_baseline", "tension_top", "tension_top_baseline", "tension_mid", "tension_mid_baseline")
        ds = xr.Dataset({n: (("seed", "time"), getattr(self, n)) for n in names},
                        coords={"seed": list(self.seeds), "time": self.times})
        for n in names:
            ds[n].attrs.update(units=self.VARIABLES[n][0], long_name=self.VARIABLES[n][1])
        ds["time"].attrs.update(units="s", long_name="time")
        ds.attrs.update(ae_n=self.theta[0], internal_damping_n_s=self.theta[1])
        return ds

    def summary(self) -> dict:
        return {"success": self.success, "message": self.message, "status": self.status,
                "ae_n": self.theta[0], "internal_damping_n_s": self.theta[1],
                "baseline_ae_n": self.theta_baseline[0], "baseline_internal_damping_n_s": self.theta_baseline[1],
                "objective_heave_variance_m2": self.objective, "baseline_heave_variance_m2": self.objective_baseline,
                "heave_std_m": self.heave_std_m, "baseline_heave_std_m": math.sqrt(self.objective_baseline),
                "heave_reduction_db": 10 * math.log10(self.objective / self.objective_baseline),
                "constraints": {k: {"value": v, "bound": b} for k, (v, b) in self.constraints.items()},
                "constraints_baseline": {k: {"value": v, "bound": b} for k, (v, b) in self.constraints_baseline.items()},
                "seeds": list(self.seeds), "limits": self.limits, "stats": self.stats}


def _evaluate(problem, fns, z):
    """(objective, {row: (value, bound)}, series per seed (S, 4, N)) at z."""
    th = np.array(fns.theta(z)).ravel()
    Ys = np.array([np.array(fns.series(th, E.T)[0]) for E in problem.exogenous])
    f, g = fns.fg(z)
    g = np.array(g).ravel()
    return float(f), {r: (float(v), float(b)) for r, v, b in zip(fns.rows, g, fns.ub)}, Ys


def scan_starts(problem, fns, n_ae: int = 17, n_ci: int = 3) -> list:
    """IPOPT's starts from a scan of n_ae x n_ci log-spaced designs: the feasible design of least
    objective and the best one at least a quarter of the log-AE range away from it (the heave variance
    has a local optimum on each side of the axial resonance's passage through the sea band: a soft
    insert below it, a stiff line above). Without a feasible design: the least violations."""
    pts = [(a, b) for a in np.linspace(0.0, 1.0, n_ae) for b in np.linspace(0.1, 0.9, n_ci)]
    scored = []
    for zz in pts:
        f, g = fns.fg(zz)
        viol = float(np.max(np.maximum(np.array(g).ravel() - fns.ub, 0.0))) if fns.ub.size else 0.0
        scored.append((viol > 0, viol if viol > 0 else float(f), zz))
    scored.sort(key=lambda t: (t[0], t[1]))
    first = scored[0]
    other = next((t for t in scored[1:] if abs(t[2][0] - first[2][0]) >= 0.25 and t[0] == first[0]), None)
    return [tuple(problem.theta(t[2])) for t in (first, other) if t is not None]


@timed
def time_domain_design(problem: TimeDesignProblem, *, starts=None, max_iter: int = 50,
                       tol: float = 1e-6) -> TimeDesignResult:
    """The design of least mean heave variance meeting every constraint in every seed (module docstring).

    Parameters
    ----------
    problem : TimeDesignProblem
        From :func:`time_design_problem`.
    starts : sequence of (AE, C_I), optional
        IPOPT's starting designs (default: the two of a 17 x 3 scan,
        :func:`scan_starts`); the feasible optimum of least objective is kept.
    max_iter, tol : int, float
        IPOPT's iteration limit and tolerance per start.
    """
    fns = design_functions(problem)
    z = ca.MX.sym("z", 2)
    t0 = time.perf_counter()
    f0 = float(fns.fg(problem.z(problem.theta_nominal))[0])
    scale = 1.0 / f0 if f0 > 0 else 1.0
    cb = _NLP(fns, scale)
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
              "ae_bounds_n": list(problem.ae_bounds), "damping_bounds_n_s": list(problem.damping_bounds)}
    stats = {"iterations": sum(r["iterations"] for r in runs), "solve_s": solve_s, "starts": len(runs),
             "setup_and_scan_s": scan_s,
             "runs": [{k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in r.items() if k != "history"}
                      for r in runs], "intervals": problem.N, "dt_s": problem.dt, "seeds": list(problem.seeds)}
    return TimeDesignResult(theta=tuple(float(v) for v in problem.theta(best["z"])),
                            theta_baseline=problem.theta_nominal, objective=f_opt, objective_baseline=f_base,
                            constraints=c_opt, constraints_baseline=c_base, seeds=problem.seeds, times=times,
                            heave=centre(Y[:, 0]), heave_baseline=centre(Yb[:, 0]), tension_top=Y[:, 3],
                            tension_top_baseline=Yb[:, 3], tension_mid=Y[:, 2], tension_mid_baseline=Yb[:, 2],
                            history=best["history"], limits=limits, status=best["status"], success=success,
                            message=message, stats=stats)


def evaluate_design(problem: TimeDesignProblem, theta) -> dict:
    """The roll-out's objective and constraint values (row -> (value, bound)) at ``theta`` = (AE, C_I):
    e.g. the frequency-domain optimum seen by the nonlinear time domain."""
    fns = design_functions(problem)
    f, c, _ = _evaluate(problem, fns, problem.z(theta))
    return {"objective_heave_variance_m2": f, "constraints": c}


def resimulate_design(problem: TimeDesignProblem, theta) -> dict:
    """The design ``theta`` re-run by the plain time domain (:func:`cablesys.time_domain.simulate`, the
    scene's integrator and tolerances, output every ``numerics.output_step``) in every seed, judged over
    the same window by the sampled extremes: peak ``tension_top`` / working load, least ``tension_mid`` /
    its mean (the slack ratio), largest |y_b - mean| and |x_b - mean| / max excursion, and var(y_b).

    Returns
    -------
    dict
        per seed the values, ``max_relative_violation`` (largest (value - bound) / |bound|, 0 when all hold)
        and ``heave_variance_m2`` (mean over the seeds).
    """
    from ..time_domain import simulate
    scene = problem.designed_scene(theta)
    per_seed, worst, variances = {}, 0.0, []
    for s in problem.seeds:
        sea = dataclasses.replace(scene.top_motion.spectrum, seed=int(s))
        run = simulate(scene.replace(top_motion=dataclasses.replace(scene.top_motion, spectrum=sea)))
        if not run.success:
            per_seed[s] = {"success": False, "message": run.message}
            worst = math.inf
            continue
        m = run.time >= problem.window_start * problem.dt - 1e-9
        d = {k: np.asarray(run.data[k])[m] for k in ("tension_top", "tension_mid", "y_b", "x_b")}
        h, xb = d["y_b"] - d["y_b"].mean(), d["x_b"] - d["x_b"].mean()
        vals = {}
        if math.isfinite(problem.working_load):
            vals["peak_tension"] = (float(d["tension_top"].max() / problem.working_load), 1.0)
        if problem.slack_fraction is not None:
            vals["slack"] = (float(-d["tension_mid"].min() / d["tension_mid"].mean()), -problem.slack_fraction)
        if problem.max_excursion is not None:
            vals["excursion"] = (float(max(np.abs(h).max(), np.abs(xb).max()) / problem.max_excursion), 1.0)
        viol = max([max(v - b, 0.0) / abs(b) for v, b in vals.values()] or [0.0])
        worst = max(worst, viol)
        variances.append(float(np.mean(h ** 2)))
        per_seed[s] = {"success": True, "constraints": vals, "max_relative_violation": viol,
                       "heave_variance_m2": variances[-1], "tension_top_max_n": float(d["tension_top"].max()),
                       "tension_mid_min_n": float(d["tension_mid"].min())}
    return {"theta": [float(v) for v in theta], "per_seed": per_seed, "max_relative_violation": worst,
            "heave_variance_m2": float(np.mean(variances)) if variances else math.nan,
            "integrator": scene.numerics.integrator, "drag_segments": scene.numerics.drag_segments}
