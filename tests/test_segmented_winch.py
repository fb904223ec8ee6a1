"""The winch in the segmented node model (cablesys.model.segmented_winch): the fixed-length model at zero payout,
the quasi-static payout against the elastic hanging cable's closed form, the mass in the water, the N = 1 node
model against Wang's 2-DOF winch (cablesys.model.winch) rolled out the same way, and the [winch] input errors."""

import dataclasses
import tomllib

import casadi as ca
import numpy as np
import pytest
from scipy.integrate import solve_ivp

import cablesys
from cablesys.errors import ParameterError
from cablesys.model import build_model
from cablesys.model.segmented import build_segmented_model
from cablesys.model.winch import build_winch_model, rest_state
from cablesys.result_protocol import unit_of
from cablesys.scene import (Body, Cable, Environment, Leg, Numerics, Seabed, Sinusoid, TopMotion, Winch, dump_scene,
                            scene_from_dict)
from cablesys.scene.scene import single_section_scene
from cablesys.time_domain import simulate

G = 9.80665
W_B, M_B, W_R, M_R, AE, L0 = 500.0, 100.0, 8.0, 1.0, 1e6, 50.0


def _scene(n=4, *, winch=None, top=None, current=0.0, cd=0.0, c_i=0.0, cda=0.0, mass_switch=1.0, duration=10.0,
           output_step=0.5):
    cable = Cable(length=L0, ae=AE, diameter=0.02, mass_per_length=M_R, weight_per_length=W_R, added_mass_factor=0.0,
                  cd_normal=cd, ct_tangential=0.3 * cd, internal_damping=c_i, cable_mass_switch=mass_switch, segments=n)
    body = Body(weight=W_B, mass_x=M_B, mass_y=M_B, drag_area_normal=cda, drag_area_tangential=cda)
    return single_section_scene(cable=cable, body=body, environment=Environment(gravity=G, current_speeds=(current,)),
                                top_motion=top or TopMotion(), winch=winch,
                                numerics=Numerics(duration=duration, output_step=output_step))


def test_zero_payout_is_the_fixed_length_model():
    """speed = 0: the winch model's right-hand side and outputs equal the fixed-length node model's to 1e-10 along a
    dynamic run (heaving top, current, drag, Voigt damping), and so does the run itself."""
    top = TopMotion(y=(Sinusoid(amplitude=1.0, frequency=1.2),), x=(Sinusoid(amplitude=0.5, frequency=0.7),))
    kw = dict(top=top, current=0.5, cd=1.2, c_i=2e4, cda=0.5, duration=6.0, output_step=0.25)
    fixed, wound = _scene(**kw), _scene(**kw, winch=Winch(speed=0.0, start=1.0, duration=3.0, ramp=1.0, max_length=60.0))
    mf, mw = build_model(fixed), build_model(wound)
    pf, pw = mf.parameters(fixed), mw.parameters(wound)
    run = simulate(fixed, model=mf)
    t, x = np.asarray(run.time), np.asarray(run.states).T
    names = [n for n in mf.output_labels]
    idx = [mw.output_labels.index(n) for n in names]
    for k in range(0, len(t), 3):
        xdot_f = np.array(mf.ode(x[k], t[k], pf)).ravel()
        xdot_w = np.array(mw.ode(x[k], t[k], pw)).ravel()
        np.testing.assert_allclose(xdot_w, xdot_f, rtol=1e-10, atol=1e-10 * np.max(np.abs(xdot_f)))
        e = np.array(mf.top(t[k], pf)).ravel()
        yf, yw = np.array(mf.outputs(x[k], e, pf)).ravel(), np.array(mw.outputs(x[k], e, pw)).ravel()[idx]
        np.testing.assert_allclose(yw, yf, rtol=1e-10, atol=1e-10)
    other = simulate(wound, model=mw)
    for name in ("y_b", "x_b", "tension_top"):
        np.testing.assert_allclose(other[name], run[name], rtol=1e-10, atol=1e-10 * np.max(np.abs(run[name])))


