"""The statistics' definitions (cablesys/statistics.py) on synthetic signals with known answers: a sinusoid, Gaussian
noise of a known spectrum, a constant and round-off noise, tensions that go below zero, crossed extremes."""

import math

import numpy as np
import pytest

from cablesys import statistics as st


def test_sinusoid():
    """A sin(2 pi t / P) + c: std A / sqrt(2), significant amplitude 2 std = sqrt(2) A, T_z = P, half the
    peak-to-peak A, extremes c +- A; MPM over D: c + std sqrt(2 ln(D / P))."""
    A, P, c = 1.7, 3.0, -4.0
    t = np.linspace(0.0, 30 * P, 30 * 200, endpoint=False)    # 30 whole periods, 200 samples a period
    s = st.time_domain(t, c + A * np.sin(2 * np.pi * t / P + 0.3), duration=3600.0)
    assert s["std"] == pytest.approx(A / math.sqrt(2), rel=1e-6)
    assert s["significant_amplitude"] == pytest.approx(math.sqrt(2) * A, rel=1e-6)
    assert s["zero_upcrossing_period_s"] == pytest.approx(P, rel=1e-9)
    # sampled extremes: within 1 - cos(pi / 200) = 1.2e-4 of the crests
    assert s["amplitude"] == pytest.approx(A, rel=2e-4)
    assert s["max"] == pytest.approx(c + A, abs=2e-4 * A) and s["min"] == pytest.approx(c - A, abs=2e-4 * A)
    assert s["mean"] == pytest.approx(c, abs=1e-9)
    assert s["most_probable_max"] == pytest.approx(c + A / math.sqrt(2) * math.sqrt(2 * math.log(3600.0 / P)), rel=1e-6)
    assert "zero_upcrossing_note" not in s


def _gaussian(sigma_target, seed):
    """Gaussian noise with a flat spectrum on [w1, w2] of variance sigma_target^2 (many random-phase components):
    m0 = sigma^2, m2 = sigma^2 (w2^3 - w1^3) / (3 (w2 - w1)), T_z = 2 pi sqrt(m0 / m2)."""
    rng = np.random.default_rng(seed)
    w1, w2, n = 0.5, 1.5, 400
    w = np.linspace(w1, w2, n)
    dw = w[1] - w[0]
    S = sigma_target**2 / (w2 - w1)
    t = np.arange(0.0, 20000.0, 0.2)
    y = np.zeros_like(t)
    for wk, ek in zip(w, rng.uniform(0, 2 * np.pi, n)):
        y += math.sqrt(2 * S * dw) * np.cos(wk * t + ek)
    m0 = S * dw * n
    m2 = S * dw * np.sum(w**2)
    return t, y, w, np.full(n, S), 2 * math.pi * math.sqrt(m0 / m2)


def test_gaussian_noise_of_known_sigma():
    """std = sigma, significant amplitude 2 sigma and T_z = 2 pi sqrt(m0 / m2) of its spectrum, within the sampling
    error of ~3000 up-crossings (a few %); the spectral route gives the same numbers by construction."""
    sigma = 0.8
    t, y, w, S, tz = _gaussian(sigma, seed=4)
    s = st.time_domain(t, y)
    assert s["std"] == pytest.approx(sigma, rel=0.03)
    assert s["significant_amplitude"] == pytest.approx(2 * sigma, rel=0.03)
    assert s["zero_upcrossing_period_s"] == pytest.approx(tz, rel=0.03)
    f = st.frequency_domain(w, S, duration=20000.0)
    assert f["std"] == pytest.approx(sigma, rel=0.01)
    assert f["zero_upcrossing_period_s"] == pytest.approx(tz, rel=0.01)
    assert f["significant_amplitude"] == pytest.approx(2 * f["std"])
    # the largest of ~3000 Rayleigh peaks lies near the MPM (its Gumbel scatter: sigma / sqrt(2 ln N) ~ 0.2 sigma)
    assert abs(s["max"] - s["most_probable_max"]) < 1.0 * sigma


