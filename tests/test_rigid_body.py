"""The rigid, pitching body of the segmented cable (cablesys/model/rigid_body.py) against the point body,
the compound pendulum's linear modes, energy conservation, the static moment balance, and bad input."""

import math
import tomllib

import casadi as ca
import numpy as np
import pytest
import scipy.linalg

from cablesys.errors import ParameterError
from cablesys.ladder.auto import decide
from cablesys.linear import linearize, modes
from cablesys.model import build_model
from cablesys.scene import Anchor, Body, Cable, Environment, Numerics, Scene, Seabed, Section, Sinusoid, TopMotion
from cablesys.scene.scene import single_section_scene
from cablesys.scene.toml_io import dump_scene, scene_from_dict
from cablesys.statics import steady_state
from energy_checks import energy_history

G = 9.80665


def _cable(n=2, *, length=10.0, m=1.0, w=0.0, ae=1e7, cd=0.0, gamma=0.0):
    return Cable(length=length, tension_ref=0.0, ae=ae, diameter=0.02, mass_per_length=m, weight_per_length=w,
                 added_mass_factor=gamma, cd_normal=cd, ct_tangential=0.0, segments=n)


def _scene(body, cable=None, *, current=0.0, top=None, numerics=None, rho=1025.0):
    return single_section_scene(cable=cable or _cable(), body=body,
                                environment=Environment(density=rho, gravity=G, current_speeds=(current,)),
                                top_motion=top or TopMotion(), numerics=numerics or Numerics())


def test_point_body_limit():
    """Zero offsets, no buoyancy, no pitch damping: the rigid body's node accelerations and energies are the point
    body's (Wang 1971 eq. 16, 32-35) to 1e-10 at random states, with cable drag, a current and top motion; its
    pitch is decoupled (theta'' = 0) for equal virtual masses at any attitude (sphere drag does not depend on it).
    With M_bvx != M_bvy (and a cylinder's axis, which turns with the body) they agree at theta = 0, where the
    pitch feels the Munk moment alone: (I + I_a) theta'' = (M_bvx - M_bvy) v_x v_y (Newman 1977, sec. 4.13)."""
    top = TopMotion(x=(Sinusoid(amplitude=0.5, frequency=0.7),), y=(Sinusoid(amplitude=0.3, frequency=1.1),))
    cable = _cable(4, m=2.0, w=15.0, ae=2e6, cd=1.2, gamma=1.0)
    rng = np.random.default_rng(3)
    J = 45.0
    for masses, drag in (((180.0, 180.0), dict(drag_area_normal=0.4, drag_area_tangential=0.4)),
                         ((150.0, 230.0), dict(drag_area_normal=0.6, drag_area_tangential=0.1, axis_angle_deg=20.0))):
        point = Body(weight=800.0, mass_x=masses[0], mass_y=masses[1], **drag)
        rigid = Body(weight=800.0, mass_x=masses[0], mass_y=masses[1], pitch_inertia=J - 5.0, pitch_added_inertia=5.0,
                     **drag)
        sp, sr = _scene(point, cable, current=0.6, top=top), _scene(rigid, cable, current=0.6, top=top)
        mp, mr = build_model(sp), build_model(sr)
        pp, pr = mp.parameters(sp), mr.parameters(sr)
        assert mr.q_labels == mp.q_labels + ("theta_b",) and mr.nq == mp.nq + 1
        nq = mp.nq
        free = point.is_sphere and masses[0] == masses[1]
        for _ in range(5):
            q = np.column_stack([rng.normal(0, 1, 4), 2.5 * np.arange(1, 5) + rng.normal(0, 0.1, 4)]).ravel()
            qd = rng.normal(0, 0.5, nq)
            th, thd = (rng.normal(0, 0.5), rng.normal(0, 0.5)) if free else (0.0, 0.0)
            t = rng.uniform(0, 10)
            ap = np.array(mp.ode(np.concatenate([q, qd]), t, pp)).ravel()
            ar = np.array(mr.ode(np.concatenate([q, [th], qd, [thd]]), t, pr)).ravel()
            np.testing.assert_allclose(ar[nq + 1:2 * nq + 1], ap[nq:], rtol=1e-10, atol=1e-10 * np.max(np.abs(ap)))
            munk = (masses[0] - masses[1]) * qd[-2] * qd[-1] / J
            assert ar[-1] == pytest.approx(munk, rel=1e-10, abs=1e-12)
            e = np.array(mp.top(t, pp)).ravel()
            Kp, Vp = (float(v) for v in mp.energy(np.concatenate([q, qd]), e, pp))
            Kr, Vr = (float(v) for v in mr.energy(np.concatenate([q, [th], qd, [0.0]]), e, pr))
            assert Kr == pytest.approx(Kp, rel=1e-12) and Vr == pytest.approx(Vp, rel=1e-12)
        # the statics: the same node positions; the neutral pitch stays at its guess (level)
        qs_p, qs_r = steady_state(mp, pp).q, steady_state(mr, pr).q
        np.testing.assert_allclose(qs_r[:nq], qs_p, rtol=1e-10, atol=1e-10)
        assert qs_r[-1] == 0.0


