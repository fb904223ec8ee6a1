"""The irregular sea at the top (cablesys/scene/sea.py): realised spectrum, seeds, RAO phase, loading."""

import dataclasses
import math
import tomllib

import numpy as np
import pytest

from cablesys.errors import ParameterError
from cablesys.examples import example_path
from cablesys.scene import TopMotion, default_scene, dump_scene, scene_from_dict
from cablesys.scene.sea import MotionRAO, SeaSpectrum, top_transfer


def _periodogram(t, y):
    """One-sided spectral density estimate (m^2 s/rad) on omega_j = 2 pi j / T."""
    n, dt = len(y), t[1] - t[0]
    Y = np.fft.rfft(y)
    omega = 2 * np.pi * np.fft.rfftfreq(n, dt)
    S = 2 * np.abs(Y) ** 2 * dt / (2 * np.pi * n)
    return omega, S


def test_realised_sea_matches_target_hs_and_tp():
    """A long realisation: Hs = 4 std within 2 %, spectral peak within one frequency bin of Tp."""
    sea = SeaSpectrum(hs=2.5, tp=10.0, n_components=400, seed=3)
    t = np.arange(0.0, 6 * 3600.0, 0.25)
    eta = sea.elevation(t)
    assert 4 * np.std(eta) == pytest.approx(2.5, rel=0.02)
    w, a, _ = sea.components()
    dw = (sea.band()[1] - sea.band()[0]) / sea.n_components
    k = int(np.argmax(a))
    assert abs(w[k] - 2 * np.pi / 10.0) <= 1.5 * dw    # the largest component sits in the peak bin
    omega, S = _periodogram(t, eta)
    # smoothed periodogram: its peak within one design bin of omega_p, its area = m0
    win = max(1, round(dw / (omega[1] - omega[0])))
    Ss = np.convolve(S, np.ones(win) / win, mode="same")
    assert abs(omega[np.argmax(Ss)] - 2 * np.pi / 10.0) <= dw
    assert np.trapezoid(S, omega) == pytest.approx(sea.hs**2 / 16, rel=0.02)


def test_same_seed_same_series_other_seed_other_series():
    t = np.linspace(0, 300, 1201)
    a = SeaSpectrum(hs=2.0, tp=8.0, seed=7).elevation(t)
    b = SeaSpectrum(hs=2.0, tp=8.0, seed=7).elevation(t)
    c = SeaSpectrum(hs=2.0, tp=8.0, seed=8).elevation(t)
    assert np.array_equal(a, b)
    assert np.max(np.abs(a - c)) > 0.1


def test_pure_heave_rao_phase_convention():
    """Heave |R| = 0.5 leading the wave by 30 deg: y_s(t) = -0.5 eta(t + 30 deg / omega) (y down)."""
    w0 = 2 * np.pi / 10.0
    sea = SeaSpectrum(kind="pierson-moskowitz", hs=1.0, tp=10.0, n_components=2, omega_min=w0 - 1e-4,
                      omega_max=w0 + 1e-4, seed=1)
    rao = MotionRAO(omega=(0.1, 2.0), heave_amplitude=(0.5, 0.5), heave_phase_deg=(30.0, 30.0))
    top = TopMotion(spectrum=sea, rao=rao)
    assert top.x == ()                       # no surge given
    t = np.linspace(0, 60, 601)
    y = sum(s.amplitude * np.sin(s.frequency * t + s.phase) for s in top.y)
    w, a, e = sea.components()
    expected = -0.5 * sum(ak * np.sin(wk * t + ek + np.radians(30.0)) for wk, ak, ek in zip(w, a, e))
    np.testing.assert_allclose(y, expected, atol=1e-12)
    _, Y, _ = top_transfer(rao, [w0])
    assert Y[0] == pytest.approx(-0.5 * np.exp(1j * np.radians(30.0)))


def test_without_rao_the_top_heaves_with_the_surface():
    sea = SeaSpectrum(hs=1.5, tp=7.0, n_components=30)
    top = TopMotion(spectrum=sea)
    t = np.linspace(0, 100, 501)
    y = sum(s.amplitude * np.sin(s.frequency * t + s.phase) for s in top.y)
    np.testing.assert_allclose(y, -sea.elevation(t), atol=1e-12)


