"""One statistics window per run (cablesys.statistics.window): the last 5 forcing periods, in the run's second
half, after the smooth start; shared by summary.json's groups, its amplitudes, the verdict's statistics and the
model ladder's error checks."""

import json

import numpy as np
import pytest

from cablesys import statistics as st
from cablesys.commands.run import write_run
from cablesys.ladder import metrics
from cablesys.profiles import statistics_window
from cablesys.scene import dale_scene
from cablesys.time_result import TimeResult
from cablesys.verdict import run_statistics
from cablesys.verdict import statistics_window as verdict_mask

T = np.linspace(0.0, 60.0, 1201)


def test_last_five_periods_of_the_second_half_after_the_ramp():
    assert statistics_window(T, period=6.0, settled_s=18.0) == (30.0, 60.0)      # 5 periods = the second half
    assert statistics_window(T, period=2.0, settled_s=6.0) == (50.0, 60.0)       # a long run: its last 5 periods
    # 5 periods of 10 s would start at 10 s, in the start-up transient: the second half (3 periods)
    assert statistics_window(T, period=10.0, settled_s=0.0) == (30.0, 60.0)
    assert statistics_window(T) == (30.0, 60.0)                                 # no periodic forcing: the half


def test_a_window_never_starts_inside_the_ramp_when_a_period_is_left():
    # a ramp over 52 s of 60: what follows it (2 periods of 4 s)
    assert statistics_window(T, period=4.0, settled_s=52.0) == (52.0, 60.0)
    # less than a period after the ramp: the last period, and the window says it is inside the ramp
    assert statistics_window(T, period=10.0, settled_s=55.0) == (50.0, 60.0)
    assert "inside the smooth start" in st.window(T, 10.0, 55.0)[2]
    # a run shorter than a forcing period still gets a window: its second half
    assert statistics_window(T, period=500.0) == (30.0, 60.0)


def test_given_window_wins_and_verdict_uses_the_same_window():
    assert statistics_window(T, (5.0, 9.0), period=1.0, settled_s=30.0) == (5.0, 9.0)
    result = TimeResult(time=T, data={"x_b": np.sin(T)}, forcing_period_s=6.0, ramp_s=18.0)
    mask = verdict_mask(T, None, result)
    assert (T[mask][0], T[mask][-1]) == result.statistics_window


def test_the_ladder_window_is_the_summary_window():
    # the ladder's mask and the result's window agree for every combination, ramps longer than half the run included
    for period, ramp in ((None, 0.0), (6.0, 18.0), (10.0, 0.0), (4.0, 52.0), (10.0, 55.0), (2.0, 45.0)):
        r = TimeResult(time=T, data={"x_b": np.sin(T)}, forcing_period_s=period, ramp_s=ramp)
        np.testing.assert_array_equal(metrics.window(T, period, ramp), r.window_mask())


@pytest.fixture(scope="module")
def dale_run(tmp_path_factory):
    import cablesys
    scene = dale_scene(omega_ratio=1.5, duration=12.0).with_numerics(model="as-built")
    result = cablesys.simulate(scene)
    out = tmp_path_factory.mktemp("run")
    write_run(scene, result, out, plot=False)
    return scene, result, json.loads((out / "summary.json").read_text())


def test_a_summary_names_one_window_and_everything_uses_its_samples(dale_run):
    scene, result, summary = dale_run
    period = metrics.forcing_period(scene)
    t0, t1 = summary["window"]["start_s"], summary["window"]["end_s"]
    assert summary["window_s"] == [t0, t1] and summary["statistics"]["window_s"][0] == t0
    assert t1 == result.time[-1] and t0 == pytest.approx(max(0.5 * t1, t1 - 5 * period), abs=1e-12)
    assert summary["window"]["how"]
    w = (result.time >= t0 - 1e-9 * t1) & (result.time <= t1 + 1e-9 * t1)
    assert 10 < w.sum() < result.time.size
    x, y, top = (np.asarray(result[k])[w] for k in ("x_b", "y_b", "tension_top"))
    half = lambda v: 0.5 * (v.max() - v.min())
    # the amplitudes, the body group, the verdict's statistics and the ladder's statistics: the same samples
    for got in (summary["amplitudes_m"]["x_b"], summary["body"]["x_amplitude_m"],
                run_statistics(result, scene.limits)["x_b"]["amplitude"],
                metrics.statistics(result, period, scene.top_motion.effective_ramp_s)["x_b_amplitude"]):
        assert got == pytest.approx(half(x), rel=1e-12, abs=1e-15)
    assert summary["amplitudes_m"]["y_b"] == pytest.approx(half(y), rel=1e-12)
    assert summary["amplitudes_N"]["tension_top"] == pytest.approx(half(top), rel=1e-12)
    ladder = metrics.statistics(result, period, scene.top_motion.effective_ramp_s)
    assert ladder["y_b_mean"] == pytest.approx(summary["body"]["y_mean_m"], rel=1e-12)
    # the summary's window maximum is located between these samples (cablesys.time_domain.peaks): its grid value is
    # the ladder's, and the refined one lies above it
    refined = {e["key"]: e for e in summary["peak_refinement"]["estimates"]}["tension.top_max_N"]
    assert ladder["tension_top_max"] == pytest.approx(refined["grid"], rel=1e-12)
    assert summary["tension"]["top_max_N"] == refined["refined"] >= refined["grid"]
    assert summary["amplitude_periods"] == pytest.approx((t1 - t0) / period, rel=1e-12)
