"""A rigid body's initial attitude (body.initial_roll_deg / initial_pitch_deg / initial_yaw_deg): the run starts from
the static equilibrium with the body turned about its attachment point and released at rest; the statics do not move.
A small pitch (and roll) release of the compound pendulum follows the linear modal response of the hand-derived
eigenproblem of tests/test_rigid_body.py, in the plane and in 3-D."""

import math

import numpy as np
import pytest
import scipy.linalg
import scipy.spatial.transform
import tomllib

from cablesys.errors import ParameterError
from cablesys.model import build_model
from cablesys.scene import Body, Cable, Environment, Numerics
from cablesys.scene.scene import single_section_scene
from cablesys.scene.toml_io import dump_scene, scene_from_dict
from cablesys.statics import steady_state
from cablesys.time_domain import simulate
from cablesys.time_domain.initial import initial_state
from cablesys.time_domain.integrators import IntegratorSettings
from cablesys.time_domain.run import Simulator

G = 9.80665
L, AE, W, M_C, A = 10.0, 1e7, 1000.0, 1.0, 0.8          # cable length, stiffness, body weight, cable mass, CG offset


def _scene(dims=None, **body):
    cable = Cable(length=L, tension_ref=0.0, ae=AE, diameter=0.02, mass_per_length=M_C, weight_per_length=0.0,
                  added_mass_factor=0.0, cd_normal=0.0, ct_tangential=0.0, segments=2)
    base = dict(weight=W, mass_x=150.0, mass_y=150.0, pitch_inertia=40.0, attachment_y=-A)
    if dims == 3:
        base.update(mass_z=190.0, inertia_xx=15.0, inertia_yy=25.0)
    return single_section_scene(cable=cable, body=Body(**{**base, **body}), environment=Environment(gravity=G),
                                numerics=Numerics(duration=10.0, output_step=0.05, dimensions=dims))


def _linear_release(M, J, theta0, t):
    """theta(t) of the compound pendulum released from (phi_1, phi_2, theta) = (0, 0, theta0) at rest: the modal sum
    sum_k v_k (v_k^T M x_0) cos(omega_k t) of the generalized eigenproblem K v = omega^2 M v (mass-normalized v_k;
    Goldstein, Classical Mechanics, sec. 6.2), with M and K those of tests/test_rigid_body.py's
    test_compound_pendulum_modes: x_1 = l phi_1, x_2 = l (phi_1 + phi_2), x_cg = x_2 - a theta, l the stretched
    element length, node masses m_c h and m_c h / 2 (the half elements), K = W diag(l, l, a)."""
    h = L / 2
    ln = h + W * h / AE
    rows = np.array([[ln, 0, 0], [ln, ln, 0], [ln, ln, -A]])
    Mm = (M_C * h * np.outer(rows[0], rows[0]) + M_C * h / 2 * np.outer(rows[1], rows[1]) + M * np.outer(rows[2], rows[2])
          + np.diag([0, 0, J]))
    w2, V = scipy.linalg.eigh(W * np.diag([ln, ln, A]), Mm)
    c = V.T @ Mm @ np.array([0.0, 0.0, theta0])
    return (V[2] * c) @ np.cos(np.outer(np.sqrt(w2), t))


def _run(sc):
    model = build_model(sc)
    sim = Simulator(model, sc.output_times, IntegratorSettings(method="cvodes-adams", rtol=1e-9, atol=1e-9, compiled=False))
    r = simulate(sc, model=model, simulator=sim)
    assert r.success
    return model, r


@pytest.mark.parametrize("dims, field, name, M, J", [
    (None, "initial_pitch_deg", "theta_b", 150.0, 40.0),     # the plane: theta_b
    (3, "initial_pitch_deg", "theta_b", 150.0, 40.0),        # in space, pitch about z: M_x, I_zz
    (3, "initial_roll_deg", "roll_b", 190.0, 15.0),          # in space, roll about x: M_z, I_xx
])
def test_small_release_follows_the_compound_pendulums_linear_response(dims, field, name, M, J):
    """Released from 0.03 deg (nodes at their static places, all at rest), the angle over 10 s (about 15 periods of
    the fastest swing mode) is the linear modal response within 1e-4 of the release angle (the nonlinear terms are
    O(theta_0^2) of it: 2e-5 at this angle, 4x less at half of it)."""
    theta0 = 0.03
    sc = _scene(dims, **{field: theta0})
    model, r = _run(sc)
    t, th = np.asarray(r.time), np.asarray(r[name])
    assert th[0] == pytest.approx(math.radians(theta0), rel=1e-12)
    lin = _linear_release(M, J, math.radians(theta0), t)
    assert np.max(np.abs(th - lin)) < 1e-4 * math.radians(theta0)
    assert np.ptp(th) > 1.5 * math.radians(theta0)                 # it does swing (the modes beat)


