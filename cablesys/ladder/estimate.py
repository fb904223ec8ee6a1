"""Error estimates of each rung against the converged segmented cable (relative numbers).

Two errors per rung, as the tolerance names them (:mod:`.metrics`): ``body`` (body-motion amplitude
relative to the largest body amplitude) and ``tension`` (tension extremes relative to the largest
tension).

- quasi-static vs Wang: the stretch of a spring with mass driven at omega responds by
  1 / (1 - r^2 + i 2 zeta r) of its quasi-static value (r = omega / omega_ax, Voigt damping
  zeta r = C_I omega / (2 AE), Wang 1971 eq. 46), so the quasi-static tension and stretch miss the
  fraction r^2 / |1 - r^2 + i 2 zeta r| of their dynamic parts (the dynamic tension and the body
  amplitude come from Wang's own equivalent-linear response, :func:`linear_response`);
- Wang vs segmented: the straight cable is one linear element with consistent mass; the continuous
  cable's string (transverse) and rod (axial) dynamics with the body at the end and the drag
  equivalently linearized are solved in closed form, and their body amplitudes and end forces
  compared (:mod:`.continuum`: string and rod dynamic stiffness, Rayleigh-Ritz, describing function).
  The straight cable also cannot bow under a current: its static sag / chord q L / (8 T), amplified
  near the swing resonance by 1 / |1 - (omega/omega_swing)^2| (at most SWING_AMPLIFICATION, drag
  bounds it), is kept as a second term (a closed form not yet replaced by a derivation).
  Partial slack (least tension of the linear response below the floor) puts the straight cable
  outside its validity: infinite error;
- segmented with N elements: N lumped-mass linear elements of the same continuum (:mod:`.continuum`:
  each element at its own tension on a hanging cable, the drag at the segmented model's own points,
  whose number per element changes with N, so the error converges unevenly: Dale at 2 omega_n
  0.31 / 0.18 / 0.24 % at N = 4 / 5 / 8), tabulated at :func:`continuum_counts` and interpolated as a
  power law within one drag rule; near a string mode also with the drag linearized element by element
  (:mod:`.local_drag`), the larger stated; and no less than a floor x N^-ORDER (:func:`segmented_error`:
  the static bow below the first string mode, the straight cable's error at or above it). With partial
  slack N^-SLACK_ORDER from the straight cable's O(1) error (checked a posteriori by the run at N/2,
  :mod:`.auto`);
- quasi-static segmented with N elements: the segmented estimate at N plus the quasi-static stretch's
  part (above), :func:`quasistatic_segmented_error`.

Estimates are floored at RESOLUTION: below it, start-up transients, the reference's own
convergence and nonlinear terms these linear estimates leave out are of the same size.

The estimates speak of the settled forced response. A window that ends before the ramped forcing has
travelled down the string (:func:`settling_time`) measures a front, not that response. Measured on
the 1000 m wire / 300 kg sphere of the model-ladder study (``heavy1000``: 1 m heave and surge at
T = 10 s, omega / omega_string = 2.74; segmented rung, CasADi VM, CVODES rtol 1e-7), every body error
is the body's surge x_b (the heave y_b agrees to 2e-4 m), and it is not monotone in N for two causes:

1. the window. The study ran 40 s with a 30 s ramp; the surge takes 14.7 s to run down the hanging
   string (:func:`continuum.string_travel_time`: the body's x_b is 1e-4 m at 15 s, 9 mm at 20 s), so the
   full forcing reaches the body at ~45 s and the window 20-40 s holds the arriving front. Errors
   vs N = 40 there (%, N = 4 / 5 / 6 / 7 / 8 / 9 / 10 / 12 / 14 / 16 / 20): 0.51 / 0.66 / 0.54 / 2.00 /
   1.49 / 1.13 / 0.90 / 0.63 / 0.47 / 0.37 / 0.25. Settled (120 s, window 100-120 s, against N = 80;
   N = 40 is 0.007 % from it): 1.40 / 1.02 / 0.59 / 1.23 / 0.96 / 0.71 / 0.54 (N = 4..10), 0.16 (N = 20).
   Stated here: 2.92 / 1.87 / 1.30 / 1.82 / 0.80 / 0.58 / 0.47 / 0.12: within 2x of the settled errors
   from N = 5 up (N = 4 and 6: 2.1x and 2.2x pessimistic); auto's N = 10 is 0.54 % against 0.47 % stated
   (0.86). The quasi-static segmented rung is the segmented one to 1e-5 m here (N = 5: x_b 0.01132 m,
   N = 10: 0.02745 m, the same as the node model), and N = 5 at 1.02 % is outside the 1 % tolerance.
2. the drag rule (:func:`cablesys.model.segmented.drag_points`: 10 points per section shared, two per
   element at N <= 6, one from N = 7). The surge wave is drag-controlled (equivalent damping ~6 x m omega
   at the top, decaying algebraically under quadratic drag: :mod:`.local_drag`'s continuous string
   gives x_b = 0.0236 m, the settled N = 80 run 0.0219 m, the one-damping string 8e-5 m). Settled x_b
   (m) at N = 4 / 5 / 6 is 0.0074 / 0.0113 / 0.0157 (the two-point chain passes too little of the wave:
   its points damp the element's antisymmetric motion, shares (5/16, 3/16), the mid-point's (1/4, 1/4)
   do not, and the mid-point sees the phase-averaged speed), at N = 7 / 8 / 10 / 20 0.0345 /
   0.0318 / 0.0275 / 0.0235 (the lumped chain passes too much of the wave): the error changes sign
   between N = 6 and 7, so its size dips at N = 6 (0.59 %) and jumps at 7. :mod:`.local_drag`, with the
   drag linearized at the model's own points on the interpolated complex velocity, follows both sides
   (x_b 0.0071 / 0.0107 / 0.0150 m at N = 4 / 5 / 6, 0.0324 / 0.0301 / 0.0266 m at N = 7 / 8 / 10); its
   errors against its own continuous string (x_b 0.0236 m; the N = 80 run 0.0219 m) are 1.60 / 1.25 /
   0.84 / 0.86 / 0.64 / 0.30 % at N = 4 / 5 / 6 / 7 / 8 / 10 against the settled 1.40 / 1.02 / 0.59 /
   1.23 / 0.96 / 0.54 %. Without the straight cable's floor (:func:`segmented_error`: it had covered a
   start-up transient) the stated estimate at N = 4 .. 10 is the larger of the two tables: 1.60 / 1.25 / 0.84 /
   1.82 / 0.80 / 0.46 / 0.34 %, within 2x of the settled errors at every N (1.1-1.5x at N = 4-7, 0.6-0.8x at
   N = 8-10). The quasi-static segmented cable adds its stretch part, 0.11 % here
   (omega/omega_ax = 0.152), and runs with the compiled rk23 pair; auto (compiled) takes it at N = 6, estimated
   0.95 %, within the tolerance but not within half of it, and checks it a posteriori against N = 3
   (:func:`cablesys.ladder.choice.element_plan`): Richardson states 0.31 % against an actual 0.49 %
   (model_ladder study, vs N = 40, 120 s).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..errors import SolverError
from ..linear import harmonic_response, linearize, steady_state
from ..linear.periodic import scene_input_amplitude
from ..model import build_model
from ..scene import Scene
from ..scene.labels import section_suffix
from . import continuum, local_drag
from .indicators import SceneNumbers, other_components, scene_numbers, static_angle, top_phasors
from .rung.base import with_segments

ORDER = 2.0         # convergence order of the segmented cable in N (taut; Dale study: 2-3)
REMAINDER_ORDER = 2.0   # q of the next term after the first order under partial slack (integer powers of 1/N)
SLACK_ORDER = 1.0   # with partial slack and snap loads (300 m wire at T = 6 s: 11 % at N = 15 vs N = 40)
SLACK_MARGIN = 0.05  # a least tension within 5 % of the static tension of the floor counts as slack
SWING_AMPLIFICATION = 10.0
HB_PHASES, HB_CONTINUATION = 16, 1   # harmonic balance of linear_response (see there)
LOCAL_STRING_RATIO = 0.3     # omega / omega_string above which the string's drag is also linearized per element
LOCAL_MAX_N = 16             # the element-by-element table stops here (one drag point per element beyond ~7)
SETTLE_FRACTION = 0.01   # the slow drift's part left at the settling time; generated chains in currents
#                          (studies/ladder_generated.py, seed 22, N = 128) then change 2e-4 / 5e-4 / 0 between the window's
#                          halves (metrics.window_change), 0.012 / 0.022 / 0.107 with the ramp and string travel alone
RESOLUTION = 1e-4    # estimates are not resolved below this (start-up transients, reference convergence)
CONTINUUM_N = (2, 4, 8, 16, 32, 64, 128)   # elements at which the segmented estimate is tabulated (and see
#                                            continuum_counts: where the segmented model's drag rule changes)


def continuum_counts(scene: Scene) -> tuple:
    """Element counts at which the continuum estimate is tabulated: CONTINUUM_N and both ends of every run
    of N with the same drag points per element (:func:`cablesys.model.segmented.drag_points`, numerics.drag_segments
    shared among the elements): the drag rule, and with it the error, jumps between runs (Dale at 2 omega_n:
    0.31 % at N = 4, 0.18 % at 5, 0.24 % at 8), so the power-law interpolation of :func:`segmented_error`
    stays within one run."""
    from ..model.segmented import drag_points
    top = CONTINUUM_N[-1]
    pts = [drag_points(scene, n) for n in range(1, top + 2)]          # pts[n - 1] at n elements
    ends = {n for n in range(2, top + 1) if pts[n - 2] != pts[n - 1] or pts[n] != pts[n - 1]}
    return tuple(sorted(set(CONTINUUM_N) | ends))


@dataclasses.dataclass(frozen=True)
class LinearResponse:
    """Wang's response at the dominant forcing: body amplitudes (m), tension mean and amplitude (N)."""

    omega: float
    body_amplitude: float
    tension_mean: dict
    tension_amplitude: dict
    stretch_amplitude: float
    method: str

    @property
    def least_tension(self) -> float:
        return min(self.tension_mean[k] - self.tension_amplitude[k] for k in self.tension_mean)

    @property
    def largest_tension(self) -> float:
        return max(self.tension_mean[k] + self.tension_amplitude[k] for k in self.tension_mean)


