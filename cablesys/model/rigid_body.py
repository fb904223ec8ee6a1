"""A rigid body on an attachment point off its centre of gravity: pitch in the x-y plane, six degrees of freedom
in space (one formulation, the plane its special case).

Wang (1971) p. 32, "Extensions": body rotation "where the body is fairly large and the cable is not attached to
the center of mass" adds one degree of freedom in the plane, three in space. The cable's last node of a section
is the body's attachment point r_a ((x, y) in the plane, (x, y, z) in space; y down from the mean top depth).
The body's orientation is R, the rotation from body axes to the scene's axes (body axes = scene axes at R = I):

- in the plane, the pitch theta_b: R(theta) = [[cos, -sin], [sin, cos]] (+x towards +y, about +z), body rate
  omega = theta';
- in space, a quaternion a = (a_w, a_x, a_y, a_z) (Euler parameters; no gimbal lock), R the rotation of the unit
  quaternion a / |a| (Shuster, "A survey of attitude representations", J. Astronaut. Sci. 41, 1993, eq. 125 with
  his vector-first order changed to scalar first; Diebel, "Representing attitude", 2006, eq. 125) and the body-axis
  angular velocity omega = 2 vec(a* (x) a') / |a|^2, the inverse of a' = 1/2 a (x) (0, omega) (Diebel eq. 109,
  Hamilton product (x)); a pitch theta_b about z is a = (cos theta/2, 0, 0, sin theta/2).

With c the attachment point, b the centre of buoyancy and e the centre of pressure from the CG in body axes:
r_cg = r_a - R c, r_cb = r_cg + R b, r_cp = r_cg + R e, and

- kinetic energy T = 1/2 sum_i M_bv,i w_i^2 + 1/2 omega^T (I + I_a) omega with w = R^T v_cg the CG's velocity in
  body axes: Wang's virtual masses (eq. 16, mass plus added mass, ``mass_x/y/z``) along the body axes, the
  added-mass tensor fixed in the body (Newman, Marine Hydrodynamics, 1977, sec. 4.13: its Munk moment
  w x (M_bv w) follows; Fossen, Handbook of Marine Craft Hydrodynamics and Motion Control, 2011, ch. 6: the
  6-DOF M = M_RB + M_A about the CG with diagonal added mass), I the inertia tensor about the CG (the scalar I_zz in
  the plane) and I_a the added inertia per body axis (rigid-body kinetic energy about the CG, Goldstein, Classical
  Mechanics, 3rd ed., sec. 5.1);
- potential energy V = -(W_b + B) y_cg + B y_cb (y down): the weight W_b + B at the CG, the buoyancy B at the
  centre of buoyancy, so that the weight in water is Wang's W_b (eq. 15);
- generalized forces by virtual work (Wang eq. 37): the body drag at r_cp with that point's velocity, Wang's
  eq. 32-35 in body axes (the cylinder's axis at phi_b in the body's x-y plane turns with the body; the sphere's
  drag is along the relative flow in any axes) plus a quadratic drag per body axis (``drag_area_x/y/z``), and the
  rotational damping moment -c omega_i - d |omega_i| omega_i
  per body axis (in the plane -c theta' - d |theta'| theta').

Lagrange's equations M q'' = f in (r_a, theta) or (r_a, a) come by CasADi AD of T and V (:func:`rigid_body`), as
for the cable elements (:func:`.segmented_element.element_inertia`); in space this is Lagrange's form of the
Kirchhoff equations (Lamb, Hydrodynamics, 6th ed., 1932, sec. 124-126; Fossen eq. 6.1-6.2) in Euler parameters
(Nikravesh, Computer-Aided Analysis of Mechanical Systems, 1988, ch. 6 and 11). T and V do not change along
a -> lambda a, so M has the null vector n = (0, a / |a|): the unit-norm constraint |a|^2 = 1 closes the system
by Baumgarte's stabilization (Baumgarte, Comput. Methods Appl. Mech. Eng. 1, 1972, 1-16), C'' + 2 beta C' +
beta^2 C = 0 for C = |a|^2 - 1 (critically damped at the rate beta = :data:`BAUMGARTE_RATE`): the equations in
n's direction are replaced by that one, M + J_r n n^T and P f + J_r s n (P = I - n n^T, s = n . q'' from the
constraint, J_r a reference inertia that keeps M's scale). Renormalization is not used: the stiff and adaptive
integrators (CVODES/IDAS) do not let the state be projected between steps, and the constraint row also makes the
statics square (|a| = 1 at rest). The physics never sees |a| (R and omega are those of a / |a|), so the term only
keeps the coordinates bounded; beta = 10/s is well below the cable's axial frequencies (no new stiffness for the
integrators) and above a body's swing. A linearized model (``cablesys.linear``) therefore has one more, non-physical
mode per body in space: undamped frequency beta, damping ratio 1 (the norm), besides the neutral yaw of a body
hanging still (frequency 0). With c = b = e = 0 and M_bvx = M_bvy (= M_bvz) the translation is the point
body's exactly. SI throughout (m, N, kg, kg m^2, rad).
"""

