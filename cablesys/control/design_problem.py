"""The time-domain design problem of a scene (:mod:`.design`): its model, its seas and its limits.

The plant is a winch model of the control (:func:`cablesys.control.payout.control_model`: Wang's 2-DOF winch,
:mod:`cablesys.model.winch`, or the segmented node model's, :mod:`cablesys.model.segmented_winch_control`; by
default the ladder's choice for the scene, :func:`.model_choice.resolve_model`) held at
zero payout (w = alpha = 0, L = l_0: the fixed-length model exactly), rolled out by the classical RK4 of
:mod:`.kernels` (``substeps`` steps per ``dt``) from the rest state of each candidate design, in each of ``seeds``
realisations of the scene's sea (:mod:`cablesys.scene.sea`: same spectrum, phases from ``default_rng(seed)``).
The design theta = (AE, C_I) of the section's cable lies in the ``[design]`` table's bounds; the RK4 step is
chosen for the stiffest design of that box (:func:`design_substeps`), so every candidate rolls out stably.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..errors import ParameterError, require_positive
from ..model.params import ParameterLayout
from ..model.top_motion import top_motion_function
from .model_choice import ModelChoice, resolve_model
from .payout import (RK4_STABILITY, RK4_STEP_LAMBDA, control_model, describe_model, fastest_mode, floor_output,
                     heave_problem, model_rest_state)

# the rolled-out series (rows of the roll-out's output): the body heave and surge, the tension the no-slack
# floor bounds (the model's floor output: Wang's F_bc, the node model's least element tension), the top tension
SERIES = ("heave", "x_b", "tension_floor", "tension_top")
# the design's parameters, theta = (AE N, C_I N s) of the (single) section's cable
PARAMETERS = ("cable.ae", "cable.internal_damping")


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

    ``scene`` is the scene of the design's model (its ``cable.segments`` the model's N); ``exogenous`` holds,
    per seed, the top motion at the RK4 stage times of every interval
    (:meth:`cablesys.control.payout.HeaveProblem.exogenous`, shape (N, 7 (2 substeps + 1))); ``model_choice`` says
    which model the design runs and why (:class:`.model_choice.ModelChoice`: the ladder's choice by default).
    """

    scene: object
    heave: object                       # the HeaveProblem (model, p, c, substeps) of the nominal scene
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
    fastest_mode: float = math.nan      # max |lambda| over the design box's corners (1/s)
    model_choice: ModelChoice | None = None

    @property
    def model_reason(self) -> str:
        """Why the design's model runs (:attr:`model_choice`'s reason)."""
        return "" if self.model_choice is None else self.model_choice.reason

    @property
    def duration(self) -> float:
        return self.N * self.dt

    @property
    def model(self):
        """The design's winch model."""
        return self.heave.model

    @property
    def floor_output(self) -> str:
        """The model's output the no-slack floor bounds (``tension_floor`` of :data:`SERIES`)."""
        return floor_output(self.heave.model)

    def describe(self) -> str:
        """One line naming the design's model and its RK4 roll-out."""
        return (f"{describe_model(self.model)} at zero payout, RK4 roll-out {self.heave.substeps} steps per "
                f"{self.dt:g} s (stiffest design's |lambda| {self.fastest_mode:.4g} 1/s)")

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
        """The scene (of the design's model) with the cable's AE and C_I set to ``theta``."""
        return self.scene.replace_section(0, cable={"ae": float(theta[0]), "internal_damping": float(theta[1])})


def selection(problem: TimeDesignProblem):
    """(base, B): p(theta) = base + B theta, the nominal parameters with AE and C_I replaced."""
    hp = problem.heave
    lay = hp.model.layout
    idx = [lay.index(n) for n in PARAMETERS]
    base = np.array(hp.p, float)
    base[idx] = 0.0
    B = np.zeros((len(base), 2))
    B[idx[0], 0] = B[idx[1], 1] = 1.0
    return base, B


def design_substeps(model, p, c, dt: float, ae_bounds, damping_bounds) -> tuple:
    """(substeps, max |lambda|): the least n >= 2 RK4 steps per ``dt`` with (dt / n) |lambda| <= RK4_STEP_LAMBDA
    for the stiffest mode at rest (:func:`cablesys.control.payout.fastest_mode`) of every corner of the design box
    (the axial modes stiffen with AE, the Voigt damping's real eigenvalues grow with C_I), each at its own rest
    state: a roll-out stable for every candidate design."""
    lay = model.layout
    lam = 0.0
    for ae in ae_bounds:
        for ci in damping_bounds:
            pk = np.array(p, float)
            pk[lay.index("cable.ae")], pk[lay.index("cable.internal_damping")] = ae, ci
            lam = max(lam, fastest_mode(model, model_rest_state(model, pk, c), pk, c))
    n = max(2, math.ceil(dt * lam / RK4_STEP_LAMBDA))
    assert dt / n * lam <= RK4_STABILITY
    return n, lam