def _payout_errors(speed):
    """Largest relative errors of the top tension against W_b + w L(t) and of the body depth against the elastic
    hanging cable L + (W_b L + w L^2 / 2) / AE, over the constant-speed part of a 6 m payout in still water."""
    ramp = 2.0
    dur = 6.0 / speed + ramp
    sc = _scene(winch=Winch(speed=speed, start=0.0, duration=dur, ramp=ramp, max_length=60.0), c_i=0.05 * AE,
                duration=dur, output_step=0.5)
    run = simulate(sc)
    t, L = np.asarray(run.time), run["winch_length"]
    steady = (t > ramp + 3.0) & (t < dur - ramp)
    np.testing.assert_allclose(L, L0 + np.array([sc.winch.profile(ti)[0] for ti in t]), rtol=1e-12)
    T_err = np.max(np.abs(run["tension_top"][steady] / (W_B + W_R * L[steady]) - 1))
    depth = L + (W_B * L + 0.5 * W_R * L**2) / AE
    y_err = np.max(np.abs(run["y_b"][steady] - depth[steady])) / np.max(depth - L)
    return T_err, y_err


def test_slow_payout_hangs_as_the_elastic_cable_of_each_length():
    """Paying out a body in still water slowly, the top tension is W_b + w L(t) (to the integrator's tolerance) and
    the body depth the elastic static closed form at each L; the depth's error is the Voigt damping (C_I = 0.05 s AE)
    of the elements' growing strain, first order in the speed (module segmented_winch: neglected convection of
    the strain), so a speed 4x lower gives about 4x less."""
    errs = np.array([_payout_errors(v) for v in (0.5, 0.125)])
    assert np.all(errs[:, 0] < 1e-5), errs
    assert errs[1, 1] < errs[0, 1] / 3 and errs[1, 1] < 1e-4, errs


def _accelerating_error(ae):
    """Largest error (N) of the top tension against the rigid cable's W_b + w L - (M_b + m_r L) alpha over a
    smoothstep payout to 2 m/s and back (ramps of 4 s, alpha up to 0.75 m/s^2) of a heavy cable (m_r = 10 kg/m),
    and the largest inertia term (M_b + m_r L) |alpha| (N)."""
    m_r = 10.0
    cable = Cable(length=L0, ae=ae, diameter=0.02, mass_per_length=m_r, weight_per_length=W_R, added_mass_factor=0.0,
                  cd_normal=0.0, ct_tangential=0.0, internal_damping=0.05 * ae, segments=4)
    body = Body(weight=W_B, mass_x=M_B, mass_y=M_B, drag_area_normal=0.0, drag_area_tangential=0.0)
    sc = single_section_scene(cable=cable, body=body, environment=Environment(gravity=G),
                              numerics=Numerics(duration=12.0, output_step=0.25),
                              winch=Winch(speed=2.0, start=0.0, duration=12.0, ramp=4.0, max_length=100.0))
    run = simulate(sc)
    t, L, a = np.asarray(run.time), run["winch_length"], run["winch_acceleration"]
    inertia = (M_B + m_r * L) * a
    sel = (t > 1.0) & (t < 11.0)
    return np.max(np.abs(run["tension_top"] - (W_B + W_R * L - inertia))[sel]), np.max(np.abs(inertia))


def test_accelerating_payout_carries_the_inertia_of_cable_and_body():
    """While the winch accelerates, the whole line (body and the cable in the water) accelerates with it along the
    vertical: the top tension is W_b + w L - (M_b + m_r L) alpha for a rigid cable (Newton on the line); the
    model's difference is its elastic response, falling as 1 / AE. Checks the prescribed-L inertia terms of
    Lagrange's equations and the sheave's half element (its material acceleration, not the node's)."""
    soft, inertia = _accelerating_error(1e7)
    stiff, _ = _accelerating_error(1e8)
    assert inertia > 500.0
    assert soft < 5e-3 * inertia and stiff < soft / 5, (soft, stiff, inertia)