from __future__ import annotations

import dataclasses

import casadi as ca
import numpy as np

from . import fluid
from .section import SectionParameters
from .segmented_element import flow_at

__all__ = ["BAUMGARTE_RATE", "ORIENTATION_REST", "RigidParameters", "attitude", "body_rate", "euler_rotation", "free_body",
           "rigid_body", "rotation", "turned_orientation"]

#: beta of the quaternion's norm stabilization (1/s): C = |a|^2 - 1 decays as (1 + beta t) e^(-beta t) (module
#: docstring: below the cable's axial frequencies, above a body's swing).
BAUMGARTE_RATE = 10.0
#: The level attitude's orientation coordinates: theta_b = 0 in the plane, the unit quaternion in space.
ORIENTATION_REST = {2: (0.0,), 3: (1.0, 0.0, 0.0, 0.0)}


@dataclasses.dataclass(frozen=True)
class RigidParameters:
    """The rigid body's entries of the parameter vector (symbols): SI, body axes (see the module docstring).
    In the plane ``inertia`` and ``added_inertia`` are the scalars about z; in space the 3 x 3 inertia tensor
    about the CG and the added inertias about the body's x, y, z."""

    inertia: ca.SX          # I about the CG (kg m^2): scalar I_zz in the plane, 3 x 3 tensor in space
    added_inertia: ca.SX    # I_a (kg m^2): scalar in the plane, 3-vector (per body axis) in space
    c: tuple                # attachment point from the CG, body axes (m)
    b: tuple                # centre of buoyancy from the CG, body axes (m)
    e: tuple                # centre of pressure (where the drag acts) from the CG, body axes (m)
    buoyancy: ca.SX         # B (N)
    damping: ca.SX          # c (N m s)
    drag: ca.SX             # d (N m s^2)
    axis_drag: tuple = ()   # (C_D A)_i per body axis (m^2): x, y in the plane, x, y, z in space

    @classmethod
    def from_layout(cls, layout, prefix: str, dim: int = 2) -> "RigidParameters":
        b = lambda n: layout.sym(f"{prefix}body.{n}")
        if dim == 2:
            return cls(inertia=b("pitch_inertia"), added_inertia=b("pitch_added_inertia"),
                       c=(b("attachment_x"), b("attachment_y")), b=(b("buoyancy_x"), b("buoyancy_y")),
                       e=(b("drag_centre_x"), b("drag_centre_y")),
                       buoyancy=b("buoyancy"), damping=b("pitch_damping"), drag=b("pitch_drag"),
                       axis_drag=(b("drag_area_x"), b("drag_area_y")))
        ixx, iyy, izz = b("inertia_xx"), b("inertia_yy"), b("pitch_inertia")
        ixy, ixz, iyz = b("inertia_xy"), b("inertia_xz"), b("inertia_yz")
        tensor = ca.vertcat(ca.horzcat(ixx, ixy, ixz), ca.horzcat(ixy, iyy, iyz), ca.horzcat(ixz, iyz, izz))
        return cls(inertia=tensor,
                   added_inertia=ca.vertcat(b("added_inertia_x"), b("added_inertia_y"), b("pitch_added_inertia")),
                   c=tuple(b(f"attachment_{k}") for k in "xyz"), b=tuple(b(f"buoyancy_{k}") for k in "xyz"),
                   e=tuple(b(f"drag_centre_{k}") for k in "xyz"),
                   buoyancy=b("buoyancy"), damping=b("pitch_damping"), drag=b("pitch_drag"),
                   axis_drag=tuple(b(f"drag_area_{k}") for k in "xyz"))


