"""The AD-derived 2-DOF equations against the terms printed in Wang (1971)."""

import math

import numpy as np
import pytest

from cablesys.model import build_model
from cablesys.scene import Body, Cable, Environment, Numerics, Sinusoid, TopMotion, single_section_scene


def make_scene(*, sphere=True, n_seg=7, current=((0.0, 0.3), (0.4, -0.1)), cbmas=1.0):
    """A scene with every term switched on: thinning, added mass, current profile, two sinusoids."""
    cable = Cable(length=12.0, tension_ref=300.0, ae=2.0e5, diameter=0.02, mass_per_length=0.9,
                  weight_per_length=6.0, thinning_ratio=0.3, added_mass_factor=1.1, cd_normal=1.3,
                  ct_tangential=0.02, internal_damping=40.0, tension_floor=0.0, cable_mass_switch=cbmas)
    body = Body(weight=250.0, mass_x=40.0, mass_y=55.0, drag_area_normal=0.3,
                drag_area_tangential=0.3 if sphere else 0.05, axis_angle_deg=999.0 if sphere else 20.0)
    env = Environment(density=1025.0, gravity=9.81, current_depths=(current[0][0], 3.0 + current[1][0] * 10),
                      current_speeds=(current[0][1], current[1][1]), system_speed=0.2, top_depth=1.0)
    top = TopMotion(x=(Sinusoid(amplitude=0.5, frequency=0.7, phase=0.2),),
                    y=(Sinusoid(amplitude=0.3, frequency=1.1, phase=-0.4),), ramp_s=0.0)   # the bare sinusoids
    return single_section_scene(cable=cable, body=body, environment=env, top_motion=top,
                                numerics=Numerics(drag_segments=n_seg))


def zero_tension(c: Cable):
    """Wang (1971) eq. 1, 4, 5: k, l_0, d_0, M_c."""
    k = c.ae / c.length
    l0 = c.length - c.tension_ref / k
    d0 = c.diameter * (1 - c.thinning_ratio * c.tension_ref / (k * c.length))
    return k, l0, d0, c.mass_per_length * c.length


STATES = [(0.3, 0.01), (-0.7, 0.02), (1.2, -0.005), (0.0, 0.0)]


@pytest.mark.parametrize("phi,u", STATES)
def test_mass_matrix_equals_A1_A2_A3(phi, u):
    """M from d2L/dq'2 equals A1, A2, A3 of Wang (1971) eq. 47-48 (M_cv with eq. 3 thinning)."""
    scene = make_scene()
    m = build_model(scene)
    p = m.parameters(scene)
    M, _ = m.dynamics([phi, u], [0.1, -0.2], np.zeros(7), p)
    M = np.array(M)
    c, b = scene.cable, scene.body
    _, l0, d0, Mc = zero_tension(c)
    l = l0 + u
    Mcv = Mc + c.added_mass_factor * 1025.0 * math.pi * d0**2 / 4 * (1 - c.thinning_ratio * u / c.length) ** 2 * l
    s, co = math.sin(phi), math.cos(phi)
    A1 = l**2 * (Mcv / 3 + b.mass_x * co**2 + b.mass_y * s**2)
    A2 = l * s * co * (b.mass_x - b.mass_y)
    A3 = Mc / 3 + b.mass_x * s**2 + b.mass_y * co**2
    np.testing.assert_allclose(M, [[A1, A2], [A2, A3]], rtol=1e-13, atol=1e-13 * A1)


def test_cable_mass_switch_drops_mass_terms():
    """CBMAS < 0: the cable mass and added-mass terms vanish (the report's program note)."""
    scene = make_scene(cbmas=-1.0)
    m = build_model(scene)
    M, _ = m.dynamics([0.4, 0.01], [0.0, 0.0], np.zeros(7), m.parameters(scene))
    b, l0 = scene.body, zero_tension(scene.cable)[1]
    l, s, co = l0 + 0.01, math.sin(0.4), math.cos(0.4)
    np.testing.assert_allclose(np.array(M)[1, 1], b.mass_x * s**2 + b.mass_y * co**2, rtol=1e-13)
    np.testing.assert_allclose(np.array(M)[0, 0], l**2 * (b.mass_x * co**2 + b.mass_y * s**2), rtol=1e-13)


