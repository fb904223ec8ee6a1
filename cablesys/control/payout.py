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
seconds, alpha piecewise constant, exact first and second derivatives by CasADi's AD, IPOPT.
The top motion depends on time only, so it is tabulated outside the NLP: each interval's
parameters are the exogenous vector e (:data:`cablesys.model.signals.EXO_LABELS`) at the
2 ``substeps`` + 1 times its RK4 stages read (:meth:`HeaveProblem.exogenous`); the NLP's
functions and their derivatives then contain the cable and body dynamics only (the 60 sinusoids of
a JONSWAP sea, their rates and accelerations were two thirds of the right-hand side).
"""

from __future__ import annotations

import dataclasses
import math
from typing import ClassVar

import casadi as ca
import numpy as np

from ..compiled import compile_functions, compiles
from ..derivatives import state_derivatives
from ..disk_cache import digest
from ..errors import ParameterError, require_positive
from ..model.segmented_winch_control import NodeWinchModel, build_node_winch_model
from ..model.segmented_winch_control import rest_state as node_rest_state
from ..model.winch import COMPENSATOR_PARAMETERS, WINCH_OUTPUTS, WinchModel, build_winch_model, rest_state
from .. import statistics as st
from ..results import ResultBase, timed
from .limits import WinchLimits
from .shooting import PathConstraint, ShootingNLP

# rows of the stage function's path outputs g: the power, the tension the no-slack floor bounds (the model's
# ``floor_output``: Wang's F_bc "tension_mid", the node model's least element tension), the top tension
G_ROWS = ("power", "tension_floor", "tension_top")
# the control's models (heave_problem's ``model``): Wang's 2-DOF winch, the segmented node model's winch
MODELS = ("wang", "segmented")


def output_labels(model) -> tuple:
    """The rows of ``model.outputs``: :data:`WINCH_OUTPUTS` (the node model adds ``tension_least``)."""
    return getattr(model, "output_labels", WINCH_OUTPUTS)


def floor_output(model) -> str:
    """The output the no-slack floor bounds: the 2-DOF model's spring force F_bc (``tension_mid``, Wang 1971 eq.
    54), the node model's least element tension (``tension_least``)."""
    return getattr(model, "floor_output", "tension_mid")


def model_rest_state(model, p, c=None) -> np.ndarray:
    """The rest state of either control model (:func:`cablesys.model.winch.rest_state`,
    :func:`cablesys.model.segmented_winch_control.rest_state`)."""
    return (node_rest_state if isinstance(model, NodeWinchModel) else rest_state)(model, p, c)


def describe_model(model) -> str:
    """One line naming the control model."""
    if isinstance(model, NodeWinchModel):
        return model.describe()
    return "wang 2-DOF with winch (cablesys.model.winch)" + (", compensator" if model.compensator else "")


def control_model(scene, model="wang", segments: int | None = None, *, compensator: bool = False):
    """(scene, model) for a control model name: "wang" (the scene's first section as one straight element,
    ``segments`` must be None or 1) or "segmented" (N = ``segments`` elements, default the scene's
    ``cable.segments`` when above 1); the scene is returned with that N."""
    if model not in MODELS:
        raise ParameterError("model", model, f"allowed: {', '.join(MODELS)} (or a built winch model)")
    if segments is not None and not (isinstance(segments, (int, np.integer)) and segments >= 1):
        raise ParameterError("segments", segments, "must be an integer >= 1")
    n_scene = scene.sections[0].cable.segments if len(scene.sections) == 1 else None
    if model == "wang":
        if segments not in (None, 1):
            raise ParameterError("segments", segments, "Wang's 2-DOF winch is one straight element: 1 or unset")
        sc = scene if n_scene in (None, 1) else scene.replace_section(cable={"segments": 1})
        return sc, build_winch_model(sc, compensator=compensator)
    n = segments if segments is not None else n_scene
    if n is None or n < 2:
        raise ParameterError("segments", segments, "the segmented model needs N >= 2 elements (segments, or the "
                                                   "scene's cable.segments)")
    sc = scene if n == n_scene else scene.replace_section(cable={"segments": int(n)})
    return sc, build_node_winch_model(sc, compensator=compensator)


