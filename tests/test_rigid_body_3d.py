"""The rigid body in space (cablesys/model/rigid_body.py, quaternion orientation): free rotation conserves Kirchhoff's
impulses and the energy, a planar scene run by the 3-D equations is the pitching body's run, a body hanging on a bridle
takes the attitude of the closed-form moment balance, the 3-D compound pendulum's two planes of swing against the
hand-derived eigenproblems, the named angles' sequence, energy conservation on a cable, and bad input."""

import dataclasses
import math
import sys
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg
import scipy.spatial.transform
import tomllib

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies"))
from _three_d_rigid import cases, planar_equivalence, tumble  # noqa: E402

from cablesys.errors import ParameterError  # noqa: E402
from cablesys.linear import linearize, modes  # noqa: E402
from cablesys.model import build_model  # noqa: E402
from cablesys.model.rigid_body import BAUMGARTE_RATE  # noqa: E402
from cablesys.scene import Body, Cable, Environment, Numerics, Scene, Section, TopMotion  # noqa: E402
from cablesys.scene.body import RIGID_FIELDS_3D  # noqa: E402
from cablesys.scene.scene import single_section_scene  # noqa: E402
from cablesys.scene.toml_io import dump_scene, scene_from_dict  # noqa: E402
from cablesys.statics import steady_state  # noqa: E402
from energy_checks import energy_history  # noqa: E402

G = 9.80665


def _cable(n=2, *, length=10.0, m=1.0, w=0.0, ae=1e7, cd=0.0, gamma=0.0):
    return Cable(length=length, tension_ref=0.0, ae=ae, diameter=0.02, mass_per_length=m, weight_per_length=w,
                 added_mass_factor=gamma, cd_normal=cd, ct_tangential=0.0, segments=n)


def _scene(body, cable=None, *, current=0.0, top=None, numerics=None, rho=1025.0, dims=3):
    return single_section_scene(cable=cable or _cable(), body=body,
                                environment=Environment(density=rho, gravity=G, current_speeds=(current,)),
                                top_motion=top or TopMotion(),
                                numerics=dataclasses.replace(numerics or Numerics(), dimensions=dims))


def _R(a):
    """Rotation of the quaternion a (scalar first), by SciPy (an independent route: its scalar-last convention)."""
    a = np.asarray(a, float)
    return scipy.spatial.transform.Rotation.from_quat([a[1], a[2], a[3], a[0]]).as_matrix()


@pytest.mark.parametrize("case", ["intermediate_axis", "intermediate_axis_with_added_mass"])
def test_free_rotation_conserves_impulse_and_energy(case):
    """A free asymmetric body (I = diag(10, 20, 30) kg m^2) spun about its intermediate axis tumbles (omega_y changes
    sign: Goldstein sec. 5.6); alone and in a fluid with added mass and inertia per axis and a product of inertia
    (the Munk moment couples its translation), Kirchhoff's linear and angular impulse (Lamb 1932 sec. 119, a closed
    form of the state) and the kinetic energy stay constant to 1e-8 over 100 s; |a| = 1 to 1e-10."""
    r = tumble(*cases()[case])
    assert r["flipped"]
    assert r["angular_impulse_drift_rel"] < 1e-8 and r["energy_drift_rel"] < 1e-8
    assert r["linear_impulse_drift_rel"] < 1e-8
    assert r["quaternion_norm_error"] < 1e-10


def test_planar_scene_in_space_is_the_pitching_body():
    """A planar scene (cylinder drag at a centre of pressure, current, surge + heave of the top, pitch damping) run by
    the 3-D equations (numerics.dimensions = 3) is the pitching body (studies/_three_d_rigid.py planar_equivalence):
    at random states the node accelerations agree and the quaternion's a'' is d2/dt2 of (cos theta/2, 0, 0,
    sin theta/2) with the planar theta'' (1e-10 normwise), nothing moves out of the plane, the outputs agree and the
    body rate about z is theta'; over a run at tight tolerance (each on its own steps) theta_b (the pitch Euler angle),
    the CG and the tensions agree to ~1e-9."""
    r = planar_equivalence(quick=False)
    assert r["three_d_orientation_labels"] == ["quat_w_b", "quat_x_b", "quat_y_b", "quat_z_b"]
    assert r["equations_max_rel"] < 1e-10 and r["equations_out_of_plane_max_abs"] < 1e-12
    assert r["run_pitch_range_rad"] > 0.3
    assert all(v < 3e-9 for v in r["run_per_output_rel"].values()), r["run_per_output_rel"]
    assert r["run_out_of_plane_max_abs"] < 1e-12


