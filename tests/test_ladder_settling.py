"""When the forced response reaches the body: the transverse wave's travel time down a hanging string.

The ladder's estimates speak of the settled response; a window that ends before the ramped forcing has
run down the string measures a front (cablesys/ladder/estimate.py docstring: the 1000 m wire's 40 s
study run). Checks: the closed form of the travel time against its integral, and against the front of
a segmented run.
"""

import math

import numpy as np
from scipy.integrate import quad

from cablesys.ladder import run_rung
from cablesys.ladder.continuum import Member, string_travel_time
from cablesys.ladder.estimate import settling_time
from cablesys.scene import Body, Cable, Environment, Numerics, Sinusoid, TopMotion
from cablesys.scene.scene import single_section_scene


def test_travel_time_is_the_integral_of_ds_over_the_local_wave_speed():
    # hanging string: T(s) = T_b + g s from the body up, c = sqrt(T / m)
    mb = Member(length=1000.0, stiffness=complex(7000.0), mass=1.3, drag=0.0, end_mass=300.0, end_drag=0.0,
                current=0.0, gradient=9.4)
    t_top, t_bot = mb.end_stiffness()
    want, _ = quad(lambda s: math.sqrt(mb.mass / (t_bot + mb.gradient * s)), 0.0, mb.length)
    assert math.isclose(string_travel_time(mb), want, rel_tol=1e-10)
    assert t_top - t_bot == 9.4 * 1000.0
    # uniform string: L / c
    uni = Member(length=300.0, stiffness=complex(5000.0), mass=2.5, drag=0.0, end_mass=1.0, end_drag=0.0, current=0.0)
    assert math.isclose(string_travel_time(uni), 300.0 / math.sqrt(5000.0 / 2.5), rel_tol=1e-12)


def _hanging_wire(length=500.0, ramp=2.0, duration=13.0):
    """16 mm steel wire rope (9.4 N/m in water) with a 300 kg sphere of 0.5 m, surged at the top."""
    rho, g = 1025.0, 9.80665
    vol = math.pi / 6 * 0.5**3
    w_b = 300.0 * g - rho * g * vol
    cable = Cable(length=length, tension_ref=w_b + 0.5 * 9.4 * length, ae=1.2e7, diameter=0.016,
                  mass_per_length=1.1, weight_per_length=9.4, cd_normal=1.2, ct_tangential=0.01)
    body = Body(weight=w_b, mass_x=300.0 + 0.5 * rho * vol, mass_y=300.0 + 0.5 * rho * vol,
                drag_area_normal=0.5 * math.pi / 4 * 0.25, drag_area_tangential=0.5 * math.pi / 4 * 0.25)
    top = TopMotion(x=(Sinusoid(amplitude=1.0, frequency=2 * math.pi / 4.0),), ramp_s=ramp)
    return single_section_scene(cable=cable, body=body, environment=Environment(density=rho, gravity=g),
                                top_motion=top, numerics=Numerics(duration=duration, output_step=0.05))


def test_the_surge_reaches_the_body_after_the_string_travel_time():
    # 500 m: T 2284 N at the body, 6984 N at the top, travel 8.70 s; 20 elements (a lumped chain's fastest
    # waves are the long ones, at the continuum's speed: nothing arrives early)
    sc = _hanging_wire()
    ramp = sc.top_motion.effective_ramp_s
    travel = settling_time(sc) - ramp
    assert 8.5 < travel < 8.9
    r = run_rung(sc, "segmented", 20)
    t, x = np.asarray(r.time), np.abs(np.asarray(r["x_b"]))
    # 1 m at the top: the body still within 0.1 mm at 0.8 travel times (measured 4e-6 m), moving by
    # 1 cm within 1.2 travel times after the ramp (measured 0.04 m)
    assert np.max(x[t <= 0.8 * travel]) < 1e-4
    assert np.max(x[t <= ramp + 1.2 * travel]) > 1e-2


