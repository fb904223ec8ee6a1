"""Optimal heave compensation by the winch: the open-loop optimal payout for a known top motion.

The problem (on a winch model with the unstretched length L driven by the payout rate w, w' = alpha the
control: Wang's 2-DOF cable, :mod:`cablesys.model.winch`, or the segmented node model's winch,
:mod:`cablesys.model.segmented_winch_control`, whose no-slack floor bounds the least element tension in place
of the 2-DOF model's F_bc):

    minimize   int_0^T [ (y_b - y_b0)^2 + c_T ((T_top - T_0) / T_0)^2 + c_a alpha^2 ] dt
    subject to |w| <= w_max, |alpha| <= a_max, |T_top w| <= P_max,
               F_bc >= T_floor (no slack, Wang 1971 eq. 54), T_top <= working load,

from the rest state, with the scene's top motion (sinusoids or a realised JONSWAP sea, which
the model composes in). y_b is the body's depth below the top's mean depth, earth-fixed: its
deviation from rest is the body heave relative to the seabed. Transcription: direct multiple
shooting (:mod:`.shooting`) with ``substeps`` RK4 steps per control interval of ``dt``
seconds, alpha piecewise constant, exact first derivatives by CasADi's AD, IPOPT with the objective's
Gauss-Newton matrix for the Hessian of the Lagrangian (the stage cost is a sum of squares, :func:`payout_nlp`)
or the exact second derivatives.
The top motion depends on time only, so it is tabulated outside the NLP: each interval's
parameters are the exogenous vector e (:data:`cablesys.model.signals.EXO_LABELS`) at the
2 ``substeps`` + 1 times its RK4 stages read (:meth:`HeaveProblem.exogenous`); the NLP's
functions and their derivatives then contain the cable and body dynamics only (the 60 sinusoids of
a JONSWAP sea, their rates and accelerations were two thirds of the right-hand side). The per-interval
functions and their compiled kernels are in :mod:`.kernels`, the result of a payout in :mod:`.payout_result`.
"""

from __future__ import annotations

import dataclasses
import math

import casadi as ca
import numpy as np

from ..errors import ParameterError, require_positive
from ..model.segmented_winch_control import NodeWinchModel, build_node_winch_model
from ..model.segmented_winch_control import rest_state as node_rest_state
from ..model.winch import COMPENSATOR_PARAMETERS, WinchModel, build_winch_model, rest_state
from ..results import timed
from .kernels import (G_ROWS, SUBSTEP_KERNELS_FROM, floor_output, gauss_newton_function, gauss_newton_kernel,
                      interval_functions, interval_kernels, nlp_functions, output_labels, residual_function,
                      substep_kernels)
from .limits import WinchLimits
from .model_choice import MODELS, ModelChoice, resolve_model
from .payout_result import PayoutResult, heave_reduction_db, payout_result, statistics_window
from .shooting import PathConstraint, ShootingNLP

# names of the problem's pieces that live in .kernels and .payout_result, importable from here too
__all__ = ["G_ROWS", "MODELS", "SUBSTEP_KERNELS_FROM", "HeaveProblem", "ModelChoice", "PayoutResult", "check_window",
           "control_model", "describe_model", "fastest_mode", "floor_output", "gauss_newton_function", "gauss_newton_kernel",
           "heave_problem", "heave_reduction_db", "interval_kernels", "model_rest_state", "optimal_payout",
           "output_labels", "payout_nlp", "payout_result", "solution_message", "statistics_window",
           "substep_kernels"]

def model_rest_state(model, p, c=None) -> np.ndarray:
    """The rest state of either control model (:func:`cablesys.model.winch.rest_state`,
    :func:`cablesys.model.segmented_winch_control.rest_state`)."""
    return (node_rest_state if isinstance(model, NodeWinchModel) else rest_state)(model, p, c)