@dataclasses.dataclass(frozen=True)
class HeaveProblem:
    """A scene, its winch model and the numbers of the compensation problem (SI units)."""

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
        """(step, stage, compiled): the NLP's (x, alpha, E_k) -> x_{k+1} and -> (cost, g).

        Compiled (:func:`interval_kernels`): MX functions that call the compiled per-interval kernels with
        this problem's numbers (p, c and w = (heave at rest, T_0, c_T, c_a, dt)) as inputs, so one
        library per model structure serves every scene value, and the NLP's derivatives are the kernels'
        compiled forward, adjoint and forward-over-adjoint derivatives with respect to (x, alpha) only.
        In CasADi's virtual machine: ``step`` and ``stage`` (the numbers inlined, SX)."""
        if self.substeps > SUBSTEP_KERNELS_FROM:
            return self._substep_nlp_functions()
        kernels = interval_kernels(self.interval)
        if kernels is None or not kernels.compiled:
            return self.step, self.stage, False
        f = kernels.functions
        nx, ne = self.model.nx, self.step.size1_in(2)
        x, u, e = ca.MX.sym("x", nx), ca.MX.sym("u"), ca.MX.sym("E", ne)
        w = ca.DM([self.heave_rest, self.static_tension, self.tension_weight, self.control_weight, self.dt])
        args = (x, u, e, ca.DM(self.p), ca.DM(self.c), w)
        step = ca.Function("step", [x, u, e], [f["ocp_step"](*args)])
        stage = ca.Function("stage", [x, u, e], f["ocp_stage"](*args))
        return step, stage, True

    def _substep_nlp_functions(self):
        """:meth:`nlp_functions` from one compiled RK4 step called ``substeps`` times (:func:`substep_kernels`):
        the C of a whole interval of the node model's stiff steps is too large to compile (54 MB at N = 4 with
        11 steps), one step's is a substeps-th of it."""
        kernels = substep_kernels(self.substep, self.start)
        if kernels is None or not kernels.compiled:
            return self.step, self.stage, False
        f = kernels.functions
        nx, ne = self.model.nx, self.step.size1_in(2)
        x, u, e = ca.MX.sym("x", nx), ca.MX.sym("u"), ca.MX.sym("E", ne)
        p, c, h = ca.DM(self.p), ca.DM(self.c), self.dt / self.substeps
        w = ca.DM([self.heave_rest, self.static_tension, self.tension_weight, self.control_weight, self.dt])
        xn = x
        for i in range(self.substeps):
            xn = f["ocp_rk4"](xn, u, e[7 * 2 * i: 7 * (2 * i + 3)], p, c, h)
        step = ca.Function("step", [x, u, e], [xn])
        stage = ca.Function("stage", [x, u, e], f["ocp_start"](x, u, e[:7], p, c, w))
        return step, stage, True

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
                  compensator: dict | None = None, model="wang", segments: int | None = None) -> HeaveProblem:
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
    model : str or WinchModel or NodeWinchModel
        "wang" (Wang's 2-DOF winch, :mod:`cablesys.model.winch`), "segmented" (the node model's winch on
        ``segments`` elements, :mod:`cablesys.model.segmented_winch_control`), or a model built before for this
        scene's structure.
    segments : int, optional
        N of the segmented model (default the scene's ``cable.segments``).

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
    if isinstance(model, str):
        scene, model = control_model(scene, model, segments, compensator=compensator is not None)
    elif model is None:
        scene, model = control_model(scene, "wang", None, compensator=compensator is not None)
    p = model.parameters(scene)
    c = np.zeros(len(COMPENSATOR_PARAMETERS))
    if compensator is not None:
        unknown = set(compensator) - {"mass", "stiffness", "damping"}
        if unknown:
            raise ParameterError("compensator", sorted(unknown), "allowed keys: mass, stiffness, damping")
        require_positive("compensator.mass", compensator.get("mass", 0.0), "kg")
        c[:3] = [compensator["mass"], compensator.get("stiffness", 0.0), compensator.get("damping", 0.0)]
        plain = build_winch_model(scene)
        x_plain = rest_state(plain, p)
        t_top = dict(zip(WINCH_OUTPUTS, np.array(plain.outputs(x_plain, [0, 0], 0.0, p, c)).ravel()))["tension_top"]
        # y down: the precharge pushes the sheave up against the cable's vertical pull and its own weight
        c[3] = -t_top * math.cos(x_plain[0]) - c[0] * p[model.layout.index("environment.gravity")]
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
    step, stage, interval, substep, start = _interval_functions(model, dt, substeps, p, c, y_rest, tension_weight,
                                                                control_weight)
    return HeaveProblem(scene=scene, model=model, p=p, c=c, x_rest=x_rest, limits=limits, floor=floor,
                        working_load=wl, static_tension=T0, heave_rest=y_rest["heave"], dt=float(dt),
                        substeps=substeps, tension_weight=float(tension_weight),
                        control_weight=float(control_weight), step=step, stage=stage,
                        interval=interval, substep=substep, start=start)



def _interval_functions(model, dt, substeps, p, c, y_rest, tension_weight, control_weight):
    """(step, stage, interval, substep, start) of one control interval; step and stage are SX functions of
    (x, alpha, E_k) with the numbers inlined; substep and start those of :func:`_substep_functions`.

    ``interval(x, u, E, p, c, w) -> (x_next, cost, g)``: ``substeps`` classical RK4 steps of the
    winch ODE with alpha = u constant and the top motion read from E (:meth:`HeaveProblem.exogenous`:
    e at the 2 substeps + 1 stage times), the stage cost at the interval start and the path outputs
    (:data:`G_ROWS`); w = (heave at rest, T_0, c_T, c_a, dt).
    """
    ne = 7
    substep, start = _substep_functions(model, len(p), len(c))
    xs, uk = ca.SX.sym("x", model.nx), ca.SX.sym("u")
    Es = ca.SX.sym("E", ne * (2 * substeps + 1))
    ps, cs, ws = ca.SX.sym("p", len(p)), ca.SX.sym("c", len(c)), ca.SX.sym("w", 5)
    h = ws[4] / substeps
    x = xs
    for i in range(substeps):                       # classical RK4, the top at its stage times 2i, 2i+1, 2i+2
        x = substep(x, uk, Es[ne * 2 * i: ne * (2 * i + 3)], ps, cs, h)
    cost, g = start(xs, uk, Es[:ne], ps, cs, ws)
    interval = ca.Function("interval", [xs, uk, Es, ps, cs, ws], [x, cost, g],
                           ["x", "u", "E", "p", "c", "w"], ["xn", "cost", "g"])
    w = ca.DM([y_rest["heave"], y_rest["tension_top"], tension_weight, control_weight, dt])
    xa, ua, ra = ca.SX.sym("x", model.nx), ca.SX.sym("u"), ca.SX.sym("E", Es.numel())
    xn, cost, g = interval(xa, ua, ra, ca.DM(p), ca.DM(c), w)
    step = ca.Function("step", [xa, ua, ra], [xn])
    stage = ca.Function("stage", [xa, ua, ra], [cost, g])
    return step, stage, interval, substep, start


def _substep_functions(model, n_p: int, n_c: int):
    """(substep, start): one classical RK4 step ``(x, u, E_j, p, c, h) -> x_next`` of the winch ODE with alpha
    = u and the top at the step's 3 stage times (E_j, 21 rows), and the stage cost and path outputs at the
    interval start ``(x, u, e, p, c, w) -> (cost, g)``, as in :func:`_interval_functions`."""
    nq, ne = model.nq, 7
    x, u, E = ca.SX.sym("x", model.nx), ca.SX.sym("u"), ca.SX.sym("E", 3 * ne)
    p, c, h, w = ca.SX.sym("p", n_p), ca.SX.sym("c", n_c), ca.SX.sym("h"), ca.SX.sym("w", 5)

    def f(xx, j):
        qdd = model.accel(xx[:nq], xx[nq:2 * nq], E[ne * j: ne * (j + 1)],
                          ca.vertcat(xx[2 * nq], xx[2 * nq + 1], u, 0.0), p, c)
        return ca.vertcat(xx[nq:2 * nq], qdd, xx[2 * nq + 1], u)
    k1 = f(x, 0)
    k2 = f(x + h / 2 * k1, 1)
    k3 = f(x + h / 2 * k2, 1)
    k4 = f(x + h * k3, 2)
    names = ["x", "u", "E", "p", "c"]
    substep = ca.Function("ocp_rk4", [x, u, E, p, c, h], [x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)], names + ["h"], ["xn"])
    e0 = ca.SX.sym("e", ne)
    y = model.outputs_e(x[:nq], x[nq:2 * nq], e0, ca.vertcat(x[2 * nq], x[2 * nq + 1], u, 0.0), p, c)
    oi = output_labels(model).index
    cost = w[4] * ((y[oi("heave")] - w[0]) ** 2 + w[2] * ((y[oi("tension_top")] - w[1]) / w[1]) ** 2 + w[3] * u ** 2)
    g = ca.vertcat(*(y[oi(floor_output(model) if name == "tension_floor" else name)] for name in G_ROWS))
    start = ca.Function("ocp_start", [x, u, e0, p, c, w], [cost, g], ["x", "u", "e", "p", "c", "w"], ["cost", "g"])
    return substep, start


