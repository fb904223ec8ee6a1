"""Auto on scenes generated at random within ranges, against the converged segmented cable."""

import math

import numpy as np
import pytest

from cablesys.ladder import choose, metrics, run_rung
from cablesys.scene import Body, Cable, Environment, Numerics, Sinusoid, TopMotion
from cablesys.scene.scene import single_section_scene



def random_scene(rng: np.random.Generator):
    """A short cable and a sphere: length 5-20 m, strain 0.3-3 %, body 50-200 kg, cable 2-20 % of the
    body weight, current 0-0.3 m/s, circular top motion 0.05-0.3 m at 0.3-1.5 x the swing frequency."""
    length = rng.uniform(5.0, 20.0)
    w_b = rng.uniform(50.0, 200.0) * 9.81 * 0.6
    w_c = rng.uniform(0.02, 0.2) * w_b
    strain = 10 ** rng.uniform(-2.5, -1.5)
    tension = w_b + 0.5 * w_c
    m_b = w_b / (9.81 * 0.6) * 1.2
    cable = Cable(length=length, tension_ref=tension, ae=tension / strain, diameter=0.01,
                  mass_per_length=w_c / length / 9.81 * 1.3, weight_per_length=w_c / length, cd_normal=1.2)
    body = Body(weight=w_b, mass_x=m_b, mass_y=m_b, drag_area_normal=0.3, drag_area_tangential=0.3)
    w_swing = math.sqrt(9.81 * 0.6 / length)
    omega = rng.uniform(0.3, 1.5) * w_swing
    a = rng.uniform(0.05, 0.3)
    top = TopMotion(x=(Sinusoid(amplitude=a, frequency=omega, phase=math.pi / 2),), y=(Sinusoid(amplitude=a, frequency=omega),))
    period = 2 * math.pi / omega
    return single_section_scene(cable=cable, body=body, environment=Environment(current_speeds=(rng.uniform(0, 0.3),)),
                                top_motion=top, numerics=Numerics(duration=6 * period, output_step=period / 20),
                                name="random")


@pytest.mark.slow
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_auto_within_tolerance_on_random_scenes(seed):
    scene = random_scene(np.random.default_rng(seed))
    choice = choose(scene)
    period = metrics.forcing_period(scene)
    ref = run_rung(scene, "segmented", max(10, 2 * choice.segments))
    got = run_rung(scene, choice.name, choice.segments)
    assert ref.success and got.success
    actual = metrics.errors(metrics.statistics(got, period), metrics.statistics(ref, period))
    tol = choice.numbers["tolerance"]
    assert actual["body"] <= tol["body"] and actual["tension"] <= tol["tension"], (choice.reason, actual)
    for k in ("body", "tension"):
        # where the error matters (above a tenth of the tolerance) the estimate is within a factor of 2;
        # below it the estimate is an upper bound
        if actual[k] > 0.1 * tol[k]:
            assert 0.5 <= choice.estimated_error[k] / actual[k] <= 2.0, (k, choice.reason, actual)
        else:
            assert choice.estimated_error[k] <= tol[k]