def test_lowering_a_package_onto_the_seabed_is_one_run():
    """A body lowered at 0.5 m/s through still water onto a [seabed] 40 m down, the winch stopping with as much cable
    out as the depth: while hanging, top tension W_b + w L(t) - (M_b + m_r L) alpha (the ramps' inertia); landed, the body rests at the bed pressed in by the
    contact law, delta = F / (k d_0 h / 2) with F = W_b + w h / 2 its node's load (MoorDyn's kBot on the node's
    contact area, model/segmented_seabed.py), and the top carries the hanging cable, w (L - h / 2): the continuum's w L
    less the half element lumped on the landed body (h = L / N)."""
    n, depth, l0, speed, ramp, k_bed, d = 4, 40.0, 32.0, 0.5, 2.0, 3e6, 0.02
    cable = Cable(length=l0, ae=AE, diameter=d, mass_per_length=M_R, weight_per_length=W_R, cd_normal=1.2,
                  ct_tangential=0.0, internal_damping=0.05 * AE, segments=n)
    body = Body(weight=W_B, mass_x=M_B, mass_y=M_B, drag_area_normal=0.0, drag_area_tangential=0.0)
    dur = (depth - l0) / speed + ramp
    sc = single_section_scene(cable=cable, body=body, environment=Environment(gravity=G),
                              seabed=Seabed(depth=depth, stiffness=k_bed),
                              numerics=Numerics(duration=dur + 8.0, output_step=0.5),
                              winch=Winch(speed=speed, duration=dur, ramp=ramp, max_length=60.0))
    run = simulate(sc)
    t, L, T, y = np.asarray(run.time), run["winch_length"], run["tension_top"], run["y_b"]
    assert L[-1] == pytest.approx(depth, rel=1e-12)
    hanging = y + 0.01 < depth
    assert np.any(hanging[t > dur / 2])
    rigid = W_B + W_R * L - (M_B + M_R * L) * run["winch_acceleration"]      # and the ramps' inertia
    np.testing.assert_allclose(T[hanging], rigid[hanging], rtol=2e-3)
    landed = t > dur + 2.0
    h = depth / n
    np.testing.assert_allclose(y[landed], depth + (W_B + W_R * h / 2) / (k_bed * d * h / 2), rtol=1e-7)
    np.testing.assert_allclose(T[landed], W_R * (depth - h / 2), rtol=1e-6)
    assert np.max(np.abs(run["y_b_rate"][landed])) < 1e-6


def test_mass_in_water_is_m_r_L():
    """The free nodes carry the body's mass and the cable's m_r L(t) less the half element lumped at the sheave:
    M_b + m_r L (1 - 1 / (2 N)) summed over the x blocks of the mass matrix (no added mass), at every L(t)."""
    n = 5
    sc = _scene(n, winch=Winch(speed=-2.0, start=1.0, duration=12.0, ramp=2.0, max_length=60.0))
    m = build_model(sc)
    p = m.parameters(sc)
    q = np.concatenate([[0.0, (j + 1) * L0 / n] for j in range(n)])
    for t in (0.0, 2.0, 5.0, 9.0, 13.0, 20.0):
        e = np.zeros(7)
        e[0] = t
        M = np.array(m.dynamics(q, np.zeros_like(q), e, p)[0])
        L = L0 + sc.winch.profile(t)[0]
        assert abs(np.trace(M[0::2, 0::2]) - (M_B + M_R * L * (1 - 1 / (2 * n)))) < 1e-9 * M_B, t
    assert L == pytest.approx(L0 - 20.0)


