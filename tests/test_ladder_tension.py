"""Top and body-end tension of Wang's 2-DOF model (momentum balances of the straight cable and body)."""

import math

import numpy as np

import pytest

from cablesys.linear.linearization import linearize
from cablesys.linear.steady import steady_state
from cablesys.model import build_model
from cablesys.scene import dale_scene


def test_hanging_tensions_are_hand_statics(dale):
    """At rest: top W_b + W_c, body end W_b, Wang's spring force k u = W_b + W_c/2 (eq. 49b, 54)."""
    scene, model, p = dale
    y = steady_state(model, p).outputs
    w_b, w_c = scene.body.weight, scene.cable.total_weight
    assert y["tension_top"] == pytest.approx(w_b + w_c, rel=1e-10)
    assert y["tension_bottom"] == pytest.approx(w_b, rel=1e-10)
    assert y["tension_mid"] == pytest.approx(w_b + 0.5 * w_c, rel=1e-10)


def test_slow_heave_tension_is_weight_plus_inertia(dale):
    """Vertical top motion far below the axial frequency: the top carries W + (M_bv + M_c) a, the
    body end W_b + M_bv a (the cable's added mass acts normal to it only, eq. 23)."""
    scene, model, p = dale
    lin = linearize(model, p)
    w_ax = math.sqrt(scene.cable.spring_constant / (scene.body.mass_y + scene.cable.total_mass / 3))
    omega = 0.01 * w_ax
    _, Y = lin.transfer([omega])
    col = lin.input_labels.index("y_s")
    top = abs(Y[0, lin.output_labels.index("tension_top"), col])
    bottom = abs(Y[0, lin.output_labels.index("tension_bottom"), col])
    m_b, m_c = scene.body.mass_y, scene.cable.total_mass
    assert top == pytest.approx((m_b + m_c) * omega**2, rel=1e-3)
    assert bottom == pytest.approx(m_b * omega**2, rel=1e-3)


def test_steady_current_top_force_balances_weight_and_drag(dale):
    """In a uniform current the top force is the vector sum of the weights and the total drag:
    F_top = (D_x, W_b + W_c + D_y), with the drag of the body (eq. 32) and of the inclined cable
    (normal along e_n, eq. 42; tangential along e_t, eq. 44) in the relative flow (U, 0)."""
    scene, _, _ = dale
    U = 0.3
    sc = scene.with_environment(current_speeds=(U,))
    model = build_model(sc)
    p = model.parameters(sc)
    st = steady_state(model, p)
    phi = st.q[0]
    c, b, rho = sc.cable, sc.body, sc.environment.density
    length = c.length_zero + st.q[1]
    d = c.diameter                                     # thinning ratio 0
    s_, c_ = math.sin(phi), math.cos(phi)
    v_n, v_t = -U * c_, -U * s_                        # (U, 0) . e_n, (U, 0) . e_t
    d_n = 0.5 * rho * c.cd_normal * d * length * abs(v_n) * v_n
    d_t = 0.5 * rho * c.ct_tangential * d * length * abs(v_t) * v_t
    d_x = 0.5 * rho * b.drag_area_normal * U * U + d_n * (-c_) + d_t * (-s_)
    d_y = d_n * (-s_) + d_t * c_
    expect = math.hypot(d_x, b.weight + c.total_weight + d_y)
    assert st.outputs["tension_top"] == pytest.approx(expect, rel=1e-9)
    assert st.outputs["tension_bottom"] == pytest.approx(math.hypot(b.weight, 0.5 * rho * b.drag_area_normal * U * U), rel=1e-9)


@pytest.mark.parametrize("current", [0.0, 0.3])
def test_top_tension_matches_the_segmented_cable_quasi_statically(current, monkeypatch):
    """Against the segmented cable at N = 40 (issue 11): hanging still (and in a 0.3 m/s current, where the
    bowed cable's drag differs from the chord's by 0.4 %), and the top-tension amplitude for a slow heave."""
    monkeypatch.setenv("CABLESYS_COMPILE", "0")
    from cablesys.ladder.rungs import build_rung, rung_scene
    scene = dale_scene().with_environment(current_speeds=(current,))
    out = {}
    for name, n in (("wang", 1), ("segmented", 40)):
        sc = rung_scene(scene, name, n)
        m = build_rung(sc, name, n)
        p = m.parameters(sc)
        st = steady_state(m, p)
        lin = linearize(m, p, steady=st)
        _, Y = lin.transfer([0.3])
        out[name] = (st.outputs["tension_top"], st.outputs["tension_bottom"],
                     abs(Y[0, lin.output_labels.index("tension_top"), lin.input_labels.index("y_s")]))
    (t_w, b_w, a_w), (t_s, b_s, a_s) = out["wang"], out["segmented"]
    assert t_w == pytest.approx(t_s, rel=1e-9 if current == 0 else 1e-2)
    assert b_w == pytest.approx(b_s, rel=1e-9)
    if current == 0:
        assert a_w == pytest.approx(a_s, rel=1e-6)


@pytest.mark.parametrize("kind, n", [("segmented", 4), ("segmented", 5), ("quasi-static", 1), ("quasi-static", 4),
                                     ("winch", 1)])
def test_every_model_names_its_hanging_tensions_alike(kind, n):
    """Hanging at rest in still water every model's tension_top is the submerged weight of cable and body,
    tension_bottom the body's and tension_mid the body's plus half the cable's (statics of the hanging line,
    Wang 1971 eq. 49b): the segmented cable's mid-length interpolation (N even: the two elements at the
    middle node; N odd: the middle element) and the quasi-static reductions mean the same as Wang's."""
    from cablesys.model.quasistatic import build_quasistatic
    from cablesys.model.winch import WINCH_OUTPUTS, build_winch_model, rest_state
    from cablesys.statics.steady import steady_state as rest
    scene = dale_scene().replace_section(0, cable={"segments": n})
    w_b, w_c = scene.body.weight, scene.cable.total_weight
    if kind == "winch":
        wm = build_winch_model(scene)
        p = wm.parameters(scene)
        for axis in "xy":                                    # the top held still
            p[wm.layout.index(f"top_motion.{axis}[0].amplitude")] = 0.0
        y = dict(zip(WINCH_OUTPUTS, np.array(wm.outputs(rest_state(wm, p), [0, 0], 0.0, p, np.zeros(4))).ravel()))
    else:
        model = build_model(scene) if kind == "segmented" else build_quasistatic(scene)
        y = rest(model, model.parameters(scene)).outputs
        assert "tension" not in model.output_labels          # a tension is named by where it is
    assert y["tension_top"] == pytest.approx(w_b + w_c, rel=1e-6)
    assert y["tension_bottom"] == pytest.approx(w_b, rel=1e-6)
    assert y["tension_mid"] == pytest.approx(w_b + 0.5 * w_c, rel=1e-6)