def _pendulum(a, inertia, m_c=1.0, body_m=150.0, body_w=1000.0, length=10.0, ae=1e9):
    return _scene(Body(weight=body_w, mass_x=body_m, mass_y=body_m, pitch_inertia=inertia, attachment_y=-a),
                  _cable(2, length=length, m=m_c, ae=ae))


def test_compound_pendulum_modes():
    """A rigid body (mass M, inertia J about its CG, CG a below the attachment) on a two-element weightless cable
    with node masses from a fixed top: the three swing frequencies of the linearized model (cablesys.linear, AD
    in node coordinates) equal the generalized eigenvalues of the chain in link angles (phi_1, phi_2, theta),
    written by hand: T = 1/2 [m_1 x_1'^2 + m_2 x_2'^2 + M (x_2' - a theta')^2 + J theta'^2], x_1 = l phi_1,
    x_2 = l (phi_1 + phi_2); V = W/2 (l phi_1^2 + l phi_2^2 + a theta^2), l the stretched element length
    (Goldstein, Classical Mechanics, sec. 6.2: small oscillations)."""
    L, ae, W, M, m_c = 10.0, 1e9, 1000.0, 150.0, 1.0
    for a, J in ((0.8, 40.0), (2.0, 5.0)):
        scene = _pendulum(a, J, m_c=m_c, body_m=M, body_w=W, length=L, ae=ae)
        model = build_model(scene)
        md = modes(linearize(model, model.parameters(scene)))
        w = np.sort(np.asarray(md.omega_undamped))[:3]
        h = L / 2
        ln = h + W * h / ae                                      # each element stretched by T = W (eq. 1)
        m1, m2 = m_c * h, m_c * h / 2                             # lumped halves of the element masses (eq. 5)
        A = np.array([[ln, 0, 0], [ln, ln, 0], [ln, ln, -a]])     # x_1, x_2, x_cg per (phi_1, phi_2, theta)
        Mm = m1 * np.outer(A[0], A[0]) + m2 * np.outer(A[1], A[1]) + M * np.outer(A[2], A[2]) + np.diag([0, 0, J])
        Kk = W * np.diag([ln, ln, a])
        exact = np.sqrt(np.sort(scipy.linalg.eigh(Kk, Mm, eigvals_only=True)))
        np.testing.assert_allclose(w, exact, rtol=1e-8)


