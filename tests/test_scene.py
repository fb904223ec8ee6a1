"""Scene description: validation names field, value and range; TOML in SI and ft/lb/slug."""

import math
import tomllib

import numpy as np
import pytest

from cablesys import units as U
from cablesys.errors import ParameterError
from cablesys.scene import (
    Body,
    Cable,
    TimeSeries,
    TopMotion,
    dale_scene,
    default_scene,
    dump_scene,
    load_scene,
    scene_from_dict,
)


def dale_toml(units="SI"):
    return tomllib.loads(dump_scene(default_scene(), units=units))


@pytest.mark.parametrize("units", ["SI", "fps"])
def test_round_trip(units):
    s = default_scene()
    back = scene_from_dict(tomllib.loads(dump_scene(s, units=units, annotate=True)))
    assert back.cable.length == pytest.approx(s.cable.length, rel=1e-14)
    assert back.body.mass_x == pytest.approx(s.body.mass_x, rel=1e-14)
    assert back.environment.density == pytest.approx(s.environment.density, rel=1e-14)
    if units == "SI":
        assert back == s


def test_fps_scene_is_converted_to_si():
    d = dale_toml("fps")
    assert d["cable"]["length"] == pytest.approx(9.0)
    assert d["body"]["weight"] == pytest.approx(0.025)
    s = scene_from_dict(d)
    assert s.cable.length == pytest.approx(9 * 0.3048)
    assert s.body.weight == pytest.approx(0.025 * 4.4482216152605)
    assert s.cable.total_mass == pytest.approx(0.000171 * U.SLUG)


def test_zero_tension_quantities():
    """Wang (1971) eq. 1, 5: l_0 = l_r - T_r/k, M_c = m_r l_r."""
    c = Cable(length=100.0, tension_ref=2000.0, ae=1e6, diameter=0.02, mass_per_length=1.0, weight_per_length=8.0)
    assert c.spring_constant == 1e4
    assert c.length_zero == pytest.approx(99.8)
    assert c.total_mass == 100.0


@pytest.mark.parametrize("section,key,value,match", [
    ("cable", "length", -3.0, r"cable.length = -3.0: must be > 0"),
    ("cable", "ae", 0.0, r"cable.ae = 0.0: must be > 0"),
    ("cable", "diameter", float("nan"), r"cable.diameter = nan: must be finite"),
    ("body", "mass_x", -1.0, r"body.mass_x = -1.0: must be > 0"),
    ("cable", "thinning_ratio", 1.5, r"cable.thinning_ratio = 1.5: must be in \[0.0, 1.0\]"),
    ("cable", "colour", "red", r"cable.colour = 'red': unknown key"),
    ("numerics", "integrator", "euler", r"numerics.integrator = 'euler': must be one of"),
    ("numerics", "rtol", 0.5, r"numerics.rtol = 0.5: must be in"),
])
def test_bad_input_names_field_value_and_range(section, key, value, match):
    d = dale_toml()
    d.setdefault(section, {})[key] = value
    with pytest.raises(ParameterError, match=match):
        scene_from_dict(d)


def test_frequency_must_be_positive():
    d = dale_toml()
    d["top_motion"]["x"][0]["frequency"] = 0.0
    with pytest.raises(ParameterError, match=r"top_motion.x\[0\].frequency = 0.0: must be > 0"):
        scene_from_dict(d)


def test_unsorted_current_profile():
    d = dale_toml()
    d["environment"]["current_depths"] = [0.0, 10.0, 5.0]
    d["environment"]["current_speeds"] = [0.1, 0.2, 0.3]
    with pytest.raises(ParameterError, match="strictly increasing"):
        scene_from_dict(d)


def test_buoyant_body_with_zero_tension_floor():
    d = dale_toml()
    d["body"]["weight"] = -0.5
    with pytest.raises(ParameterError, match=r"body.weight = -0.5: .*no taut equilibrium"):
        scene_from_dict(d)
    d["cable"]["tension_floor"] = -1.0   # a rod that takes compression: allowed
    assert scene_from_dict(d).body.weight == -0.5


def test_sphere_needs_equal_drag_areas():
    with pytest.raises(ParameterError, match="drag_area_tangential"):
        Body(weight=1.0, mass_x=1.0, mass_y=1.0, drag_area_normal=0.1, drag_area_tangential=0.2, axis_angle_deg=999)
    b = Body(weight=1.0, mass_x=1.0, mass_y=1.0, drag_area_normal=0.1, drag_area_tangential=0.2, axis_angle_deg=30)
    assert not b.is_sphere


def test_missing_file_and_bad_toml(tmp_path):
    with pytest.raises(ParameterError, match="cannot be read"):
        load_scene(tmp_path / "nope.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("[cable\nlength = 3")
    with pytest.raises(ParameterError, match="not valid TOML"):
        load_scene(bad)


def test_time_series_top_motion_matches_sinusoid():
    """A sampled sinusoid, spline-interpolated, drives the body like the sinusoid itself."""
    from cablesys.model import build_model
    from cablesys.time_domain import simulate
    base = dale_scene(duration=12.0)
    w, a = base.top_motion.x[0].frequency, base.top_motion.x[0].amplitude
    t = np.arange(0.0, 13.0, 0.05)
    series = TimeSeries(times=tuple(t), x=tuple(a * np.cos(w * t)), y=tuple(a * np.sin(w * t)))
    sampled = base.replace(top_motion=TopMotion(series=series))
    m = build_model(sampled)
    e = np.array(m.top(7.31, m.parameters(sampled))).ravel()
    np.testing.assert_allclose(e[1:5], [a * math.cos(w * 7.31), a * math.sin(w * 7.31),
                                        -a * w * math.sin(w * 7.31), a * w * math.cos(w * 7.31)], atol=1e-6)
    r1, r2 = simulate(base), simulate(sampled, model=m)
    np.testing.assert_allclose(r2["x_b"], r1["x_b"], atol=2e-6)