@pytest.mark.parametrize("phi,u", STATES)
def test_static_terms_equal_dV(phi, u):
    """At rest without current: f = -(dV/dphi, dV/du) of Wang (1971) eq. 49a, 49b."""
    scene = make_scene(current=((0.0, 0.2), (0.4, 0.2)))
    m = build_model(scene)
    p = m.parameters(scene)
    p[m.layout.index("environment.system_speed")] = 0.2        # fluid at rest relative to the system
    _, f = m.dynamics([phi, u], [0.0, 0.0], np.zeros(7), p)
    c, b = scene.cable, scene.body
    k, l0, _, _ = zero_tension(c)
    w = b.weight + 0.5 * c.weight_per_length * c.length
    dV_dphi = (l0 + u) * math.sin(phi) * w                     # eq. 49a
    dV_du = k * u - math.cos(phi) * w                           # eq. 49b
    np.testing.assert_allclose(np.array(f).ravel(), [-dV_dphi, -dV_du], rtol=1e-12, atol=1e-9)


def wang_drag_forces(scene, phi, u, phid, ud, e):
    """Q_bphi + Q_cphi and Q_bu + Q_cu written directly from Wang (1971) eq. 29-45 (NumPy)."""
    c, b, env = scene.cable, scene.body, scene.environment
    rho = env.density
    k, l0, d0, _ = zero_tension(c)
    l = l0 + u
    t, xs, ys, xsd, ysd = e[:5]
    s, co = math.sin(phi), math.cos(phi)

    def current(depth):
        return np.interp(depth, env.current_depths, env.current_speeds) - env.system_speed

    ys_depth = env.top_depth + ys
    yb = ys_depth + l * co                                                   # eq. 10d
    xbd = xsd - ud * s - l * co * phid                                       # eq. 11a
    ybd = ysd + ud * co - l * s * phid                                       # eq. 11b
    vx, vy = current(yb) - xbd, 0.0 - ybd                                    # eq. 32b
    if b.is_sphere:
        vb = math.hypot(vx, vy)
        Dbx, Dby = 0.5 * rho * b.drag_area_normal * vb * vx, 0.5 * rho * b.drag_area_normal * vb * vy  # eq. 32c-d
    else:
        pb = math.radians(b.axis_angle_deg)
        vbt = -vx * math.sin(pb) + vy * math.cos(pb)                         # eq. 34a
        vbn = -vx * math.cos(pb) - vy * math.sin(pb)                         # eq. 34b
        Dbn = 0.5 * rho * b.drag_area_normal * vbn * abs(vbn)               # eq. 33a
        Dbt = 0.5 * rho * b.drag_area_tangential * vbt * abs(vbt)           # eq. 33b
        Dbx = -math.sin(pb) * Dbt - math.cos(pb) * Dbn                       # eq. 35a
        Dby = math.cos(pb) * Dbt - math.sin(pb) * Dbn                        # eq. 35b
    Qbu = -Dbx * s + Dby * co                                                # eq. 37a
    Qbphi = l * (-Dbx * co - Dby * s)                                        # eq. 37b
    N = scene.numerics.drag_segments
    d = d0 * (1 - c.thinning_ratio * u / c.length)                           # eq. 3
    sum_n, sum_t = 0.0, 0.0
    for i in range(1, N + 1):
        a = (i - 0.5)
        yci = ys_depth + a * l / N * co                                      # eq. 30b
        vcti = -xsd * s + ysd * co + a * ud / N                              # eq. 39a
        vcni = -xsd * co - ysd * s + a * l / N * phid                        # eq. 39b
        xi, eta = current(yci), 0.0
        vfti, vfni = -xi * s + eta * co, -xi * co - eta * s                  # eq. 40a-b
        vqn, vqt = vfni - vcni, vfti - vcti                                  # eq. 41a-b
        sum_n += a * abs(vqn) * vqn
        sum_t += abs(vqt) * vqt
    Qcphi = 0.5 * rho * c.cd_normal * d * (l / N) ** 2 * sum_n               # eq. 43
    Qcu = 0.5 * c.ct_tangential * rho * d * (l / N) * sum_t                  # eq. 45
    return Qbphi + Qcphi, Qbu + Qcu


DRAG_LABELS = ("cable.cd_normal", "cable.ct_tangential", "body.drag_area_normal", "body.drag_area_tangential")