def linear_response(scene: Scene, numbers: SceneNumbers, model=None) -> LinearResponse:
    """Wang's one-harmonic (describing-function) response to the scene's forcing, or for several
    frequencies the exact linear response at each component summed (a bound). ``model``: Wang's
    model of the scene's structure if already built (its cached solvers are reused)."""
    sc = with_segments(scene, 1)                 # Wang's straight cable (the wang rung's scene and model)
    model = model or build_model(sc)
    p = model.parameters(sc)
    # every section's tensions ("tension_mid": Wang's F_bc, the slack switch, eq. 54) and bodies; a chain of
    # sections labels them tension_mid_2, x_b_2, ... (cablesys.scene.labels.section_suffix)
    sfx = [section_suffix(scene, i) for i in range(len(scene.sections))]
    keys = tuple(k + x for x in sfx for k in ("tension_top", "tension_bottom", "tension_mid"))
    # the body's coordinates: x_b, y_b and in 3-D the sway z_b (the 3-D model's outputs)
    bodies = tuple(k + x for x in sfx for k in ("x_b", "y_b", "z_b") if k + x in model.output_labels)
    stretches = tuple("u" + x for x in sfx)
    if numbers.single_frequency and not scene.environment.waves:
        omega, Z = scene_input_amplitude(sc)
        # 16 phase samples and 1 continuation step: the same amplitudes to 4 digits as 64 and 6 on the
        # Dale and 300 m heave scenes (x_b 0.07117 vs 0.07118 m), and to 1e-13 as 2 steps on Dale, the 300 m
        # heave and 21 random scenes (tests/test_ladder_random.py families, seeds 1-6), 30-50 % faster
        # (choosing is part of the user's wait)
        h = harmonic_response(model, p, [omega], Z, n_theta=HB_PHASES, ladder=HB_CONTINUATION)
        if h.success:
            lab = list(h.output_labels)
            amp = lambda k: float(abs(h.output_amplitude[0][lab.index(k)]))
            mean = lambda k: float(np.real(h.output_mean[0][lab.index(k)]))
            return LinearResponse(omega=omega, body_amplitude=max(amp(k) for k in bodies),
                                  tension_mean={k: mean(k) for k in keys}, tension_amplitude={k: amp(k) for k in keys},
                                  stretch_amplitude=max(amp(k) for k in stretches), method="harmonic (describing function)")
    st = steady_state(model, p)
    lin = linearize(model, p, steady=st)
    lab = list(lin.output_labels)
    if "z_s" in lin.input_labels:
        # 3-D: each top frequency's response to its complex top amplitudes (x_s, y_s, z_s) (which turn with the scene),
        # the waves and a series as in the plane (the largest of the top's three columns per metre)
        phasors = top_phasors(scene)
        others = other_components(scene)
        w_top = np.array([c[0] for c in phasors] + [w for w, _ in others] or [1e-6])
        _, Y = lin.transfer(w_top)
        Z = np.array([c[1:] for c in phasors], complex).reshape(-1, 3)
        amps = np.array([a for _, a in others])
        gain = lambda k: float(np.sum(np.abs(np.sum(Y[:len(phasors), lab.index(k), :3] * Z, axis=1)))
                               + np.sum(np.max(np.abs(Y[len(phasors):, lab.index(k), :3]), axis=1) * amps))
    else:
        omegas = np.array([w for w, _ in numbers.forcing]) if numbers.forcing else np.array([1e-6])
        amps = np.array([a for _, a in numbers.forcing]) if numbers.forcing else np.zeros(1)
        _, Y = lin.transfer(omegas)
        gain = lambda k: float(np.sum(np.max(np.abs(Y[:, lab.index(k), :2]), axis=1) * amps))
    return LinearResponse(omega=numbers.omega_forcing, body_amplitude=max(gain(k) for k in bodies),
                          tension_mean={k: float(st.outputs[k]) for k in keys},
                          tension_amplitude={k: gain(k) for k in keys}, stretch_amplitude=max(gain(k) for k in stretches),
                          method="exact linearization (undamped; a bound away from resonance)")