def test_one_element_winch_is_wangs_two_dof_winch():
    """N = 1 with a massless cable (CBMAS < 0): the node model's winch and Wang's 2-DOF winch (cablesys.model.winch,
    its own field and section terms) rolled out the same way from the same rest state, with a heaving top, agree in body position, L and the spring force of the uniform
    stretch (k(L) u + C_I (l' - w l / L) / l_r, ``tension_mid``; their top tensions lump the cable's drag differently)
    to 1e-6. No drag: the two cables' drag differs already at a fixed length; no Voigt damping: model/winch.py damps
    with C_I / l_r at the reference l_r, the node model with C_I over the reference length of the cable in the water
    (C_I times the strain rate), a relative difference L / l_0 - 1 in the damping force."""
    winch = Winch(speed=1.5, start=0.5, duration=6.0, ramp=1.5, max_length=80.0)
    top = TopMotion(y=(Sinusoid(amplitude=0.8, frequency=1.0),), ramp_s=0.0)
    sc = _scene(1, winch=winch, top=top, mass_switch=-1.0)
    node = build_segmented_model(sc)
    wang = build_winch_model(dataclasses.replace(sc, winch=None))
    p_n, p_w = node.parameters(sc), wang.parameters(dataclasses.replace(sc, winch=None))
    c = np.zeros(4)
    x_w0 = rest_state(wang, p_w, c, length=L0)
    phi, l = x_w0[0], x_w0[1]
    v_top = np.array(node.top(0.0, p_n)).ravel()[3:5]          # Wang's phi' = l' = 0: the body moves with the top
    x_n0 = np.array([-l * np.sin(phi), l * np.cos(phi), *v_top])
    alpha = lambda t: winch.profile(t)[2]
    times = np.linspace(0.0, 7.0, 29)
    rw = solve_ivp(lambda t, x: np.array(wang.ode(x, [alpha(t), 0.0], t, p_w, c)).ravel(), (0, 7), x_w0,
                   t_eval=times, rtol=1e-11, atol=1e-12, method="LSODA")
    rn = solve_ivp(lambda t, x: np.array(node.ode(x, t, p_n)).ravel(), (0, 7), x_n0, t_eval=times,
                   rtol=1e-11, atol=1e-12, method="LSODA")
    iw = [wang.output_index(k) for k in ("x_b", "heave", "tension_mid", "length")]
    il = [node.output_labels.index(k) for k in ("x_b", "y_b", "tension_mid", "winch_length")]
    for k, t in enumerate(times):
        yw = np.array(wang.outputs(rw.y[:, k], [alpha(t), 0.0], t, p_w, c)).ravel()[iw]
        yn = np.array(node.outputs(rn.y[:, k], np.array(node.top(t, p_n)).ravel(), p_n)).ravel()[il]
        np.testing.assert_allclose(yn, yw, rtol=1e-6, atol=1e-6)
    assert rn.y[1, -1] > L0 + 7.0       # the body went down with the 8 m paid out


def test_winch_run_door_says_which_model_and_why():
    """``cablesys.simulate`` runs a [winch] scene on the node model and says so; a rung that would ignore the winch
    is refused naming numerics.model; Wang's cable built as-built refuses the winch naming cable.segments."""
    sc = _scene(1, winch=Winch(speed=0.5, start=0.0, duration=4.0, ramp=1.0, max_length=60.0), duration=4.0)
    run = cablesys.simulate(sc, segments=4)
    assert run.stats["model"]["name"] == "segmented" and "winch" in run.stats["model"]["reason"]
    assert run["winch_length"][-1] == pytest.approx(L0 + 1.5, rel=1e-12)
    assert np.all(np.isfinite(run["winch_power"])) and unit_of("winch_power") == "W"
    for name in ("wang", "quasi-static", "frequency"):
        with pytest.raises(ParameterError, match="numerics.model.*winch"):
            cablesys.simulate(dataclasses.replace(sc, numerics=dataclasses.replace(sc.numerics, model=name)))
    with pytest.raises(ParameterError, match="cable.segments.*winch"):
        build_model(sc)


@pytest.mark.parametrize("fields, field", [
    (dict(speed=1.0, duration=0.0), "winch.duration"),
    (dict(speed=1.0, duration=4.0, ramp=0.0), "winch.ramp"),
    (dict(speed=1.0, duration=4.0, ramp=3.0), "winch.ramp"),
    (dict(speed=1.0, duration=4.0, start=-1.0), "winch.start"),
    (dict(speed=float("nan"), duration=4.0), "winch.speed"),
    (dict(speed=1.0, duration=4.0, max_length=-1.0), "winch.max_length"),
])
def test_bad_winch_fields_are_named(fields, field):
    with pytest.raises(ParameterError, match=field.replace(".", r"\.")):
        Winch(**{"max_length": 100.0, **fields})