def test_energy_conserved_free_swing():
    """No drag, no damping, top at rest: a rigid body with offset attachment and buoyancy centre swinging and
    pitching conserves K + V (the body's terms included) to 1e-6 of the swing energy over 20 s (tight rtol)."""
    body = Body(weight=800.0, mass_x=150.0, mass_y=180.0, pitch_inertia=30.0, pitch_added_inertia=10.0,
                attachment_x=0.2, attachment_y=-0.7, buoyancy=400.0, buoyancy_x=-0.1, buoyancy_y=-0.3)
    scene = _scene(body, _cable(3, length=6.0, m=2.0, w=10.0, ae=1e6), rho=1e-3,
                   numerics=Numerics(duration=20.0, output_step=0.05, rtol=1e-11, atol=1e-13))
    model = build_model(scene)
    p = model.parameters(scene)
    st = steady_state(model, p)
    x0 = np.concatenate([st.q, np.zeros(model.nq)])
    x0[model.nq:model.nq + 6:2] = 0.3 * np.arange(1, 4) / 3       # sideways node velocities
    x0[model.nq - 1] += 0.4                                        # pitched away from its static attitude
    r, E, swing = energy_history(scene, model, p, x0, st.x)
    assert swing > 1.0
    assert np.max(np.abs(E - E[0])) < 1e-6 * swing
    th = r.states[model.nq - 1]
    assert np.ptp(th) > 0.5                                        # it did pitch


@pytest.mark.parametrize("c, b, B", [((0.0, -0.5), (0.1, -0.2), 300.0),     # buoyancy centre off the axis
                                     ((0.3, -0.5), (0.0, 0.0), 0.0),        # attachment off the axis (a bridle)
                                     ((-0.2, -0.4), (0.15, -0.6), 900.0)])
def test_static_pitch_moment_balance(c, b, B):
    """Hanging at rest the cable is vertical, so the moments of W = W_b + B (down at the CG) and B (up at the
    buoyancy centre) about the attachment vanish: W_b (R c)_x + B (R b)_x = 0, tan(theta) = (W_b c_x + B b_x) /
    (W_b c_y + B b_y) (R the pitch rotation, body axes from the CG)."""
    Wb = 1000.0
    body = Body(weight=Wb, mass_x=200.0, mass_y=200.0, pitch_inertia=50.0, attachment_x=c[0], attachment_y=c[1],
                buoyancy=B, buoyancy_x=b[0], buoyancy_y=b[1])
    scene = _scene(body)
    model = build_model(scene)
    y = steady_state(model, model.parameters(scene)).outputs
    assert y["theta_b"] == pytest.approx(math.atan((Wb * c[0] + B * b[0]) / (Wb * c[1] + B * b[1])), abs=1e-10)
    assert y["x_b"] == pytest.approx(0.0, abs=1e-10)
    th = y["theta_b"]
    assert y["x_cg"] == pytest.approx(-(math.cos(th) * c[0] - math.sin(th) * c[1]), abs=1e-10)


def test_static_pitch_in_a_current():
    """A weightless, drag-free cable holding a sphere-drag body (CG a below the attachment) in a current U: the
    drag D = 1/2 rho C_D A U^2 and W_b act at the CG, so the CG lies on the line of the cable's pull,
    tan(theta) = -D / W_b, and the cable leans at atan(D / W_b) (Wang 1971 eq. 32)."""
    Wb, cda, U, rho, a = 800.0, 0.5, 1.0, 1025.0, 0.6
    body = Body(weight=Wb, mass_x=200.0, mass_y=200.0, drag_area_normal=cda, drag_area_tangential=cda,
                pitch_inertia=50.0, attachment_y=-a)
    scene = _scene(body, current=U, rho=rho)
    model = build_model(scene)
    y = steady_state(model, model.parameters(scene)).outputs
    D = 0.5 * rho * cda * U**2
    assert y["theta_b"] == pytest.approx(math.atan(-D / Wb), abs=1e-9)
    assert y["x_b"] / y["y_b"] == pytest.approx(D / Wb, rel=1e-9)