@pytest.mark.parametrize("c, b, B", [((0.3, -0.5, 0.2), (0.0, 0.0, 0.0), 0.0),       # a bridle point off the axes
                                     ((0.3, -0.5, 0.2), (0.1, -0.2, -0.15), 300.0),  # and a buoyancy centre off them
                                     ((-0.2, -0.4, -0.3), (0.15, -0.6, 0.1), 900.0)])
def test_bridle_static_attitude(c, b, B):
    """Hanging at rest on a vertical cable, the moments about the attachment point of W_b + B (down at the CG) and B
    (up at the centre of buoyancy) vanish: R (W_b c + B b) is vertical, pointing up (-y), its length |W_b c + B b|
    (c, b body axes from the CG). Without buoyancy the CG hangs right under the bridle point. Yaw about the
    vertical is neutral; the statics keep |a| = 1."""
    Wb = 1000.0
    c, b = np.array(c), np.array(b)
    body = Body(weight=Wb, mass_x=200.0, mass_y=220.0, mass_z=240.0, pitch_inertia=50.0, inertia_xx=30.0,
                inertia_yy=40.0, attachment_x=c[0], attachment_y=c[1], attachment_z=c[2], buoyancy=B,
                buoyancy_x=b[0], buoyancy_y=b[1], buoyancy_z=b[2])
    scene = _scene(body)
    model = build_model(scene)
    st = steady_state(model, model.parameters(scene))
    a = st.q[-4:]
    assert np.linalg.norm(a) == pytest.approx(1.0, abs=1e-12)
    m = Wb * c + B * b
    np.testing.assert_allclose(_R(a) @ m, [0.0, -np.linalg.norm(m), 0.0], atol=1e-9 * np.linalg.norm(m))
    y = st.outputs
    assert abs(y["x_b"]) < 1e-10 and abs(y["z_b"]) < 1e-10
    if B == 0.0:
        assert abs(y["x_cg"]) < 1e-10 and abs(y["z_cg"]) < 1e-10
    # the named angles reconstruct the attitude: R = R_y(yaw) R_z(pitch) R_x(roll)
    Rn = scipy.spatial.transform.Rotation.from_euler("YZX", [y["yaw_b"], y["theta_b"], y["roll_b"]]).as_matrix()
    np.testing.assert_allclose(Rn, _R(a), atol=1e-12)


def test_per_axis_drag_in_a_current_at_a_heading():
    """A body attached at its CG with only the per-axis drag 1/2 rho (C_D A)_i |u_i| u_i, in a current U at 30 degrees
    from +x towards +z, on a weightless drag-free cable: its orientation is neutral (no moment about the attachment:
    the statics keep it level), the drag is (C_x (U cos h)^2, 0, C_z (U sin h)^2) rho / 2, not along the flow, and the
    cable leans along W_b e_y + D: x_b / y_b = D_x / W_b, z_b / y_b = D_z / W_b."""
    Wb, U, h, rho, cx, cz = 800.0, 1.2, math.radians(30.0), 1025.0, 0.9, 0.3
    body = Body(weight=Wb, mass_x=200.0, mass_y=200.0, pitch_inertia=50.0, drag_area_x=cx, drag_area_y=0.5,
                drag_area_z=cz)
    scene = single_section_scene(cable=_cable(), body=body, environment=Environment(
        density=rho, gravity=G, current_speeds=(U,), current_headings_deg=(30.0,)))
    assert scene.three_d
    model = build_model(scene)
    y = steady_state(model, model.parameters(scene)).outputs
    assert abs(y["theta_b"]) < 1e-12 and abs(y["roll_b"]) < 1e-12 and abs(y["yaw_b"]) < 1e-12
    assert y["x_b"] / y["y_b"] == pytest.approx(0.5 * rho * cx * (U * math.cos(h)) ** 2 / Wb, rel=1e-9)
    assert y["z_b"] / y["y_b"] == pytest.approx(0.5 * rho * cz * (U * math.sin(h)) ** 2 / Wb, rel=1e-9)


