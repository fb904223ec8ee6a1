"""Optimal heave compensation on the segmented node model (cablesys.model.segmented_winch_control, cablesys.control):
the controlled node winch at zero payout equals the fixed-length node model; driven by a prescribed alpha(t) it
follows the node model's prescribed-profile winch (segmented_winch) on the same L(t); the OCP on it solves, keeps
its limits in a CVODES re-run and compensates a heaving top; on a stiff short line in still water its optimum
compensates as much as the optimum on Wang's 2-DOF winch."""

import math

import casadi as ca
import numpy as np
import pytest
from control_checks import assert_compiled_optimum_equals_vm

from cablesys.control import WinchLimits, heave_problem, optimal_payout, resimulate
from cablesys.errors import ParameterError
from cablesys.model import build_model
from cablesys.model.segmented_winch_control import build_node_winch_model, rest_state
from cablesys.model.winch import WINCH_OUTPUTS
from cablesys.scene import Body, Cable, Environment, Numerics, Sinusoid, TopMotion, Winch
from cablesys.scene.ends import payout_profile
from cablesys.scene.scene import single_section_scene

G = 9.80665
W_B, M_B, W_R, M_R, AE, L0 = 500.0, 100.0, 8.0, 1.0, 1e6, 50.0


def _scene(n=4, *, winch=None, top=None, current=0.0, cd=0.0, c_i=0.0, cda=0.0, duration=10.0, ae=AE,
           length=L0, w_b=W_B, m_b=M_B):
    cable = Cable(length=length, ae=ae, diameter=0.02, mass_per_length=M_R, weight_per_length=W_R,
                  added_mass_factor=0.0, cd_normal=cd, ct_tangential=0.3 * cd, internal_damping=c_i, segments=n)
    body = Body(weight=w_b, mass_x=m_b, mass_y=m_b, drag_area_normal=cda, drag_area_tangential=cda)
    return single_section_scene(cable=cable, body=body, environment=Environment(gravity=G, current_speeds=(current,)),
                                top_motion=top or TopMotion(), winch=winch,
                                numerics=Numerics(duration=duration, output_step=0.5))


HEAVE = TopMotion(y=(Sinusoid(amplitude=1.0, frequency=0.8),), x=(Sinusoid(amplitude=0.3, frequency=0.5),))


def test_zero_payout_is_the_fixed_length_node_model():
    """alpha = 0, w = 0, L = l_0: the controlled winch's right-hand side and outputs equal the fixed-length node
    model's to 1e-10 at states along that model's own run (heaving top, current, drag, Voigt damping)."""
    from cablesys.time_domain import simulate
    kw = dict(top=HEAVE, current=0.5, cd=1.2, c_i=2e4, cda=0.5, duration=6.0)
    sc = _scene(**kw)
    fixed, ctl = build_model(sc), build_node_winch_model(sc)
    p = fixed.parameters(sc)
    run = simulate(sc, model=fixed)
    t, X = np.asarray(run.time), np.asarray(run.states).T
    l0 = float(rest_state(ctl, p)[-2])
    pairs = [(n, fixed.output_labels.index(m)) for n, m in (("heave", "y_b"), ("x_b", "x_b"),
                                                           ("tension_top", "tension_top"),
                                                           ("tension_mid", "tension_mid"),
                                                           ("tension_bottom", "tension_bottom"), ("stretch", "u"))]
    for k in range(1, len(t), 2):
        xf = np.array(fixed.ode(X[k], t[k], p)).ravel()
        xc = np.array(ctl.ode(np.r_[X[k], l0, 0.0], [0.0, 0.0], t[k], p, np.zeros(4))).ravel()
        np.testing.assert_allclose(xc[:-2], xf, rtol=1e-10, atol=1e-10 * np.max(np.abs(xf)))
        assert xc[-2] == 0.0 and xc[-1] == 0.0
        yf = np.array(fixed.outputs(X[k], fixed.top(t[k], p), p)).ravel()
        yc = np.array(ctl.outputs(np.r_[X[k], l0, 0.0], [0.0, 0.0], t[k], p, np.zeros(4))).ravel()
        for name, j in pairs:
            assert yc[WINCH_OUTPUTS.index(name)] == pytest.approx(yf[j], rel=1e-10, abs=1e-9)
        tens = [yf[fixed.output_labels.index(f"element_tension[{e}]")] for e in range(4)]
        assert yc[ctl.output_index("tension_least")] == pytest.approx(min(tens), rel=1e-12)