def precharge(model, scene, p, c) -> float:
    """The compensator's precharge F_pre (N, down +) that holds the static load at zero stroke: the sheave's
    acceleration s'' is affine in F_pre (the piston's equation, :mod:`cablesys.model.winch`,
    :mod:`cablesys.model.segmented_winch_control`), so F_pre is the root of s'' at the plain model's rest state with
    s = 0 (the cable's vertical pull on the sheave, with the sign that holds it up), from two evaluations."""
    plain = (build_node_winch_model if isinstance(model, NodeWinchModel) else build_winch_model)(scene)
    x = model_rest_state(plain, p)
    nq = plain.nq
    q, qd = np.append(x[:nq], 0.0), np.zeros(nq + 1)
    s_dd = lambda f: float(np.array(model.accel(q, qd, np.zeros(7), [x[-2], 0.0, 0.0, 0.0], p,
                                                np.r_[c[:3], f])).ravel()[-1])
    a0, a1 = s_dd(0.0), s_dd(1.0)
    return -a0 / (a1 - a0)


def describe_model(model) -> str:
    """One line naming the control model."""
    if isinstance(model, NodeWinchModel):
        return model.describe()
    return "wang 2-DOF with winch (cablesys.model.winch)" + (", compensator" if model.compensator else "")


def control_model(scene, model, segments: int | None = None, *, compensator: bool = False):
    """(scene, model) for a control model name: "wang" (the scene's one section as one straight element,
    ``segments`` must be None or 1) or "segmented" (N = ``segments`` elements per section, default the scene's
    ``cable.segments`` when above 1; a chain of sections runs this model only, from N = 1 per section, the winch
    paying out its first section, :mod:`cablesys.model.segmented_winch_control`); the scene is returned with that N. Which name a scene
    runs by default: :func:`.model_choice.resolve_model`."""
    if model not in MODELS:
        raise ParameterError("model", model, f"allowed: {', '.join(MODELS)} (or a built winch model)")
    if segments is not None and not (isinstance(segments, (int, np.integer)) and segments >= 1):
        raise ParameterError("segments", segments, "must be an integer >= 1")
    chain = len(scene.sections) > 1
    n_scene = max(s.cable.segments for s in scene.sections)
    if model == "wang":
        if chain:
            raise ParameterError("model", model, f"Wang's 2-DOF winch has one section; this scene is a chain of "
                                                 f"{len(scene.sections)}: ask for 'segmented' (the node model)")
        if segments not in (None, 1):
            raise ParameterError("segments", segments, "Wang's 2-DOF winch is one straight element: 1 or unset")
        sc = scene if n_scene == 1 else scene.replace_section(cable={"segments": 1})
        return sc, build_winch_model(sc, compensator=compensator)
    n = segments if segments is not None else (n_scene if n_scene > 1 or chain else None)
    if n is None or n < (1 if chain else 2):
        raise ParameterError("segments", segments, "the segmented model needs N >= 2 elements (segments, or the "
                                                   "scene's cable.segments; a chain: N >= 1 per section)")
    sc = scene
    for i, sec in enumerate(scene.sections):
        if sec.cable.segments != n:
            sc = sc.replace_section(i, cable={"segments": int(n)})
    return sc, build_node_winch_model(sc, compensator=compensator)


