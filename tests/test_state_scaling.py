"""State scaling (per-state absolute tolerances from the natural scales, cablesys.model.scales)."""

import math

import numpy as np
import pytest

from cablesys.ladder.auto import integrator_settings
from cablesys.model import build_model
from cablesys.model.scales import state_scale_values
from cablesys.scene import Body, Cable, Sinusoid, TopMotion, dale_scene
from cablesys.scene.scene import single_section_scene
from cablesys.time_domain import (
    IntegratorSettings,
    Simulator,
    initial_state,
    make_integrator,
)
from cablesys.time_domain.integrators import ScaledIntegrator, compiled_dae


def _ramped_dale(duration=10.0):
    """Dale with a one-period smooth start (the stretch mode is not rung by the start)."""
    base = dale_scene(duration=duration, output_step=0.1)
    tm = base.top_motion
    return base.replace(top_motion=TopMotion(x=tm.x, y=tm.y, ramp_s=2 * math.pi / tm.x[0].frequency))


def _run(model, scene, settings):
    p = model.parameters(scene)
    rec = Simulator(model, scene.output_times, settings).run(p, initial_state(scene, model, p))
    assert rec.success
    return rec


def test_wang_scales_are_the_static_stretch_the_swing_and_the_forcing_frequency():
    """Dale (Wang 1971 Table 1): u by T L / AE (eq. 46, 54: k = AE / L), phi by the top's amplitude
    over the length, rates by these times the forcing frequency."""
    sc = dale_scene()
    model = build_model(sc)
    S = state_scale_values(model, model.parameters(sc))
    c, top = sc.sections[0].cable, sc.top_motion
    u0 = c.tension_ref * c.length / c.ae
    phi = (abs(top.x[0].amplitude) + abs(top.y[0].amplitude)) / c.length
    w = top.x[0].frequency
    assert model.state_labels == ("phi", "u", "phi_rate", "u_rate")
    np.testing.assert_allclose(S, [phi, u0, phi * w, u0 * w], rtol=1e-12)
    # the static stretch is the steady state's (the initial u of the scene at rest, to its bow)
    x0 = initial_state(sc, model, model.parameters(sc))
    assert S[1] == pytest.approx(x0[1], rel=2e-2)


def test_segmented_scales_follow_the_element_stretch_closed_form():
    """The segmented model's scales: positions T h / AE (T = tension_ref, or W_b + w L / 2 without it;
    Wang eq. 46), rates max(top speed a omega, delta sqrt(AE / (m h^2))), with and without tension_ref."""
    w = 2 * math.pi / 10
    top = TopMotion(y=(Sinusoid(amplitude=1.0, frequency=w),))
    sc = single_section_scene(cable=Cable(length=300.0, tension_ref=4877.0, ae=4.0e7, diameter=0.025,
                                          mass_per_length=2.5, weight_per_length=19.6, segments=6),
                              body=Body(weight=1937.0, mass_x=2900.0, mass_y=2900.0), top_motion=top)
    for s, n, tension in ((sc, 6, 4877.0),
                          (sc.replace_section(0, cable={"tension_ref": 0.0, "segments": 3}), 3,
                           1937.0 + 19.6 * 300.0 / 2)):
        model = build_model(s)
        h = 300.0 / n
        delta = tension * h / 4.0e7
        speed = max(1.0 * w, delta * math.sqrt(4.0e7 / (2.5 * h**2)))
        S = state_scale_values(model, model.parameters(s))
        np.testing.assert_allclose(S, np.r_[np.full(2 * n, delta), np.full(2 * n, speed)], rtol=1e-12)


