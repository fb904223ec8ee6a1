"""Error estimates of each rung against the converged segmented cable (relative numbers).

Two errors per rung, as the tolerance names them: ``body`` (body-motion amplitude relative to
the largest body amplitude) and ``tension`` (tension extremes relative to the largest tension).

- quasi-static vs Wang: the stretch of a spring with mass driven at omega responds by
  1 / (1 - r^2 + i 2 zeta r) of its quasi-static value (r = omega / omega_ax, Voigt damping
  zeta r = C_I omega / (2 AE), Wang 1971 eq. 46), so the quasi-static tension and stretch miss the
  fraction r^2 / |1 - r^2 + i 2 zeta r| of their dynamic parts (the dynamic tension and the body
  amplitude come from Wang's own equivalent-linear response, :func:`linear_response`);
- Wang vs segmented: a straight chord cannot bow. The error grows with the sag the normal drag
  (current, and the motion's own drag) and the cable's inertia near its first string mode would
  give the real cable, relative to its chord (:func:`straight_cable_error`).
  Partial slack (least tension of the linear response below the floor) puts the straight cable
  outside its validity: infinite error;
- segmented with N elements: each element is a straight cable of length L / N, so the straight
  cable's error falls as N^-ORDER (checked a posteriori by the run at N/2, :mod:`.auto`).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..errors import SolverError
from ..linear import harmonic_response, linearize, steady_state
from ..linear.periodic import scene_input_amplitude
from ..scene import Scene
from .indicators import SceneNumbers
from .rungs import build_rung, rung_scene

DYNAMIC_BOW_GAIN = 2.0   # body-amplitude error per unit dynamic sag / chord (see straight_cable_error)
ORDER = 2.0         # convergence order of the segmented cable in N (taut; Dale study: 2-3)
SLACK_ORDER = 1.0   # with partial slack and snap loads (300 m wire at T = 6 s: 11 % at N = 15 vs N = 40)
SLACK_MARGIN = 0.05
SWING_AMPLIFICATION = 10.0
RESOLUTION = 1e-4    # estimates are not resolved below this (start-up transients, reference convergence)  # a least tension within 5 % of the static tension of the floor counts as slack


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
    sc = rung_scene(scene, "wang")
    model = model or build_rung(sc, "wang")
    p = model.parameters(sc)
    keys = ("tension_top", "tension_bottom", "tension")      # "tension": Wang's F_bc, the slack switch (eq. 54)
    if numbers.single_frequency and not scene.environment.waves:
        omega, Z = scene_input_amplitude(sc)
        h = harmonic_response(model, p, [omega], Z)
        if h.success:
            lab = list(h.output_labels)
            amp = lambda k: float(abs(h.output_amplitude[0][lab.index(k)]))
            mean = lambda k: float(np.real(h.output_mean[0][lab.index(k)]))
            return LinearResponse(omega=omega, body_amplitude=max(amp("x_b"), amp("y_b")),
                                  tension_mean={k: mean(k) for k in keys}, tension_amplitude={k: amp(k) for k in keys},
                                  stretch_amplitude=amp("u"), method="harmonic (describing function)")
    st = steady_state(model, p)
    lin = linearize(model, p, steady=st)
    omegas = np.array([w for w, _ in numbers.forcing]) if numbers.forcing else np.array([1e-6])
    amps = np.array([a for _, a in numbers.forcing]) if numbers.forcing else np.zeros(1)
    _, Y = lin.transfer(omegas)
    lab = list(lin.output_labels)
    gain = lambda k: float(np.sum(np.max(np.abs(Y[:, lab.index(k), :2]), axis=1) * amps))
    return LinearResponse(omega=numbers.omega_forcing, body_amplitude=max(gain("x_b"), gain("y_b")),
                          tension_mean={k: float(st.outputs[k]) for k in keys},
                          tension_amplitude={k: gain(k) for k in keys}, stretch_amplitude=gain("u"),
                          method="exact linearization (undamped; a bound away from resonance)")


def axial_factor(scene: Scene, numbers: SceneNumbers) -> float:
    """r^2 / |1 - r^2 + i 2 zeta r|: the part of the dynamic stretch the quasi-static rung misses."""
    r = numbers.axial_ratio
    c = max((s.cable.internal_damping * numbers.omega_forcing / s.cable.ae for s in scene.sections), default=0.0)
    den = abs(complex(1.0 - r * r, c))
    return math.inf if den == 0.0 else r * r / den


def straight_cable_error(numbers: SceneNumbers) -> float:
    """Relative body-amplitude error of one straight cable vs the converged segmented one.

    - static bowing under current (sag / chord of a uniformly loaded string, q L / 8 T), amplified
      like the body's swing near its resonance, 1 / |1 - (omega/omega_swing)^2| (at most
      SWING_AMPLIFICATION: drag bounds it);
    - dynamic bowing under the drag of the motion itself: DYNAMIC_BOW_GAIN x its sag / chord;
    - string inertia: a string of tension T driven at its end has the dynamic stiffness
      (T/L) kL cot kL = (T/L) (1 - (kL)^2/3 - (kL)^4/45 - ...), kL = pi omega / omega_string; the
      straight cable (a linear shape, Wang 1971 eq. 22-25) keeps the first two terms exactly and
      misses (pi^4/45) (omega/omega_string)^4, times the part of the top motion normal to the cable.
    Capped at 1: above the first string mode the straight cable is simply wrong (O(1) errors).
    The two gains were set on the Dale scene and six random short-cable scenes against the
    segmented cable (tests/test_ladder_random.py, studies/model_ladder.py); they are estimates.
    """
    sr = numbers.string_ratio if math.isfinite(numbers.string_ratio) else 0.0
    detune = abs(1.0 - (numbers.omega_forcing / numbers.omega_swing) ** 2) if numbers.omega_swing > 0 else 1.0
    amp = min(SWING_AMPLIFICATION, 1.0 / max(detune, 1e-12))
    string = numbers.transverse_fraction * math.pi**4 / 45.0 * sr**4
    return min(1.0, amp * numbers.static_bow + DYNAMIC_BOW_GAIN * numbers.dynamic_bow + string)


def estimate_errors(scene: Scene, numbers: SceneNumbers, response: LinearResponse) -> dict:
    """{rung: {"body": e, "tension": e, "note": str}} estimated against the converged segmented cable.

    The segmented entry is the error at N = 1 scaled by N^-ORDER: ``segmented_error(errors, N)``.
    """
    t_max = max(response.largest_tension, 1e-300)
    d_t = max(response.tension_amplitude.values())
    e_wang = straight_cable_error(numbers)
    floor = numbers.tension_floor
    slack = response.least_tension < floor + SLACK_MARGIN * numbers.tension_static
    e_wang = max(e_wang, RESOLUTION)
    wang = {"body": e_wang, "tension": max(e_wang * max(d_t / t_max, 0.1), RESOLUTION) if not slack else math.inf,
            "note": "straight cable: bowing and string inertia (closed form)"}
    if slack:
        wang["body"] = math.inf
        wang["note"] = (f"partial slack predicted: least tension of the linear response {response.least_tension:.4g} N "
                        f"vs floor {floor:.4g} N (static {numbers.tension_static:.4g} N); one stretch coordinate "
                        "cannot make part of the cable slack")
    f_ax = axial_factor(scene, numbers)
    k_eff = min(s.cable.spring_constant for s in scene.sections)
    body_qs = f_ax * (d_t / k_eff) / max(response.body_amplitude, 1e-300)
    qs = {"body": wang["body"] + body_qs, "tension": wang["tension"] + f_ax * d_t / t_max,
          "note": f"stretch quasi-static: omega/omega_ax = {numbers.axial_ratio:.3g} misses {f_ax:.2g} of the "
                  "dynamic stretch"}
    if f_ax >= 0.5:
        qs.update(body=math.inf, tension=math.inf, note=f"forcing near or above the axial frequency (omega/omega_ax = "
                                                        f"{numbers.axial_ratio:.3g}): the stretch is not quasi-static")
    freq = dict(wang)
    if not numbers.single_frequency:
        freq.update(body=math.inf, tension=math.inf, note="no single forcing frequency: no periodic steady state")
    order = SLACK_ORDER if slack else ORDER
    seg = {"body": e_wang if not slack else 1.0, "tension": wang["tension"] if not slack else 1.0, "order": order,
           "note": f"error of one straight element, scaled by N^-{order:g}"
                   + (" (snap loads converge slowly)" if slack else "")}
    return {"frequency": freq, "quasi-static": qs, "wang": wang, "segmented_1": seg}


def segmented_error(errors: dict, n: int) -> dict:
    """Estimated errors of the segmented rung with ``n`` elements per section."""
    base = errors["segmented_1"]
    scale = float(n) ** -base.get("order", ORDER)
    return {"body": base["body"] * scale, "tension": base["tension"] * scale, "note": base["note"]}


def check_response(response: LinearResponse) -> None:
    if not (math.isfinite(response.body_amplitude) and math.isfinite(response.largest_tension)):
        raise SolverError("the linear response used to choose the model is not finite (undamped resonance?)")
