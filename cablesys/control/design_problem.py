"""The time-domain design problem of a scene (:mod:`.design`): its model, its seas and its limits.

The plant is a winch model of the control (:func:`cablesys.control.payout.control_model`: Wang's 2-DOF winch,
:mod:`cablesys.model.winch`, or the segmented node model's, :mod:`cablesys.model.segmented_winch_control`; by
default the ladder's choice for the scene, :func:`.model_choice.resolve_model`) held at
zero payout (w = alpha = 0, L = l_0: the fixed-length model exactly), rolled out by the classical RK4 of
:mod:`.kernels` (``substeps`` steps per ``dt``) from the rest state of each candidate design, in each of ``seeds``
realisations of the scene's sea (:mod:`cablesys.scene.sea`: same spectrum, phases from ``default_rng(seed)``).
The design theta holds the variables of :func:`cablesys.model.design_variables.section_variables`, the frequency-domain
design's: per section, top first, its cable's AE and C_I (one section: theta = (AE, C_I); a chain of sections adds
the soft insert's or the lower line's), and with ``intermediate_mass_bounds`` the intermediate body's mass (the body
scaled as a whole), each within the ``[design]`` table's bounds. A chain runs on the node model's winch (the control's
only chain, :mod:`cablesys.model.segmented_winch_control`). The RK4 step is chosen for the stiffest design of the
bounds' box (:func:`design_substeps`), so every candidate rolls out stably.
"""

from __future__ import annotations

import dataclasses
import itertools
import math

import numpy as np

from ..errors import ParameterError, require_positive
from ..model.design_variables import bound_pairs, current_values, designed_scene, kind, linear_map, section_variables
from ..model.params import ParameterLayout
from ..model.top_motion import top_motion_function
from .kernels import output_labels
from .model_choice import ModelChoice, resolve_model
from .payout import (RK4_STABILITY, RK4_STEP_LAMBDA, control_model, describe_model, fastest_mode, floor_output,
                     heave_problem, model_rest_state)

# the rolled-out series (rows of the roll-out's output): the body heave and surge (the lowest body's), the tension
# the no-slack floor bounds (the model's floor output: Wang's F_bc, the node model's least element tension), the top
# tension; a chain's lower sections' top tensions follow (tension_top_2, ...: :func:`series_names`)
SERIES = ("heave", "x_b", "tension_floor", "tension_top")
# the units of the design's variables (:func:`cablesys.model.design_variables.section_variables`), by name prefix
UNITS = {"ae": "N", "internal_damping": "N s", "intermediate_mass": "kg"}


def series_names(sections: int) -> tuple:
    """:data:`SERIES` and, in a chain of ``sections``, the top tensions of its lower sections."""
    return SERIES + tuple(f"tension_top_{i + 1}" for i in range(1, sections))


def unit(name: str) -> str:
    """The unit of the design variable ``name`` (:data:`UNITS`)."""
    return UNITS[kind(name)]


def symbol(name: str, single: bool = False) -> str:
    """The short symbol of a design variable: AE and C_I of one section, AE_i, C_I,i of a chain's section i, m_1 the
    intermediate body's heave mass."""
    if name == "intermediate_mass":
        return "m_1"
    kind, i = name.rsplit("_", 1)
    base = "AE" if kind == "ae" else "C_I"
    return base if single else (f"{base}_{i}" if base == "AE" else f"{base},{i}")


def describe_theta(names, theta) -> str:
    """"AE 1.2e+05 N, C_I 1.6e+05 N s" (one section) or "AE_1 ... N, C_I,1 ... N s, ..., m_1 ... kg" (a chain)."""
    single = tuple(names) == ("ae_1", "internal_damping_1")
    return ", ".join(f"{symbol(n, single)} {v:.3g} {unit(n)}" for n, v in zip(names, theta))


def _pairs(design: dict, name: str, n: int) -> tuple:
    """``n`` (lo, hi) pairs from the ``[design]`` table's ``name`` (one section: [[lo, hi]] or [lo, hi])."""
    v = design.get(name)
    if v is None:
        raise ParameterError(f"design.{name}", None, f"needs {n} pair(s) [lo, hi], one per section, top first")
    if n == 1 and np.ndim(v) == 1:
        v = [v]
    return bound_pairs(f"design.{name}", v, n)


def _per_section(design: dict, name: str, n: int, default):
    """A per-section number of the ``[design]`` table (one value, or one per section): a tuple of n, or None."""
    v = design.get(name, default)
    if v is None:
        return None
    v = np.ravel(np.asarray(v, float))
    if v.size == 1:
        v = np.repeat(v, n)
    if v.size != n or not np.all(v > 0):
        raise ParameterError(f"design.{name}", design.get(name), f"one value > 0, or one per section ({n})")
    return tuple(float(a) for a in v)