def test_prescribed_alpha_follows_the_payout_profile_model():
    """Driven by the profile's alpha(t) from rest, the controlled winch integrates L and w itself (L' = w, w' =
    alpha) while the [winch] scene reads L(t), w(t) in closed form (payout_profile): the two runs agree to the
    integrators' tolerance, 3 m of payout in 10 s through a current with drag and Voigt damping."""
    wch = Winch(speed=0.5, start=1.0, duration=8.0, ramp=2.0, max_length=60.0)
    kw = dict(top=HEAVE, current=0.4, cd=1.2, c_i=2e4, cda=0.5, duration=10.0)
    sc_ctl, sc_pay = _scene(**kw), _scene(**kw, winch=wch)
    ctl, pay = build_node_winch_model(sc_ctl), build_model(sc_pay)
    pc, pp = ctl.parameters(sc_ctl), pay.parameters(sc_pay)
    x0 = rest_state(ctl, pc)
    t_out = np.linspace(0.0, 10.0, 21)
    alpha = lambda t: wch.profile(t)[2]
    x, t = ca.SX.sym("x", ctl.nx), ca.SX.sym("t")
    a_t = payout_profile(t, wch.speed, wch.start, wch.duration, wch.ramp, fmin=ca.fmin, fmax=ca.fmax)[2]
    opts = {"reltol": 1e-10, "abstol": 1e-10}
    run_ctl = ca.integrator("ctl", "cvodes", {"x": x, "t": t, "ode": ctl.ode(x, ca.vertcat(a_t, 0), t, pc, np.zeros(4))},
                            0.0, t_out[1:], opts)
    run_pay = ca.integrator("pay", "cvodes", {"x": x[:-2], "t": t, "ode": pay.ode(x[:-2], t, pp)}, 0.0, t_out[1:], opts)
    rc_y = np.column_stack([x0, np.array(run_ctl(x0=x0)["xf"])])
    rp_y = np.column_stack([x0[:-2], np.array(run_pay(x0=x0[:-2])["xf"])])
    L_closed = x0[-2] + np.array([wch.profile(t)[0] for t in t_out])
    np.testing.assert_allclose(rc_y[-2], L_closed, atol=1e-8)
    assert L_closed[-1] - L_closed[0] == pytest.approx(0.5 * 6.0, rel=1e-12)
    np.testing.assert_allclose(rc_y[:-2], rp_y, atol=1e-6)
    # and the outputs: the sheave tension with the half element's material acceleration, the power T_top w
    k = 12
    yc = np.array(ctl.outputs(rc_y[:, k], [alpha(t_out[k]), 0], t_out[k], pc, np.zeros(4))).ravel()
    yp = np.array(pay.outputs(rp_y[:, k], pay.top(t_out[k], pp), pp)).ravel()
    for name, src in (("tension_top", "tension_top"), ("power", "winch_power"), ("heave", "y_b")):
        assert yc[WINCH_OUTPUTS.index(name)] == pytest.approx(yp[pay.output_labels.index(src)], rel=1e-6)


def test_node_winch_refuses_what_it_would_drop():
    """A [winch] profile (the control drives L: the scene's payout would be dropped) is a named error."""
    with pytest.raises(ParameterError, match="winch"):
        build_node_winch_model(_scene(winch=Winch(speed=0.5, start=1.0, duration=8.0, ramp=2.0, max_length=60.0)))


