"""One name per physical quantity across the models; old slack keys still load, with a warning."""

import dataclasses
import tomllib

import pytest

from cablesys.errors import ParameterError
from cablesys.scene import Cable as WangCable
from cablesys.slack import Cable as SlackCable
from cablesys.slack.scene import EXAMPLE_TOML, scene_from_dict


def test_the_same_quantity_has_the_same_name():
    wang = {f.name for f in dataclasses.fields(WangCable)}
    slack = {f.name for f in dataclasses.fields(SlackCable)}
    assert {"length", "mass_per_length", "ae", "added_mass_factor"} <= wang & slack
    assert not {"axial_stiffness", "added_mass_coefficient"} & slack


def test_old_slack_keys_are_deprecated_aliases():
    doc = tomllib.loads(EXAMPLE_TOML.replace("ae = ", "axial_stiffness = "))
    doc["masses"][0]["added_mass_coefficient"] = 0.8
    with pytest.warns(DeprecationWarning) as caught:
        scene = scene_from_dict(doc)
    assert sorted(str(w.message) for w in caught) == [
        "cable.axial_stiffness is deprecated: write ae",
        "masses[0].added_mass_coefficient is deprecated: write added_mass_factor"]
    new = scene_from_dict(tomllib.loads(EXAMPLE_TOML))
    assert scene.cable.ae == new.cable.ae and scene.masses[0].added_mass_factor == 0.8
    doc["cable"]["ae"] = 1.0
    with pytest.raises(ParameterError, match="old name of cable.ae"):
        scene_from_dict(doc)