@dataclasses.dataclass(frozen=True)
class TimeDesignProblem:
    """The time-domain design problem of a scene (module docstring; SI units).

    ``scene`` is the scene of the design's model (its ``cable.segments`` the model's N); ``exogenous`` holds,
    per seed, the top motion at the RK4 stage times of every interval
    (:meth:`cablesys.control.payout.HeaveProblem.exogenous`, shape (N, 7 (2 substeps + 1))); ``variables`` the
    design's variables (:class:`cablesys.model.design_variables.Variable`: name, bounds, the layout labels each sets);
    ``working_load`` and ``strain_limit`` one number per section (the peak of each section's top tension, the static
    strain of each); ``model_choice`` says which model the design runs and why (:class:`.model_choice.ModelChoice`:
    the ladder's choice by default).
    """

    scene: object
    heave: object                       # the HeaveProblem (model, p, c, substeps) of the nominal scene
    seeds: tuple
    exogenous: tuple
    dt: float
    N: int
    window_start: int                   # first interval of the statistics window
    variables: tuple                    # model.design_variables.Variable, theta's order
    working_load: tuple                 # N per section (inf: none)
    slack_fraction: float | None
    max_excursion: float | None         # m
    strain_limit: tuple | None          # static u_0 / l_0 per section
    rho: float
    theta_nominal: tuple                # the scene's values of the variables
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
    def sections(self) -> int:
        return len(self.scene.sections)

    @property
    def names(self) -> tuple:
        """The design variables' names (theta's order)."""
        return tuple(v.name for v in self.variables)

    @property
    def series(self) -> tuple:
        """The rolled-out series' names (:func:`series_names`)."""
        return series_names(self.sections)

    @property
    def floor_output(self) -> str:
        """The model's output the no-slack floor bounds (``tension_floor`` of :data:`SERIES`)."""
        return floor_output(self.heave.model)

    def describe(self) -> str:
        """One line naming the design's model and its RK4 roll-out."""
        return (f"{describe_model(self.model)} at zero payout, RK4 roll-out {self.heave.substeps} steps per "
                f"{self.dt:g} s (stiffest design's |lambda| {self.fastest_mode:.4g} 1/s)")

    def _logs(self):
        return (np.log([v.lower for v in self.variables]), np.log([v.upper for v in self.variables]))

    def theta(self, z) -> np.ndarray:
        """The variables' values of the normalized design z in [0, 1]^n (log scale between the bounds)."""
        lo, hi = self._logs()
        return np.exp(lo + np.asarray(z, float) * (hi - lo))

    def z(self, theta) -> np.ndarray:
        lo, hi = self._logs()
        return (np.log(np.asarray(theta, float)) - lo) / (hi - lo)

    def designed_scene(self, theta):
        """The scene (of the design's model) with the variables set to ``theta`` (each of its targets, its factor
        times the value)."""
        return designed_scene(self.scene, self.variables, theta)


def selection(problem: TimeDesignProblem):
    """(base, B): p(theta) = base + B theta, the nominal parameters with the variables' targets replaced."""
    hp = problem.heave
    return linear_map(hp.model.layout, hp.p, problem.variables)


def _corners(variables) -> list:
    """The designs at the joint corners of the bounds' box: every AE at its lower or upper bound together, every
    C_I, the intermediate mass (:func:`design_substeps`)."""
    kinds = sorted({kind(v.name) for v in variables})
    out = []
    for ends in itertools.product((0, 1), repeat=len(kinds)):
        side = dict(zip(kinds, ends))
        out.append([(v.lower, v.upper)[side[kind(v.name)]] for v in variables])
    return out