# more RK4 steps per interval than this: the NLP calls one compiled step kernel per step (HeaveProblem.
# _substep_nlp_functions) instead of one kernel of the whole interval, whose C grows with the steps
SUBSTEP_KERNELS_FROM = 4


def substep_kernels(substep: ca.Function, start: ca.Function):
    """The compiled ``ocp_rk4`` and ``ocp_start`` of :func:`_substep_functions`, each with its forward, adjoint
    and forward-over-adjoint derivatives with respect to (x, u), as :func:`interval_kernels`; None when nothing
    is compiled."""
    if not compiles():
        return None
    key = digest(substep.serialize() + start.serialize())
    return _KERNELS.get(key) or _compiled_kernels(
        key, state_derivatives(substep, ("x", "u")) + state_derivatives(start, ("x", "u")))


def _compiled_kernels(key, functions):
    """``functions`` compiled (:data:`KERNEL_OPTIMIZATION`) and kept under ``key`` in the KERNELS_KEPT cache."""
    kernels = compile_functions(functions, jacobians=False, optimization=KERNEL_OPTIMIZATION)
    if kernels.compiled:
        while len(_KERNELS) >= KERNELS_KEPT:
            _KERNELS.pop(next(iter(_KERNELS)))       # the oldest first (dicts keep insertion order)
        _KERNELS[key] = kernels
    return kernels


