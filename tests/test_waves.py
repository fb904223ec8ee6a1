"""Deep-water wave particle velocities (Wang 1971 eq. 26-28) and a run driven by a wave alone."""

import math

import casadi as ca
import numpy as np
import pytest

from cablesys.model.fluid import fluid_velocity, wave_velocity
from cablesys.scene import TopMotion, Wave, dale_scene
from cablesys.time_domain import simulate


def test_wave_velocity_equals_eq_26a_and_continuity_fixes_26b():
    a, lam, g = 1.5, 80.0, 9.81
    n, sigma = 2 * math.pi / lam, math.sqrt(2 * math.pi * g / lam)
    x, y, t = 12.0, 7.0, 3.3
    vx, vy = wave_velocity(x, y, t, [(a, lam, 0.0)], g)
    assert float(vx) == pytest.approx(a * math.exp(-n * y) * sigma * math.sin(n * x - sigma * t), rel=1e-14)
    # eq. 26b printed with -sigma is the upward component; y down needs the opposite sign
    assert float(vy) == pytest.approx(a * math.exp(-n * y) * sigma * math.cos(n * x - sigma * t), rel=1e-14)
    # eq. 27-28: current minus system speed plus the wave
    env = {"current_depths": [0.0, 10.0], "current_speeds": [0.4, 0.2], "system_speed": 1.0,
           "gravity": g, "waves": [(a, lam, 0.0)]}
    fx, fy = fluid_velocity(x, y, t, env)
    assert float(fx) == pytest.approx(0.4 - 0.2 * 0.7 - 1.0 + float(vx), rel=1e-14)
    assert float(fy) == pytest.approx(float(vy), rel=1e-14)


def test_wave_field_is_incompressible_and_irrotational():
    """div v = 0 and curl v = 0 by AD at random points (a potential flow satisfying continuity)."""
    X, Y = ca.SX.sym("x"), ca.SX.sym("y")
    vx, vy = wave_velocity(X, Y, 2.7, [(1.2, 60.0, 0.4), (0.5, 25.0, 1.9)], 9.81)
    f = ca.Function("dv", [X, Y], [ca.jacobian(vx, X) + ca.jacobian(vy, Y), ca.jacobian(vy, X) - ca.jacobian(vx, Y)])
    rng = np.random.default_rng(3)
    for x, y in rng.uniform([-50, 0], [50, 40], size=(20, 2)):
        div, curl = (float(v) for v in f(x, y))
        scale = 1.2 * math.sqrt(9.81 * 2 * math.pi / 60.0) * 2 * math.pi / 25.0
        assert abs(div) < 1e-12 * scale and abs(curl) < 1e-12 * scale


def test_orbital_speed_decays_with_depth():
    """|v| = a sigma exp(-n y): one wavelength down it is exp(-2 pi) of the surface value."""
    lam = 50.0
    speeds = [float(ca.norm_2(ca.vertcat(*wave_velocity(0.0, y, 0.0, [(1.0, lam, 0.0)], 9.81)))) for y in (0.0, lam)]
    assert speeds[1] / speeds[0] == pytest.approx(math.exp(-2 * math.pi), rel=1e-12)


def test_a_wave_alone_drives_the_body_through_drag():
    """No top motion: drag of the wave orbit moves the body at the wave frequency, less at depth."""
    base = dale_scene(duration=60.0).replace(top_motion=TopMotion())
    amps = []
    for depth in (0.0, 3.0):
        scene = base.with_environment(waves=(Wave(amplitude=0.05, length=3.0),), top_depth=depth)
        r = simulate(scene)
        assert r.success
        sigma = math.sqrt(2 * math.pi * 9.80665 / 3.0)
        amps.append(r.steady_amplitude("x_b", 2 * math.pi / sigma, 5))
    assert amps[0] > 1e-4
    assert amps[1] < 0.2 * amps[0]