def test_3d_rigid_fields_round_trip():
    """The 3-D rigid fields are written and read back (SI and fps)."""
    body = Body(weight=500.0, mass_x=100.0, mass_y=120.0, mass_z=110.0, pitch_inertia=30.0, inertia_xx=20.0,
                inertia_yy=25.0, inertia_xy=1.5, inertia_xz=-0.5, inertia_yz=0.25, added_inertia_x=2.0,
                added_inertia_y=3.0, attachment_z=0.1, buoyancy=50.0, buoyancy_z=-0.2, drag_centre_z=0.3,
                drag_area_x=0.4, drag_area_y=0.2, drag_area_z=0.1)
    scene = _scene(body)
    for units in ("SI", "fps"):
        back = scene_from_dict(tomllib.loads(dump_scene(scene, units=units)))
        for name in RIGID_FIELDS_3D + ("drag_area_x", "drag_area_y"):
            assert getattr(back.sections[0].body, name) == pytest.approx(getattr(body, name), rel=1e-12), (units, name)


def test_two_rigid_bodies_in_a_chain_in_space():
    """An intermediate and a lower rigid body in 3-D: both cables pull at the upper body's attachment point along the
    vertical, so each body's static attitude is its own moment balance, R_i (W_b c + B b)_i = -|W_b c + B b|_i e_y,
    whatever hangs below (quaternion labels with the section's suffix after the nodes)."""
    specs = [(1500.0, (0.2, -0.6, 0.1), (0.1, -0.3, -0.2), 400.0), (700.0, (-0.1, -0.4, 0.25), (0.0, 0.0, 0.0), 0.0)]
    secs = tuple(Section(cable=_cable(3, length=8.0, m=1.5, w=8.0), body=Body(
        weight=wb, mass_x=150.0, mass_y=170.0, pitch_inertia=20.0, inertia_xx=15.0, attachment_x=c[0],
        attachment_y=c[1], attachment_z=c[2], buoyancy=B, buoyancy_x=b[0], buoyancy_y=b[1], buoyancy_z=b[2]))
        for wb, c, b, B in specs)
    scene = Scene(sections=secs, environment=Environment(gravity=G))
    model = build_model(scene)
    assert model.q_labels[-8:] == tuple(f"quat_{k}_b_{i}" for i in (1, 2) for k in "wxyz")
    st = steady_state(model, model.parameters(scene))
    for i, (wb, c, b, B) in enumerate(specs):
        a = st.q[model.q_labels.index(f"quat_w_b_{i + 1}"):][:4]
        m = wb * np.array(c) + B * np.array(b)
        np.testing.assert_allclose(_R(a) @ m, [0.0, -np.linalg.norm(m), 0.0], atol=1e-9 * np.linalg.norm(m))
        assert f"roll_b_{i + 1}" in model.output_labels