def slow_decay_time(scene: Scene, model=None) -> float:
    """Time constant tau_slow (s) of the slowest free motion below the forcing frequency in the current: Wang's
    cable (the wang rung's model) linearized exactly about its steady state in the flow (:func:`linearize`: the
    drag slope 2 x 1/2 rho C_D A |U| damps the motion across the flow), whose free response is a sum of
    c_k v_k exp(lambda_k t) (eigenvalues lambda_k of the state matrix; Meirovitch, *Fundamentals of Vibrations*,
    2001, sec. 7.13), so each part decays as exp(Re lambda_k t) and tau_slow = 1 / min(-Re lambda_k) over the
    eigenvalues with |lambda_k| below the forcing frequency (:attr:`SceneNumbers.omega_forcing`).

    Those are the mean offset's drift under drag (real eigenvalues: a body in a current pushed off its mean by
    the forcing's added mean drag creeps back without oscillating) and the body's swing; the axial and higher
    string modes above the forcing carry no mean and are damped further by the forced drag. Measured on
    generated scenes (``studies/ladder_generated.py``, seed 22): a two-body chain in a 1.41 m/s current
    (``chain-22-3``) has its slowest real eigenvalue at -0.0214 1/s, the decay rate of the body's mean offset in
    the run; the four scenes whose reference amplitudes still changed by 2-11 % between the halves of the
    statistics window all had 4.6 tau_slow longer than the ramp plus the string travel time.

    0 without a relative flow (no current and no tow: the linearized drag has no slope, the linear model is
    undamped and says nothing of the decay, which quadratic drag then sets) or without periodic forcing.

    Parameters
    ----------
    scene : Scene
        The scene.
    model : CableModel, optional
        Wang's model of the scene's structure if already built.

    Returns
    -------
    float
        tau_slow (s); math.inf when such a motion is undamped in the flow.
    """
    env = scene.environment
    omega = scene_numbers(scene).omega_forcing
    if omega <= 0.0 or all(u == env.system_speed for u in env.current_speeds):
        return 0.0
    sc = with_segments(scene, 1)
    model = model or build_model(sc)
    lam = np.linalg.eigvals(linearize(model, model.parameters(sc)).A)
    rate = -lam.real[np.abs(lam) < omega]
    if rate.size == 0:
        return 0.0
    slowest = float(np.min(rate))
    return math.inf if slowest <= 0.0 else 1.0 / slowest