# optimization flag of the kernels (see interval_kernels)
KERNEL_OPTIMIZATION = "-O1"
# compiled kernels by the serialized interval function (its structure: the scene numbers are its inputs),
# the KERNELS_KEPT most recent (a loaded library is not checked and opened again on every MPC step)
_KERNELS: dict = {}
KERNELS_KEPT = 8


def interval_kernels(interval: ca.Function):
    """The compiled per-interval kernels of ``interval`` (:func:`_interval_functions`), a
    :class:`cablesys.compiled.Compiled` with ``ocp_step`` (x, u, E, p, c, w) -> x_{k+1} and ``ocp_stage``
    -> (cost, g), each with its forward, adjoint and forward-over-adjoint derivatives with respect to
    (x, u) (:func:`cablesys.derivatives.state_derivatives`) in the same library, where ``casadi.external``
    finds them. The NLP maps them over its intervals (``Function.map`` in :class:`.shooting.ShootingNLP`),
    so one small kernel serves every interval. None when nothing is compiled (``CABLESYS_COMPILE=0``, no
    compiler), and a ``Compiled`` with ``compiled`` False when compilation failed: the callers then keep
    the inlined SX functions."""
    if not compiles():
        return None
    key = digest(interval.serialize())
    kernels = _KERNELS.get(key)
    if kernels is None:
        x, u, e, p, c, w = (ca.SX.sym(n, interval.sparsity_in(i)) for i, n in enumerate(interval.name_in()))
        xn, cost, g = interval(x, u, e, p, c, w)
        names = ["x", "u", "E", "p", "c", "w"]
        step = ca.Function("ocp_step", [x, u, e, p, c, w], [xn], names, ["xn"])
        stage = ca.Function("ocp_stage", [x, u, e, p, c, w], [cost, g], names, ["cost", "g"])
        functions = state_derivatives(step, ("x", "u")) + state_derivatives(stage, ("x", "u"))
        # -O1: Hessians as fast as at -O2 for a fraction of its compile; -O0 compiles sooner with slower Hessians
        kernels = _compiled_kernels(key, functions)
    return kernels