@pytest.mark.parametrize("heading", [None, 60.0])
def test_rigid_intermediate_body_on_an_anchored_line(heading):
    """Two sections from the top to an anchor with a rigid body between them (attachment above the CG, buoyancy
    centre off it). Both sections pull at the attachment point, so the body's attitude balances its weight and
    buoyancy about it alone, tan(theta) = (W_b c_x + B b_x) / (W_b c_y + B b_y) as hanging free, and the line's nodes
    are those of a point body of net weight W_b. In space (a current heading with no flow: the 3-D equations) the
    yaw about the vertical is neutral and the attitude is the planar pitch, a = (cos(theta/2), 0, 0, sin(theta/2))."""
    Wb, B, c, b = 2000.0, 300.0, (0.0, -0.5), (0.1, -0.2)
    env = Environment(gravity=G, current_speeds=(0.0,), current_headings_deg=() if heading is None else (heading,))
    cable = _cable(4, length=150.0, m=100.0, w=800.0, ae=5e8)
    end = Body(weight=0.0, mass_x=1.0, mass_y=1.0)

    def static(**rigid):
        mid = Body(weight=Wb, mass_x=300.0, mass_y=300.0, **rigid)
        scene = Scene(sections=(Section(cable=cable, body=mid), Section(cable=cable, body=end)),
                      anchor=Anchor(x=250.0, y=100.0), environment=env)
        model = build_model(scene)
        return model, steady_state(model, model.parameters(scene))

    model, rigid = static(pitch_inertia=50.0, attachment_x=c[0], attachment_y=c[1], buoyancy=B, buoyancy_x=b[0],
                          buoyancy_y=b[1])
    _, point = static()
    assert model.dim == (2 if heading is None else 3) and model.anchored
    n_rot = model.n_rotations
    assert np.max(np.abs(rigid.q[:-n_rot] - point.q)) < 1e-9 * 300.0
    theta = math.atan((Wb * c[0] + B * b[0]) / (Wb * c[1] + B * b[1]))
    assert rigid.outputs["theta_b_1"] == pytest.approx(theta, abs=1e-10)
    if heading is not None:
        assert rigid.q[-4:] == pytest.approx([math.cos(theta / 2), 0.0, 0.0, math.sin(theta / 2)], abs=1e-10)
        assert rigid.outputs["yaw_b_1"] == pytest.approx(0.0, abs=1e-10)


def test_bad_rigid_input():
    """Field-named errors before any model is built."""
    with pytest.raises(ParameterError, match="body.attachment_y"):
        Body(weight=1.0, mass_x=1.0, mass_y=1.0, attachment_y=-0.5)            # an offset on a point body
    with pytest.raises(ParameterError, match="body.pitch_inertia"):
        Body(weight=1.0, mass_x=1.0, mass_y=1.0, pitch_inertia=-1.0)
    with pytest.raises(ParameterError, match="body.pitch_inertia"):
        Body(weight=1.0, mass_x=1.0, mass_y=1.0, pitch_inertia=0.0)            # no rotary inertia at all
    with pytest.raises(ParameterError, match="body.pitch_damping"):
        Body(weight=1.0, mass_x=1.0, mass_y=1.0, pitch_inertia=1.0, pitch_damping=-2.0)
    with pytest.raises(ParameterError, match="body.buoyancy_x"):
        Body(weight=1.0, mass_x=1.0, mass_y=1.0, pitch_inertia=1.0, buoyancy_x=math.nan)
    rigid = Body(weight=1.0, mass_x=1.0, mass_y=1.0, pitch_inertia=1.0)
    with pytest.raises(ParameterError, match="body.pitch_inertia.*2-DOF"):
        _scene(rigid, _cable(1))                                               # Wang's 2-DOF model has no pitch
    with pytest.raises(ParameterError, match="body.pitch_inertia.*seabed"):
        single_section_scene(cable=_cable(), body=rigid, environment=Environment(), seabed=Seabed(depth=200.0))


def test_rigid_body_toml_round_trip():
    """The rigid fields are written and read back (SI and fps), and an unknown rigid key is refused by name."""
    body = Body(weight=500.0, mass_x=100.0, mass_y=120.0, pitch_inertia=30.0, pitch_added_inertia=4.0,
                attachment_x=0.1, attachment_y=-0.4, buoyancy=200.0, buoyancy_x=0.05, buoyancy_y=-0.1,
                pitch_damping=3.0, pitch_drag=1.5)
    scene = _scene(body)
    for units in ("SI", "fps"):
        back = scene_from_dict(tomllib.loads(dump_scene(scene, units=units)))
        for name in ("pitch_inertia", "pitch_added_inertia", "attachment_y", "buoyancy", "pitch_damping", "pitch_drag"):
            assert getattr(back.sections[0].body, name) == pytest.approx(getattr(body, name), rel=1e-12), (units, name)
    data = tomllib.loads(dump_scene(scene))
    data["body"]["pitch_inertai"] = 1.0
    with pytest.raises(ParameterError, match="pitch_inertai"):
        scene_from_dict(data)