def rotation(a):
    """R, body axes to the scene's: the plane rotation by theta = a[0], or the rotation of the quaternion a / |a|
    (scalar first; Diebel 2006 eq. 125, written with a's squares over |a|^2 so that no square root appears)."""
    if a.numel() == 1:
        c, s = ca.cos(a[0]), ca.sin(a[0])
        return ca.vertcat(ca.horzcat(c, -s), ca.horzcat(s, c))
    w, x, y, z = a[0], a[1], a[2], a[3]
    k = 2.0 / ca.sumsqr(a)
    return ca.vertcat(ca.horzcat(1 - k * (y * y + z * z), k * (x * y - w * z), k * (x * z + w * y)),
                      ca.horzcat(k * (x * y + w * z), 1 - k * (x * x + z * z), k * (y * z - w * x)),
                      ca.horzcat(k * (x * z - w * y), k * (y * z + w * x), 1 - k * (x * x + y * y)))


def body_rate(a, ad):
    """The body-axis angular velocity: theta' in the plane; 2 vec(a* (x) a') / |a|^2 in space (the inverse of
    a' = 1/2 a (x) (0, omega), Diebel 2006 eq. 109; exact for any |a|, the rate of a / |a|)."""
    if a.numel() == 1:
        return ad
    av, adv = a[1:4], ad[1:4]
    return 2.0 * (a[0] * adv - ad[0] * av - ca.cross(av, adv)) / ca.sumsqr(a)


def attitude(a):
    """Named angles of R(a) (rad): roll phi about the body x, pitch theta about z, yaw psi about the vertical y, in
    the sequence R = R_y(psi) R_z(theta) R_x(phi) (yaw, then pitch, then roll: the marine z-y-x sequence of Fossen
    2011 sec. 2.2.1 with the vertical along y and the pitch axis the plane's normal z); pitch in [-pi/2, pi/2]
    (gimbal lock of the named angles only, at |theta| = pi/2). In the plane only the pitch, theta_b itself."""
    if a.numel() == 1:
        return {"theta_b": a[0]}
    R = rotation(a)
    return {"roll_b": ca.atan2(-R[1, 2], R[1, 1]), "theta_b": ca.atan2(R[1, 0], ca.sqrt(R[0, 0] ** 2 + R[2, 0] ** 2)),
            "yaw_b": ca.atan2(-R[2, 0], R[0, 0])}