def test_euler_angle_sequence_and_rates():
    """At random attitudes and rates the outputs roll_b, theta_b, yaw_b rebuild the quaternion's rotation as
    R_y(yaw) R_z(pitch) R_x(roll) (SciPy's intrinsic 'YZX'), quat_*_b is the unit quaternion, omega_*_b the body
    rate 2 vec(a* (x) a'), and the angle rates are d/dt of the angles (finite differences along the state)."""
    body = Body(weight=1000.0, mass_x=200.0, mass_y=200.0, pitch_inertia=50.0, attachment_y=-0.5)
    scene = _scene(body)
    model = build_model(scene)
    p = model.parameters(scene)
    nq = model.nq
    q0 = steady_state(model, p).q
    rng = np.random.default_rng(2)
    lab = model.output_labels
    for _ in range(5):
        a = rng.normal(size=4)
        a *= rng.uniform(0.9, 1.1) / np.linalg.norm(a)
        ad = rng.normal(size=4)
        x = np.concatenate([q0[:-4], a, np.zeros(nq - 4), ad])
        e = np.array(model.top(0.0, p)).ravel()
        y = np.array(model.outputs(x, e, p)).ravel()
        g = {k: y[lab.index(k)] for k in lab}
        Rn = scipy.spatial.transform.Rotation.from_euler("YZX", [g["yaw_b"], g["theta_b"], g["roll_b"]]).as_matrix()
        np.testing.assert_allclose(Rn, _R(a), atol=1e-12)
        un = a / np.linalg.norm(a)
        assert [g[f"quat_{k}_b"] for k in "wxyz"] == pytest.approx(list(un), abs=1e-14)
        # omega from the rotation's rate: [omega]_x = R^T R'
        h = 1e-6
        Rd = (_R(a + h * ad) - _R(a - h * ad)) / (2 * h)
        W = _R(a).T @ Rd
        assert [g["omega_x_b"], g["omega_y_b"], g["omega_z_b"]] == pytest.approx([W[2, 1], W[0, 2], W[1, 0]], abs=1e-7)
        yp = np.array(model.outputs(x + h * np.concatenate([np.zeros(nq - 4), ad, np.zeros(nq)]), e, p)).ravel()
        ym = np.array(model.outputs(x - h * np.concatenate([np.zeros(nq - 4), ad, np.zeros(nq)]), e, p)).ravel()
        for name in ("roll_b", "theta_b", "yaw_b"):
            k = lab.index(name)
            assert g[f"{name}_rate"] == pytest.approx((yp[k] - ym[k]) / (2 * h), rel=1e-6, abs=1e-7)


def test_compound_pendulum_in_two_planes():
    """A rigid body (virtual masses M_x in x, M_z in z, CG a below the attachment, inertias I_xx != I_zz) on a
    two-element weightless cable with node masses: the linearized 3-D model's swing frequencies are the two
    hand-derived chains' (Goldstein sec. 6.2), in-plane (phi_1, phi_2, pitch) with M_x and I_zz and out-of-plane
    (psi_1, psi_2, roll) with M_z and I_xx, as in tests/test_rigid_body.py's planar chain. Besides them: the yaw
    (neutral: 0) and the quaternion's norm constraint at the Baumgarte rate beta (its own check)."""
    L, ae, W, Mx, Mz, m_c, a = 10.0, 1e9, 1000.0, 150.0, 190.0, 1.0, 0.8
    Izz, Ixx = 40.0, 15.0
    body = Body(weight=W, mass_x=Mx, mass_y=Mx, mass_z=Mz, pitch_inertia=Izz, inertia_xx=Ixx, inertia_yy=25.0,
                attachment_y=-a)
    scene = _scene(body, _cable(2, length=L, m=1.0, ae=ae))
    model = build_model(scene)
    w = np.sort(np.asarray(modes(linearize(model, model.parameters(scene))).omega_undamped))
    h = L / 2
    ln = h + W * h / ae
    A = np.array([[ln, 0, 0], [ln, ln, 0], [ln, ln, -a]])
    exact = []
    for M, J in ((Mx, Izz), (Mz, Ixx)):
        Mm = m_c * h * np.outer(A[0], A[0]) + m_c * h / 2 * np.outer(A[1], A[1]) + M * np.outer(A[2], A[2]) \
            + np.diag([0, 0, J])
        exact += list(np.sqrt(scipy.linalg.eigh(W * np.diag([ln, ln, a]), Mm, eigvals_only=True)))
    exact = np.sort(exact)
    swing = w[(w > 1e-3) & (w < 100.0) & (np.abs(w - BAUMGARTE_RATE) > 1e-6 * BAUMGARTE_RATE)]   # axial: > 800 rad/s
    assert swing.size == 6
    np.testing.assert_allclose(swing, exact, rtol=1e-8)
    assert np.min(np.abs(w)) < 1e-4                                           # yaw
    assert np.min(np.abs(w - BAUMGARTE_RATE)) < 1e-6 * BAUMGARTE_RATE         # the norm constraint