def test_node_compensator_is_wangs_on_one_massless_element():
    """The passive heave compensator under the sheave (piston m_p, spring k_p, damper c_p, precharge) in the node
    model (Newton's equation of the piston with the cable's force on the sheave) and in Wang's 2-DOF winch (Lagrange's
    equations with the piston's kinetic energy, cablesys.model.winch): N = 1 with a massless cable, no drag, no Voigt
    damping, a heaving top and a payout alpha(t): two derivations, one system; body position, stroke and top tension
    agree to 1e-6 over 8 s from the rest state that heave_problem's precharge sets (the stroke 0 there, to 1e-9 m:
    the precharge carries the static load, the cable's weight and the body's), the body moving with the top."""
    from scipy.integrate import solve_ivp
    from cablesys.control.payout import model_rest_state, precharge
    from cablesys.model.winch import build_winch_model
    top = TopMotion(y=(Sinusoid(amplitude=0.8, frequency=1.0),), ramp_s=0.0)
    sc = _scene(1, top=top).replace_section(cable={"cable_mass_switch": -1.0})
    node, wang = build_node_winch_model(sc, compensator=True), build_winch_model(sc, compensator=True)
    p_n, p_w = node.parameters(sc), wang.parameters(sc)
    c = np.array([300.0, 4e3, 1.5e3, 0.0])
    c_n, c_w = np.r_[c[:3], precharge(node, sc, p_n, c)], np.r_[c[:3], precharge(wang, sc, p_w, c)]
    assert c_n[3] == pytest.approx(c_w[3], rel=1e-9) and c_n[3] == pytest.approx(-(W_B + W_R * L0), rel=1e-3)
    x_n0, x_w0 = model_rest_state(node, p_n, c_n), model_rest_state(wang, p_w, c_w)
    assert abs(x_n0[node.nq - 1]) < 1e-9 and abs(x_w0[wang.nq - 1]) < 1e-9
    # Wang's rest (phi' = l' = s' = 0) moves the body with the top, which starts at 0.8 m/s: the node's the same
    x_n0[node.nq: node.nq + 2] = np.array(node.top(0.0, p_n)).ravel()[3:5]
    alpha = lambda t: 0.3 * math.sin(0.7 * t)
    times = np.linspace(0.0, 8.0, 17)
    run = lambda m, p, cc, x0: solve_ivp(lambda t, x: np.array(m.ode(x, [alpha(t), 0.0], t, p, cc)).ravel(), (0, 8),
                                         x0, t_eval=times, rtol=1e-11, atol=1e-12, method="LSODA")
    rn, rw = run(node, p_n, c_n, x_n0), run(wang, p_w, c_w, x_w0)
    names = ("x_b", "heave", "stroke", "tension_top", "length")
    for k, t in enumerate(times):
        yn = np.array(node.outputs(rn.y[:, k], [alpha(t), 0.0], t, p_n, c_n)).ravel()
        yw = np.array(wang.outputs(rw.y[:, k], [alpha(t), 0.0], t, p_w, c_w)).ravel()
        for name in names:
            assert yn[node.output_index(name)] == pytest.approx(yw[wang.output_index(name)], rel=1e-6, abs=1e-6), name
    assert np.ptp(rn.y[node.nq - 1]) > 0.05                  # the piston strokes


# a light 100 m line, soft enough (AE = 2.5e4 N) that RK4 at dt / 2 is stable for the node model's axial modes
# at N = 4, with its first axial mode (about 1.1 rad/s with the body) well above the 0.4 rad/s tip heave and no
# current: the quasi-static stretch both the 2-DOF and the node model carry; |w| <= 0.2 m/s against the tip's
# 0.4 m/s peak, so the speed limit decides the residual
SOFT = dict(ae=2.5e4, length=100.0, w_b=1000.0, m_b=150.0)
LIMITS = WinchLimits(speed=0.2, acceleration=1.0)


def _soft_scene(n):
    sc = _scene(n, top=TopMotion(y=(Sinusoid(amplitude=1.0, frequency=0.4),), ramp_s=4.0), duration=20.0, **SOFT)
    return sc.replace_section(cable={"mass_per_length": 2.0, "weight_per_length": 17.0})


@pytest.fixture(scope="module")
def optima():
    out = {}
    for model in ("wang", "segmented"):
        pr = heave_problem(_soft_scene(4), LIMITS, dt=0.5, model=model)
        out[model] = (pr, optimal_payout(pr, 20.0))
    return out