def test_ladder_runs_the_node_model_alone():
    """A rigid body's pitch is a coordinate of the node model only: the ladder chooses it alone, with its own N,
    and refuses a straight-cable rung by name (before any work)."""
    body = Body(weight=1000.0, mass_x=200.0, mass_y=200.0, pitch_inertia=50.0, attachment_y=-0.5)
    scene = _scene(body)
    choice, _, _ = decide(scene, "auto", None, None)
    assert choice.name == "segmented" and choice.segments >= 2 and "pitch" in choice.reason
    for name in ("wang", "quasi-static"):
        with pytest.raises(ParameterError, match="rigid body"):
            decide(scene, name, None, None)


def test_two_rigid_bodies_in_a_chain():
    """An intermediate and a lower rigid body: both cables pull at the upper body's attachment point, so each
    body's static pitch is its own moment balance, tan(theta_i) = (W_b c_x + B b_x) / (W_b c_y + B b_y), whatever
    hangs below (labels theta_b_1, theta_b_2 after the nodes)."""
    specs = [(1500.0, (0.2, -0.6), (0.1, -0.3), 400.0), (700.0, (-0.1, -0.4), (0.0, 0.0), 0.0)]
    secs = tuple(Section(cable=_cable(3, length=8.0, m=1.5, w=8.0), body=Body(
        weight=wb, mass_x=150.0, mass_y=170.0, pitch_inertia=20.0, attachment_x=c[0], attachment_y=c[1],
        buoyancy=B, buoyancy_x=b[0], buoyancy_y=b[1])) for wb, c, b, B in specs)
    scene = Scene(sections=secs, environment=Environment(gravity=G))
    model = build_model(scene)
    assert model.q_labels[-2:] == ("theta_b_1", "theta_b_2")
    y = steady_state(model, model.parameters(scene)).outputs
    for i, (wb, c, b, B) in enumerate(specs):
        assert y[f"theta_b_{i + 1}"] == pytest.approx(math.atan((wb * c[0] + B * b[0]) / (wb * c[1] + B * b[1])),
                                                      abs=1e-10)


def _quadratic_eigenvalues(M, C, K):
    """The eigenvalues s of (s^2 M + s C + K) x = 0 (first-order companion form)."""
    n = M.shape[0]
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]])
    return np.linalg.eigvals(A)


def test_pitch_damping_in_the_linear_modes():
    """Linear pitch damping c in the compound pendulum of test_compound_pendulum_modes: the swing eigenvalues of the
    linearized model (M, C, K of cablesys.linear) equal those of the hand-written chain with C = diag(0, 0, c) in
    (phi_1, phi_2, theta) (the damping moment -c theta' does virtual work on theta alone)."""
    L, ae, W, M, m_c, a, J, c = 10.0, 1e9, 1000.0, 150.0, 1.0, 0.8, 40.0, 30.0
    scene = _scene(Body(weight=W, mass_x=M, mass_y=M, pitch_inertia=J, attachment_y=-a, pitch_damping=c),
                   _cable(2, length=L, m=m_c, ae=ae))
    model = build_model(scene)
    lin = linearize(model, model.parameters(scene))
    s_model = _quadratic_eigenvalues(lin.M, lin.C, lin.K)
    s_model = np.sort_complex(s_model[np.abs(s_model) < 100.0])          # the swing modes (axial ones ~ 1e4 rad/s)
    h = L / 2
    ln = h + W * h / ae
    A = np.array([[ln, 0, 0], [ln, ln, 0], [ln, ln, -a]])
    Mm = m_c * h * np.outer(A[0], A[0]) + m_c * h / 2 * np.outer(A[1], A[1]) + M * np.outer(A[2], A[2]) + np.diag([0, 0, J])
    exact = np.sort_complex(_quadratic_eigenvalues(Mm, np.diag([0.0, 0.0, c]), W * np.diag([ln, ln, a])))
    assert s_model.size == 6 and np.all(exact.real < 0)
    np.testing.assert_allclose(s_model, exact, rtol=1e-7)


