"""Smooth start ([top_motion] ramp_s): the ramp's shape, and the free vibration it avoids (closed form)."""

import math

import casadi as ca
import numpy as np
import pytest

from cablesys.errors import ParameterError
from cablesys.model import build_model
from cablesys.model.top_motion import ramp
from cablesys.scene import (
    Body,
    Cable,
    Environment,
    Numerics,
    Sinusoid,
    TopMotion,
    dale_scene,
    single_section_scene,
)
from cablesys.time_domain import simulate


def test_ramp_starts_and_ends_without_jumps():
    t, R = ca.SX.sym("t"), ca.SX.sym("R")
    r = ramp(t, R)
    d1 = ca.jacobian(r, t)
    d2 = ca.jacobian(d1, t)
    f = ca.Function("f", [t, R], [r, d1, d2])
    R0 = 7.0
    for tt, want in ((-1.0, 0.0), (0.0, 0.0), (1e-7, 0.0), (R0 - 1e-7, 1.0), (R0, 1.0), (20.0, 1.0)):
        val, rate, acc = (float(v) for v in f(tt, R0))
        assert val == pytest.approx(want, abs=1e-12) and abs(rate) < 1e-6 and abs(acc) < 1e-6
    assert float(f(R0 / 2, R0)[0]) == pytest.approx(0.5) and float(f(R0 / 2, R0)[1]) == pytest.approx(2 / R0)
    # ramp_s = 0 is the abrupt start: the factor is 1 everywhere, t = 0 included
    assert [float(f(tt, 0.0)[0]) for tt in (0.0, 1.0)] == [1.0, 1.0]


def test_ramp_is_a_parameter_and_checked():
    sc = dale_scene()
    tm = sc.top_motion
    ramped = sc.replace(top_motion=TopMotion(x=tm.x, y=tm.y, ramp_s=10.0))
    model = build_model(ramped)
    p_abrupt, p_ramped = model.parameters(sc), model.parameters(ramped)   # same structure, one function
    late = [np.array(model.top(t, p_abrupt)).ravel() for t in (10.0, 13.7)]
    assert np.allclose(late, [np.array(model.top(t, p_ramped)).ravel() for t in (10.0, 13.7)], rtol=0, atol=1e-15)
    assert np.allclose(np.array(model.top(0.0, p_ramped)).ravel()[1:], 0.0)
    with pytest.raises(ParameterError, match="ramp_s"):
        TopMotion(x=tm.x, ramp_s=-1.0)


M, W, K, L = 10.0, 50.0, 1000.0, 10.0          # kg, N, N/m, m: a mass on a massless spring, omega = 10 rad/s
A, WF = 0.1, 2.0                               # top heave amplitude (m) and frequency (rad/s)


def spring_scene(ramp_s):
    cable = Cable(length=L, tension_ref=0.0, ae=K * L, diameter=0.01, mass_per_length=0.0, weight_per_length=0.0,
                  cd_normal=0.0, ct_tangential=0.0, tension_floor=-math.inf, cable_mass_switch=-1.0)
    body = Body(weight=W, mass_x=M, mass_y=M, drag_area_normal=0.0, drag_area_tangential=0.0)
    return single_section_scene(cable=cable, body=body, environment=Environment(density=1000.0),
                                top_motion=TopMotion(y=(Sinusoid(amplitude=A, frequency=WF),), ramp_s=ramp_s),
                                numerics=Numerics(duration=3 * 2 * math.pi / WF + 3.0, output_step=0.01,
                                                  rtol=1e-10, atol=1e-12, drag_segments=1))


def free_vibration(res, t_from):
    """Largest |u - u_p| after ``t_from``: u_p = W/K + A wf^2 sin(wf t) / (w^2 - wf^2) is the forced
    response of u'' + w^2 u = W/M - y_s'' (the relative stretch of a mass on a spring, top y_s = A sin wf t)."""
    w2 = K / M
    t = res.time
    u_p = W / K + A * WF ** 2 * np.sin(WF * t) / (w2 - WF ** 2)
    keep = t >= t_from
    return float(np.max(np.abs(res["u"][keep] - u_p[keep])))


