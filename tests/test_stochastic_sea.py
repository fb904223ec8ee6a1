"""The stochastic analysis in the scene's own irregular sea: the sea and the motion RAO its time-domain run realises
(cablesys.linear.stochastic.sea_inputs), checked on the top's motion, whose standard deviation is a quadrature of the
RAO table and the spectrum (an independent route: the table interpolated here, the JONSWAP formula of
cablesys.scene.spectra); what it cannot take is refused by name."""

import dataclasses
import math
import sys
from pathlib import Path

import numpy as np
import pytest

from cablesys.errors import ParameterError
from cablesys.scene import load_scene
from cablesys.scene.spectra import jonswap
from cablesys.linear.stochastic import sea_inputs, stochastic_response
from cablesys.sweeps.analyses import ModelCache, stochastic
from cablesys.examples import example_path


def _rov():
    return load_scene(example_path("rov_lift.toml"))


def _top_std(sc):
    """The standard deviations of the top's motion (x_s, y_s, z_s) the linearization is driven by in the scene's sea,
    sqrt(int |D|^2 S d omega) on its grid (sea_inputs), and the body's response to it (the stochastic linearization)."""
    model = ModelCache().model(sc)
    omega, S, D, weights = sea_inputs(sc, model)
    st = stochastic_response(model, model.parameters(sc), omega, S, direction=D, weights=weights, n_log2=8)
    assert st.success, st.message
    top = {k: math.sqrt(sum(w * np.trapezoid(np.abs(Dd[:, j]) ** 2 * S, omega) for w, Dd in zip(weights, D)))
           for j, k in enumerate(("x_s", "y_s", "z_s")) if j < D.shape[2]}
    return top, st


def _sigma(amplitude, sea, n=20001):
    """sqrt(int |R|^2 S d omega) over the sea's band on a fine grid, |R| interpolated linearly in the table."""
    lo, hi = sea.band()
    w = np.linspace(lo, hi, n)
    return math.sqrt(np.trapezoid(amplitude(w) ** 2 * jonswap(w, sea.hs, sea.tp, sea.gamma), w))


def test_the_stochastic_analysis_moves_the_top_by_the_scenes_rao_in_the_scenes_sea():
    sc = _rov()
    sea, rao = sc.top_motion.spectrum, sc.top_motion.rao
    out, ok, msg = stochastic(sc, {}, ModelCache())
    assert ok, msg
    assert (out["sea_hs_m"], out["sea_tp_s"]) == (2.5, 10.0) and "[top_motion.rao]" in out["sea"]
    heave = _sigma(lambda w: np.interp(w, rao.omega, rao.heave_amplitude), sea)
    surge = _sigma(lambda w: np.interp(w, rao.omega, rao.surge_amplitude), sea)
    top, st = _top_std(sc)
    # 60 frequencies over the band against 20001: the trapezoid's error, well under 1 %
    assert top["y_s"] == pytest.approx(heave, rel=1e-2)
    assert top["x_s"] == pytest.approx(surge, rel=1e-2)
    # the door's answer is this linearization's; the body heaves with the tip below the wire's axial mode
    # (6.3 rad/s against a sea below 1.6 rad/s: within a few per cent of the tip's heave)
    assert out["std"]["y_b"] == pytest.approx(st.std("y_b"), rel=2e-2)
    assert st.std("y_b") == pytest.approx(heave, rel=0.1)
    # not the analysis defaults (Hs 2 m, Tp 8 s) nor the buoy orbit (|R| = 1): the heave RAO is 0.42 at 0.8 rad/s
    assert heave < 0.9 * sea.hs / 4


def test_a_scene_without_a_sea_says_which_sea_it_got():
    sc = load_scene(example_path("heave_300m.toml"))
    assert sc.top_motion.spectrum is None
    out, ok, msg = stochastic(sc, {"hs": 1.5, "tp": 9.0}, ModelCache())
    assert ok, msg
    assert "no [top_motion.spectrum] in the scene, options hs, tp" in out["sea"] and "Hs 1.5 m" in out["sea"]
    # the buoy orbit, |R| = 1, and a stiff 300 m wire: the body heaves with the surface, sigma ~ Hs / 4 of the part of
    # the spectrum inside the default band 0.25-3 rad/s
    w = np.linspace(0.25, 3.0, 60)
    assert out["std"]["y_b"] == pytest.approx(math.sqrt(np.trapezoid(jonswap(w, 1.5, 9.0), w)), rel=0.1)