def test_waves_at_cable_have_the_sea_elevation_at_x0():
    """Wang eq. 26 component k: a sin(n x - sigma t + phase) equals a_k sin(omega_k t + eps_k) at x = 0."""
    sea = SeaSpectrum(hs=2.0, tp=9.0, n_components=20, waves_at_cable=True)
    scene = default_scene().replace(top_motion=TopMotion(spectrum=sea))
    waves = scene.environment.waves
    assert len(waves) == 20
    g = scene.environment.gravity
    t = np.linspace(0, 50, 201)
    eta = sum(wv.amplitude * np.sin(-np.sqrt(2 * np.pi * g / wv.length) * t + wv.phase) for wv in waves)
    np.testing.assert_allclose(eta, sea.elevation(t), atol=1e-9)
    assert np.allclose([2 * np.pi * g / wv.length for wv in waves], sea.components()[0] ** 2)


def test_dumped_scene_reads_back_without_doubling_the_sea():
    sea = SeaSpectrum(hs=2.0, tp=9.0, n_components=12, waves_at_cable=True)
    scene = default_scene().replace(top_motion=TopMotion(spectrum=sea))
    again = scene_from_dict(tomllib.loads(dump_scene(scene)))
    assert len(again.top_motion.y) == len(scene.top_motion.y)
    assert len(again.environment.waves) == 12


def test_bad_sea_input_is_named():
    with pytest.raises(ParameterError, match="top_motion.spectrum.kind"):
        SeaSpectrum(kind="bretschneider-ish", hs=1.0, tp=8.0)
    with pytest.raises(ParameterError, match="top_motion.rao.heave_amplitude"):
        MotionRAO(omega=(0.5, 1.0), heave_amplitude=(1.0,))
    with pytest.raises(ParameterError, match="top_motion.spectrum.spreading_n"):
        SeaSpectrum(hs=1.0, tp=8.0, spreading_n=-1.0)
    with pytest.raises(ParameterError, match="top_motion.spectrum.spreading_n.*top_motion.vessel"):
        TopMotion(spectrum=SeaSpectrum(hs=1.0, tp=8.0, spreading_n=2.0),
                  rao=MotionRAO(omega=(0.5, 1.0), heave_amplitude=(1.0, 1.0)))


def test_rao_from_csv_file(tmp_path):
    f = tmp_path / "rao.csv"
    f.write_text("omega,surge_amplitude,surge_phase_deg,heave_amplitude,heave_phase_deg\n"
                 "0.2,1.0,90,1.0,0\n2.0,0.0,0,0.2,-90\n")
    r = MotionRAO(file=str(f))
    assert r.omega == (0.2, 2.0) and r.file == ""
    assert abs(r("heave", 1.1)) == pytest.approx(0.6)


def test_rov_lift_example_loads_with_sea_limits_and_design():
    data = tomllib.loads(example_path("rov-lift").read_text())
    scene = scene_from_dict(data)
    assert scene.top_motion.spectrum.tp == 10.0
    assert len(scene.top_motion.y) > 10 and len(scene.top_motion.x) > 5
    assert scene.limits.working_load == pytest.approx(630e3 / 5)
    assert scene.design["ae_bounds"]
    assert math.isclose(scene.cable.length, 500.0)
    assert dataclasses.replace(scene, name="x").top_motion == scene.top_motion