@pytest.mark.parametrize("sphere", [True, False])
@pytest.mark.parametrize("state", [(0.3, 0.01, 0.2, -0.05), (-0.6, 0.002, -0.4, 0.1)])
def test_drag_generalized_forces_match_eq_37_43_45(sphere, state):
    """Virtual-work drag forces equal Wang's eq. 37 (body), 43 and 45 (cable), current profile included."""
    scene = make_scene(sphere=sphere)
    m = build_model(scene)
    p = m.parameters(scene)
    p_off = p.copy()
    p_off[[m.layout.index(lbl) for lbl in DRAG_LABELS]] = 0.0   # same function, drag switched off by value
    phi, u, phid, ud = state
    e = np.array([0.0, 0.1, -0.05, 0.3, 0.2, 0.0, 0.0])
    _, f_on = m.dynamics([phi, u], [phid, ud], e, p)
    _, f_off = m.dynamics([phi, u], [phid, ud], e, p_off)
    Q = np.array(f_on - f_off).ravel()
    np.testing.assert_allclose(Q, wang_drag_forces(scene, phi, u, phid, ud, e), rtol=1e-11, atol=1e-12)


def test_internal_damping_and_slack_force():
    """Q_Iu = -(C_I/l_r) u' (eq. 46); while slack the cable force is TENS (eq. 54)."""
    scene = make_scene()
    m = build_model(scene)
    p = m.parameters(scene)
    p_drag_off = p.copy()
    p_drag_off[[m.layout.index(lbl) for lbl in DRAG_LABELS]] = 0.0
    p_ci0 = p_drag_off.copy()
    p_ci0[m.layout.index("cable.internal_damping")] = 0.0
    q, qd = [0.2, 0.01], [0.0, 0.3]
    _, f1 = m.dynamics(q, qd, np.zeros(7), p_drag_off)
    _, f0 = m.dynamics(q, qd, np.zeros(7), p_ci0)
    c = scene.cable
    np.testing.assert_allclose(float(f1[1] - f0[1]), -c.internal_damping / c.length * 0.3, rtol=1e-12)
    p_slack = p_drag_off.copy()
    p_slack[m.layout.index("slack")] = 1.0
    p_slack[m.layout.index("cable.tension_floor")] = 5.0
    _, fs = m.dynamics(q, qd, np.zeros(7), p_slack)
    _, ft = m.dynamics(q, qd, np.zeros(7), p_drag_off)
    F_bc = c.ae / c.length * 0.01 + c.internal_damping / c.length * 0.3
    np.testing.assert_allclose(float(fs[1] - ft[1]), F_bc - 5.0, rtol=1e-12)


def test_changing_a_value_needs_no_rebuild():
    """One compiled function serves any AE: the static stretch follows k u = W_b + W_c/2."""
    scene = make_scene()
    m = build_model(scene)
    from cablesys.linear import steady_state
    for ae in (1e4, 1e5, 1e7):
        s2 = scene.replace_section(0, cable={"ae": ae}).with_environment(current_speeds=(0.2, 0.2))
        ss = steady_state(m, m.parameters(s2))
        c, b = s2.cable, s2.body
        assert ss.q[0] == pytest.approx(0.0, abs=1e-12)
        assert ss.q[1] == pytest.approx((b.weight + 0.5 * c.weight_per_length * c.length) * c.length / ae, rel=1e-10)


def test_parameter_labels_follow_scene_fields():
    scene = make_scene()
    m = build_model(scene)
    p = m.parameters(scene)
    assert p[m.layout.index("cable.ae")] == scene.cable.ae
    assert p[m.layout.index("top_motion.y[0].frequency")] == 1.1
    assert p[m.layout.index("body.axis_angle")] == pytest.approx(math.radians(999.0))
    with pytest.raises(ValueError, match="not a model parameter"):
        m.layout.index("cable.youngs_modulus")


def test_top_motion_function_and_derivatives():
    scene = make_scene()
    m = build_model(scene)
    p = m.parameters(scene)
    t = 1.7
    e = np.array(m.top(t, p)).ravel()
    a, w, ph = 0.5, 0.7, 0.2
    np.testing.assert_allclose(e[[1, 3, 5]], [a * math.sin(w * t + ph), a * w * math.cos(w * t + ph),
                                              -a * w * w * math.sin(w * t + ph)], rtol=1e-13)