def test_node_model_optimum_solves_and_holds_its_limits(optima):
    """The OCP on the node model (N = 4, 20 s, dt 0.5 s): IPOPT converges, CVODES between the grid points keeps
    every limit within 1 % (speed at its bound most of each period), and the body heave is cut by more than a
    factor 2.5 against the winch held still (measured 3.3: the rate limit's residual)."""
    pr, res = optima["segmented"]
    assert pr.model.segments == 4 and pr.model.nx == 18
    assert res.success and res.status == "Solve_Succeeded", res.message
    check = resimulate(pr, res, per_interval=4)
    assert check["max_relative_violation"] < 0.01, check
    assert res.speed_max_m_s <= LIMITS.speed * (1 + 1e-6)
    assert res.speed_max_m_s > 0.99 * LIMITS.speed                # the limit is what stops it
    assert res.heave_rms_m < res.uncompensated_heave_rms_m / 2.5
    assert res.tension_min_n > pr.floor


def test_wang_and_node_optima_agree_where_the_models_do(optima):
    """No current, the axial mode above the heave: Wang's 2-DOF winch and the node model (N = 4) give the same
    uncompensated heave within 3 % and optimal heave reductions within 3 % of each other (measured 1.7 % and
    0.5 %): two models, two transcriptions, one physical limit of compensation."""
    (pw, rw), (pn, rn) = optima["wang"], optima["segmented"]
    assert rw.success and rn.success
    assert rn.uncompensated_heave_rms_m == pytest.approx(rw.uncompensated_heave_rms_m, rel=0.03)
    assert rn.heave_reduction_db == pytest.approx(rw.heave_reduction_db, rel=0.03)
    assert rw.heave_reduction_db < -8.0


def test_gauss_newton_hessian_finds_the_exact_hessians_optimum(optima):
    """IPOPT with the objective's Gauss-Newton matrix (the default, no second derivatives of the dynamics) and with
    the exact AD Hessian solve one NLP: on the node model (N = 4, speed limit active), both to IPOPT's tolerance
    1e-10 over 10 s, the two optima agree to 1e-9 in the objective and 1e-6 m/s^2 in the controls (but the last: below); the
    Gauss-Newton residuals
    are the stage cost's square roots (r^T r equals the stage cost at any state, to rounding)."""
    from cablesys.control.kernels import residual_function
    pr, default = optima["segmented"]
    assert default.stats["hessian"] == "gauss-newton"
    gn = optimal_payout(pr, 10.0, tol=1e-10)
    exact = optimal_payout(pr, 10.0, hessian="exact", tol=1e-10)
    assert exact.success and gn.success
    assert gn.objective == pytest.approx(exact.objective, rel=1e-9)
    # the last interval's alpha moves only the terminal node (its heave, and w against the speed bound there) besides
    # its own small weight c_a: a nearly flat direction, not compared
    np.testing.assert_allclose(gn.acceleration[:-1], exact.acceleration[:-1], atol=1e-6)
    r = residual_function(pr)
    E = pr.exogenous([3.0])[0]
    for k in (5, 12, 19):
        x, u = gn.states[k], gn.acceleration[k]
        cost = float(pr.stage(x, u, E)[0])
        assert float(ca.sumsqr(r(x, u, E))) == pytest.approx(cost, rel=1e-12)
    with pytest.raises(ParameterError, match="hessian"):
        optimal_payout(pr, 4.0, hessian="bfgs")


def test_control_model_names_are_checked():
    with pytest.raises(ParameterError, match="model"):
        heave_problem(_soft_scene(4), LIMITS, model="chain")
    with pytest.raises(ParameterError, match="segments"):
        heave_problem(_soft_scene(1), LIMITS, model="segmented")
    with pytest.raises(ParameterError, match="substeps"):
        heave_problem(_soft_scene(4), LIMITS, dt=0.5, model="segmented", substeps=1)