@dataclasses.dataclass(frozen=True)
class PayoutResult(ResultBase):
    """An open-loop optimal payout (or any payout evaluated on the problem's grid) and its response.

    ``times`` (N+1,) s; ``states`` (N+1, nx) with labels ``state_labels``; ``acceleration`` (N,)
    m/s^2, the control alpha on each interval; ``outputs`` (N+1, n_out) with labels
    ``output_labels`` (:data:`cablesys.model.winch.WINCH_OUTPUTS`) and the same for the run
    without compensation (``uncompensated``, alpha = 0). ``status`` is IPOPT's return status,
    ``violated`` the constraint that could not be met ("" when all hold), ``violations`` the
    largest violation of each, relative to its scale (the static tension for forces). ``tension_min_n`` is the
    least of the tension the no-slack floor bounds (:attr:`HeaveProblem.floor_output`: Wang's F_bc, the node
    model's least element tension), ``tension_max_n`` the largest top tension.
    """

    times: np.ndarray
    states: np.ndarray
    acceleration: np.ndarray
    outputs: np.ndarray
    uncompensated: np.ndarray
    state_labels: tuple
    output_labels: tuple
    status: str
    violated: str
    violations: dict
    objective: float
    heave_rms_m: float
    uncompensated_heave_rms_m: float
    heave_reduction_db: float
    tension_max_n: float
    tension_min_n: float
    speed_max_m_s: float
    power_max_w: float
    success: bool = True
    message: str = ""
    stats: dict = dataclasses.field(default_factory=dict)

    VARIABLES: ClassVar[dict] = {
        "heave": ("m", "body heave from rest, earth-fixed (down +)"),
        "heave_uncompensated": ("m", "body heave from rest without compensation"),
        "tension_top": ("N", "cable tension at the sheave"),
        "tension_top_uncompensated": ("N", "cable tension at the sheave without compensation"),
        "tension_mid": ("N", "tension at mid-length: the spring force F_bc of the cable (Wang 1971 eq. 54)"),
        "length": ("m", "unstretched length in the water"), "speed": ("m/s", "payout rate w"),
        "acceleration": ("m/s^2", "payout acceleration (the control)"), "power": ("W", "winch power T_top w")}

    def output(self, name: str, compensated: bool = True) -> np.ndarray:
        """One output's time series (``heave`` is taken from rest)."""
        Y = self.outputs if compensated else self.uncompensated
        y = Y[:, self.output_labels.index(name)]
        return y - Y[0, self.output_labels.index(name)] if name == "heave" else y

    def to_xarray(self):
        """The trajectories on dimension ``time`` (the control on the interval starts)."""
        import xarray as xr
        data = {name: ("time", self.output(name)) for name in ("heave", "tension_mid", "tension_top", "length",
                                                               "speed", "power")}
        data["heave_uncompensated"] = ("time", self.output("heave", False))
        data["tension_top_uncompensated"] = ("time", self.output("tension_top", False))
        data["acceleration"] = ("time", np.append(self.acceleration, np.nan))
        return xr.Dataset(data, coords={"time": self.times})