def settling_time(scene: Scene, model=None) -> float:
    """Earliest time (s) at which the body can carry the full forced response the estimates speak of: the
    top motion's ramp (``effective_ramp_s``), plus the transverse wave's travel time down every section's
    hanging string to the lowest body (:func:`continuum.string_travel_time`; the axial wave is faster), plus
    ln(1 / SETTLE_FRACTION) x tau_slow, the time for the slowest free motion below the forcing in the current
    (:func:`slow_decay_time`: the mean offset's drift under drag) to fall to SETTLE_FRACTION of its start.
    A statistics window should start after it (module docstring: the 1000 m wire's 40 s run with a 30 s ramp
    and a 14.7 s travel time measured the arriving front).

    Parameters
    ----------
    scene : Scene
        The scene.
    model : CableModel, optional
        Wang's model of the scene's structure if already built.

    Returns
    -------
    float
        Ramp plus string travel time plus the slow decay (s).
    """
    angle = static_angle(scene)
    travel = sum(continuum.string_travel_time(string) for string, _ in continuum.members(scene, 1.0, angle))
    slow = math.log(1.0 / SETTLE_FRACTION) * slow_decay_time(scene, model)
    return float(scene.top_motion.effective_ramp_s) + travel + slow


def axial_factor(scene: Scene, numbers: SceneNumbers) -> float:
    """r^2 / |1 - r^2 + i 2 zeta r|: the part of the dynamic stretch the quasi-static rung misses."""
    r = numbers.axial_ratio
    c = max((s.cable.internal_damping * numbers.omega_forcing / s.cable.ae for s in scene.sections), default=0.0)
    den = abs(complex(1.0 - r * r, c))
    return math.inf if den == 0.0 else r * r / den


