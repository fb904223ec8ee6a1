"""The open-loop optimal payout (cablesys.control) against closed forms, re-simulation and bad input."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from cablesys.control import WinchLimits, heave_problem, optimal_payout, resimulate
from cablesys.errors import ParameterError
from cablesys.examples import example_path
from cablesys.scene import Sinusoid, TopMotion
from cablesys.scene.toml_io import load_scene

A, OMEGA = 1.0, 2 * math.pi / 10.0       # crane-tip heave 1 m at 10 s


def _sine_scene(duration=100.0, light=False):
    sc = load_scene(example_path("rov-lift")).with_numerics(drag_segments=1, duration=duration)
    sc = sc.replace(top_motion=TopMotion(y=(Sinusoid(amplitude=A, frequency=OMEGA, phase=0.0),), ramp_s=20.0))
    if light:   # no cable inertia and no drag: the payout can hold the body exactly still
        sc = sc.replace_section(cable={"cable_mass_switch": -1.0, "cd_normal": 0.0, "ct_tangential": 0.0},
                                body={"drag_area_normal": 0.0, "drag_area_tangential": 0.0})
        sc = sc.with_environment(current_depths=(0.0,), current_speeds=(0.0,))
    return sc


@pytest.fixture(scope="module")
def light_optimum():
    pr = heave_problem(_sine_scene(60.0, light=True), WinchLimits(), control_weight=1e-9, model="wang")
    return pr, optimal_payout(pr, 60.0)


def test_unbounded_winch_cancels_the_heave(light_optimum):
    """With no speed limit the optimum keeps the body still: y_b - y_b0 -> 0 while the
    uncompensated body heaves with the tip (0.7 m rms), and the payout speed is the tip's speed."""
    pr, res = light_optimum
    assert res.success, res.message
    assert res.uncompensated_heave_rms_m > 0.5
    assert res.heave_rms_m < 1e-4 * res.uncompensated_heave_rms_m
    t = res.times
    tip_speed = A * OMEGA * np.cos(OMEGA * t)          # y down: L must grow as the tip rises (y_s falls)
    window = (t > 25.0) & (t < 55.0)                    # after the 20 s ramp, before the horizon's end
    speed = res.output("speed")
    # the body stays put, so L' (1 + strain) = -y_s' (strain ~ 3e-4; RK4 on 0.125 s steps)
    assert np.max(np.abs(speed[window] + tip_speed[window])) < 5e-3 * A * OMEGA


def test_resimulated_optimum_meets_the_constraints(light_optimum):
    """CVODES on the winch model with the optimal alpha, 8 outputs per interval (not the
    transcription's grid): the same heave and every limit within 1 %."""
    pr, res = light_optimum
    check = resimulate(pr, res, per_interval=8)
    assert check["max_relative_violation"] < 0.01
    assert check["heave_rms_m"] == pytest.approx(res.heave_rms_m, abs=1e-3 * res.uncompensated_heave_rms_m)


def _bound(w_max):
    """Closed-form rms residual of rate-limited tracking of A sin(omega t) (module-free derivation):
    the error e = y_s + z (z the payout's shift, |z'| <= w_max) is zero where the tip is slower
    than w_max and on the fast arcs |theta| < theta_1 (theta = omega t about a zero crossing)
    follows A sin(theta) - (w_max/omega) theta, with sin(theta_1)/theta_1 = r = w_max/(A omega)
    (Pontryagin: the costate vanishes at both ends, so int e = 0 on the arc). Mean square:
    (A^2/pi) * 2 [theta_1/2 - sin(2 theta_1)/4 - 2 r (sin theta_1 - theta_1 cos theta_1) + r^2 theta_1^3/3]."""
    r = w_max / (A * OMEGA)
    th = brentq(lambda x: math.sin(x) / x - r, 1e-9, math.pi - 1e-12)
    ms = A ** 2 / math.pi * 2 * (th / 2 - math.sin(2 * th) / 4 - 2 * r * (math.sin(th) - th * math.cos(th))
                                 + r ** 2 * th ** 3 / 3)
    return math.sqrt(ms)


def test_speed_limit_residual_matches_the_closed_form_bound():
    """|w| <= 0.3 m/s against a 1 m, 10 s tip heave (0.63 m/s peak): the residual body heave
    over whole periods is the rate-limited bound (the stiff rope's axial mode, 6 rad/s, makes
    the quasi-static bound exact to (0.63/6.3)^2 ~ 1 %)."""
    w_max = 0.3
    pr = heave_problem(_sine_scene(100.0, light=True), WinchLimits(speed=w_max), control_weight=1e-9,
                       model="wang")
    res = optimal_payout(pr, 100.0)
    assert res.success, res.message
    assert res.speed_max_m_s <= w_max * (1 + 1e-6)
    h = res.output("heave")
    window = (res.times >= 30.0) & (res.times < 80.0)    # 5 whole periods, away from the ramp and the end
    rms = float(np.sqrt(np.mean(h[window] ** 2)))
    assert rms == pytest.approx(_bound(w_max), rel=0.03)
    # with the speed limit active on most of every period, CVODES between the nodes stays within it
    check = resimulate(pr, res, per_interval=4)
    assert check["speed"] < 0.01 and check["max_relative_violation"] < 0.01


def test_working_load_below_static_weight_is_refused():
    with pytest.raises(ParameterError, match="working_load"):
        heave_problem(_sine_scene(), WinchLimits(working_load=1.0e4), model="wang")   # the rope holds ~2.4e4 N at rest


@pytest.mark.parametrize("field", ["speed", "acceleration", "power"])
def test_zero_limit_is_refused(field):
    with pytest.raises(ParameterError, match=field):
        WinchLimits(**{field: 0.0})


def test_horizon_longer_than_the_record_is_refused():
    pr = heave_problem(_sine_scene(100.0), WinchLimits(), model="wang")
    with pytest.raises(ParameterError, match="horizon"):
        optimal_payout(pr, 150.0)


def test_unreachable_tension_floor_reports_the_constraint():
    """A floor at 98 % of the static tension with a 0.05 m/s winch: the 1 m heave must slacken the
    rope below it, so the result is infeasible and names the tension floor."""
    sc = _sine_scene(40.0)
    pr = heave_problem(sc, WinchLimits(speed=0.05, tension_floor=0.98 * 23887.0), model="wang")
    res = optimal_payout(pr, 40.0, max_iter=150)
    assert not res.success
    assert res.violated == "tension floor (no slack)", res.message
    assert "tension floor" in res.message


def test_payout_result_protocol(light_optimum):
    """success/message/stats, a JSON-able summary and an annotated dataset of the trajectories."""
    import json
    _, res = light_optimum
    summary = res.summary()
    json.dumps(summary)
    assert summary["status"] == "Solve_Succeeded" and summary["stats"]["iterations"] > 0
    assert summary["stats"]["solve_s"] > 0
    ds = res.to_xarray()
    assert ds["speed"].attrs["units"] == "m/s" and ds["heave"].attrs["units"] == "m"
    np.testing.assert_allclose(ds["heave_uncompensated"].values, res.output("heave", False))