def statistics_window(times: np.ndarray, start: float | None, top_motion=None) -> np.ndarray:
    """Mask of the samples in the statistics window: from ``start`` (s), by default the window of every run's
    summary (:func:`cablesys.statistics.window` with the top motion's forcing period and smooth start)."""
    if start is None:
        period = None if top_motion is None else top_motion.window_period_s
        ramp = 0.0 if top_motion is None else top_motion.effective_ramp_s
        start = st.window(times, period, ramp)[0]
    return times >= start


def heave_reduction_db(heave, reference, mask) -> float:
    """20 log10(rms(heave) / rms(reference)) over ``mask`` (dB; negative: reduced)."""
    a, b = np.sqrt(np.mean(np.square(heave[mask]))), np.sqrt(np.mean(np.square(reference[mask])))
    return float(20 * np.log10(max(a, 1e-300) / b)) if b > 0 else float("nan")


def payout_result(problem: HeaveProblem, X, U, *, status: str, violated: str = "", violations=None,
                  objective: float = float("nan"), success: bool = True, message: str = "",
                  stats=None, stats_start: float | None = None) -> PayoutResult:
    """A :class:`PayoutResult` of node states ``X`` and controls ``U`` on the problem's grid."""
    N = len(U)
    t = problem.dt * np.arange(N + 1)
    Uext = np.append(np.ravel(U), 0.0)
    Y = problem.outputs(X, Uext, t)
    X0 = problem.rollout(problem.x_rest, np.zeros(N))
    Y0 = problem.outputs(X0, np.zeros(N + 1), t)
    mask = statistics_window(t, stats_start, problem.scene.top_motion)
    oi = problem.output_labels.index
    h, h0 = Y[:, oi("heave")] - problem.heave_rest, Y0[:, oi("heave")] - problem.heave_rest
    return PayoutResult(times=t, states=np.asarray(X), acceleration=np.ravel(U), outputs=Y, uncompensated=Y0,
                        state_labels=problem.model.state_labels, output_labels=problem.output_labels, status=status,
                        violated=violated, violations=dict(violations or {}), objective=float(objective),
                        heave_rms_m=float(np.sqrt(np.mean(h[mask] ** 2))),
                        uncompensated_heave_rms_m=float(np.sqrt(np.mean(h0[mask] ** 2))),
                        heave_reduction_db=heave_reduction_db(h, h0, mask),
                        tension_max_n=float(np.max(Y[:, oi("tension_top")])),
                        tension_min_n=float(np.min(Y[:, oi(problem.floor_output)])),
                        speed_max_m_s=float(np.max(np.abs(Y[:, oi("speed")]))),
                        power_max_w=float(np.max(np.abs(Y[:, oi("power")]))),
                        success=success, message=message, stats=dict(stats or {}))


def payout_nlp(problem: HeaveProblem, N: int, *, max_iter: int = 300, tol: float = 1e-8,
               expand: bool = False, warm_duals: bool = False, constrain_first: bool = True) -> ShootingNLP:
    """The multiple-shooting NLP of ``problem`` over N intervals (start state and the tabulated top motion, :meth:`HeaveProblem.exogenous`, are its
    parameters: :meth:`.shooting.ShootingNLP.solve` takes them), with the last node's heave
    in the cost (the stage cost at alpha = 0). ``expand``: IPOPT on the SX expansion of the NLP, for the
    virtual machine's inlined functions only (compiled kernels, :meth:`HeaveProblem.nlp_functions`, are
    external code, faster than any expansion, and are kept as they are)."""
    ub, xb = problem.bounds()
    xN, EN = ca.SX.sym("x", problem.model.nx), ca.SX.sym("E", problem.step.size1_in(2))
    terminal = ca.Function("terminal", [xN, EN], [problem.stage(xN, 0.0, EN)[0]])   # the last node's cost
    step, stage, compiled = problem.nlp_functions()
    return ShootingNLP(step, stage, N, constraints=problem.constraints(), u_bounds=ub,
                       x_bounds=xb, terminal=terminal, x_ref=problem.x_rest, x_scale=problem.scales(),
                       ipopt={"max_iter": max_iter, "tol": tol}, expand=expand and not compiled,
                       warm_duals=warm_duals, constrain_first=constrain_first)


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
                   max_iter: int = 300, tol: float = 1e-8, stats_start: float | None = None) -> PayoutResult:
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
    sol = payout_nlp(problem, N, max_iter=max_iter, tol=tol).solve(problem.x_rest,
                                                                   problem.exogenous(problem.dt * np.arange(N + 1)), guess)
    return payout_result(problem, sol.X, sol.U, status=sol.status, violated=sol.worst, violations=sol.violations,
                         objective=sol.objective, success=sol.success, message=solution_message(sol),
                         stats={"iterations": sol.iterations, "solve_s": sol.solve_s, "intervals": N,
                                "ipopt_timing_s": sol.timing},
                         stats_start=stats_start)