@dataclasses.dataclass(frozen=True)
class HeaveProblem:
    """A scene, its winch model and the numbers of the compensation problem (SI units); ``model_choice`` says which
    model it is and why (:class:`.model_choice.ModelChoice`: the ladder's choice for the scene by default)."""

    scene: object
    model: WinchModel
    p: np.ndarray
    c: np.ndarray                     # compensator parameters (COMPENSATOR_PARAMETERS)
    x_rest: np.ndarray
    limits: WinchLimits
    floor: float                      # least F_bc (N)
    working_load: float               # largest top tension (N)
    static_tension: float             # T_top at rest (N)
    heave_rest: float                 # y_b at rest (m)
    dt: float
    substeps: int
    tension_weight: float
    control_weight: float
    step: ca.Function = dataclasses.field(repr=False)     # (x, alpha, E_k) -> x_{k+1}
    stage: ca.Function = dataclasses.field(repr=False)    # (x, alpha, E_k) -> (cost, g)
    # (x, alpha, E_k, p, c, w) -> (x_{k+1}, cost, g) with the parameters symbolic (sensitivities);
    # E_k = exogenous(t_k), the top motion at the interval's RK4 stage times
    interval: ca.Function = dataclasses.field(repr=False, default=None)
    # (x, alpha, E_j, p, c, h) -> x after one RK4 step of h s, E_j = e at the step's 3 stage times; and
    # (x, alpha, e, p, c, w) -> (cost, g) at the interval start: the kernels of a model with many substeps
    substep: ca.Function = dataclasses.field(repr=False, default=None)
    start: ca.Function = dataclasses.field(repr=False, default=None)
    model_choice: ModelChoice | None = None

    @property
    def model_reason(self) -> str:
        """Why this model runs (:attr:`model_choice`'s reason)."""
        return "" if self.model_choice is None else self.model_choice.reason

    def describe(self) -> str:
        """One line naming the problem's winch model (:func:`describe_model`)."""
        return describe_model(self.model)

    @property
    def record_s(self) -> float:
        """Length of the known top-motion record (s): a sampled series' end, else the scene's duration."""
        series = self.scene.top_motion.series
        return float(series.times[-1]) if series is not None else float(self.scene.numerics.duration)

    @property
    def output_labels(self) -> tuple:
        """The rows of :meth:`outputs` (:func:`output_labels`)."""
        return output_labels(self.model)

    @property
    def floor_output(self) -> str:
        """The output the no-slack floor bounds (:func:`floor_output`)."""
        return floor_output(self.model)

    def outputs(self, X: np.ndarray, U: np.ndarray, t: np.ndarray) -> np.ndarray:
        """Winch-model outputs (:attr:`output_labels`) at states X (n, nx), controls U (n,), times t."""
        v = np.vstack([np.ravel(U), np.zeros(len(t))])
        f = self.model.outputs.map(len(t))
        return np.array(f(X.T, v, np.asarray(t, float)[None, :], self.p, self.c)).T

    def exogenous(self, t_start) -> np.ndarray:
        """The interval parameters E_k (n, 7 (2 substeps + 1)) of intervals starting at ``t_start`` (n,) s:
        the top's exogenous vector (t, x_s, y_s, x_s', y_s', x_s'', y_s'') at t_k + j h / 2,
        j = 0 .. 2 substeps, h = dt / substeps (the RK4 stage times; j = 0 is also the stage cost's)."""
        t_start = np.ravel(np.asarray(t_start, float))
        m = 2 * self.substeps + 1
        times = (t_start[:, None] + (self.dt / (m - 1)) * np.arange(m)[None, :]).ravel()
        e = np.array(self.model.top.map(len(times))(times[None, :], self.p))      # (7, n m)
        return e.T.reshape(len(t_start), -1)

    def rollout(self, x0, U: np.ndarray, t0: float = 0.0) -> np.ndarray:
        """Node states (N+1, nx) of the transcription's RK4 steps under the controls ``U`` (N,)."""
        N = len(U)
        f = self.step.mapaccum(N)
        X = np.array(f(np.asarray(x0, float), np.ravel(U)[None, :], self.exogenous(t0 + self.dt * np.arange(N)).T)).T
        return np.vstack([x0, X])

    def constraints(self) -> list[PathConstraint]:
        """The path constraints: power, no slack, working load (rows of ``stage``'s g)."""
        lim = self.limits
        return [PathConstraint("winch power", (0,), -lim.power, lim.power, max(self.static_tension, 1.0)),
                PathConstraint("tension floor (no slack)", (1,), self.floor, math.inf, self.static_tension),
                PathConstraint("working load", (2,), -math.inf, self.working_load, self.static_tension)]

    def bounds(self):
        """(u_bounds, x_bounds): |alpha| <= a_max; |w| <= w_max on the state w."""
        n = self.model.nx
        lo, hi = np.full(n, -np.inf), np.full(n, np.inf)
        lo[-1], hi[-1] = -self.limits.speed, self.limits.speed
        a = self.limits.acceleration
        return ([-a], [a]), (lo, hi)

    def nlp_functions(self):
        """(step, stage, compiled): the NLP's (x, alpha, E_k) -> x_{k+1} and -> (cost, g), calling the compiled
        kernels with this problem's numbers, or ``step`` and ``stage`` in CasADi's virtual machine
        (:func:`.kernels.nlp_functions`)."""
        return nlp_functions(self)

    def scales(self):
        """State scales for IPOPT: Wang's phi and its rate 0.05, lengths and speeds 1 (the node model's positions,
        rates, L and w: 1)."""
        nq = self.model.nq
        q = np.ones(nq) if isinstance(self.model, NodeWinchModel) else np.array([0.05] + [1.0] * (nq - 1))
        return np.concatenate([q, q, [1.0, 1.0]])