def test_state_map_puts_the_node_rest_on_wangs():
    """Still water: the node model's rest line (N = 4) seen as Wang's chord (phi, l) is Wang's rest state, the
    elastic hanging line's L + (W_b L + w L^2 / 2) / AE for both (weight linear along the line, so the lumped
    element stretches sum to the continuous one), phi = 0; and a node controller of N = 2 reads the plant's
    node 2 and node 4 (the material fractions 1/2 and 1)."""
    from cablesys.control.mpc import state_map
    sc = _soft_scene(4)
    pn = heave_problem(sc, LIMITS, dt=0.5, model="segmented")
    pw = heave_problem(sc, LIMITS, dt=0.5, model="wang")
    p2 = heave_problem(sc, LIMITS, dt=0.5, model="segmented", segments=2)
    xw = state_map(pn, pw)(pn.x_rest, 0.0)
    L = pw.x_rest[-2]
    elastic = L + (1000.0 * L + 0.5 * 17.0 * L ** 2) / SOFT["ae"]
    assert xw[1] == pytest.approx(elastic, rel=1e-9) and pw.x_rest[1] == pytest.approx(elastic, rel=1e-9)
    np.testing.assert_allclose(xw, pw.x_rest, atol=1e-7)
    x2 = state_map(pn, p2)(pn.x_rest, 0.0)
    np.testing.assert_allclose(x2[:4], pn.x_rest[[2, 3, 6, 7]], rtol=1e-12)
    np.testing.assert_allclose(x2, p2.x_rest, atol=1e-6 * elastic)
    with pytest.raises(ParameterError, match="controller"):
        state_map(pw, pn)


def test_mpc_with_a_coarser_controller_than_the_plant():
    """The closed loop of the issue's model mismatch: the plant the node model (N = 4, CVODES), the MPC's
    controller Wang's 2-DOF winch (RK4): the MPC and the open-loop optimum both cut the heave against the winch
    held still, and the record says which model ran where."""
    from cablesys.control.mpc import compare_compensation
    sc = _soft_scene(4).with_numerics(duration=30.0)
    res = compare_compensation(sc, LIMITS, duration=16.0, horizon=6.0, dt=0.5, strategies=("none", "mpc"),
                               plant_model="segmented", controller_model="wang")
    m = res.metrics
    assert res.success, res.message
    assert "segmented node model" in res.stats["plant_model"] and "wang" in res.stats["controller_model"]
    assert m["mpc"]["heave_reduction_db"] < -3.0, m["mpc"]
    assert m["mpc"]["speed_max_m_s"] <= LIMITS.speed * (1 + 1e-6)


def test_control_command_names_the_models_it_ran(tmp_path):
    """``cablesys control --model segmented --segments 4``: control.json's ``models`` name the node-model plant, on
    which every strategy played (the passive compensator too, with its piston coordinate), and the Wang controller."""
    import argparse
    import json
    from cablesys.control.cli import register
    from cablesys.scene import dump_scene
    path = tmp_path / "soft.toml"
    path.write_text(dump_scene(_soft_scene(4).with_numerics(duration=20.0)))
    parser = argparse.ArgumentParser()
    register(parser.add_subparsers(dest="command"))
    args = parser.parse_args(["control", str(path), "--out", str(tmp_path / "out"), "--duration", "10", "--horizon",
                              "4", "--speed", "0.2", "--model", "segmented", "--segments", "4",
                              "--strategies", "none,passive,mpc"])
    assert args.func(args) == 0
    doc = json.loads((tmp_path / "out" / "control.json").read_text())
    models = doc["models"]
    assert "segmented node model with winch, N = 4" in models["plant"] and "as asked" in models["plant"]
    assert models["controller"].startswith("wang 2-DOF")
    assert models["same_plant"] and "passive compensator's with its piston coordinate" in models["plant"]
    assert "NOT the control's model" in models["ladder"]          # the ladder keeps Wang for this still-water line
    assert "plant" not in doc["metrics"]["passive"]
    assert doc["metrics"]["passive"]["heave_reduction_db"] < 0


def test_compiled_step_kernels_find_the_virtual_machines_optimum(quick_compile):
    """More RK4 steps per interval than SUBSTEP_KERNELS_FROM (the node model's stiff axial modes): the NLP calls
    one compiled RK4 step kernel per step, whose C is a substeps-th of the interval's; its optimum equals the
    virtual machine's inlined interval to 1e-8 in the objective, in the same IPOPT iterations (Wang's model with
    one drag segment: the smallest kernel that takes this path)."""
    from cablesys.control.kernels import SUBSTEP_KERNELS_FROM
    sc = _soft_scene(1).with_numerics(drag_segments=1)
    pr = heave_problem(sc, LIMITS, dt=0.5, model="wang", substeps=SUBSTEP_KERNELS_FROM + 1)
    assert_compiled_optimum_equals_vm(pr, 8.0, atol=1e-8)