def test_drag_linearized_at_the_models_drag_points_gives_the_settled_surge():
    # 500 m of wire surged 1 m at T = 10 s: the surge runs down the string as a drag-controlled wave (its
    # equivalent damping several times m omega). The segmented model puts its drag at 2 points per element
    # at N = 5 and at the mid-point from N = 7 (numerics.drag_segments = 10 shared); linearized at those
    # points on the interpolated complex velocity (local_drag), the chain gives the nonlinear run's settled
    # body surge: measured 6 % (N = 5) and 0.5 % (N = 10) apart, where the element's mean node amplitude
    # (the rule before) was 15 % and 3.7 % off
    from cablesys.ladder import local_drag
    from cablesys.model.segmented import drag_points
    sc = _hanging_wire(ramp=20.0, duration=70.0)
    sc = sc.replace(top_motion=TopMotion(x=(Sinusoid(amplitude=1.0, frequency=2 * math.pi / 10.0),), ramp_s=20.0))
    assert settling_time(sc) + 2 * 10.0 < 70.0
    _, lin = local_drag.body_responses(sc, 0.0, (5, 10), lambda n: drag_points(sc, n))
    for n, within in ((5, 0.08), (10, 0.02)):
        r = run_rung(sc, "segmented", n)
        t, x = np.asarray(r.time), np.asarray(r["x_b"])
        settled = 0.5 * np.ptp(x[t >= t[-1] - 20.0])
        assert abs(lin[n]["x_b"] - settled) < within * settled, (n, lin[n]["x_b"], settled)


def test_the_mean_offset_in_a_current_settles_within_the_settling_time():
    # 200 m of wire in a uniform 0.8 m/s current surged 1 m at T = 6 s (Wang's cable: the drift is the body's
    # mean angle). From its steady state the forcing's added mean drag pushes the body ~4 m further (39.5 to
    # 43.5 m); from hanging straight down (the current switched on at t = 0) it creeps out 41 m. Both decay at
    # the slowest real eigenvalue of the cable linearized in the current (estimate.slow_decay_time: tau 64 s;
    # per-period means decay at 0.0162 and 0.0163 1/s against 1 / tau = 0.0155), and at the settling time
    # (ramp + string travel + ln(100) tau = 313 s) 0.7 % and 0.5 % of the first period's offset are left
    from cablesys.ladder import estimate as est
    from cablesys.scene import Initial
    sc = _hanging_wire(length=200.0)
    sc = sc.replace(environment=Environment(density=1025.0, gravity=9.80665, current_depths=(0.0, 400.0),
                                            current_speeds=(0.8, 0.8)),
                    top_motion=TopMotion(x=(Sinusoid(amplitude=1.0, frequency=2 * math.pi / 6.0),), ramp_s=12.0))
    tau, settle = est.slow_decay_time(sc), est.settling_time(sc)
    assert 30.0 < tau < 120.0 and settle > math.log(1 / est.SETTLE_FRACTION) * tau
    for phi in (None, 0.0):             # the steady state; hanging straight down
        r = run_rung(sc.replace(initial=Initial(phi=phi), numerics=Numerics(duration=settle + 3 * tau, output_step=0.1)),
                     "wang")
        t, x = np.asarray(r.time), np.asarray(r["x_b"])
        k = np.floor(t / 6.0).astype(int)
        means = np.array([x[k == i].mean() for i in range(k.max())])
        centre = (np.arange(means.size) + 0.5) * 6.0
        dev = np.abs(means - means[-2:].mean())           # 3 tau after settling: 5e-4 of the start left
        fit = (centre > 0.3 * settle) & (centre < settle)
        rate = -np.polyfit(centre[fit], np.log(dev[fit]), 1)[0]
        assert abs(rate * tau - 1.0) < 0.15, (phi, rate, 1 / tau)
        assert np.interp(settle, centre, dev) < est.SETTLE_FRACTION * dev[0], (phi, np.interp(settle, centre, dev), dev[0])