def test_length_leaving_its_range_is_named_before_any_work():
    """L must stay in (0, max_length]: hauling in more than is in the water, paying out past the drum, a drum
    shorter than the cable in the water, each a ParameterError naming the field; the TOML reader says the same."""
    cases = [(dict(speed=-10.0, duration=6.0, ramp=1.0, max_length=60.0), "winch.speed"),
             (dict(speed=5.0, duration=6.0, ramp=1.0, max_length=60.0), "winch.speed"),
             (dict(speed=0.1, duration=6.0, ramp=1.0, max_length=40.0), "winch.max_length")]
    for fields, field in cases:
        with pytest.raises(ParameterError, match=field.replace(".", r"\.")):
            _scene(winch=Winch(**fields))
    good = _scene(winch=Winch(speed=1.0, duration=6.0, ramp=1.0, max_length=60.0))
    data = tomllib.loads(dump_scene(good))
    assert scene_from_dict(data).winch == good.winch
    data["winch"]["speed"] = 5.0
    with pytest.raises(ParameterError, match=r"winch\.speed"):
        scene_from_dict(data)
    data["winch"] = {"speed": 1.0, "duration": 6.0, "max_length": 60.0, "pace": 2.0}
    with pytest.raises(ParameterError, match="pace"):
        scene_from_dict(data)


# ---------------------------------------------------------------- a profile of legs: payout, hold, haul-in
def _legs(*pairs, **kw):
    return Winch(leg=tuple(Leg(speed=v, duration=d) for v, d in pairs), **{"ramp": 2.0, "max_length": 60.0, **kw})


def test_legs_profile_is_smooth_and_pays_out_speed_times_duration():
    """L(t), w(t), alpha(t) of payout - hold - haul-in - payout legs: w and alpha are L's derivatives (CasADi's AD of
    the closed-form Delta L against the closed-form w, alpha), continuous (no jump between samples 1 ms apart
    beyond |alpha| or |jerk| x 1 ms), |alpha| <= 1.5 |Delta v| / ramp, and the integral of w (SciPy's quad)
    equals Delta L; at the end each leg has paid out speed x duration."""
    w = _legs((1.5, 6.0), (0.0, 3.0), (-2.0, 4.0), (0.5, 2.0), start=1.0)
    assert w.paid_out == pytest.approx(1.5 * 6 - 2.0 * 4 + 0.5 * 2) and w.end == pytest.approx(1.0 + 15.0 + 2.0)
    t = ca.SX.sym("t")
    dL, ws, al = w.profile_at(t, fmin=ca.fmin, fmax=ca.fmax)
    f = ca.Function("f", [t], [ca.jacobian(dL, t), ws, ca.jacobian(ws, t), al])
    ts = np.linspace(0.0, w.end + 2.0, 4001)
    for ti in ts:
        dLdt, wi, dwdt, ai = (float(v) for v in f(ti))
        assert abs(dLdt - wi) < 1e-12 and abs(dwdt - ai) < 1e-12, ti
    P = np.array([w.profile(ti) for ti in np.arange(0.0, w.end + 2.0, 1e-3)])
    assert np.max(np.abs(np.diff(P[:, 1]))) <= 1e-3 * np.max(np.abs(P[:, 2])) * (1 + 1e-9)
    assert np.max(np.abs(np.diff(P[:, 2]))) < 1e-3 * 6.0 * 2.5 / 2.0 ** 2       # |jerk| <= 6 |Delta v| / ramp^2
    assert np.max(np.abs(P[:, 2])) == pytest.approx(1.5 * 2.5 / 2.0, rel=1e-6)   # the ramp from -2 to 0.5 m/s
    from scipy.integrate import quad
    for ti in (2.0, 7.9, 12.5, 16.3, w.end, w.end + 2.0):
        integral = quad(lambda s: w.profile(s)[1], 0.0, ti, points=[1, 3, 7, 9, 10, 12, 14, 16, 18], limit=200)[0]
        assert integral == pytest.approx(w.profile(ti)[0], abs=1e-10)
    assert w.profile(w.end) == pytest.approx((w.paid_out, 0.0, 0.0), abs=1e-12)


def test_single_speed_form_is_one_leg():
    """The old [winch] (speed for duration, ramps included) is one leg of duration - ramp: the same L(t), w, alpha."""
    old = Winch(speed=1.5, start=0.5, duration=6.0, ramp=1.5, max_length=80.0)
    one = Winch(leg=(Leg(speed=1.5, duration=4.5),), start=0.5, ramp=1.5, max_length=80.0)
    for t in np.linspace(0.0, 8.0, 81):
        assert old.profile(t) == pytest.approx(one.profile(t), abs=1e-14)
    assert old.paid_out == one.paid_out == pytest.approx(6.75) and old.end == one.end == 6.5