def euler_rotation(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """R = R_y(yaw) R_z(pitch) R_x(roll) (rad), the sequence of :func:`attitude`'s named angles, as a 3 x 3 array."""
    c, s = np.cos, np.sin
    Ry = np.array([[c(yaw), 0.0, s(yaw)], [0.0, 1.0, 0.0], [-s(yaw), 0.0, c(yaw)]])
    Rz = np.array([[c(pitch), -s(pitch), 0.0], [s(pitch), c(pitch), 0.0], [0.0, 0.0, 1.0]])
    Rx = np.array([[1.0, 0.0, 0.0], [0.0, c(roll), -s(roll)], [0.0, s(roll), c(roll)]])
    return Ry @ Rz @ Rx


def turned_orientation(coords, angles_deg) -> np.ndarray:
    """A body's orientation coordinates (theta_b in the plane, the quaternion in space) turned to the named angles
    ``angles_deg`` = (roll, pitch, yaw) in degrees, an entry None keeping the angle ``coords`` has (:func:`attitude`'s
    sequence); in space the unit quaternion of R = R_y(yaw) R_z(pitch) R_x(roll) (SciPy's conversion from the matrix,
    Shepperd's method), of the sign nearest ``coords``."""
    from scipy.spatial.transform import Rotation
    coords = np.asarray(coords, float)
    given = [None if a is None else np.radians(a) for a in angles_deg]
    if coords.size == 1:
        return np.array([coords[0] if given[1] is None else given[1]])
    now = {k: float(v) for k, v in attitude(ca.DM(coords)).items()}
    roll, pitch, yaw = (now[k] if g is None else g for k, g in zip(("roll_b", "theta_b", "yaw_b"), given))
    x, y, z, w = Rotation.from_matrix(euler_rotation(roll, pitch, yaw)).as_quat()
    a = np.array([w, x, y, z])
    return -a if a @ coords < 0.0 else a


def _drag(P: SectionParameters, R: RigidParameters, rho, Rm, r_cp, v_cp, t, env, depth0):
    """The body's drag at its centre of pressure: Wang's (1971 eq. 32-35), the sphere's along the relative flow or
    the cylinder's with its axis at phi_b in body axes, plus the quadratic drag per body axis 1/2 rho (C_D A)_i
    |u_i| u_i of the relative flow's body-axis components u_i (eq. 33a's law on each axis; Fossen 2011 sec. 6.4,
    the diagonal quadratic damping); the relative flow turned into body axes, the force back."""
    dim = v_cp.numel()
    u = flow_at(tuple(r_cp[k] for k in range(dim)), t, env, depth0)
    vr = ca.vertcat(*[u[k] - v_cp[k] for k in range(dim)])
    vb = ca.mtimes(Rm.T, vr)
    axes = ca.vertcat(*[fluid.quadratic_drag(rho, R.axis_drag[k], vb[k]) for k in range(dim)])
    if P.sphere:
        return ca.vertcat(*fluid.sphere_drag(rho, P.cda_n, *[vr[k] for k in range(dim)])) + ca.mtimes(Rm, axes)
    law = fluid.axial_body_drag if dim == 2 else fluid.axial_body_drag_3d
    return ca.mtimes(Rm, ca.vertcat(*law(rho, P.cda_n, P.cda_t, P.phi_b, *[vb[k] for k in range(dim)])) + axes)


def rigid_body(P: SectionParameters, R: RigidParameters, p, rho, t, env, depth0, dim: int = 2) -> ca.Function:
    """Lagrange's equations of the rigid body in its coordinates (r_a, theta) in the plane or (r_a, a) in space:
    ``(r, v, a, a_rate, p, t) -> (M, f, K, V, r_cg, v_cg, omega)`` with M = d2T/dq'2, f = dT/dq - (d2T/dq' dq) q'
    - dV/dq + Q (Wang 1971 eq. 8-9, 37), in space with the norm constraint of the quaternion in n's direction
    (Baumgarte 1972; module docstring), so that M q'' = f plus the cable's forces at the attachment node (N, N m);
    K, V the body's kinetic and potential energy (J); r_cg, v_cg the CG's position (m) and velocity (m/s); omega the
    body-axis angular velocity (rad/s). ``t`` the time symbol the fluid velocity depends on."""
    n_a = 1 if dim == 2 else 4
    r, v = ca.SX.sym("r", dim), ca.SX.sym("v", dim)
    a, ad = ca.SX.sym("theta" if dim == 2 else "quat", n_a), ca.SX.sym("theta_rate" if dim == 2 else "quat_rate", n_a)
    q, qd = ca.vertcat(r, a), ca.vertcat(v, ad)
    Rm = rotation(a)
    r_cg = r - ca.mtimes(Rm, ca.vertcat(*R.c))
    v_cg = ca.jtimes(r_cg, q, qd)
    r_cb = r_cg + ca.mtimes(Rm, ca.vertcat(*R.b))
    w = ca.mtimes(Rm.T, v_cg)                                    # the CG's velocity in body axes
    om = body_rate(a, ad)
    masses = (P.m_bx, P.m_by, P.m_bz)[:dim]
    J = R.inertia + (ca.diag(R.added_inertia) if dim == 3 else R.added_inertia)
    K = 0.5 * sum(masses[k] * w[k] ** 2 for k in range(dim)) + 0.5 * ca.dot(om, ca.mtimes(J, om))
    V = -(P.w_b + R.buoyancy) * r_cg[1] + R.buoyancy * r_cb[1]
    # drag at the centre of pressure with its velocity (eq. 32-35); virtual work (eq. 37); the damping moment
    r_cp = r_cg + ca.mtimes(Rm, ca.vertcat(*R.e))
    v_cp = ca.jtimes(r_cp, q, qd)
    D = _drag(P, R, rho, Rm, r_cp, v_cp, t, env, depth0)
    Q = ca.mtimes(ca.jacobian(v_cp, qd).T, D)
    Q = Q + ca.mtimes(ca.jacobian(om, qd).T, -R.damping * om - R.drag * ca.fabs(om) * om)
    mom = ca.gradient(K, qd)
    M = ca.jacobian(mom, qd)
    f = ca.gradient(K, q) - ca.mtimes(ca.jacobian(mom, q), qd) - ca.gradient(V, q) + Q
    if dim == 3:     # |a| = 1 by Baumgarte's C'' + 2 beta C' + beta^2 C = 0 in the direction n = (0, a / |a|)
        na = ca.norm_2(a)
        n = ca.vertcat(ca.SX.zeros(3), a / na)
        beta = BAUMGARTE_RATE
        s = (-ca.sumsqr(ad) - 2 * beta * ca.dot(a, ad) - 0.5 * beta**2 * (ca.sumsqr(a) - 1.0)) / na   # n . q''
        j_ref = 4.0 * ca.trace(J) / 3.0           # the scale of M's quaternion block, 4 G^T J G
        M = M + j_ref * ca.mtimes(n, n.T)
        f = f - n * ca.dot(n, f) + j_ref * s * n
    return ca.Function("rigid_body", [r, v, a, ad, p, t], [M, f, K, V, r_cg, v_cg, om],
                       ["r", "v", "a", "a_rate", "p", "t"], ["M", "f", "K", "V", "r_cg", "v_cg", "omega"])


def free_body(scene, section: int = 0) -> dict:
    """The rigid body of ``scene``'s section ``section`` alone, in space, without its cable (nothing pulls at the
    attachment point): the equations of :func:`rigid_body` as a first-order system, for checks of the rigid-body
    equations themselves (free rotation: Goldstein sec. 5.6; Lamb 1932 sec. 119-126 with added mass).

    Returns a dict of CasADi functions of the state x = (r_a, a, v_a, a') (m, -, m/s, 1/s; a the quaternion) and the
    scene's parameter vector p (``ParameterLayout.from_scene(scene)``): ``ode(x, t, p) -> x'``, ``state(x, p) ->
    (r_cg, v_cg, omega, R)`` (m, m/s, rad/s in body axes, the 3 x 3 rotation body -> scene), ``energy(x, p) ->
    (K, V)`` (J), ``impulse(x, p) -> (P, L)`` Kirchhoff's linear (N s) and angular (N m s, about the origin) impulse
    of body and fluid (Lamb 1932 sec. 119; a closed form, not the Lagrangian's momenta), and ``p`` the numeric
    parameter vector; ``scene`` must be a 3-D scene with a rigid body there."""
    from .params import ParameterLayout, environment_symbols, section_prefix

    layout = ParameterLayout.from_scene(scene)
    n_sec = len(scene.sections)
    pre = section_prefix(n_sec, section)
    P = SectionParameters.from_layout(layout, pre, scene.sections[section].body.is_sphere, True)
    env = environment_symbols(layout, scene)
    t = ca.SX.sym("t")
    body = rigid_body(P, RigidParameters.from_layout(layout, pre, 3), layout.symbol, env["density"], t, env,
                      env["top_depth"], 3)
    x, p = ca.SX.sym("x", 14), layout.symbol
    r, a, v, ad = x[0:3], x[3:7], x[7:10], x[10:14]
    M, f, K, V, r_cg, v_cg, om = body(r, v, a, ad, p, t)
    xdot = ca.vertcat(v, ad, ca.solve(M, f))
    # Kirchhoff's impulses of the body and the fluid it carries (Lamb 1932 sec. 119), about the scene's origin:
    # P = R M_bv w, L = r_cg x P + R (I + I_a) omega; both constant in free motion
    Rm = rotation(a)
    Rp = RigidParameters.from_layout(layout, pre, 3)
    w = ca.mtimes(Rm.T, v_cg)
    P_lin = ca.mtimes(Rm, ca.vertcat(P.m_bx * w[0], P.m_by * w[1], P.m_bz * w[2]))
    L_ang = ca.cross(r_cg, P_lin) + ca.mtimes(Rm, ca.mtimes(Rp.inertia + ca.diag(Rp.added_inertia), om))
    return {"ode": ca.Function("free_body", [x, t, p], [xdot], ["x", "t", "p"], ["xdot"]),
            "state": ca.Function("free_body_state", [x, p], [r_cg, v_cg, om, rotation(a)], ["x", "p"],
                                 ["r_cg", "v_cg", "omega", "R"]),
            "energy": ca.Function("free_body_energy", [x, p], [K, V], ["x", "p"], ["K", "V"]),
            "impulse": ca.Function("free_body_impulse", [x, p], [P_lin, L_ang], ["x", "p"], ["P", "L"]),
            "p": np.asarray(layout.values(scene), float)}