def _crane(heading_deg=None, **sea):
    """studies/_bench_3d.py's crane tip (300 m wire, 2 t sphere, [top_motion.vessel] at a lever arm) in a long-crested
    JONSWAP sea at the case's wave heading (or ``heading_deg``)."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies"))
    import _bench_3d as B
    from cablesys.scene.sea import SeaSpectrum
    base = B.crane_scene(60.0)
    spectrum = SeaSpectrum(hs=1.0, tp=10.0, heading_deg=B.WAVE_HEADING_DEG if heading_deg is None else heading_deg,
                           n_components=40, **sea)
    top = dataclasses.replace(base.top_motion, x=(), y=(), z=(), spectrum=spectrum, vessel=B.vessel_rao())
    return dataclasses.replace(base, top_motion=top), B.vessel_rao()


def test_the_seas_velocities_at_the_cable_are_refused_by_name_not_left_out():
    sc, _ = _crane(waves_at_cable=True)
    with pytest.raises(ParameterError, match=r"top_motion\.spectrum\.waves_at_cable"):
        stochastic(sc, {}, ModelCache())


def test_options_that_define_a_sea_replace_the_scenes_and_say_so():
    """The isolation design's sea (the surface orbit, a JONSWAP of its own Hs and Tp: notebooks/isolation_design.ipynb
    sweeps it over Hs) is asked for by options: then it runs, and ``sea`` names what it replaced."""
    out, ok, msg = stochastic(_rov(), {"hs": 4.0, "tp": 9.0}, ModelCache())
    assert ok, msg
    assert "options hs, tp in place of the scene's [top_motion.spectrum]" in out["sea"] and "surface orbit" in out["sea"]
    assert (out["sea_hs_m"], out["sea_tp_s"]) == (4.0, 9.0)


def test_a_vessel_rao_moves_the_crane_tip_in_three_directions():
    """[top_motion.vessel] (6-DOF, lever arm, vessel heading) in a long-crested sea at 120 deg to the vessel: the tip's
    standard deviation per axis is the quadrature of the rigid-body transfer (VesselRAO.transfer, the time-domain
    run's), and the 3-D equations take the sway."""
    sc, vessel = _crane()
    out, ok, msg = stochastic(sc, {}, ModelCache())
    assert ok, msg
    assert "[top_motion.vessel]" in out["sea"]
    top, st = _top_std(sc)
    sea = sc.top_motion.spectrum
    for k, label in enumerate(("x_s", "y_s", "z_s")):
        want = _sigma(lambda w: np.abs(vessel.transfer(w, sea.heading_deg)[k]), sea)
        assert top[label] == pytest.approx(want, rel=1e-2), label
    # 300 m below, the body barely follows the tip's wave-frequency sway (its pendulum period is ~35 s): in the
    # regular wave of the crane_rao benchmark its sway amplitude is 3.4 % of the tip's; broadband, between 0.5 % and 10 %
    assert 0.005 < st.std("z_b") / top["z_s"] < 0.1
    assert out["std"]["z_b"] == pytest.approx(st.std("z_b"), rel=5e-2)


def test_a_spread_sea_sums_the_directions_as_the_double_integral_over_frequency_and_heading():
    """A cos^2 spread sea (DNV-RP-C205 3.5.8) on the vessel, 150 deg relative heading (the table's 60-180 deg cover
    +-90 deg by port-starboard symmetry): the tip's variance per axis is int int |T(omega, theta)|^2 S(omega) D(theta),
    here by the trapezoid over 721 headings against the analysis' Gauss-Legendre directions; the body's response is
    the sum over the directions, so its sway differs from the long-crested sea's."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies"))
    import _bench_3d as B
    heading = B.VESSEL_HEADING_DEG + 150.0
    sc, vessel = _crane(heading, spreading_n=2.0)
    sea = sc.top_motion.spectrum
    top, st = _top_std(sc)
    lo, hi = sea.band()
    w, th = np.linspace(lo, hi, 4001), np.linspace(sea.heading_deg - 90.0, sea.heading_deg + 90.0, 721)
    T = np.array([np.abs(np.array(vessel.transfer(w, float(t)))) ** 2 for t in th])      # (theta, axis, omega)
    dens = sea.spreading(th)[:, None, None] * np.radians(1.0)                           # D(theta) per degree
    var = np.trapezoid(np.trapezoid(T * dens * jonswap(w, sea.hs, sea.tp, sea.gamma), w, axis=2), th, axis=0)
    for k, label in enumerate(("x_s", "y_s", "z_s")):
        assert top[label] == pytest.approx(math.sqrt(var[k]), rel=1e-2), label
    long_top, long_st = _top_std(_crane(heading)[0])
    assert abs(st.std("z_b") / long_st.std("z_b") - 1.0) > 0.02       # the spread changes what the body sees
    out, ok, msg = stochastic(sc, {}, ModelCache())
    assert ok, msg
    assert "spread cos^2" in out["sea"]