def test_scaled_integrator_returns_physical_states_and_its_own_compiled_function():
    """The scaled DAE is a function of its own (its own cache key); the wrapper takes and gives
    physical states, counts its steps, and agrees with the unscaled integrator to the tolerance."""
    sc = _ramped_dale(4.0)
    model = build_model(sc)
    p = model.parameters(sc)
    x0 = initial_state(sc, model, p)
    grid = np.linspace(0.0, 4.0, 41)
    pp = np.concatenate([p, [0.0, 1.0]])
    on = IntegratorSettings(method="cvodes", rtol=1e-9, atol=1e-9)
    off = IntegratorSettings(method="cvodes", rtol=1e-9, atol=1e-9, scaled=False)
    tight = IntegratorSettings(method="cvodes", rtol=1e-12, atol=1e-16, scaled=False, max_num_steps=10**6)
    Fs, Fu, Ft = (make_integrator(model, st, grid) for st in (on, off, tight))
    assert isinstance(Fs, ScaledIntegrator) and not isinstance(Fu, ScaledIntegrator)
    assert compiled_dae(model, on) is not compiled_dae(model, off)
    Xs, Xu, Xt = (np.array(F(x0=x0, p=pp)["xf"]) for F in (Fs, Fu, Ft))
    assert Fs.stats()["nsteps"] > 0
    # every state within 1e-3 of its range of the tight run (positions 1e-6); one SI atol = 1e-9
    # leaves the stretch rate (range 4e-6 m/s) ~10 % off, 100 times the scaled run's error
    rng = np.ptp(Xt, axis=1)
    err_s, err_u = (np.abs(X - Xt).max(axis=1) / rng for X in (Xs, Xu))
    assert np.all(err_s < 1e-3) and np.all(err_s[:2] < 1e-5), err_s
    assert err_u[3] > 100 * err_s[3], (err_u, err_s)
    # positional call like a casadi.Function
    np.testing.assert_array_equal(np.array(Fs(x0, pp)["xf"]), Xs)
    # a fixed-step method is never scaled (no error test for the scales to act on)
    assert not isinstance(make_integrator(model, IntegratorSettings(method="rk"), grid), ScaledIntegrator)


@pytest.mark.parametrize("method", ["cvodes-bdf2", "idas"])
def test_scaled_and_unscaled_agree_to_the_tolerance(method):
    """Same settings, scaled and not: both within the tolerance of a tight run on the ramped Dale
    scene (body to 1e-2 of its range, tension to 1e-2 of its dynamic range)."""
    sc = _ramped_dale()
    model = build_model(sc)
    ref = _run(model, sc, IntegratorSettings(method="cvodes", rtol=1e-11, atol=1e-11, max_num_steps=10**6))
    for scaled in (True, False):
        r = _run(model, sc, IntegratorSettings(method=method, rtol=1e-4, atol=1e-7, scaled=scaled))
        for k in ("x_b", "y_b", "tension_mid"):
            assert np.max(np.abs(r[k] - ref[k])) < 1e-2 * np.ptp(ref[k]), (scaled, k)


def test_ladder_tolerance_resolves_the_dynamic_tension():
    """The ladder's settings (BDF <= 2, rtol 1e-4, atol = rtol / 10 of each state's scale) on the
    ramped Dale scene: the tension series (whose dynamic range is 5 % of its mean: the stretch
    moves by 3e-6 m on 7e-5 m) within 1e-3 of its dynamic range of a tight run, the body within
    5e-3 of its range, and the tension no worse than with the former absolute atol = rtol / 1000
    (in SI: 3 % of the stretch's dynamic range, issue 13)."""
    sc = _ramped_dale()
    model = build_model(sc)
    settings = integrator_settings(sc, (1e-2, 2e-2))
    assert settings.scaled and settings.atol == pytest.approx(settings.rtol / 10)
    ref = _run(model, sc, IntegratorSettings(method="cvodes", rtol=1e-11, atol=1e-11, max_num_steps=10**6))
    r = _run(model, sc, settings)
    assert np.ptp(ref["tension_mid"]) < 0.1 * np.mean(ref["tension_mid"])
    err = {k: np.max(np.abs(r[k] - ref[k])) / np.ptp(ref[k]) for k in ("tension_mid", "x_b", "y_b")}
    assert err["tension_mid"] < 1e-3 and err["x_b"] < 5e-3 and err["y_b"] < 5e-3, err
    old = _run(model, sc, IntegratorSettings(method=settings.method, rtol=settings.rtol, atol=settings.rtol * 1e-3,
                                             scaled=False))
    assert err["tension_mid"] <= 2 * np.max(np.abs(old["tension_mid"] - ref["tension_mid"])) / np.ptp(ref["tension_mid"])