def time_design_problem(scene, *, seeds=(1, 2, 3), duration: float | None = None, dt: float = 0.5,
                        substeps: int | None = None, rho: float = 200.0, model="auto",
                        segments: int | None = None) -> TimeDesignProblem:
    """Set the time-domain design of ``scene`` up (module docstring and :mod:`.design`'s).

    Parameters
    ----------
    scene : Scene
        One section, a ``[top_motion.spectrum]`` sea, a ``[design]`` table (``ae_bounds``,
        ``damping_bounds``, optionally ``strain_limit`` and ``working_load``) and ``[limits]``.
    seeds : sequence of int
        Seeds of the sea's random phases; each is one realised record.
    duration : float, optional
        Record length (s; default ``numerics.duration``).
    dt : float
        RK4 interval (s) of the series (the statistics' sampling).
    substeps : int, optional
        RK4 steps per interval (default :func:`design_substeps`: stable for the stiffest design in the bounds).
    rho : float
        KS parameter on the normalized constraints (the envelope is within ln(N)/rho of the max).
    model : str or ModelChoice
        "auto" (default): the winch form of the ladder's a priori choice for the scene with the record's duration
        (where ``cablesys run`` starts, before its checks may grow N; :func:`.model_choice.resolve_model`, as ``cablesys control --design``; on the packaged
        ROV lift the node model at N = 4); "wang" (Wang's 2-DOF cable) or "segmented" (the node model of
        ``segments`` elements, default the scene's ``cable.segments``): :func:`cablesys.control.payout.control_model`.
    segments : int, optional
        N of the node model (with "auto": in place of the ladder's N).

    Returns
    -------
    TimeDesignProblem
        Its ``model_choice`` says which model the design runs and why.
    """
    if not scene.design:
        raise ParameterError("design", None, "the scene needs a [design] table (ae_bounds, damping_bounds)")
    if len(scene.sections) != 1:
        raise ParameterError("sections", len(scene.sections), "must be 1: the time-domain design tunes one section's (AE, "
                             "C_I); a soft insert or an intermediate body (a chain of sections) is designed in the "
                             "frequency domain only (cablesys design)")
    if scene.top_motion.spectrum is None:
        raise ParameterError("top_motion.spectrum", None, "a realised sea is needed: give [top_motion.spectrum]")
    seeds = tuple(seeds)
    if not seeds or not all(isinstance(s, (int, np.integer)) and s >= 0 for s in seeds) or len(set(seeds)) < len(seeds):
        raise ParameterError("seeds", seeds, "one or more distinct integers >= 0")
    require_positive("rho", rho, "")
    duration = float(scene.numerics.duration if duration is None else duration)
    require_positive("duration", duration, "s")
    require_positive("dt", dt, "s")
    if substeps is not None and not (isinstance(substeps, (int, np.integer)) and substeps >= 1):
        raise ParameterError("substeps", substeps, "must be an integer >= 1")
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
    choice = resolve_model(scene, model, segments)
    scene, winch = control_model(scene, choice.model, choice.segments)
    p, c = winch.parameters(scene), np.zeros(4)
    n_auto, lam = design_substeps(winch, p, c, dt, ae_b, ci_b)
    hp = dataclasses.replace(heave_problem(scene, dt=dt, substeps=substeps or n_auto, tension_weight=0.0,
                                           control_weight=0.0, model=winch), model_choice=choice)
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
                             rho=float(rho), theta_nominal=(float(cable.ae), float(cable.internal_damping)),
                             fastest_mode=float(lam), model_choice=choice)


def _exogenous(scene, hp, N: int) -> np.ndarray:
    """The interval table E (N, 7 (2 substeps + 1)) of ``scene``'s top motion on ``hp``'s grid
    (:meth:`cablesys.control.payout.HeaveProblem.exogenous`); a seed's own top-motion function, since
    another seed may realise a different number of sinusoids (another structure of the model)."""
    layout = ParameterLayout.from_scene(scene)
    top = top_motion_function(scene, layout)
    return dataclasses.replace(hp, model=dataclasses.replace(hp.model, top=top),
                               p=layout.values(scene)).exogenous(hp.dt * np.arange(N))
