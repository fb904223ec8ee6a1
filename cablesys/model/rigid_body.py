"""A rigid body that pitches in the x-y plane on an attachment point off its centre of gravity.

Wang (1971) p. 32, "Extensions": body rotation "where the body is fairly large and the cable is not
attached to the center of mass" adds one degree of freedom in the plane. The cable's last node of a
section is the body's attachment point r_a = (x, y) (y down from the mean top depth); the pitch
theta_b turns the body axes from the scene's (x, y) (+x towards +y, about +z). With R(theta) the plane
rotation [[cos, -sin], [sin, cos]], c the attachment point and b the centre of buoyancy from the centre
of gravity (CG) in body axes (``body.attachment_x/y``, ``body.buoyancy_x/y``):

- r_cg = r_a - R(theta) c,  r_cb = r_cg + R(theta) b;
- kinetic energy T = 1/2 (M_bvx w_x^2 + M_bvy w_y^2) + 1/2 (I + I_a) theta'^2 with w = R(theta)^T v_cg the
  CG's velocity in body axes: Wang's virtual masses (eq. 16, mass plus added mass) along the body's axes,
  which are the scene's x and y at theta = 0 (the added-mass tensor is fixed in the body: Newman, Marine
  Hydrodynamics, 1977, sec. 4.13; its Munk moment (M_bvx - M_bvy) w_x w_y follows); I the body's moment of
  inertia about its CG and I_a the added moment of inertia (rigid-body kinetic energy about the CG,
  Goldstein, Classical Mechanics, 3rd ed., sec. 5.1);
- potential energy V = -(W_b + B) y_cg + B y_cb (y down): the weight W_b + B at the CG, the buoyancy B
  at the centre of buoyancy, so the weight in water is Wang's W_b (eq. 15);
- generalized forces by virtual work (Wang eq. 37): the body drag of eq. 32-35 at the centre of pressure
  r_cp = r_cg + R(theta) e (``body.drag_centre_x/y``; e = 0: the CG) with that point's velocity and the body
  axis at phi_b + theta, and the pitch moment -c theta' - d |theta'| theta'.

Lagrange's equations come by CasADi AD of T and V (:func:`planar_rigid_body`), as for the cable
elements (:func:`.segmented_element.element_inertia`). With c = b = 0 and M_bvx = M_bvy the translation
is the point body's exactly and theta decouples; with M_bvx != M_bvy they agree at theta = 0. SI throughout
(m, N, kg, kg m^2, rad).
"""

from __future__ import annotations

import dataclasses

import casadi as ca

from .section import SectionParameters
from .segmented_element import body_drag

__all__ = ["RigidParameters", "planar_rigid_body"]


@dataclasses.dataclass(frozen=True)
class RigidParameters:
    """The rigid body's entries of the parameter vector (symbols): SI, body axes (see the module docstring)."""

    inertia: ca.SX          # I about the CG (kg m^2)
    added_inertia: ca.SX    # I_a (kg m^2)
    c: tuple                # attachment point from the CG, body axes (m)
    b: tuple                # centre of buoyancy from the CG, body axes (m)
    e: tuple                # centre of pressure (where the drag acts) from the CG, body axes (m)
    buoyancy: ca.SX         # B (N)
    damping: ca.SX          # c (N m s)
    drag: ca.SX             # d (N m s^2)

    @classmethod
    def from_layout(cls, layout, prefix: str) -> "RigidParameters":
        b = lambda n: layout.sym(f"{prefix}body.{n}")
        return cls(inertia=b("pitch_inertia"), added_inertia=b("pitch_added_inertia"),
                   c=(b("attachment_x"), b("attachment_y")), b=(b("buoyancy_x"), b("buoyancy_y")),
                   e=(b("drag_centre_x"), b("drag_centre_y")),
                   buoyancy=b("buoyancy"), damping=b("pitch_damping"), drag=b("pitch_drag"))


def _rotate(theta, v):
    """R(theta) v in the x-y plane (+x towards +y)."""
    c, s = ca.cos(theta), ca.sin(theta)
    return ca.vertcat(c * v[0] - s * v[1], s * v[0] + c * v[1])


def planar_rigid_body(P: SectionParameters, R: RigidParameters, p, rho, t, env, depth0) -> ca.Function:
    """Lagrange's equations of the pitching body in its coordinates (x_a, y_a, theta):
    ``(r, v, theta, theta_rate, p) -> (M, f, K, V, r_cg, v_cg)`` with M = d2T/dq'2 (3 x 3),
    f = dT/dq - (d2T/dq' dq) q' - dV/dq + Q (Wang 1971 eq. 8-9, 37), so that M q'' = f plus the cable's
    forces at the attachment node (N, N m); K, V the body's kinetic and potential energy (J); r_cg, v_cg
    the CG's position (m) and velocity (m/s). ``t`` the time symbol the fluid velocity depends on."""
    r, v = ca.SX.sym("r", 2), ca.SX.sym("v", 2)
    th, thd = ca.SX.sym("theta"), ca.SX.sym("theta_rate")
    q, qd = ca.vertcat(r, th), ca.vertcat(v, thd)
    r_cg = r - _rotate(th, ca.vertcat(*R.c))
    v_cg = ca.jtimes(r_cg, q, qd)
    r_cb = r_cg + _rotate(th, ca.vertcat(*R.b))
    w = _rotate(-th, v_cg)                                       # the CG's velocity in body axes
    K = 0.5 * (P.m_bx * w[0] ** 2 + P.m_by * w[1] ** 2) + 0.5 * (R.inertia + R.added_inertia) * thd ** 2
    V = -(P.w_b + R.buoyancy) * r_cg[1] + R.buoyancy * r_cb[1]
    # drag at the centre of pressure with its velocity, the body's axis turned with it (eq. 32-35); virtual
    # work (eq. 37)
    r_cp = r_cg + _rotate(th, ca.vertcat(*R.e))
    v_cp = ca.jtimes(r_cp, q, qd)
    D = body_drag(dataclasses.replace(P, phi_b=P.phi_b + th), rho, (r_cp[0], r_cp[1]), (v_cp[0], v_cp[1]),
                  t, env, depth0)
    Q = ca.mtimes(ca.jacobian(v_cp, qd).T, ca.vertcat(D[0], D[1]))
    Q = Q + ca.vertcat(0.0, 0.0, -R.damping * thd - R.drag * ca.fabs(thd) * thd)
    mom = ca.gradient(K, qd)
    M = ca.jacobian(mom, qd)
    f = ca.gradient(K, q) - ca.mtimes(ca.jacobian(mom, q), qd) - ca.gradient(V, q) + Q
    return ca.Function("rigid_body", [r, v, th, thd, p, t], [M, f, K, V, r_cg, v_cg],
                       ["r", "v", "theta", "theta_rate", "p", "t"], ["M", "f", "K", "V", "r_cg", "v_cg"])
