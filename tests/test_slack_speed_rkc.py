"""Runge-Kutta-Chebyshev (cablesys.time_domain.rkc) and its use by the slack extrapolation.

Closed forms: the stability polynomial agrees with exp(z) to second order and its real stability interval
is ~0.65 s^2 (Sommeijer, Shampine & Verwer 1997: 2/3 (s^2 - 1)(1 - 2 eps / 15) with eps = 2/13); on a stiff
non-autonomous equation with a known solution the step converges at second order. The stage count chosen
for a spectrum is stable on every eigenvalue and one stage fewer is not. The compiled loop steps a
segmented cable as RK4 at its stable step does (the same series to the time-step error), and on a wire
whose Voigt damping makes the element modes stiff the extrapolation's settings take it with fewer
right-hand sides per output than RK4.
"""

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

import cablesys
from cablesys.errors import ParameterError
from cablesys.ladder import RungCache
from cablesys.ladder import extrapolation as X
from cablesys.ladder.rungs import rung_scene
from cablesys.ladder.run_settings import start
from cablesys.scene import load_scene
from cablesys.time_domain import IntegratorSettings, rkc, simulate
from cablesys.time_domain.failures import spectrum


def test_stability_polynomial_is_second_order_with_a_long_real_interval():
    for s in (2, 3, 5, 8):
        z = np.array([1e-3, -1e-3, 1e-3j, -2e-3 + 1e-3j])
        resid = np.abs(rkc.amplification(z, s) - (1 + z + z**2 / 2))
        assert np.all(resid < 1.0 * np.abs(z) ** 3), (s, resid)          # R = exp(z) + O(z^3)
    for s in (4, 8, 16):
        x = -np.linspace(0.0, 1.0, 400001) * s * s
        beta = -x[np.argmax(np.abs(rkc.amplification(x, s)) > 1 + 1e-12)]
        closed = 2.0 / 3.0 * (s * s - 1) * (1 - 2 * rkc.EPS / 15)
        assert beta == pytest.approx(closed, rel=0.02), (s, beta, closed)
    with pytest.raises(ParameterError, match="stages"):
        rkc.coefficients(1)


def test_step_converges_at_second_order_on_a_forced_equation():
    """y' = lam (y - cos t) - sin t, y(0) = 1: y = cos t (lam = -2; the stages' time arguments c_j h matter). The
    error constant depends on s, so s is fixed along each sequence. Stiff (h lam << -1) the error of a Chebyshev
    method reaches h^2 only for small steps (its internal stages are first order: Verwer 1996); the cable's runs
    are checked against RK4 instead (below)."""
    lam = -2.0
    f = lambda y, t: lam * (y - math.cos(t)) - math.sin(t)
    for s in (4, 8):
        errs = []
        for n in (20, 40, 80, 160):
            h, y = 1.0 / n, 1.0
            for i in range(n):
                y = rkc.step(f, y, i * h, h, s)
            errs.append(abs(y - math.cos(1.0)))
        orders = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
        assert np.all(np.abs(orders[1:] - 2.0) < 0.1), (s, errs, orders)


def test_stages_are_the_fewest_that_keep_the_spectrum_stable():
    eig = np.array([-2.0e4, -300.0 + 400.0j, -300.0 - 400.0j, -5.0 + 20.0j])
    h = 2e-3
    s = rkc.stages_for(h, eig)
    assert s is not None and 0.65 * s * s >= 0.9 * h * 2.0e4
    assert np.all(np.abs(rkc.amplification(h * eig, s)) <= 1.0)
    assert np.any(np.abs(rkc.amplification(h * eig, s - 1)) > 0.97)
    assert rkc.stages_for(h, [1e3j]) is None           # an undamped mode far up the imaginary axis: no strip reaches it


def damped_wire(n: int):
    """60 m of 30 mm wire (C_I 1e5 N s) under a 200 kg-in-water cage, the ROV-lift example's sea: at N elements the
    Voigt damping's real eigenvalue ~ -4 C_I / (m l_e^2) sets RK4's step."""
    scene = load_scene(Path(cablesys.__file__).parent / "data" / "rov_lift.toml")
    scene = scene.replace_section(0, cable={"length": 60.0, "tension_ref": 2958.8}, body={"weight": 1961.3})
    return rung_scene(scene.with_numerics(duration=2.0, output_step=0.01), "segmented", n)


def test_extrapolation_takes_rkc_where_the_damping_is_stiff_and_it_matches_rk4():
    sc = damped_wire(24)
    cache = RungCache()
    model = cache.model(sc, "segmented", 24)
    x0 = start(sc, model, cache)
    eig = spectrum(model, x0, 0.0, model.parameters(sc))
    lam = eig[np.argmax(np.abs(eig))]
    assert abs(lam.imag) < 1e-6 * abs(lam) and lam.real < -4 * 1e5 / (3.9 * (60.0 / 24) ** 2) * 0.5   # the damping's
    s = X.settings(sc, model, None, x0)
    s4 = X.settings(sc, model, "rk", x0)
    assert s.method == "rkc" and s4.method == "rk"
    assert s.stages * s.steps_per_output < X.RKC_GAIN * 4 * s4.steps_per_output
    h = sc.numerics.output_step / s.steps_per_output
    assert h <= X.element_travel_time(sc) * (1 + 1e-12)
    assert np.all(np.abs(rkc.amplification(h * eig, s.stages)) <= 1.0)
    r = simulate(sc, model=model, simulator=cache.simulator(model, sc.output_times, s), x0=x0)
    r4 = simulate(sc, model=model, simulator=cache.simulator(model, sc.output_times, s4), x0=x0)
    assert r.success and r4.success and r.stats["method"] == "rkc"
    for k in ("y_b", "x_b", "tension_top"):
        scale = max(np.ptp(r4[k]), 1e-9 * np.max(np.abs(r4[k])))
        assert np.max(np.abs(r[k] - r4[k])) < 1e-4 * scale, k
    # the same run at half the RKC step moves less than the RK4 difference bound: the step error is small
    half = dataclasses.replace(s, steps_per_output=2 * s.steps_per_output)
    r2 = simulate(sc, model=model, simulator=cache.simulator(model, sc.output_times, half), x0=x0)
    assert np.max(np.abs(r2["tension_top"] - r["tension_top"])) < 1e-4 * np.ptp(r4["tension_top"])


def test_rkc_settings_need_their_stages():
    with pytest.raises(ParameterError, match="stages"):
        IntegratorSettings(method="rkc", steps_per_output=4)