# |h lambda| of classical RK4 steps: the stability region's boundary crosses the imaginary axis at 2.83 and the
# real axis at -2.79 (Hairer & Wanner, Solving ODEs II, sec. IV.2, Fig. 2.1); the chosen steps keep the stiffest
# mode of the linearization at rest within RK4_STEP_LAMBDA, an explicit count past RK4_STABILITY is refused
RK4_STEP_LAMBDA = 2.4
RK4_STABILITY = 2.78


def fastest_mode(model, x_rest, p, c) -> float:
    """max |lambda| (1/s) of the model's Jacobian d x'/d x at rest (alpha = 0): its stiffest mode, the axial
    waves of the node model's elements (omega ~ 2 N sqrt(AE / m) / L), the spring of Wang's 2-DOF model."""
    x = ca.SX.sym("x", model.nx)
    J = ca.Function("J", [x], [ca.jacobian(model.ode(x, ca.DM.zeros(2), 0.0, p, c), x)])
    return float(np.max(np.abs(np.linalg.eigvals(np.array(J(x_rest))))))

def heave_problem(scene, limits: WinchLimits | None = None, *, dt: float = 0.25, substeps: int | None = None,
                  tension_weight: float = 0.0, control_weight: float = 1e-3,
                  compensator: dict | None = None, model="auto", segments: int | None = None) -> HeaveProblem:
    """Set up the heave-compensation problem of ``scene`` (module docstring).

    Parameters
    ----------
    scene : Scene
        A one-section scene (its top motion is the known record).
    limits : WinchLimits, optional
        Winch and tension limits (default: unbounded winch, the scene's tension band).
    dt : float
        Control interval (s): alpha is constant on each.
    substeps : int, optional
        RK4 steps per interval; default the least n >= 2 with (dt / n) max |lambda| <= 2.4 (:func:`fastest_mode`:
        the node model's stiff axial modes need many); a count past RK4's stability limit is refused.
    tension_weight : float
        c_T, weight of the relative tension fluctuation (m^2 per unit of ((T - T_0)/T_0)^2).
    control_weight : float
        c_a, weight of alpha^2 (m^2 s^4 / m^2): keeps the optimum unique and smooth.
    compensator : dict, optional
        ``mass``, ``stiffness``, ``damping`` of a passive compensator under the sheave (the
        precharge is set to hold the static load at zero stroke).
    model : str or ModelChoice or WinchModel or NodeWinchModel
        "auto" (default): the winch form of the ladder's a priori choice for the scene (the model ``cablesys
        run`` starts from, before the checks that may grow its N: :func:`.model_choice.resolve_model`; on the packaged ROV lift the node model at N = 4); "wang" (Wang's
        2-DOF winch, :mod:`cablesys.model.winch`), "segmented" (the node model's winch on ``segments`` elements,
        :mod:`cablesys.model.segmented_winch_control`), a resolved :class:`.model_choice.ModelChoice`, or a model
        built before for this scene's structure. :attr:`HeaveProblem.model_choice` says which ran and why.
    segments : int, optional
        N of the segmented model (default the scene's ``cable.segments``; with "auto" in place of the ladder's N).

    Returns
    -------
    HeaveProblem
    """
    limits = WinchLimits() if limits is None else limits
    require_positive("dt", dt, "s")
    if substeps is not None and not (isinstance(substeps, int) and substeps >= 1):
        raise ParameterError("substeps", substeps, "must be an integer >= 1")
    for name, v in (("tension_weight", tension_weight), ("control_weight", control_weight)):
        if not (v >= 0 and math.isfinite(v)):
            raise ParameterError(name, v, "must be a finite number >= 0")
    if compensator is not None:
        unknown = set(compensator) - {"mass", "stiffness", "damping"}
        if unknown:
            raise ParameterError("compensator", sorted(unknown), "allowed keys: mass, stiffness, damping")
        require_positive("compensator.mass", compensator.get("mass", 0.0), "kg")
    if model is None or isinstance(model, (str, ModelChoice)):
        choice = resolve_model(scene, "auto" if model is None else model, segments)
        scene, model = control_model(scene, choice.model, choice.segments, compensator=compensator is not None)
    else:
        node = isinstance(model, NodeWinchModel)
        choice = ModelChoice(model="segmented" if node else "wang", segments=model.segments if node else None,
                             reason="the caller's built model, as built")
    p = model.parameters(scene)
    c = np.zeros(len(COMPENSATOR_PARAMETERS))
    if compensator is not None:
        c[:3] = [compensator["mass"], compensator.get("stiffness", 0.0), compensator.get("damping", 0.0)]
        c[3] = precharge(model, scene, p, c)
    x_rest = model_rest_state(model, p, c)
    y_rest = dict(zip(output_labels(model), np.array(model.outputs(x_rest, [0, 0], 0.0, p, c)).ravel()))
    lam = fastest_mode(model, x_rest, p, c)
    if substeps is None:
        substeps = max(2, math.ceil(dt * lam / RK4_STEP_LAMBDA))
    elif dt / substeps * lam > RK4_STABILITY:
        raise ParameterError("substeps", substeps, f"RK4 steps of {dt / substeps:.3g} s are unstable for the model's "
                                                   f"fastest mode |lambda| = {lam:.4g} 1/s: at least "
                                                   f"{math.ceil(dt * lam / RK4_STABILITY)}")
    floor, wl = limits.band(scene, y_rest["tension_top"])
    T0 = y_rest["tension_top"]
    step, stage, interval, substep, start = interval_functions(model, dt, substeps, p, c, y_rest, tension_weight,
                                                               control_weight)
    return HeaveProblem(scene=scene, model=model, p=p, c=c, x_rest=x_rest, limits=limits, floor=floor,
                        working_load=wl, static_tension=T0, heave_rest=y_rest["heave"], dt=float(dt),
                        substeps=substeps, tension_weight=float(tension_weight),
                        control_weight=float(control_weight), step=step, stage=stage,
                        interval=interval, substep=substep, start=start, model_choice=choice)



