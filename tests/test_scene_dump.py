"""dump_scene writes every table a scene carries, so a dumped scene loads back to the same scene."""

import math
import tomllib

from cablesys.examples import example_path
from cablesys.scene import dump_scene, load_scene, scene_from_dict


def test_limits_and_design_survive_a_round_trip():
    scene = load_scene(example_path("rov-lift"))
    assert scene.limits is not None and scene.design        # the example carries both tables
    for units in ("SI", "fps"):
        back = scene_from_dict(tomllib.loads(dump_scene(scene, units=units, annotate=True)))
        assert back.design == scene.design                   # [design] is SI whatever `units` says
        for name in ("minimum_breaking_load", "max_excursion", "slack_fraction", "exposure"):
            a, b = getattr(back.limits, name), getattr(scene.limits, name)
            assert math.isclose(a, b, rel_tol=1e-12), (units, name, a, b)