def test_ramp_leaves_no_free_vibration_where_the_abrupt_start_rings():
    R = 3 * 2 * math.pi / WF
    abrupt = simulate(spring_scene(0.0))
    smooth = simulate(spring_scene(R))
    assert abrupt.success and smooth.success
    w = math.sqrt(K / M)
    # abrupt start from rest relative to the top: u'(0) - u_p'(0) = -A wf^3 / (w^2 - wf^2), so the
    # free vibration has amplitude A wf^3 / (w (w^2 - wf^2)) (undamped: it never decays)
    expected = A * WF ** 3 / (w * (w ** 2 - WF ** 2))
    assert free_vibration(abrupt, R) == pytest.approx(expected, rel=0.02)
    assert free_vibration(smooth, R) < 1e-2 * expected


# -- Wang's model on the Dale scene: consistent start, stretch mode left at rest ---------------
def dale(ramp_s):
    sc = dale_scene(duration=30.0)
    tm = sc.top_motion
    return sc.replace(top_motion=TopMotion(x=tm.x, y=tm.y, ramp_s=ramp_s))


def test_default_ramp_is_three_forcing_periods_and_zero_is_abrupt():
    sc = dale_scene()
    tm = sc.top_motion
    assert tm.ramp_s == 0.0 and tm.effective_ramp_s == 0.0        # Wang's runs: abrupt, explicitly
    auto = TopMotion(x=tm.x, y=(Sinusoid(amplitude=0.01, frequency=0.5),))
    assert auto.ramp_s is None and auto.effective_ramp_s == pytest.approx(3 * 2 * math.pi / 0.5)
    assert TopMotion().effective_ramp_s == 0.0
    model = build_model(sc.replace(top_motion=auto))
    p = model.parameters(sc.replace(top_motion=auto))
    assert p[model.layout.index("top_motion.ramp_s")] == pytest.approx(12 * math.pi)


def test_steady_start_is_consistent_with_the_ramped_top():
    """x0 = (static q, 0) is an equilibrium of the ramped problem at t = 0 (top at rest, no
    acceleration: Wang (1971) eq. 49 with x_s'' = y_s'' = 0), not of the abrupt one."""
    from cablesys.time_domain import initial_state
    for ramp_s, consistent in ((3 * 2 * math.pi / 1.14, True), (0.0, False)):
        sc = dale(ramp_s)
        model = build_model(sc)
        p = model.parameters(sc)
        x0 = initial_state(sc, model, p)
        acc = np.array(model.ode(x0, 0.0, p)).ravel()[model.nq:]
        top = np.array(model.top(0.0, p)).ravel()
        if consistent:
            assert np.allclose(top[1:], 0.0, atol=1e-15)
            assert np.max(np.abs(acc)) < 1e-8          # q'' of the static state: solver tolerance
        else:
            assert np.max(np.abs(top[5:7])) > 0.05    # the abrupt top accelerates at t = 0 (m/s^2)
            assert np.max(np.abs(acc)) > 1e-2


def stretch_band_energy(res, t_from, omega_s):
    """Mean square of the stretch rate u' in the band 0.5-2 omega_s after ``t_from`` (FFT)."""
    keep = res.time >= t_from
    t, v = res.time[keep], res["u_rate"][keep]
    v = v - v.mean()
    f = np.fft.rfftfreq(t.size, t[1] - t[0]) * 2 * math.pi
    V = np.abs(np.fft.rfft(v * np.hanning(t.size))) ** 2
    band = (f > 0.5 * omega_s) & (f < 2.0 * omega_s)
    return float(V[band].sum())


@pytest.mark.slow
def test_ramp_leaves_the_stretch_mode_at_rest_on_dale():
    """Wang's model, Dale scene (undamped stretch mode, C_I = 0): after the ramp the energy in the
    stretch band is a tiny fraction of what the abrupt start leaves ringing for ever."""
    R = 3 * 2 * math.pi / 1.14
    sc = dale(R)
    c, b = sc.sections[0].cable, sc.sections[0].body
    omega_s = math.sqrt(c.ae / c.length / (b.mass_y + c.mass_per_length * c.length / 3.0))   # ~250 rad/s
    times = np.concatenate([[0.0], np.arange(R + 1.0, R + 5.0, 0.002)])
    e = {}
    for name, scene in (("ramped", sc), ("abrupt", dale(0.0))):
        res = simulate(scene, times=times, rtol=1e-9, atol=1e-12, max_num_steps=1_000_000)
        assert res.success, res.message
        e[name] = stretch_band_energy(res, R + 1.0, omega_s)
    assert e["ramped"] < 1e-4 * e["abrupt"]