def test_legs_in_toml_round_trip_and_their_errors():
    """``[[winch.leg]]`` reads and writes back (SI and fps); a leg shorter than the ramp, a speed given beside the legs,
    no profile at all, each named; hauling in past L = 0 or paying out past max_length names the leg's speed,
    the leg and the time L leaves its range (each ramp acts as a change of speed ramp / 2 = 1 s after the leg
    starts, so L is piecewise linear in the closed forms of the cases' comments)."""
    good = _scene(winch=_legs((1.0, 8.0), (0.0, 4.0), (-1.0, 8.0)))
    for units in ("SI", "fps"):
        text = dump_scene(good, units=units)
        assert text.count("[[winch.leg]]") == 3 and "\nspeed =" in text
        back = scene_from_dict(tomllib.loads(text)).winch
        assert [x for g in back.leg for x in (g.speed, g.duration)] == pytest.approx([1.0, 8.0, 0.0, 4.0, -1.0, 8.0])
        assert back.speed is None and back.duration is None
    data = tomllib.loads(dump_scene(good))
    data["winch"]["leg"][1]["duration"] = 1.0
    with pytest.raises(ParameterError, match=r"^winch\.leg\[1\]\.duration = 1\.0: must be >= winch\.ramp"):
        scene_from_dict(data)
    data["winch"]["leg"][1]["duration"] = -4.0
    with pytest.raises(ParameterError, match=r"^winch\.leg\[1\]\.duration"):
        scene_from_dict(data)
    data["winch"]["leg"][1]["duration"] = 4.0
    data["winch"]["speed"] = 1.0
    with pytest.raises(ParameterError, match=r"^winch\.speed = 1\.0: must be unset with \[\[winch\.leg\]\]"):
        scene_from_dict(data)
    with pytest.raises(ParameterError, match=r"^winch\.speed = 'missing': is required"):
        scene_from_dict({**data, "winch": {"max_length": 60.0}})
    # l_0 = 50 m: +8 m, hold, then 3 m/s in: L = 58 - 3 (t - 13) reaches 0 at t = 13 + 58 / 3 (ramps: delays of 1 s)
    with pytest.raises(ParameterError, match=r"^winch\.leg\[2\]\.speed = -3\.0: hauls in .* to 0 m at t = 32\.3333 s "
                                             r"in leg 2"):
        _scene(winch=_legs((1.0, 8.0), (0.0, 4.0), (-3.0, 30.0)))
    # paying out 8 m, hauling in 2 m, paying out 6 m: L = 56 + (t - 11) from t = 11 s reaches 60 m at t = 15 s, 62 m
    # when the winch stops (t = 18 s)
    with pytest.raises(ParameterError, match=r"^winch\.leg\[2\]\.speed = 1\.0: pays out .* to 60 m at t = 15 s in leg 2 "
                                             r"\(and to 62 m at t = 18 s\)"):
        _scene(winch=_legs((1.0, 8.0), (-1.0, 2.0), (1.0, 6.0)))
    # a haul-in that takes L to exactly 0 is refused as well: L must stay > 0
    with pytest.raises(ParameterError, match=r"winch\.leg\[1\]\.speed"):
        _scene(winch=_legs((0.0, 2.0), (-1.0, 50.0)))
    _scene(winch=_legs((0.0, 2.0), (-1.0, 49.5)))        # 0.5 m left in the water: allowed


def _lift():
    import sys
    from pathlib import Path
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies"))
    import _lift
    return _lift


