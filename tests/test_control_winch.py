"""The winch model (cablesys.model.winch) against Wang's model and against Newton's law by hand."""

import dataclasses

import numpy as np
import pytest

from cablesys.errors import ParameterError
from cablesys.examples import example_path
from cablesys.model import build_model
from cablesys.model.winch import WINCH_OUTPUTS, build_winch_model, rest_state
from cablesys.scene import Sinusoid, TopMotion
from cablesys.scene.toml_io import load_scene


@pytest.fixture(scope="module")
def rov():
    return load_scene(example_path("rov-lift")).with_numerics(drag_segments=2)


def _l0(model, p):
    lay = model.layout
    l_r, t_r, ae = (p[lay.index(f"cable.{n}")] for n in ("length", "tension_ref", "ae"))
    return l_r - t_r * l_r / ae


def test_fixed_length_is_wangs_model(rov):
    """w = 0 and L = l_0: accelerations and outputs equal Wang's 2-DOF model's (l = l_0 + u)."""
    wm, m = build_winch_model(rov), build_model(rov)
    p = wm.parameters(rov)
    l0 = _l0(wm, p)
    rng = np.random.default_rng(3)
    for t in (17.0, 33.0):
        q, qd = np.array([0.05, 0.2]) * rng.standard_normal(2), 0.3 * rng.standard_normal(2)
        xw = np.r_[q[0], l0 + q[1], qd, l0, 0.0]
        a = np.array(wm.ode(xw, [0, 0], t, p, np.zeros(4))).ravel()
        b = np.array(m.ode(np.r_[q, qd], t, p)).ravel()
        np.testing.assert_allclose(a[:4], b, rtol=1e-10, atol=1e-9)
        yw = dict(zip(WINCH_OUTPUTS, np.array(wm.outputs(xw, [0, 0], t, p, np.zeros(4))).ravel()))
        yb = dict(zip(m.output_labels, np.array(m.outputs(np.r_[q, qd], m.top(t, p), p)).ravel()))
        for mine, wang in (("heave", "y_b"), ("tension_mid", "tension_mid"), ("tension_top", "tension_top"),
                           ("tension_bottom", "tension_bottom")):
            assert yw[mine] == pytest.approx(yb[wang], rel=1e-9, abs=1e-6)


def test_paying_out_vertical_cable_is_newtons_law(rov):
    """A vertical massless cable without drag: m_by (y_s'' + l'') = W_b + W_c/2 - F_bc with
    F_bc = k_r l_0/L (l - L) + (C_I/l_r)(l' - w l/L) and W_c = w_r l_r L/l_0 (half the cable's
    weight acts at the body end in Wang's potential, eq. 15), at any L, w, alpha."""
    sc = rov.replace_section(cable={"mass_per_length": 1e-9, "cable_mass_switch": -1.0, "cd_normal": 0.0,
                                    "ct_tangential": 0.0},
                             body={"drag_area_normal": 0.0, "drag_area_tangential": 0.0})
    sc = sc.with_environment(current_depths=(0.0,), current_speeds=(0.0,))
    sc = sc.replace(top_motion=TopMotion(y=(Sinusoid(amplitude=1.5, frequency=0.7, phase=0.3),), ramp_s=0.0))
    wm = build_winch_model(sc)
    p = wm.parameters(sc)
    lay = wm.layout
    g = lambda n: p[lay.index(n)]
    k_r, l0 = g("cable.ae") / g("cable.length"), _l0(wm, p)
    for L, w, alpha, l, ld, t in ((480.0, 0.8, 0.3, 480.4, -0.2, 4.0), (530.0, -1.1, -2.0, 529.9, 0.5, 9.0)):
        x = np.array([0.0, l, 0.0, ld, L, w])
        ldd = np.array(wm.ode(x, [alpha, 0.0], t, p, np.zeros(4))).ravel()[3]
        ys_dd = float(np.array(wm.top(t, p)).ravel()[6])
        F = k_r * l0 / L * (l - L) + g("cable.internal_damping") / g("cable.length") * (ld - w * l / L)
        W_c = g("cable.weight_per_length") * g("cable.length") * L / l0
        expected = (g("body.weight") + W_c / 2 - F) / g("body.mass_y") - ys_dd
        assert ldd == pytest.approx(expected, rel=1e-9)


def test_rest_state_holds_the_weight(rov):
    """At rest the spring force is W_b + W_c/2 (Wang's mean tension) to Newton's tolerance."""
    wm = build_winch_model(rov)
    p = wm.parameters(rov)
    x = rest_state(wm, p)
    y = dict(zip(WINCH_OUTPUTS, np.array(wm.outputs(x, [0, 0], 0.0, p, np.zeros(4))).ravel()))
    lay = wm.layout
    W_b, W_c = p[lay.index("body.weight")], p[lay.index("cable.weight_per_length")] * p[lay.index("cable.length")]
    assert abs(y["tension_mid"] * np.cos(x[0])) == pytest.approx(W_b + W_c / 2, rel=2e-3)   # current: the angle


def test_passive_compensator_is_a_spring_in_series(rov):
    """At rest the piston balances precharge, spring and cable pull: k_p s = F_pre + T_y, so 2 kN
    less precharge moves it down by 2e3 / k_p = 0.1 m (to 1e-4: the body sits 0.1 m deeper in
    the sheared current, which changes its drag and the pull T_y by a few N)."""
    wm = build_winch_model(rov, compensator=True)
    p = wm.parameters(rov)
    T0 = 7293.7 + 33.25 * 500.0
    c = np.array([500.0, 2e4, 5e3, -T0])
    x = rest_state(wm, p, c)
    c2 = c + np.array([0, 0, 0, 2e3])          # 2 kN less upward push
    x2 = rest_state(wm, p, c2)
    assert x2[2] - x[2] == pytest.approx(2e3 / 2e4, rel=1e-4)


def test_chain_is_refused():
    from cablesys.scene import dale_scene
    sc = dale_scene()
    two = dataclasses.replace(sc, sections=sc.sections * 2)
    with pytest.raises(ParameterError, match="sections"):
        build_winch_model(two)