def design_substeps(model, p, c, dt: float, variables) -> tuple:
    """(substeps, max |lambda|): the least n >= 2 RK4 steps per ``dt`` with (dt / n) |lambda| <= RK4_STEP_LAMBDA
    for the stiffest mode at rest (:func:`cablesys.control.payout.fastest_mode`) of every joint corner of the design
    box (:func:`_corners`: the axial modes stiffen with AE, the Voigt damping's real eigenvalues grow with C_I, a
    lighter body raises the frequencies; each section's modes follow its own AE and C_I, so every section at its
    stiffest together bounds them), each at its own rest state: a roll-out stable for every candidate design."""
    base, B = linear_map(model.layout, p, variables)
    lam = 0.0
    for values in _corners(variables):
        pk = base + B @ np.asarray(values, float)
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
        One section or a chain of sections, a ``[top_motion.spectrum]`` sea, a ``[design]`` table (``ae_bounds``
        and ``damping_bounds``, one pair per section, top first; optionally ``intermediate_mass_bounds`` (kg, a chain),
        ``strain_limit`` and ``working_load``, one value or one per section) and ``[limits]``.
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
        (where ``cablesys run`` starts, before its checks may grow N; :func:`.model_choice.resolve_model`, as
        ``cablesys control --design``; on the packaged ROV lift the node model at N = 4); "wang" (Wang's 2-DOF cable,
        one section) or "segmented" (the node model of ``segments`` elements per section, default the scene's
        ``cable.segments``): :func:`cablesys.control.payout.control_model`.
    segments : int, optional
        N of the node model (with "auto": in place of the ladder's N).

    Returns
    -------
    TimeDesignProblem
        Its ``model_choice`` says which model the design runs and why.
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
    require_positive("dt", dt, "s")
    if substeps is not None and not (isinstance(substeps, (int, np.integer)) and substeps >= 1):
        raise ParameterError("substeps", substeps, "must be an integer >= 1")
    lim = scene.limits
    start = float(lim.statistics_start) if lim is not None and lim.statistics_start is not None else 0.2 * duration
    if start >= duration - 10 * dt:
        raise ParameterError("duration", duration, f"must exceed the statistics start {start:g} s by 10 intervals")
    design, n_sec = scene.design, len(scene.sections)
    mass_b = design.get("intermediate_mass_bounds")
    variables = section_variables(scene, _pairs(design, "ae_bounds", n_sec), _pairs(design, "damping_bounds", n_sec),
                                  None if mass_b is None else bound_pairs("design.intermediate_mass_bounds",
                                                                          [mass_b])[0])
    wl = _per_section(design, "working_load", n_sec,
                      lim.working_load if lim is not None and lim.working_load is not None else None)
    strain = _per_section(design, "strain_limit", n_sec, None)
    scene = scene.with_numerics(duration=duration)
    choice = resolve_model(scene, model, segments)
    scene, winch = control_model(scene, choice.model, choice.segments)
    p, c = winch.parameters(scene), np.zeros(4)
    n_auto, lam = design_substeps(winch, p, c, dt, variables)
    hp = dataclasses.replace(heave_problem(scene, dt=dt, substeps=substeps or n_auto, tension_weight=0.0,
                                           control_weight=0.0, model=winch), model_choice=choice)
    if wl is not None:
        x_rest = hp.x_rest
        y0 = dict(zip(output_labels(winch), np.array(winch.outputs(x_rest, [0, 0], 0.0, p, c)).ravel()))
        for i, (name, w) in enumerate(zip(series_names(n_sec)[3:], wl)):
            if not w > y0[name]:
                raise ParameterError(f"design.working_load[{i}]" if n_sec > 1 else "design.working_load", w,
                                     f"must exceed the static tension at the top of section {i + 1}, {y0[name]:.6g} N")
    N = int(round(duration / dt))
    exo = []
    for s in seeds:
        sea = dataclasses.replace(scene.top_motion.spectrum, seed=int(s))
        sc = scene.replace(top_motion=dataclasses.replace(scene.top_motion, spectrum=sea))
        exo.append(_exogenous(sc, hp, N))
    return TimeDesignProblem(scene=scene, heave=hp, seeds=seeds, exogenous=tuple(exo), dt=float(dt), N=N,
                             window_start=int(math.ceil(start / dt - 1e-9)), variables=variables,
                             working_load=tuple([math.inf] * n_sec) if wl is None else wl,
                             slack_fraction=None if lim is None else lim.slack_fraction,
                             max_excursion=None if lim is None else lim.max_excursion, strain_limit=strain,
                             rho=float(rho), theta_nominal=tuple(float(v) for v in current_values(scene, variables)),
                             fastest_mode=float(lam), model_choice=choice)


def _exogenous(scene, hp, N: int) -> np.ndarray:
    """The interval table E (N, 7 (2 substeps + 1)) of ``scene``'s top motion on ``hp``'s grid
    (:meth:`cablesys.control.payout.HeaveProblem.exogenous`); a seed's own top-motion function, since
    another seed may realise a different number of sinusoids (another structure of the model)."""
    layout = ParameterLayout.from_scene(scene)
    top = top_motion_function(scene, layout)
    return dataclasses.replace(hp, model=dataclasses.replace(hp.model, top=top),
                               p=layout.values(scene)).exogenous(hp.dt * np.arange(N))