def static_bow_error(numbers: SceneNumbers) -> float:
    """Body error of a straight cable that cannot bow under a current: sag / chord of a uniformly loaded
    string, q L / (8 T), amplified like the body's swing near its resonance, 1 / |1 - (omega/omega_swing)^2|
    (at most SWING_AMPLIFICATION: drag bounds it)."""
    detune = abs(1.0 - (numbers.omega_forcing / numbers.omega_swing) ** 2) if numbers.omega_swing > 0 else 1.0
    return min(SWING_AMPLIFICATION, 1.0 / max(detune, 1e-12)) * numbers.static_bow


def continuum_errors(scene: Scene, numbers: SceneNumbers, largest_tension: float) -> dict:
    """{"wang": {body, tension}, n: {body, tension} for n in :func:`continuum_counts`} against the
    continuous cable (:mod:`.continuum`), without floors."""
    angle = static_angle(scene)
    kw = {"forcing": list(numbers.forcing)}
    kw["parts"] = continuum.forcing_members(scene, angle, kw["forcing"])      # once for the dozen responses below
    ref = continuum.response(scene, angle, "exact", **kw)
    out = {"wang": continuum.relative_errors(continuum.response(scene, angle, "wang", **kw), ref, largest_tension)}
    counts = continuum_counts(scene)
    for n in counts:
        out[n] = continuum.relative_errors(continuum.response(scene, angle, "segmented", n, **kw), ref, largest_tension)
    if numbers.string_ratio > LOCAL_STRING_RATIO:
        # near a string mode the string bulges between its ends: its drag linearized element by element too
        from ..model.segmented import drag_points
        ref_l, table = local_drag.body_responses(scene, angle, [k for k in counts if k <= LOCAL_MAX_N],
                                                 lambda n: drag_points(scene, n), forcing=kw["forcing"])
        keys = [k for k in ("x_b", "y_b", "z_b") if k in ref_l]           # z_b: the sway across the flow (3-D)
        a_ref = max(max(ref_l[k] for k in keys), 1e-300)
        out["local"] = {n: {"body": max(abs(got[k] - ref_l[k]) for k in keys) / a_ref, "tension": 0.0}
                        for n, got in table.items()}
    return out


