"""Steady state (rootfinder) against a long time-domain run and against hand statics (issue 3)."""

import numpy as np
import pytest

from cablesys.linear import steady_state
from cablesys.model import build_model
from cablesys.scene import Initial, TopMotion, dale_scene


@pytest.mark.parametrize("current,speed", [((0.15, 0.05), 0.0), ((0.0, 0.0), 0.1)])
def test_current_deflected_equilibrium_is_where_a_long_run_settles(current, speed):
    """A sheared current (or a tow speed) deflects the cable; a run started hanging straight settles there."""
    scene = dale_scene(duration=90.0, output_step=0.5).replace(top_motion=TopMotion()).with_environment(
        current_depths=(0.0, 3.0), current_speeds=current, system_speed=speed
    ).replace_section(0, cable={"internal_damping": 10.0})   # damp the stretch mode so the run settles;
    # Voigt damping (eq. 46) acts on du/dt only and leaves the equilibrium unchanged
    model = build_model(scene)
    ss = steady_state(model, model.parameters(scene))
    assert abs(ss.q[0]) > 0.02                                   # visibly deflected
    from cablesys.time_domain import simulate
    hanging = scene.replace(initial=Initial(phi=0.0, u=ss.q[1]))
    r = simulate(hanging, model=model)
    assert r.success
    assert r["phi"][-1] == pytest.approx(ss.q[0], abs=1e-6)
    assert r["u"][-1] == pytest.approx(ss.q[1], rel=1e-6)
    assert r["tension_mid"][-1] == pytest.approx(ss.outputs["tension_mid"], rel=1e-6)
    # the body drifts downstream: x_b > 0 for a current in +x, x_b < 0 when towed in +x
    assert np.sign(ss.outputs["x_b"]) == (1 if speed == 0 else -1)


def test_hanging_tension_equals_submerged_weights():
    """No current: phi = 0 and F_bc = k u = W_b + W_c / 2 (Wang 1971 eq. 49b with dV/du = 0)."""
    scene = dale_scene()
    model = build_model(scene)
    ss = steady_state(model, model.parameters(scene))
    assert ss.q[0] == 0.0
    assert ss.outputs["tension_mid"] == pytest.approx(scene.body.weight + 0.5 * scene.cable.total_weight, rel=1e-12)
    assert ss.outputs["y_b"] == pytest.approx(scene.cable.length_zero + ss.q[1], rel=1e-14)


def test_bad_guess_does_not_return_an_inverted_compressed_cable():
    """A root with phi = -pi and u < 0 solves the equations but is not a hanging equilibrium."""
    scene = dale_scene()
    model = build_model(scene)
    ss = steady_state(model, model.parameters(scene), guess=np.array([3.0, -0.01]))
    assert ss.q[0] == pytest.approx(0.0, abs=1e-12) and ss.q[1] > 0