def payout_nlp(problem: HeaveProblem, N: int, *, max_iter: int = 300, tol: float = 1e-8,
               expand: bool = False, warm_duals: bool = False, constrain_first: bool = True,
               hessian: str = "exact") -> ShootingNLP:
    """The multiple-shooting NLP of ``problem`` over N intervals (start state and the tabulated top motion, :meth:`HeaveProblem.exogenous`, are its
    parameters: :meth:`.shooting.ShootingNLP.solve` takes them), with the last node's heave
    in the cost (the stage cost at alpha = 0). ``expand``: IPOPT on the SX expansion of the NLP, for the
    virtual machine's inlined functions only (compiled kernels, :meth:`HeaveProblem.nlp_functions`, are
    external code, faster than any expansion, and are kept as they are). ``hessian``: "exact" (AD, the
    kernels' forward-over-adjoint derivatives through every RK4 step) or "gauss-newton" (2 J^T J of the stage
    residuals, :func:`.kernels.residual_function`: no second derivatives of the dynamics; the same NLP)."""
    ub, xb = problem.bounds()
    xN, EN = ca.SX.sym("x", problem.model.nx), ca.SX.sym("E", problem.step.size1_in(2))
    terminal = ca.Function("terminal", [xN, EN], [problem.stage(xN, 0.0, EN)[0]])   # the last node's cost
    residual = residual_function(problem)
    terminal_residual = ca.Function("terminal_residual", [xN, EN], [residual(xN, 0.0, EN)])
    step, stage, compiled = problem.nlp_functions()
    return ShootingNLP(step, stage, N, constraints=problem.constraints(), u_bounds=ub,
                       x_bounds=xb, terminal=terminal, x_ref=problem.x_rest, x_scale=problem.scales(),
                       ipopt={"max_iter": max_iter, "tol": tol}, expand=expand and not compiled,
                       warm_duals=warm_duals, constrain_first=constrain_first, residual=residual,
                       terminal_residual=terminal_residual, hessian=hessian)


