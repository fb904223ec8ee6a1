"""Scene fields of the 3-D equations: TOML in and out, typed errors, and planar scenes left as they are."""

import json
import math

import pytest

from cablesys.errors import ParameterError
from cablesys.examples import example_text
from cablesys.scene import Wave
from cablesys.scene.toml_io import dump_scene, scene_from_dict

import tomllib

THREE_D = """
name = "sway"
[cable]
length = 60.0
ae = 4.0e7
diameter = 0.024
mass_per_length = 2.4
weight_per_length = 18.0
[body]
weight = 6000.0
mass_x = 900.0
mass_y = 1100.0
mass_z = 950.0
[environment]
current_depths = [0.0, 50.0]
current_speeds = [0.8, 0.2]
current_headings_deg = [30.0, 75.0]
[[environment.waves]]
amplitude = 0.5
length = 80.0
heading_deg = 45.0
[[top_motion.z]]
amplitude = 1.5
frequency = 0.6
"""


def _load(text):
    return scene_from_dict(tomllib.loads(text))


def test_3d_fields_load_dump_and_load_again_in_si_and_fps():
    sc = _load(THREE_D)
    assert sc.three_d
    assert sc.three_d_fields() == ("top_motion.z", "environment.current_headings_deg",
                                   "environment.waves[0].heading_deg", "body.mass_z")
    assert sc.top_motion.z[0].amplitude == 1.5 and sc.body.virtual_mass_z == 950.0
    assert sc.environment.headings_per_depth_deg == (30.0, 75.0)
    for units in ("SI", "fps"):
        again = scene_from_dict(tomllib.loads(dump_scene(sc, units=units)))
        assert again.top_motion.z[0].amplitude == pytest.approx(1.5, rel=1e-12)
        assert again.environment.current_headings_deg == pytest.approx((30.0, 75.0), rel=1e-12)
        assert again.environment.waves[0].heading_deg == pytest.approx(45.0, rel=1e-12)
        assert again.body.mass_z == pytest.approx(950.0, rel=1e-12)


def test_one_heading_holds_at_every_depth():
    sc = _load(THREE_D.replace("current_headings_deg = [30.0, 75.0]", "current_headings_deg = [30.0]"))
    assert sc.environment.headings_per_depth_deg == (30.0, 30.0)


def test_a_planar_scene_dumps_as_today():
    # the example scene sets no 3-D field: its dump names none, and it loads back planar
    sc = scene_from_dict(tomllib.loads(example_text("rov-lift")))
    sc = sc.with_environment(waves=(Wave(amplitude=0.4, length=90.0),))
    text = dump_scene(sc, annotate=True)
    doc = tomllib.loads(text)
    assert "current_headings_deg" not in doc["environment"] and "mass_z" not in doc["body"]
    assert "heading_deg" not in doc["environment"]["waves"][0] and "z" not in doc["top_motion"]
    assert "dimensions" not in doc["numerics"]
    again = scene_from_dict(doc)
    assert not again.three_d and dump_scene(again, annotate=True) == text


@pytest.mark.parametrize("edit, field, says", [
    (("current_headings_deg = [30.0, 75.0]", "current_headings_deg = [1.0, 2.0, 3.0]"),
     "environment.current_headings_deg", "one per current depth"),
    (("current_headings_deg = [30.0, 75.0]", 'current_headings_deg = ["north", 1.0]'),
     "environment.current_headings_deg[0]", "number"),
    (("heading_deg = 45.0", "heading_deg = nan"), "heading_deg", "finite"),
    (("mass_z = 950.0", "mass_z = -1.0"), "body.mass_z", "> 0"),
    (("[[top_motion.z]]\namplitude = 1.5\nfrequency = 0.6", "[[top_motion.z]]\namplitude = 1.5\nfrequency = -0.6"),
     "frequency", "> 0"),
])
def test_bad_3d_fields_are_named_with_value_and_range(edit, field, says):
    with pytest.raises(ParameterError) as err:
        _load(THREE_D.replace(*edit))
    msg = str(err.value)
    assert field in msg and says in msg


def test_dimensions_two_refuses_a_3d_field_and_3d_takes_a_seabed():
    with pytest.raises(ParameterError, match="numerics.dimensions.*top_motion.z"):
        _load(THREE_D + "\n[numerics]\ndimensions = 2\n")
    with pytest.raises(ParameterError, match="numerics.dimensions.*2 or 3"):
        _load(THREE_D + "\n[numerics]\ndimensions = 4\n")
    # the node model runs in 3-D (segments > 1) with an anchor (held at z = 0 unless anchor.z is set) and a seabed
    nodes = THREE_D.replace("weight_per_length = 18.0", "weight_per_length = 18.0\nsegments = 4")
    assert _load(nodes).three_d and _load(nodes + "\n[anchor]\nx = 10.0\ny = 50.0\n").anchor.x == 10.0
    bed = _load(nodes + "\n[seabed]\ndepth = 70.0\nheading_deg = 30.0\n")
    assert bed.three_d and bed.seabed.heading_deg == 30.0

    with pytest.raises(ParameterError, match="initial.phi_rate = 0.1.*3-D"):
        _load(THREE_D + "\n[initial]\nphi_rate = 0.1\n")


def test_heading_in_radians_in_the_parameter_vector():
    from cablesys.model.params import parameter_items
    items = dict(parameter_items(_load(THREE_D)))
    assert items["environment.current_headings[1]"] == pytest.approx(math.radians(75.0))
    assert items["environment.waves[0].heading"] == pytest.approx(math.radians(45.0))
    assert items["top_motion.z[0].amplitude"] == 1.5 and items["body.mass_z"] == 950.0
    json.dumps(items)
