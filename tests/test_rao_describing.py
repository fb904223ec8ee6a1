"""The describing-function RAO of a segmented cable against the time domain, and where it stops holding (slack).

The 300 m steel wire with a 2 t sphere (cablesys/data/heave_300m.toml) at N = 4 elements, heaved at its top:
- taut orbits: the one-harmonic balance's first harmonics of the body heave and the end tensions agree with the
  nonlinear time domain (``simulate`` of the same model, sinusoidal heave, half range over the last 5 periods)
  within 0.5 % (measured 0.06 % and below);
- an orbit whose one-harmonic balance goes slack is marked so, and the time domain does go slack there: the
  describing function is outside its domain (its tension amplitude is 30 % off the time domain's at 5 rad/s);
- ``cablesys rao`` says in ``rao_summary.json`` where its describing function holds and where the scene's own
  1 m heave at T = 6 s makes the orbit slack, and writes the describing-function table only where it holds.
"""

import dataclasses
import json

from pathlib import Path

import numpy as np
import pytest

import cablesys

from cablesys.cli import main
from cablesys.ladder.rung.base import with_segments
from cablesys.linear.equivalent import harmonic_response
from cablesys.model import build_model
from cablesys.scene import dump_scene, load_scene
from cablesys.time_domain import simulate

HEAVE = Path(cablesys.__file__).parent / "data" / "heave_300m.toml"


@pytest.fixture(scope="module")
def wire():
    scene = with_segments(load_scene(HEAVE), 4)
    return scene, build_model(scene)


def _heaved(scene, omega, amplitude):
    tm = scene.top_motion
    return scene.replace(top_motion=dataclasses.replace(
        tm, y=(dataclasses.replace(tm.y[0], amplitude=amplitude, frequency=omega, phase=0.0),)))


@pytest.mark.parametrize("omega, amplitude", [(0.6, 0.5), (3.0, 0.05)])
def test_taut_describing_function_matches_time_domain(wire, omega, amplitude):
    scene, model = wire
    sc = _heaved(scene, omega, amplitude)
    T = 2 * np.pi / omega
    res = simulate(sc, model=model, times=np.arange(0.0, 40 * T, T / 40))
    h = harmonic_response(model, model.parameters(sc), [omega], np.array([0.0, amplitude], complex), n_theta=32)
    assert h.converged and not h.slack[0] and h.least_tension[0] > 0.0
    for out in ("y_b", "tension_top", "tension_bottom"):
        assert h.amplitude(out)[0] == pytest.approx(res.steady_amplitude(out, T, 5), rel=5e-3), out


def test_slack_orbit_is_marked_and_the_time_domain_goes_slack(wire):
    scene, model = wire
    omega, amplitude = 5.0, 0.02
    sc = _heaved(scene, omega, amplitude)
    T = 2 * np.pi / omega
    h = harmonic_response(model, model.parameters(sc), [omega], np.array([0.0, amplitude], complex), n_theta=32)
    assert h.slack[0] and h.least_tension[0] == pytest.approx(0.0, abs=1e-9)     # the floor, eq. 54
    res = simulate(sc, model=model, times=np.arange(0.0, 20 * T, T / 40))
    assert res.time_slack() > 0.0


def test_rao_summary_states_where_the_describing_function_holds(tmp_path):
    scene = with_segments(load_scene(HEAVE), 4)
    scene = scene.replace(numerics=dataclasses.replace(scene.numerics, model="as-built"))
    path = tmp_path / "heave.toml"
    path.write_text(dump_scene(scene))
    assert main(["rao", str(path), "--out", str(tmp_path / "rao"), "--n", "40"]) == 0
    doc = json.loads((tmp_path / "rao" / "rao_summary.json").read_text())
    df = doc["linearizations"]["describing function y_s"]
    assert df["amplitude_m"] == pytest.approx(1.0)
    # the scene's 1 m at T = 6 s makes the lower cable slack (its file says so; the time domain above): the
    # describing function holds below the first slack orbit, and the scene's own frequency is past it
    w_s = 2 * np.pi / 6.0
    assert df["valid"] > 0 and df["valid_band_rad_s"][1] < min(df["slack_rad_s"]) <= w_s
    assert df["max_residual"] < 1e-8
    rows = np.loadtxt(tmp_path / "rao" / "rao_describing_y_s.csv", delimiter=",", skiprows=1)
    assert rows.shape[0] == df["valid"] and rows[:, 0].max() == pytest.approx(df["valid_band_rad_s"][1])