@pytest.mark.parametrize("value", [0.0, 12.5, -3.0e4])
def test_constant_has_no_period_and_is_settled(value):
    """A constant: std 0, amplitudes 0, no T_z as a number (None with a reason), MPM = the value, settled."""
    t = np.linspace(0.0, 60.0, 601)
    y = np.full_like(t, value)
    s = st.time_domain(t, y, duration=3600.0)
    assert s["std"] == 0.0 and s["significant_amplitude"] == 0.0 and s["amplitude"] == 0.0
    assert s["zero_upcrossing_period_s"] is None and "resolution" in s["zero_upcrossing_note"]
    assert s["most_probable_max"] == s["most_probable_min"] == value
    assert st.settled(t, y) == (True, 0.0)


def test_round_off_noise_is_no_oscillation():
    """A steady tow held at 150 m with a 5.6e-12 m jitter: no T_z from the jitter's crossings, and settled even
    though the jitter's amplitude 'changes' by a large fraction between the halves (floor: 1 micrometre)."""
    rng = np.random.default_rng(1)
    t = np.linspace(0.0, 120.0, 2401)
    y = 150.0 + 5.6e-12 * rng.standard_normal(t.size) * np.where(t > 60.0, 2.0, 1.0)
    s = st.time_domain(t, y, floor=st.FLOORS["m"])
    assert s["zero_upcrossing_period_s"] is None
    assert s["most_probable_max"] == pytest.approx(s["mean"], abs=0.0)
    ok, change = st.settled(t, y, floor=st.FLOORS["m"])
    assert ok and change == 0.0
    # without the floor, the round-off resolution (1e-9 x 150 m) still hides it
    assert st.settled(t, y)[0]


def test_settled_sees_a_growing_amplitude():
    """A sinusoid whose amplitude grows 10 % over the window is not settled; the change is the relative
    difference of the halves' amplitudes."""
    t = np.linspace(0.0, 40.0, 4001)
    amp = 1.0 + 0.1 * t / 40.0
    ok, change = st.settled(t, amp * np.sin(2 * np.pi * t / 2.0), rtol=1e-3, floor=st.FLOORS["m"])
    a1, a2 = 1.0 + 0.1 * 19.5 / 40, 1.0 + 0.1 * 39.5 / 40        # last crests of each half (t = 19.5, 39.5 s)
    assert not ok and change == pytest.approx((a2 - a1) / a2, rel=0.02)


def test_tension_below_zero_reports_zero_and_the_slack_time():
    """A 'tension' T0 + A sin(w t) with A > T0 (a model without a rope's floor): every statistic >= 0, the slack
    time is the time below zero, the fraction 1/2 - asin(T0 / A) / pi of the run, and a note names the raw minimum."""
    T0, A, P = 300.0, 600.0, 5.0
    t = np.linspace(0.0, 20 * P, 20 * 1000 + 1)
    y = T0 + A * np.sin(2 * np.pi * t / P)
    s = st.time_domain(t, y, duration=3600.0, nonnegative=True)
    assert all(s[k] >= 0.0 for k in ("max", "min", "mean", "most_probable_max", "most_probable_min"))
    assert s["min"] == 0.0 and s["max"] == pytest.approx(T0 + A, rel=1e-6)
    frac = 0.5 - math.asin(T0 / A) / math.pi
    assert s["slack_time_s"] == pytest.approx(frac * t[-1], abs=20 * (t[1] - t[0]))   # 20 intervals, each to dt
    assert "-300" in s["note"]
    assert s["mean"] == pytest.approx(np.mean(np.maximum(y, 0.0)))


def test_gaussian_minimum_below_zero_is_zero_with_the_slack_probability():
    """A spectrum whose most probable minimum is below 0 N: reported as 0 with P(T < 0) = Phi(-mean / sigma)."""
    w = np.linspace(0.5, 1.5, 201)
    sigma, mean = 400.0, 600.0
    f = st.frequency_domain(w, np.full(w.size, sigma**2), duration=10800.0, mean=mean, nonnegative=True)
    assert f["most_probable_min"] == 0.0 and f["min"] == 0.0
    assert f["slack_probability"] == pytest.approx(0.5 * math.erfc(mean / sigma / math.sqrt(2)), rel=1e-9)
    assert f["slack_probability"] == pytest.approx(0.0668, abs=1e-4)           # Phi(-1.5)
    assert "slack" in f["note"]
    raw = st.frequency_domain(w, np.full(w.size, sigma**2), duration=10800.0, mean=mean)
    assert raw["most_probable_min"] < 0.0                                      # the injected case is below zero


