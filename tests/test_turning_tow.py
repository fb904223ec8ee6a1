"""Towing in a circle (Wang 1971 p. 32): the steady turn of the node model against the closed form of a
body on a light line, a run started on it that stays on it, and the track's field-named errors."""

import dataclasses
import math
import sys
from pathlib import Path

import numpy as np
import pytest
import tomllib
from scipy.optimize import brentq

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies"))
import _turning  # noqa: E402

import cablesys
from cablesys.errors import ParameterError
from cablesys.ladder.rung.base import TURNING
from cablesys.ladder.rung.wang import RUNG as WANG
from cablesys.model import build_model
from cablesys.scene import scene_from_dict
from cablesys.scene.toml_io import dump_scene
from cablesys.statics.turning import turning_initial_state

LIGHT = """
name = "body on a light line, towed in a circle, no drag"
[cable]
length = 50.0
ae = 1.0e9
diameter = 0.001
mass_per_length = 0.001
weight_per_length = 0.001
cd_normal = 0.0
ct_tangential = 0.0
segments = 4
[body]
weight = 1000.0
mass_x = 200.0
mass_y = 200.0
mass_z = 200.0
[top_motion.track]
radius = 20.0
speed = 3.0
direction = "{direction}"
"""


def _scene(text, **numerics):
    sc = scene_from_dict(tomllib.loads(text))
    return dataclasses.replace(sc, numerics=dataclasses.replace(sc.numerics, **numerics)) if numerics else sc


@pytest.mark.parametrize("direction, side", [("counter-clockwise", -1.0), ("clockwise", 1.0)])
def test_steady_turn_of_a_body_on_a_light_line_is_the_conical_pendulum_of_the_tow_circle(direction, side):
    """Without drag the line lies in the plane of the axis and the tow point: T cos a = W, T sin a = M W^2 r_b,
    r_b = R + L sin a (the body swings out), so tan a = M Omega^2 (R + L sin a) / W."""
    sc = _scene(LIGHT.format(direction=direction))
    model = build_model(sc)
    p = model.parameters(sc)
    x0 = turning_initial_state(sc, model, p)
    body = x0[:model.nq].reshape(-1, 3)[-1]
    R, w, L, M, W = 20.0, 3.0 / 20.0, 50.0, 200.0, 1000.0
    a = brentq(lambda a: math.tan(a) - M * w**2 * (R + L * math.sin(a)) / W, 0.0, 1.5)
    r_b = R + L * math.sin(a)
    assert abs(body[0]) < 1e-6 * L                                  # no drag: no lag behind the tow point
    assert body[2] == pytest.approx(side * r_b, rel=2e-4)          # the tow point starts at z = -R (ccw), +R (cw)
    assert body[1] == pytest.approx(L * math.cos(a), rel=2e-4)
    v = x0[model.nq:].reshape(-1, 3)[-1]
    assert np.hypot(v[0], v[2]) == pytest.approx(w * r_b, rel=2e-4)


TOW = _turning.TOW         # the study's scene: 60 m of 20 mm wire, a 3 kN body, 80 m radius at 2 m/s


def test_a_run_started_on_the_steady_turn_stays_on_it():
    """The node model's own time domain (CVODES, tight tolerance) from the steady turn: the body, turned back by
    -Omega t, keeps its place, and the tensions stay constant, to the integration's accuracy."""
    sc = _scene(TOW, duration=20.0, output_step=0.5, rtol=1e-9, atol=1e-9)
    res = cablesys.simulate(sc, model="segmented", segments=6)
    assert res.model_info["name"] == "segmented"
    t = np.asarray(res.time)
    w = sc.top_motion.track.turn_rate
    xb, yb, zb = (np.asarray(res[k]) for k in ("x_b", "y_b", "z_b"))
    c, s = np.cos(w * t), np.sin(w * t)
    x_back, z_back = c * xb + s * zb, -s * xb + c * zb             # the turn undone (x' = c x - s z, z' = s x + c z)
    assert x_back[0] < -5.0                                          # the body trails the tow point
    for y in (x_back, yb, z_back):
        assert np.ptp(y) < 1e-5 * 60.0
    top = np.asarray(res["tension_top"])
    assert np.ptp(top) < 1e-5 * top.mean()


def test_towing_in_a_circle_runs_the_node_model_and_says_why():
    sc = _scene(TOW)
    assert sc.three_d and WANG.valid(sc) == TURNING
    again = scene_from_dict(tomllib.loads(dump_scene(sc)))
    assert len(again.top_motion.x) == len(again.top_motion.z) == 1 and again.top_motion.track == sc.top_motion.track
    assert again.top_motion.effective_ramp_s == 0.0


@pytest.mark.parametrize("extra, field", [
    ("[environment]\ncurrent_depths = [0.0, 50.0]\ncurrent_speeds = [0.5, 0.0]\n", "environment.current_speeds[0]"),
    ("[environment]\nsystem_speed = 1.0\n", "environment.system_speed"),
    ("[[top_motion.y]]\namplitude = 1.0\nfrequency = 0.5\n", "top_motion.y[0]"),
    ("[top_motion.spectrum]\nhs = 2.0\ntp = 8.0\n", "top_motion.spectrum"),
    ("[initial]\nphi = 0.1\n", "initial.phi"),
])
def test_a_track_with_motion_or_flow_that_breaks_the_steady_turn_is_a_named_error(extra, field):
    with pytest.raises(ParameterError) as err:
        scene_from_dict(tomllib.loads(TOW + extra))
    assert err.value.field == field


@pytest.mark.parametrize("line, field", [
    ('kind = "zigzag"', "top_motion.track.kind"), ("radius = 0.0", "top_motion.track.radius"),
    ("speed = -1.0", "top_motion.track.speed"), ('direction = "left"', "top_motion.track.direction"),
])
def test_bad_track_fields_are_named(line, field):
    key = line.split(" = ")[0]
    text = "\n".join(ln for ln in TOW.splitlines() if not ln.startswith(f"{key} ="))
    text = text.replace("[top_motion.track]", f"[top_motion.track]\n{line}")
    with pytest.raises(ParameterError) as err:
        scene_from_dict(tomllib.loads(text))
    assert err.value.field == field
