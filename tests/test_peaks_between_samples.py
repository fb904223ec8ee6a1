"""Tension peaks located between output samples (cablesys.time_domain.peaks): a snap shorter than the output
step and a taut harmonic stretch, against closed forms (free fall then M u'' = W - k u, Wang 1971 eq. 54 with
TENS = 0) and against the same run sampled 100x finer."""

import math

import numpy as np
import pytest

from cablesys.scene import Initial, Numerics
from cablesys.time_domain import simulate
from test_time_domain_slack import U0, W, bouncing_scene

M, K = 10.0, 1e5          # kg, N/m: the stretch period 2 pi sqrt(M/K) = 63 ms, the taut pulse ~31 ms
DURATION, STEP = 1.2, 0.07    # s: the output step longer than the taut pulse


def _scene(step, initial=Initial(phi=0.0, u=U0)):
    sc = bouncing_scene(duration=DURATION).replace_section(0, cable={"ae": K * 10.0})
    return sc.replace(initial=initial, numerics=Numerics(duration=DURATION, output_step=step, rtol=1e-10, atol=1e-10,
                                                         integrator="cvodes", drag_segments=2))


def _snap_closed_form():
    """Snap tension k (u_e + R) after a fall from u = U0 < 0 (u_e = W/k, R the taut oscillation's amplitude)."""
    g, w = W / M, math.sqrt(K / M)
    v1 = g * math.sqrt(2 * abs(U0) / g)
    return K * (W / K + math.hypot(W / K, v1 / w))


@pytest.fixture(scope="module")
def snap_runs():
    coarse = simulate(_scene(STEP))
    fine = simulate(_scene(STEP / 100))
    assert coarse.success and fine.success, (coarse.message, fine.message)
    return coarse, fine


def test_snap_peak_from_refinement_equals_the_run_sampled_100x_finer(snap_runs):
    coarse, fine = snap_runs
    s = coarse.summary()
    peak_fine = float(np.max(fine["tension_bottom"]))
    grid = float(np.max(coarse["tension_bottom"]))
    assert abs(grid - peak_fine) > 0.05 * peak_fine              # the output grid misses the snap
    assert s["tension_bottom_max_N"] == pytest.approx(peak_fine, rel=0.01)       # the check
    assert s["tension_bottom_max_N"] == pytest.approx(_snap_closed_form(), rel=0.01)
    assert s["tension_top_max_N"] == pytest.approx(peak_fine, rel=0.01)          # no cable mass: the same force
    assert s["peaks"].startswith("refined between samples (resolution ")
    est = {e["key"]: e for e in s["peak_refinement"]["estimates"]}["tension_bottom_max_N"]
    assert est["grid"] == pytest.approx(grid) and est["complete"]
    # the resolution says how far below the peak the refined value lies: the located snap load (Newton on
    # dF/dt = 0, an independent route) lies above it by that, to 20 %
    located = max(x.tension for x in coarse.snaps)
    assert located == pytest.approx(_snap_closed_form(), rel=1e-6)
    assert located - s["tension_bottom_max_N"] == pytest.approx(est["resolution"] * located, rel=0.2)
    assert 0 < est["resolution"] < 0.01


def test_minimum_and_window_extremes_stay_physical(snap_runs):
    coarse, _ = snap_runs
    s = coarse.summary()
    assert s["tension_bottom_min_N"] == 0.0              # slack: TENS = 0, never below 0 N in a summary
    for key in ("top_max_N", "bottom_max_N"):            # the window group refined too, never below its grid value
        est = {e["key"]: e for e in s["peak_refinement"]["estimates"]}[f"tension.{key}"]
        assert est["refined"] >= est["grid"]


def test_taut_harmonic_peak_matches_the_closed_form():
    """Taut from the static stretch with du/dt = v0: F = W + k (v0 / w) sin(w t), peak W + k v0 / w."""
    w, v0 = math.sqrt(K / M), 0.002
    initial = Initial(phi=0.0, u=W / K, u_rate=v0)
    r = simulate(_scene(0.02, initial).with_numerics(duration=0.07))     # one crest, at 15.7 ms, between samples
    assert r.success, r.message
    exact = W + K * v0 / w
    assert np.min(r["tension_bottom"]) > 0                     # stays taut: no switch
    assert abs(float(np.max(r["tension_bottom"])) - exact) > 1e-3 * exact    # the grid misses the crests
    s = r.summary()
    est = {e["key"]: e for e in s["peak_refinement"]["estimates"]}["tension_bottom_max_N"]
    assert s["tension_bottom_max_N"] == pytest.approx(exact, rel=1e-5)
    assert exact - s["tension_bottom_max_N"] == pytest.approx(est["resolution"] * exact, rel=0.05)   # the sampling error
    assert s["tension_bottom_min_N"] == pytest.approx(W - K * v0 / w, rel=1e-5)


def test_fixed_step_refinement_takes_the_integrators_own_steps():
    """RK4 with 10 steps per output: the refined peak is the largest of its own steps, the maximum of the same
    steps output one by one (steps_per_output = 1 on a 10x finer grid: the same arithmetic)."""
    w, v0 = math.sqrt(K / M), 0.002
    sc = _scene(0.02, Initial(phi=0.0, u=W / K, u_rate=v0)).with_numerics(duration=0.07, integrator="rk")
    coarse = simulate(sc.with_numerics(steps_per_output=10))
    steps = simulate(sc.with_numerics(output_step=0.002, steps_per_output=1))
    assert coarse.success and steps.success
    s = coarse.summary()
    assert s["peak_refinement"]["fine_per_interval"] == 10
    assert abs(float(np.max(coarse["tension_bottom"])) - float(np.max(steps["tension_bottom"]))) > 0.1   # N
    assert s["tension_bottom_max_N"] == pytest.approx(float(np.max(steps["tension_bottom"])), rel=1e-9)
    assert s["tension_bottom_max_N"] == pytest.approx(W + K * v0 / w, rel=1e-3)      # RK4 at h w = 0.2


def test_segmented_snap_and_top_peak_are_the_integrators_own_steps():
    """A 300 m segmented cable that goes slack and snaps (RK4, 10 steps per 50 ms output): the refined top
    tension and snap peak are the largest of its own steps, the maxima of the same run output step by step."""
    from test_segmented_slack import _rk4, _scene as heave_scene
    sc = heave_scene(5, 26.0)
    r, steps = _rk4(sc, 10), _rk4(sc.with_numerics(output_step=0.005), 1)
    s = r.summary()
    top = float(np.max(steps["tension_top"]))
    assert float(np.max(r["tension_top"])) < 0.97 * top                 # the 50 ms grid misses the top's snap
    assert s["tension_top_max_N"] == pytest.approx(top, rel=1e-9)
    est = {e["key"]: e for e in s["peak_refinement"]["estimates"]}["slack.snap_peak_N"]
    snap = next(x for x in r.snap_loads() if x.tension == est["grid"])      # the largest in the window
    near = np.abs(steps.time - snap.time) <= 0.1
    assert s["slack"]["snap_peak_N"] == pytest.approx(
        float(np.max(steps.profiles["element_tension"][near, snap.element])), rel=1e-9)