def test_crossed_extremes_fall_back_to_bounding_ones():
    """An extrapolated record with max 1836 N below min 2613 N gets the fallback pair (which bound each other);
    a floored minimum stays at the floor; an uncrossed pair is kept."""
    rec = {"tension_top_max": 1836.0, "tension_top_min": 2613.0, "tension_bottom_max": 900.0,
           "tension_bottom_min": -20.0, "x_b_amplitude": -1e-3}
    fine = {"tension_top_max": 2700.0, "tension_top_min": 2500.0, "tension_bottom_max": 880.0,
            "tension_bottom_min": 10.0, "x_b_amplitude": 0.0}
    out, crossed = st.bound_extremes(rec, fine, floor=5.0)
    assert crossed == ["tension_top"]
    assert (out["tension_top_max"], out["tension_top_min"]) == (2700.0, 2500.0)
    assert (out["tension_bottom_max"], out["tension_bottom_min"]) == (900.0, 5.0)
    assert out["x_b_amplitude"] == 0.0
    assert all(out[k + "_max"] >= out[k + "_min"] for k in ("tension_top", "tension_bottom"))


def test_amplitude_change_on_an_absolute_floor():
    """A zero amplitude becoming 1e-12 m is no change; 1 mm becoming 2 mm is a change of 1/2."""
    assert st.amplitude_change(0.0, 1e-12, st.FLOORS["m"]) == 0.0
    assert st.amplitude_change(0.0, 0.0) == 0.0
    assert st.amplitude_change(1e-3, 2e-3, st.FLOORS["m"]) == pytest.approx(0.5)
    assert st.amplitude_change(1e-3, 2e-3, st.FLOORS["m"], scale=0.1) == pytest.approx(0.01)
    assert st.amplitude_change(0.1, 0.1 + 5e-7, st.FLOORS["m"], scale=0.1) == 0.0


def test_run_summary_settled_flag():
    """A TimeResult holding a steady tow (x_b constant with 5.6e-12 m jitter) is settled; one whose heave grows by
    10 % over the window is not, with the change of the amplitudes of the window's halves."""
    from cablesys.results import TimeResult
    rng = np.random.default_rng(2)
    t = np.linspace(0.0, 100.0, 2001)
    tow = TimeResult(time=t, data={"x_b": 80.0 + 5.6e-12 * rng.standard_normal(t.size), "y_b": np.full(t.size, 40.0)})
    body = tow.summary()["body"]
    assert body["settled"] and body["amplitude_change"] == 0.0
    grow = 1.0 + 0.1 * t / 100.0
    heave = TimeResult(time=t, data={"x_b": np.zeros(t.size), "y_b": 40.0 + grow * np.sin(2 * np.pi * t / 4.0)})
    body = heave.summary()["body"]          # no forcing period: the window is the second half, amplitude 1.05 .. 1.1
    assert not body["settled"] and body["amplitude_change"] == pytest.approx(0.025 / 1.1, rel=0.05)


def test_a_varying_series_without_a_period_has_no_most_probable_extremes():
    """A ramp varies (std > 0) but never crosses its mean upwards twice: no T_z, so no Rayleigh most probable
    extremes (None, not the mean under that name); a constant's are its value."""
    t = np.linspace(0.0, 10.0, 101)
    s = st.time_domain(t, 2.0 * t, duration=3600.0)
    assert s["std"] > 0 and s["zero_upcrossing_period_s"] is None
    assert s["most_probable_max"] is None and s["most_probable_min"] is None
    tension = st.time_domain(t, 100.0 - 2.0 * t, nonnegative=True)
    assert tension["most_probable_min"] is None and tension["min"] == pytest.approx(80.0)