def estimate_errors(scene: Scene, numbers: SceneNumbers, response: LinearResponse) -> dict:
    """{rung: {"body": e, "tension": e, "note": str}} estimated against the converged segmented cable.

    The segmented entry ``segmented_1`` is the error at N = 1 with its ``order`` and the continuum
    table ``continuum`` ({N: {body, tension}}): ``segmented_error(errors, N)``.
    """
    t_max = max(response.largest_tension, 1e-300)
    d_t = max(response.tension_amplitude.values())
    cont = continuum_errors(scene, numbers, t_max)
    e_wang = min(1.0, max(cont["wang"]["body"], static_bow_error(numbers)))
    floor = numbers.tension_floor
    slack = response.least_tension < floor + SLACK_MARGIN * numbers.tension_static
    e_wang = max(e_wang, RESOLUTION)
    t_wang = max(min(1.0, cont["wang"]["tension"]), RESOLUTION)
    wang = {"body": e_wang, "tension": t_wang if not slack else math.inf,
            "note": "straight cable vs the continuous string and rod (string/rod dynamic stiffness) and its static bow"}
    if slack:
        wang["body"] = math.inf
        wang["note"] = (f"partial slack predicted: least tension of the linear response {response.least_tension:.4g} N "
                        f"vs floor {floor:.4g} N (static {numbers.tension_static:.4g} N); one stretch coordinate "
                        "cannot make part of the cable slack")
    f_ax = axial_factor(scene, numbers)
    k_eff = min(s.cable.spring_constant for s in scene.sections)
    body_qs = f_ax * (d_t / k_eff) / max(response.body_amplitude, 1e-300)
    stretch = {"body": body_qs, "tension": f_ax * d_t / t_max}
    qs = {"body": wang["body"] + stretch["body"], "tension": wang["tension"] + stretch["tension"], "stretch": stretch,
          "note": f"stretch quasi-static: omega/omega_ax = {numbers.axial_ratio:.3g} misses {f_ax:.2g} of the "
                  "dynamic stretch"}
    if f_ax >= 0.5:
        qs.update(body=math.inf, tension=math.inf, stretch={"body": math.inf, "tension": math.inf},
                  note=f"forcing near or above the axial frequency (omega/omega_ax = "
                       f"{numbers.axial_ratio:.3g}): the stretch is not quasi-static")
    freq = dict(wang)
    if not numbers.single_frequency:
        freq.update(body=math.inf, tension=math.inf, note="no single forcing frequency: no periodic steady state")
    order = SLACK_ORDER if slack else ORDER
    seg = {"body": e_wang if not slack else 1.0, "tension": t_wang if not slack else 1.0, "order": order,
           "continuum": {str(n): v for n, v in cont.items() if isinstance(n, int)} if not slack else {},
           "continuum_local": {str(n): v for n, v in cont.get("local", {}).items()} if not slack else {},
           # at least the static bow's polygon error (see segmented_error)
           "floor": static_bow_error(numbers),
           "note": ("N lumped elements vs the continuous cable (one drag damping, and element by element near a "
                    "string mode), at least the static bow's polygon error x N^-2"
                    if not slack else
                    f"partial slack: the straight cable's O(1) error x N^-{order:g} (snap loads converge slowly)")}
    return {"frequency": freq, "quasi-static": qs, "wang": wang, "segmented_1": seg}


def _continuum_at(table: dict, n: int, key: str) -> float:
    """The continuum estimate at ``n`` elements: tabulated at CONTINUUM_N, interpolated in between as the
    power law through the two neighbours (e ~ N^-s, s from the pair); the nearest N above instead would
    state the error of up to twice the elements (a 5-element cable got the 8-element estimate)."""
    ns = sorted(int(k) for k in table)
    if not ns:
        return 0.0
    if n <= ns[0] or n >= ns[-1]:
        return float(table[str(ns[0] if n <= ns[0] else ns[-1])][key])
    lo = max(k for k in ns if k <= n)
    hi = min(k for k in ns if k >= n)
    e_lo, e_hi = float(table[str(lo)][key]), float(table[str(hi)][key])
    if hi == lo or e_lo <= 0.0 or e_hi <= 0.0:
        return max(e_lo, e_hi) if hi != lo else e_lo
    s = math.log(e_lo / e_hi) / math.log(hi / lo)
    return e_lo * (n / lo) ** -s


