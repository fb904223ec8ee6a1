"""The packaged light-cage lift (``cablesys/data/light_lift.toml``): the ROV-lift example edited as stated in its
header, its numbers consistent with their stated sources."""

import pytest

from cablesys.errors import ParameterError
from cablesys.examples import EXAMPLES, example_path
from cablesys.scene import load_scene


def test_light_lift_is_the_rov_lift_edited_as_its_header_says():
    light, rov = load_scene(example_path("light-lift")), load_scene(example_path("rov-lift"))
    c, b, g = light.sections[0].cable, light.sections[0].body, light.environment.gravity
    assert "light-lift" in EXAMPLES
    assert c.length == 60.0 and b.weight == pytest.approx(200.0 * g, rel=1e-4)           # 200 kg in water
    assert c.tension_ref == pytest.approx(b.weight + c.weight_per_length * c.length / 2, rel=1e-4)   # W_b + w l / 2
    assert c.internal_damping == 1e5 and c.diameter == 0.030
    sea, sea_rov = light.top_motion.spectrum, rov.top_motion.spectrum
    assert (sea.hs, sea.tp) == (5.0, 9.0) and light.numerics.duration == 600.0
    # everything else is the ROV lift's: its wire, cage masses, current profile, crane-tip RAO and sea seed
    rc = rov.sections[0].cable
    assert (c.ae, c.mass_per_length, c.weight_per_length) == (rc.ae, rc.mass_per_length, rc.weight_per_length)
    assert (b.mass_x, b.mass_y) == (rov.sections[0].body.mass_x, rov.sections[0].body.mass_y)
    assert light.environment.current_speeds == rov.environment.current_speeds
    assert light.top_motion.rao == rov.top_motion.rao and sea.seed == sea_rov.seed
    # the buoyant ROV of the header: (1000 kg - 1025 kg/m3 x 0.7805 m3) g
    assert (1000.0 - 1025.0 * 0.7805) * g == pytest.approx(b.weight, rel=1e-3)


def test_an_unknown_example_is_a_parameter_error():
    with pytest.raises(ParameterError, match="light-lift"):
        example_path("light-lift-x")