def check_window(problem: HeaveProblem, t0: float, horizon: float) -> int:
    """Number of intervals of [t0, t0 + horizon]; a window beyond the record or under 2 intervals is refused."""
    require_positive("horizon", horizon, "s")
    if t0 + horizon > problem.record_s + 1e-9:
        raise ParameterError("horizon", horizon, f"must end within the top-motion record, {problem.record_s:g} s "
                                                 f"(numerics.duration or the series' end), starting at {t0:g} s")
    N = int(round(horizon / problem.dt))
    if N < 2:
        raise ParameterError("horizon", horizon, f"must span at least 2 control intervals of {problem.dt:g} s")
    return N


def solution_message(sol) -> str:
    """'' on success; else which constraint could not be met, or why IPOPT stopped."""
    if sol.success:
        return ""
    if sol.worst:
        return (f"infeasible: '{sol.worst}' cannot be met within the winch limits (needs "
                f"{sol.violations[sol.worst]:.3g} of its scale more; IPOPT: {sol.status})")
    return f"IPOPT stopped with {sol.status}; try more iterations (max_iter) or a warm start"


@timed
def optimal_payout(problem: HeaveProblem, horizon: float, *, warm_start: PayoutResult | None = None,
                   max_iter: int = 300, tol: float = 1e-8, stats_start: float | None = None,
                   hessian: str = "gauss-newton") -> PayoutResult:
    """The open-loop optimal payout over [0, horizon] for the problem's known top motion.

    Parameters
    ----------
    problem : HeaveProblem
        From :func:`heave_problem`.
    horizon : float
        Length of the optimized record (s); at most the record (:attr:`HeaveProblem.record_s`).
    warm_start : PayoutResult, optional
        A previous optimum (same dt; truncated, or repeated to length) as IPOPT's start.
    max_iter, tol : int, float
        IPOPT's iteration limit and tolerance.
    stats_start : float, optional
        Start of the window of the heave statistics (s; default the window of every run's summary, :func:`cablesys.statistics.window`).
    hessian : str
        IPOPT's Hessian of the Lagrangian: "gauss-newton" (default: the objective's, no second derivatives of the
        dynamics, :func:`payout_nlp`) or "exact" (AD through every RK4 step): the same NLP and optimum.

    Returns
    -------
    PayoutResult
        ``success`` False with ``violated`` naming the constraint when IPOPT finds no feasible
        point (the phase-one problem of :func:`.shooting.solve_shooting` names it), or when it
        stops early (``status``); the trajectory computed is kept either way.
    """
    N = check_window(problem, 0.0, horizon)
    U = np.zeros(N) if warm_start is None else np.resize(warm_start.acceleration, N)
    guess = (problem.rollout(problem.x_rest, U), U[:, None])
    sol = payout_nlp(problem, N, max_iter=max_iter, tol=tol, hessian=hessian).solve(problem.x_rest,
                                                                   problem.exogenous(problem.dt * np.arange(N + 1)), guess)
    return payout_result(problem, sol.X, sol.U, status=sol.status, violated=sol.worst, violations=sol.violations,
                         objective=sol.objective, success=sol.success, message=solution_message(sol),
                         stats={"iterations": sol.iterations, "solve_s": sol.solve_s, "intervals": N,
                                "ipopt_timing_s": sol.timing, "hessian": hessian},
                         stats_start=stats_start)