def test_the_release_leaves_the_statics_and_the_nodes_where_they_are():
    """The attitude is an initial condition: the model's parameters, its steady state and the node positions and
    velocities of x0 are those without it; only the orientation coordinate changes (theta_b in the plane)."""
    plain, turned = _scene(), _scene(initial_pitch_deg=12.0)
    m = build_model(plain)
    p, pt = m.parameters(plain), m.parameters(turned)
    assert np.array_equal(p, pt)
    np.testing.assert_array_equal(steady_state(m, p).q, steady_state(m, pt).q)
    x, xt = initial_state(plain, m, p), initial_state(turned, m, pt)
    k = m.q_labels.index("theta_b")
    assert xt[k] == pytest.approx(math.radians(12.0), rel=1e-14) and x[k] == 0.0
    np.testing.assert_array_equal(np.delete(x, k), np.delete(xt, k))


def _bridle(**attitude):
    return _scene(3, attachment_x=0.3, attachment_z=0.2, buoyancy=300.0, buoyancy_x=0.1, buoyancy_y=-0.2,
                  buoyancy_z=-0.15, **attitude)


def test_a_turned_body_starts_at_the_named_angles_and_keeps_the_static_ones_unset():
    """A body on a bridle (its static attitude tilted): roll, pitch and yaw all given, x0's quaternion is the rotation
    R_y(yaw) R_z(pitch) R_x(roll) (SciPy's intrinsic 'YZX', an independent route) and the outputs name those angles;
    the pitch alone given, the static roll and yaw stay."""
    angles = (25.0, -30.0, 40.0)
    sc = _bridle(initial_roll_deg=angles[0], initial_pitch_deg=angles[1], initial_yaw_deg=angles[2])
    m = build_model(sc)
    p = m.parameters(sc)
    x0 = initial_state(sc, m, p)
    a = x0[m.nq - 4:m.nq]
    R = scipy.spatial.transform.Rotation.from_quat([a[1], a[2], a[3], a[0]]).as_matrix()
    want = scipy.spatial.transform.Rotation.from_euler("YZX", np.radians(angles[::-1])).as_matrix()
    np.testing.assert_allclose(R, want, atol=1e-13)
    y = np.array(m.outputs(x0, np.array(m.top(0.0, p)).ravel(), p)).ravel()
    got = [math.degrees(y[m.output_labels.index(k)]) for k in ("roll_b", "theta_b", "yaw_b")]
    assert got == pytest.approx(list(angles), abs=1e-10)
    static = steady_state(m, p).outputs
    assert abs(static["roll_b"]) > 1e-3 and abs(static["theta_b"]) > 1e-3                   # the bridle tilts it
    only = _bridle(initial_pitch_deg=-30.0)
    x1 = initial_state(only, m, p)
    y1 = np.array(m.outputs(x1, np.array(m.top(0.0, p)).ravel(), p)).ravel()
    assert y1[m.output_labels.index("roll_b")] == pytest.approx(static["roll_b"], abs=1e-12)
    assert y1[m.output_labels.index("yaw_b")] == pytest.approx(static["yaw_b"], abs=1e-12)
    assert math.degrees(y1[m.output_labels.index("theta_b")]) == pytest.approx(-30.0, abs=1e-10)
    np.testing.assert_array_equal(x1[:m.nq - 4], steady_state(m, p).q[:m.nq - 4])


def test_bad_initial_attitude_is_named():
    with pytest.raises(ParameterError, match=r"body\.initial_pitch_deg.*needs body\.pitch_inertia"):
        Body(weight=1.0, mass_x=1.0, mass_y=1.0, initial_pitch_deg=5.0)
    with pytest.raises(ParameterError, match=r"body\.initial_pitch_deg"):
        _scene(initial_pitch_deg=95.0)
    with pytest.raises(ParameterError, match=r"body\.initial_yaw_deg"):
        _scene(initial_yaw_deg=-181.0)
    assert _scene(initial_roll_deg=5.0).three_d                      # a roll leaves the plane
    with pytest.raises(ParameterError, match=r"numerics\.dimensions.*body\.initial_roll_deg"):
        _scene(2, initial_roll_deg=5.0)


def test_initial_attitude_round_trip():
    sc = _bridle(initial_roll_deg=1.5, initial_pitch_deg=-2.0, initial_yaw_deg=30.0)
    back = scene_from_dict(tomllib.loads(dump_scene(sc, units="fps")))
    assert back.body.initial_attitude_deg == pytest.approx((1.5, -2.0, 30.0), rel=1e-12)