def segmented_error(errors: dict, n: int) -> dict:
    """Estimated errors of the segmented rung with ``n`` elements per section: the continuum estimates at
    ``n`` (:func:`_continuum_at`; the larger of the one-damping string's and, near a string mode, the
    element-by-element one's, :mod:`.local_drag`), and no less than ``floor`` x n^-ORDER, the static bow's
    error (a polygon of n chords inscribed in the bowed cable leaves 1 / n^2 of its sag, which the
    straight-line continuum does not have).

    Forced at or above the first string mode the floor was the straight cable's error (Richardson from
    N = 1), because on random heavy-6 (omega/omega_string = 1.55) the linear estimates fell 5-10x short:
    4.4 / 0.46 / 1.9 % at N = 4 / 6 / 8 against N = 64, the continuum 0.47 / 0.17 / 0.22 %. Those runs were
    7 periods with 3 of ramp, the window starting at 15.5 s, before :func:`settling_time` (16.8 s): their
    body surge x_b was 0.128 m at N = 64 against 0.0121 m settled. Settled (20 periods) the errors are
    0.10 / 0.046 / 0.19 % (N = 32 is 0.009 % from N = 64), within 3x of the continuum's and the local
    estimate's (0.27 / 0.12 / 0.19 %). The estimates speak of the settled response; a run whose statistics
    window starts before :func:`settling_time` is told so (:func:`cablesys.ladder.choice.choose` warns) instead
    of every settled run paying for that floor (heavy1000: N = 10 where N = 6 is within the tolerance).
    Under partial slack (no continuum table) the straight cable's error x n^-SLACK_ORDER."""
    base = errors["segmented_1"]
    table, local = base.get("continuum", {}), base.get("continuum_local", {})
    if not table:
        scale = float(n) ** -base.get("order", ORDER)
        return {k: max(base[k] * scale, RESOLUTION) for k in ("body", "tension")} | {"note": base["note"]}
    bow = base.get("floor", 0.0) * float(n) ** -ORDER
    out = {k: max(_continuum_at(table, n, k), RESOLUTION) for k in ("body", "tension")}
    out["body"] = max(out["body"], _local_at(local, n) if local else 0.0, bow)
    return out | {"note": base["note"]}


def _local_at(local: dict, n: int) -> float:
    """The element-by-element estimate at ``n`` (:mod:`.local_drag`): interpolated as :func:`_continuum_at`
    within its table (up to LOCAL_MAX_N), beyond it the last entry x (N_last / n)^ORDER: one drag point per
    element from N ~ 7 on, where the chain converges at second order (tests/test_ladder_continuum.py);
    holding the last entry stated a 300 m wire surged at T = 10 s unreachable at N = 128."""
    last = max(int(k) for k in local)
    if n <= last:
        return _continuum_at(local, n, "body")
    return float(local[str(last)]["body"]) * (last / n) ** ORDER


def quasistatic_segmented_error(errors: dict, n: int) -> dict:
    """Estimated errors of the quasi-static segmented rung (``n`` elements, their stretches following the
    tension): the segmented cable's at ``n`` (:func:`segmented_error`) plus the part of the dynamic
    stretch a quasi-static stretch misses (the same r^2 / |1 - r^2 + i 2 zeta r| as the straight
    quasi-static rung, :func:`axial_factor`: the N-element cable's lowest stretch mode is the rod's with
    the body at its end, Wang's omega_ax to O(m L / M)); infinite where the quasi-static rung is invalid
    (forcing near the axial frequency, or partial slack: a quasi-static stretch cannot go slack)."""
    qs = errors["quasi-static"]
    stretch = qs.get("stretch")
    if stretch is None or not (math.isfinite(qs["body"]) and math.isfinite(qs["tension"])):
        return {"body": math.inf, "tension": math.inf, "note": qs["note"]}
    seg = segmented_error(errors, n)
    return ({k: seg[k] + stretch[k] for k in ("body", "tension")}
            | {"note": f"{seg['note']}; {qs['note']}"})


def check_response(response: LinearResponse) -> None:
    if not (math.isfinite(response.body_amplitude) and math.isfinite(response.largest_tension)):
        raise SolverError("the linear response used to choose the model is not finite (undamped resonance?)")


def rung_error(errors: dict, name: str, n: int = 1) -> dict:
    """Estimated errors of rung ``name`` with ``n`` elements per section (``errors`` from
    :func:`estimate_errors`): the segmented cable's at ``n`` (also for "steady", that model's steady state), the
    quasi-static segmented cable's for "quasi-static" with ``n`` > 1, else the rung's own entry."""
    if name in ("segmented", "steady"):
        return segmented_error(errors, n)
    if name == "quasi-static" and n > 1:
        return quasistatic_segmented_error(errors, n)
    return errors[name]