# the Gauss-Newton linearization kernels by the serialized kernel (structure only; see gauss_newton_kernel)
_GN_KERNELS: dict = {}


def gauss_newton_function(problem: HeaveProblem) -> ca.Function:
    """The interval's linearization for a Gauss-Newton method, an SX function of (x, u, E, p, c, w):

    ``(xn, A, B, r, Rx, Ru, g, Gx, Gu)`` with xn the interval's end state (the RK4 steps of
    :func:`_interval_functions`), A = dxn/dx, B = dxn/du; r the stage cost's residuals at the interval start,
    cost = r^T r with r = sqrt(dt) (y_b - y_b0, sqrt(c_T) (T_top - T_0) / T_0, sqrt(c_a) alpha) (the
    objective of the module docstring is a sum of squares), Rx, Ru their Jacobians; g the path outputs
    (:data:`G_ROWS`) and Gx, Gu theirs. w = (heave at rest, T_0, c_T, c_a, dt) as for ``interval``. The
    Gauss-Newton Hessian of the objective is J_r^T J_r (Bock 1983, "Recent advances in parameter
    identification techniques for ODE", in Numerical Treatment of Inverse Problems, Birkhaeuser, p. 95-121):
    no second derivatives of the dynamics."""
    model, interval = problem.model, problem.interval
    x, u, e, p, c, w = (ca.SX.sym(n, interval.sparsity_in(i)) for i, n in enumerate(interval.name_in()))
    xn, _, g = interval(x, u, e, p, c, w)
    nq = model.nq
    y = model.outputs_e(x[:nq], x[nq:2 * nq], e[:7], ca.vertcat(x[2 * nq], x[2 * nq + 1], u, 0.0), p, c)
    oi = WINCH_OUTPUTS.index
    r = ca.sqrt(w[4]) * ca.vertcat(y[oi("heave")] - w[0], ca.sqrt(w[2]) * (y[oi("tension_top")] - w[1]) / w[1],
                                   ca.sqrt(w[3]) * u)
    jac = lambda f, v: ca.jacobian(f, v)
    return ca.Function("gn_interval", [x, u, e, p, c, w],
                       [xn, jac(xn, x), jac(xn, u), r, jac(r, x), jac(r, u), g, jac(g, x), jac(g, u)],
                       ["x", "u", "E", "p", "c", "w"], ["xn", "A", "B", "r", "Rx", "Ru", "g", "Gx", "Gu"])


def gauss_newton_kernel(problem: HeaveProblem) -> ca.Function:
    """:func:`gauss_newton_function` compiled (one library per model structure: the scene's numbers are its
    inputs p, c, w; the cache is keyed by the function's serialization), or the SX function itself in
    CasADi's virtual machine (``CABLESYS_COMPILE=0``, no compiler, a failed build)."""
    f = gauss_newton_function(problem)
    if not compiles():
        return f
    key = digest(f.serialize())
    kernel = _GN_KERNELS.get(key)
    if kernel is None:
        built = compile_functions([f], jacobians=False, optimization=KERNEL_OPTIMIZATION)
        kernel = built.functions["gn_interval"]
        if built.compiled:
            while len(_GN_KERNELS) >= KERNELS_KEPT:
                _GN_KERNELS.pop(next(iter(_GN_KERNELS)))
            _GN_KERNELS[key] = kernel
    return kernel