def test_pitch_damping_power():
    """Without drag, cable damping or top motion, the model's energy changes only by the pitch moments' power:
    dE/dt = -c theta'^2 - d |theta'|^3, at random states (the chain rule of the energy along the ode, by AD)."""
    c, d = 12.0, 7.0
    body = Body(weight=900.0, mass_x=140.0, mass_y=190.0, pitch_inertia=35.0, attachment_x=0.2, attachment_y=-0.6,
                buoyancy=300.0, buoyancy_x=0.1, buoyancy_y=-0.2, pitch_damping=c, pitch_drag=d)
    scene = _scene(body, _cable(3, length=6.0, m=2.0, w=10.0, ae=1e6), rho=1e-3)
    model = build_model(scene)
    p = model.parameters(scene)
    x = ca.SX.sym("x", 2 * model.nq)
    e0 = np.array(model.top(0.0, p)).ravel()
    E = ca.sum1(ca.vertcat(*model.energy(x, e0, p)))
    power = ca.Function("power", [x], [ca.jtimes(E, x, model.ode(x, 0.0, p))])
    rng = np.random.default_rng(5)
    q0 = steady_state(model, p).q
    for _ in range(5):
        xv = np.concatenate([q0 + rng.normal(0, 0.05, model.nq), rng.normal(0, 0.5, model.nq)])
        thd = xv[-1]
        assert float(power(xv)) == pytest.approx(-c * thd**2 - d * abs(thd) ** 3, rel=1e-9)


@pytest.mark.parametrize("e", [(-0.8, 0.0), (-0.5, 0.4)])
def test_weathervane_in_a_current(e):
    """A body attached at its CG whose drag acts at a centre of pressure e off the CG is at rest in a current U when
    that point lies in line with the flow through the CG (the drag's moment about the attachment vanishes):
    R(theta) e along +x (downstream: stable) or -x (upstream: unstable), theta = -atan2(e_y, e_x) mod pi. The
    statics find an equilibrium near their guess (level, or the one given); the linearized model (cablesys.linear)
    is stable downstream and has a growing mode upstream. The cable leans at atan(D / W_b)."""
    Wb, cda, U, rho = 800.0, 0.5, 1.0, 1025.0
    body = Body(weight=Wb, mass_x=200.0, mass_y=200.0, drag_area_normal=cda, drag_area_tangential=cda,
                pitch_inertia=50.0, drag_centre_x=e[0], drag_centre_y=e[1])
    scene = _scene(body, current=U, rho=rho)
    model = build_model(scene)
    p = model.parameters(scene)
    down = -math.atan2(e[1], e[0])
    st = steady_state(model, p)
    assert math.remainder(st.outputs["theta_b"] - down, math.pi) == pytest.approx(0.0, abs=1e-9)
    guess = st.q.copy()
    guess[-1] = down + 0.3
    st_down = steady_state(model, p, guess=guess)
    assert st_down.outputs["theta_b"] == pytest.approx(down, abs=1e-9)
    assert st_down.outputs["x_b"] / st_down.outputs["y_b"] == pytest.approx(0.5 * rho * cda * U**2 / Wb, rel=1e-9)
    guess[-1] = down + math.pi + 0.3
    st_up = steady_state(model, p, guess=guess)
    assert st_up.outputs["theta_b"] == pytest.approx(down + math.pi, abs=1e-9)
    growth = {}
    for name, state in (("down", st_down), ("up", st_up)):
        lin = linearize(model, p, steady=state)
        growth[name] = np.max(_quadratic_eigenvalues(lin.M, lin.C, lin.K).real)
    assert growth["down"] < 0.0 < growth["up"]
