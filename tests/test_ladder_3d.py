"""The ladder's a priori estimates on 3-D scenes (:mod:`cablesys.ladder.estimate`, :mod:`cablesys.ladder.continuum`):
they see the top's sway and the flow's heading, and they turn with the scene (a scene turned about the vertical gets
the same estimates; sway alone is surge turned by 90 deg)."""

import dataclasses
import math
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies"))
import three_d_checks as checks  # noqa: E402

from cablesys import ladder  # noqa: E402
from cablesys.ladder.indicators import relative_flow, scene_numbers  # noqa: E402
from cablesys.scene import Numerics, Sinusoid, TopMotion  # noqa: E402


def _estimates(scene):
    c = ladder.choose(scene)
    e = c.numbers["estimates"]
    table = e["segmented_1"]["continuum"]
    return ({k: (e[k]["body"], e[k]["tension"]) for k in ("wang", "quasi-static")}
            | {f"segmented {n}": (v["body"], v["tension"]) for n, v in table.items()}), c


def test_the_estimates_turn_with_the_scene():
    """A current turning with depth, a wave at 20 deg, surge + sway + heave, and the scene turned by 50 deg: the same
    deciding numbers and estimates (the continuum's string and rod about the static cable in the flow's plane), to
    1e-9; the flow's heading turns by 50 deg."""
    sc = checks.rotation_scene().with_numerics(model="auto", duration=30.0)
    turned = checks.rotated_scene(sc, math.radians(50.0))
    assert math.degrees(relative_flow(turned)[1] - relative_flow(sc)[1]) == pytest.approx(50.0, abs=1e-9)
    a, b = scene_numbers(sc), scene_numbers(turned)
    for k in ("omega_forcing", "transverse_fraction", "static_bow", "dynamic_bow", "string_ratio"):
        assert getattr(b, k) == pytest.approx(getattr(a, k), rel=1e-9), k
    (ea, ca), (eb, cb) = _estimates(sc), _estimates(turned)
    for k in ea:
        assert eb[k] == pytest.approx(ea[k], rel=1e-9), k
    assert (ca.name, ca.segments) == (cb.name, cb.segments)


def test_sway_alone_is_estimated_as_surge_turned_by_ninety_degrees():
    """A pendulum cable swayed at the top (3-D) and the same cable surged (the plane): the sway is motion normal to
    the cable as the surge is (transverse fraction 1), and every estimate is the same to 1e-9; before, the ladder
    read only the surge and heave of a 3-D scene's top and saw no forcing in sway."""
    base = checks.pendulum_scene(ae=2e7, weight=2e4, mass=3000.0, cable_mass=True, drag=0.8,
                                 numerics=Numerics(duration=60.0, output_step=0.1, model="auto"))
    term = (Sinusoid(amplitude=1.5, frequency=0.8),)
    surge = dataclasses.replace(base, top_motion=TopMotion(x=term, ramp_s=5.0)).replace_section(0, body={"mass_z": None})
    sway = dataclasses.replace(base, top_motion=TopMotion(z=term, ramp_s=5.0))
    assert sway.three_d and not surge.three_d
    a, b = scene_numbers(surge), scene_numbers(sway)
    assert b.forcing == a.forcing and b.transverse_fraction == pytest.approx(1.0) == a.transverse_fraction
    (ea, ca), (eb, cb) = _estimates(surge), _estimates(sway)
    for k in ea:
        assert eb[k] == pytest.approx(ea[k], rel=1e-9), k
    assert b.omega_forcing == 0.8 and b.dynamic_bow > 0.0          # the sway forces and bows the cable