def test_every_model_kind_runs_scaled_to_the_tight_answer():
    """Two Wang sections (each u by its own static stretch), the quasi-static rung (angles only) and a
    top motion with a sampled series: scaled runs at rtol = atol = 1e-6 within 1e-3 of each body's
    range of a tight unscaled run."""
    import dataclasses

    from cablesys.model.quasistatic import build_quasistatic
    from cablesys.scene import Section, TimeSeries

    base = _ramped_dale(4.0)
    s = base.sections[0]
    cable = dataclasses.replace(s.cable, length=s.cable.length / 2, tension_ref=0.0)
    joint = dataclasses.replace(s.body, weight=0.01, mass_x=0.002, mass_y=0.002)
    two = base.replace(sections=(Section(cable=cable, body=joint), Section(cable=cable, body=s.body)))
    times = tuple(np.linspace(0.0, 5.0, 51))
    series = base.replace(top_motion=dataclasses.replace(
        base.top_motion, series=TimeSeries(times=times, x=tuple(0.01 * np.sin(times)), y=(0.0,) * 51)))
    cases = [(build_model(two), two, "y_b_2"), (build_quasistatic(base), base, "y_b"),
             (build_model(series), series, "x_b")]
    for model, sc, key in cases:
        S = state_scale_values(model, model.parameters(sc))
        assert S.shape == (2 * model.nq,) and np.all(S > 0)
        if model.n_sections == 2:
            # T_i = W_b,i + w L / 2 (no tension_ref): u_i by T_i L / AE, Wang (1971) eq. 46
            tension = [sc.sections[i].body.weight + cable.weight_per_length * cable.length / 2 for i in (0, 1)]
            np.testing.assert_allclose(S[[1, 3]], [t * cable.length / cable.ae for t in tension], rtol=1e-12)
        ref = _run(model, sc, IntegratorSettings(rtol=1e-11, atol=1e-13, scaled=False, max_num_steps=10**6))
        r = _run(model, sc, IntegratorSettings(rtol=1e-6, atol=1e-6))
        assert np.max(np.abs(r[key] - ref[key])) < 1e-3 * np.ptp(ref[key]), (model.kind, key)


@pytest.mark.slow
def test_state_scaling_study_quick(tmp_path):
    """studies/bench_state_scaling.py --quick: its rows mean what they say (the ladder's scaled
    default resolves the Dale tension to 1e-3 of its range; with the library's default tolerances
    the scaled stretch rate is two orders more accurate than one SI atol leaves it)."""
    import json
    import os
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    proc = subprocess.run([sys.executable, str(root / "studies" / "bench_state_scaling.py"), "--out", str(tmp_path),
                           "--quick"], check=False, cwd=root, env=dict(os.environ, MPLBACKEND="Agg"),
                          capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert (tmp_path / "bench_state_scaling.png").stat().st_size > 10_000
    res = json.loads((tmp_path / "bench_state_scaling.json").read_text())["results"][0]
    rows = {r["variant"]: r for r in res["rows"]}
    assert all(r["success"] for r in rows.values())
    assert rows["bdf2 scaled atol=rtol/10 (ladder)"]["error_over_range"]["tension_mid"] < 1e-3
    u_scaled = rows["cvodes rtol 1e-7 scaled atol=1e-9"]["error_over_range"]["u_rate"]
    u_si = rows["cvodes rtol 1e-7 unscaled atol=1e-9"]["error_over_range"]["u_rate"]
    assert u_scaled < 1e-2 * u_si