def test_directional_spreading_draws_its_cos_n_law_and_the_linear_sea_response_integrates_it():
    """A cos^n spread sea (DNV-RP-C205 sec. 3.5.8): the spreading integrates to 1 and E[cos^2(theta - heading)] =
    (n + 1) / (n + 2) in closed form, by its quadrature and, to sampling error, over the realised components'
    directions; spreading keeps the frequencies, phases and heave (direction-free) of the long-crested sea; the
    crane tip's sway variance realised in the time domain (sum of the sinusoids' a^2 / 2, each component through the
    vessel RAO at its own direction), averaged over 8 seeds, equals the spectral one sum_j w_j int S |Z(omega, theta_j)|^2 d omega."""
    from cablesys.scene.vessel import HeadingRAO, VesselRAO
    n = 2.0
    sea = SeaSpectrum(hs=3.0, tp=9.0, heading_deg=30.0, spreading_n=n, n_components=3000, seed=4)
    grid = np.linspace(-60.0, 120.0, 20001)
    assert np.trapezoid(sea.spreading(grid), np.radians(grid)) == pytest.approx(1.0, rel=1e-6)
    theta, w = sea.direction_quadrature()
    assert np.sum(w * np.cos(np.radians(theta - 30.0)) ** 2) == pytest.approx((n + 1) / (n + 2), rel=1e-10)
    dirs = sea.directions()
    assert np.all(np.abs(dirs - 30.0) <= 90.0)
    assert np.mean(np.cos(np.radians(dirs - 30.0)) ** 2) == pytest.approx((n + 1) / (n + 2), abs=0.015)
    flat = SeaSpectrum(hs=3.0, tp=9.0, heading_deg=30.0, n_components=3000, seed=4)
    for a, b in zip(flat.components(), sea.components()):
        np.testing.assert_array_equal(a, b)
    heave = [TopMotion(spectrum=s).y for s in (flat, sea)]
    assert heave[0] == heave[1]
    omega = (0.3, 0.6, 0.9, 1.5)
    beam = lambda b, v: tuple(abs(math.sin(math.radians(b))) * x for x in v)    # sway and roll in beam seas only
    tables = tuple(HeadingRAO(heading_deg=b, surge_amplitude=(1.0, 0.8, 0.4, 0.1), sway_amplitude=beam(b, (0.9, 0.7, 0.3, 0.1)),
                              heave_amplitude=(1.0, 0.9, 0.5, 0.1), roll_amplitude=beam(b, (2.0, 3.0, 1.0, 0.2)))
                   for b in (0.0, 90.0, 180.0))
    vessel = VesselRAO(omega=omega, headings=tables, lever_arm=(10.0, 15.0, 20.0))
    realised = np.mean([sum(0.5 * s.amplitude ** 2 for s in TopMotion(spectrum=dataclasses.replace(sea, seed=k),
                                                                         vessel=vessel).z) for k in range(8)])
    om = np.linspace(*sea.band(), 4000)
    spectral = sum(wj * np.trapezoid(sea.density(om) * np.abs(top_transfer(vessel, om, float(tj))[2]) ** 2, om)
                   for tj, wj in zip(theta, w))
    assert realised == pytest.approx(spectral, rel=0.06)      # 8 seeds: one's sampling scatter is ~6 %, the mean's ~2 %
    long_crested = np.trapezoid(flat.density(om) * np.abs(top_transfer(vessel, om, 30.0)[2]) ** 2, om)
    assert abs(spectral / long_crested - 1.0) > 0.1          # the spreading matters for this sway


def test_a_spread_sea_at_the_cable_is_three_dimensional_and_reads_back():
    """With waves_at_cable each realised wave travels its component's direction: the scene runs the 3-D equations,
    and a dumped scene reads back with its waves once, their headings kept."""
    sea = SeaSpectrum(hs=2.0, tp=9.0, n_components=12, waves_at_cable=True, spreading_n=4.0, seed=2)
    scene = default_scene().replace(top_motion=TopMotion(spectrum=sea))
    assert scene.three_d and "environment.waves[0].heading_deg" in scene.three_d_fields()
    headings = [w.heading_deg for w in scene.environment.waves]
    np.testing.assert_allclose(headings, sea.directions(), rtol=0, atol=1e-12)
    again = scene_from_dict(tomllib.loads(dump_scene(scene)))
    assert [w.heading_deg for w in again.environment.waves] == pytest.approx(headings, abs=1e-9)
    long_crested = default_scene().replace(top_motion=TopMotion(spectrum=dataclasses.replace(sea, spreading_n=0.0)))
    assert not long_crested.three_d