def test_energy_conserved_swinging_and_rotating_in_space():
    """No drag, no damping, top at rest: a rigid body with a full inertia tensor, added inertias, bridle and buoyancy
    centre off every axis swinging and turning in 3-D on an elastic cable conserves K + V to 1e-6 of the motion's
    energy over 20 s."""
    body = Body(weight=800.0, mass_x=150.0, mass_y=180.0, mass_z=170.0, pitch_inertia=30.0, pitch_added_inertia=10.0,
                inertia_xx=20.0, inertia_yy=25.0, inertia_xz=2.0, added_inertia_x=3.0, attachment_x=0.2,
                attachment_y=-0.7, attachment_z=0.15, buoyancy=400.0, buoyancy_x=-0.1, buoyancy_y=-0.3, buoyancy_z=0.1)
    scene = _scene(body, _cable(3, length=6.0, m=2.0, w=10.0, ae=1e6), rho=1e-3,
                   numerics=Numerics(duration=20.0, output_step=0.05))
    model = build_model(scene)
    p = model.parameters(scene)
    st = steady_state(model, p)
    nq = model.nq
    x0 = np.concatenate([st.q, np.zeros(nq)])
    x0[nq:nq + 9:3] = 0.3 * np.arange(1, 4) / 3                     # node velocities in x
    x0[nq + 2:nq + 9:3] = 0.2 * np.arange(1, 4) / 3                 # and in z
    a0 = st.q[-4:]
    om = np.array([0.6, -0.4, 0.5])
    x0[-4:] = 0.5 * np.concatenate([[-a0[1:] @ om], a0[0] * om + np.cross(a0[1:], om)])
    r, E, swing = energy_history(scene, model, p, x0, st.x)
    assert swing > 1.0
    assert np.max(np.abs(E - E[0])) < 1e-6 * swing
    assert np.ptp(r["roll_b"]) > 0.1 and np.ptp(r["yaw_b"]) > 0.1 and np.ptp(r["z_b"]) > 0.05


def test_bad_3d_rigid_input():
    """Field-named errors before any model is built: an inertia tensor that no mass distribution has (triangle
    inequality, not positive semi-definite), no rotary inertia about an axis, 3-D fields on a point body or in a
    scene held in the plane."""
    base = dict(weight=1.0, mass_x=1.0, mass_y=1.0)
    with pytest.raises(ParameterError, match=r"body\.inertia_xx.*triangle"):
        Body(**base, pitch_inertia=1.0, inertia_xx=5.0, inertia_yy=1.0)
    with pytest.raises(ParameterError, match=r"body\.pitch_inertia.*triangle"):
        Body(**base, pitch_inertia=9.0, inertia_xx=2.0, inertia_yy=3.0)
    with pytest.raises(ParameterError, match=r"body\.inertia_xy.*positive semi-definite"):
        Body(**base, pitch_inertia=1.0, inertia_xx=1.0, inertia_yy=1.0, inertia_xy=2.0)
    with pytest.raises(ParameterError, match=r"body\.inertia_yz.*triangle"):
        Body(**base, pitch_inertia=1.0, inertia_xx=2.05, inertia_yy=1.0, inertia_yz=0.01)
    with pytest.raises(ParameterError, match=r"body\.inertia_xx.*positive definite"):
        Body(**base, pitch_inertia=1.0, inertia_xx=0.0, inertia_yy=1.0)
    with pytest.raises(ParameterError, match=r"body\.inertia_yy"):
        Body(**base, pitch_inertia=1.0, inertia_yy=-1.0)
    with pytest.raises(ParameterError, match=r"body\.attachment_z.*needs body\.pitch_inertia"):
        Body(**base, attachment_z=0.1)
    with pytest.raises(ParameterError, match=r"body\.inertia_xz.*needs body\.pitch_inertia"):
        Body(**base, inertia_xz=0.1)
    rigid = Body(weight=1.0, mass_x=1.0, mass_y=1.0, pitch_inertia=1.0, inertia_xx=0.8)
    assert _scene(rigid, dims=None).three_d                       # a 3-D field makes the scene 3-D
    with pytest.raises(ParameterError, match=r"numerics\.dimensions.*body\.inertia_xx"):
        _scene(rigid, dims=2)