def test_payout_then_haulin_returns_the_initial_state():
    """30 m paid out at 1 m/s, held, hauled back in (studies/_lift.py): L returns to l_0 exactly, and 1 s after the winch
    stops the node positions are within 1e-10 m of the initial static state (velocities 1e-8 m/s, top tension 1e-8
    relative). At the stop itself they differ by ~1e-5 m (the Voigt lag of the elements' strain, physical, the same at
    every rtol); it decays with the axial damping, so what is left 1 s later is the integrator's: it shrinks by more
    than 30x from rtol 1e-6 to 1e-8."""
    L = _lift()
    coarse, fine = L.payout_haulin(1e-6), L.payout_haulin(1e-8)
    for r in (coarse, fine):
        assert r["success"] and r["length_m"] == pytest.approx([20.0, 50.0, 20.0], abs=1e-12)
        assert r["at_stop_max_abs_m"] > 1e-6
    assert coarse["at_stop_max_abs_m"] == pytest.approx(fine["at_stop_max_abs_m"], rel=0.05)
    assert coarse["return_max_abs_m"] < 1e-10 and coarse["return_velocity_max_abs_m_s"] < 1e-8
    assert coarse["return_tension_rel"] < 1e-8
    for key in ("return_max_abs_m", "return_velocity_max_abs_m_s", "return_tension_rel"):
        assert fine[key] < coarse[key] / 30, key


def test_haulin_tension_is_weight_plus_drag():
    """Hauling in at a constant 1 m/s: top tension W_b + w L + 1/2 rho (C_D A + C_t d L) v^2 (the drag of body and cable
    pulls down with the weight, the sign reversed from lowering) within 0.05 %, the drag a > 15 % share, while the
    payout leg of the same run matches W_b + w L - 1/2 rho (...) v^2 as the single-speed lowering does."""
    r = _lift().payout_haulin(1e-8)
    assert r["haulin_tension_rel_err"] < 5e-4 and r["haulin_drag_share"] > 0.15
    assert r["payout_tension_rel_err"] < 5e-4


def test_mass_in_water_follows_L_both_ways():
    """The free nodes carry M_b + m_r L (1 - 1 / (2 N)) while paying out, holding and hauling back in, and after the
    round trip the mass matrix is the fixed-length model's, to rounding."""
    assert _lift().payout_mass() < 1e-12


LOWER_AND_RECOVER = """
name = "lower a package 30 m and recover it"
[cable]
length = 20.0
ae = 2e7
diameter = 0.03
mass_per_length = 3.0
weight_per_length = 25.0
cd_normal = 1.5
ct_tangential = 0.3
internal_damping = 1e6
segments = 4
[body]
weight = 2000.0
mass_x = 400.0
mass_y = 400.0
drag_area_normal = 1.0
drag_area_tangential = 1.0
[numerics]
duration = 50.0
output_step = 0.5
[winch]
ramp = 3.0
max_length = 60.0
[[winch.leg]]      # lower
speed = 1.5
duration = 20.0
[[winch.leg]]      # hold at depth
speed = 0.0
duration = 5.0
[[winch.leg]]      # recover
speed = -1.5
duration = 20.0
"""


def test_lowering_and_recovery_runs_from_the_cli(tmp_path):
    """``cablesys run`` of a TOML lowering-and-recovery scene (``[[winch.leg]]``, the model ladder's choice, the VM):
    L goes from 20 m to 20 + 1.5 x 20 = 50 m and back, and 2 s after the winch stops the top tension is back at its
    static value W_b + w l_0 (the sheave's pull carries the whole line) to 1e-6. The length changes by design, so the
    ladder does not call the run unsettled (its halves differ because the system does)."""
    import json
    from cablesys.cli import main
    f = tmp_path / "lift.toml"
    f.write_text(LOWER_AND_RECOVER)
    assert main(["run", str(f), "--out", str(tmp_path / "out")]) == 0
    d = np.genfromtxt(tmp_path / "out" / "timeseries.csv", delimiter=",", names=True)
    L, T = d["winch_length_m"], d["tension_top_N"]
    assert L[0] == L[-1] == pytest.approx(20.0, abs=1e-9) and L.max() == pytest.approx(50.0, abs=1e-9)
    assert T[0] == pytest.approx(2000.0 + 25.0 * 20.0, rel=1e-9) and T[-1] == pytest.approx(T[0], rel=1e-6)
    model = json.loads((tmp_path / "out" / "summary.json").read_text())["model"]
    assert model["name"] == "segmented" and "not settled" not in model["reason"]
