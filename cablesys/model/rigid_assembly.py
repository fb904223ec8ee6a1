"""A rigid body's place in a node model: its block of the mass matrix, its node's solve and its outputs.

Both node models (the chain of sections, :mod:`.segmented`, and the graph of lines, :mod:`.system`) put a rigid body
(:mod:`.rigid_body`: Wang 1971 p. 32, body rotation "where the body is fairly large and the cable is not attached to
the center of mass") at a node of the cable: the node is its attachment point r_a, its orientation (the pitch
theta_b in the plane, a quaternion a in space) more coordinates after every node's, and node and orientation share
one block of Lagrange's equations M q'' = f (3 x 3 in the plane, 7 x 7 in space): the lines' element terms and the
body's own (:func:`.rigid_body.rigid_body`, by CasADi AD of its kinetic and potential energy) summed on the node's
rows. This module is that shared piece: :func:`rigid_block` builds a body's terms, :func:`assemble` adds them into
the model's M and f, :func:`node_acceleration` solves the node's block (the plane's 3 x 3 in closed form by
:func:`.segmented_element.block_solve`, space's 7 x 7 by CasADi's ``solve``), :func:`rigid_outputs` lists the body's
outputs (:data:`RIGID_OUTPUTS`, in space also :data:`RIGID_OUTPUTS_3D`). SI throughout (m, rad, N, N m).
"""

from __future__ import annotations

import dataclasses

import casadi as ca

from .rigid_body import RigidParameters, attitude, rigid_body
from .segmented_element import block_solve

__all__ = ["RIGID_OUTPUTS", "RIGID_OUTPUTS_3D", "RigidBlock", "assemble", "node_acceleration", "orientation_names",
           "rigid_block", "rigid_outputs"]

# a rigid body's outputs (model/rigid_body.py): pitch theta_b (rad) and its rate, the CG's x, y (m) and rates
RIGID_OUTPUTS = ("theta_b", "theta_b_rate", "x_cg", "x_cg_rate", "y_cg", "y_cg_rate")
# and in space: roll and yaw (rad, sequence in rigid_body.attitude) and rates, the CG's z (m) and rate, the body-axis
# angular velocity (rad/s) and the unit quaternion (scalar first)
RIGID_OUTPUTS_3D = ("roll_b", "roll_b_rate", "yaw_b", "yaw_b_rate", "z_cg", "z_cg_rate", "omega_x_b", "omega_y_b",
                    "omega_z_b", "quat_w_b", "quat_x_b", "quat_y_b", "quat_z_b")


def orientation_names(dim: int) -> tuple:
    """The names of a body's orientation coordinates: ``theta_b`` in the plane, ``quat_w_b`` .. ``quat_z_b`` in space
    (their level values :data:`.rigid_body.ORIENTATION_REST`)."""
    return ("theta_b",) if dim == 2 else tuple(f"quat_{c}_b" for c in "wxyz")


@dataclasses.dataclass(frozen=True)
class RigidBlock:
    """One rigid body's terms in a node model: ``rows`` the positions of its node's coordinates in q, ``k`` those of
    its orientation; ``M``, ``f`` its block of Lagrange's equations on (node, orientation) (kg, kg m^2; N, N m),
    ``K``, ``V`` its kinetic and potential energy (J), ``r_cg``, ``v_cg`` its CG (m, m/s), ``omega`` its body-axis
    angular velocity (rad/s), ``a``, ``ad`` its orientation coordinates and their rates (SX of q, q')."""

    rows: tuple
    k: tuple
    M: ca.SX
    f: ca.SX
    K: ca.SX
    V: ca.SX
    r_cg: ca.SX
    v_cg: ca.SX
    omega: ca.SX
    a: ca.SX
    ad: ca.SX


def rigid_block(P, layout, prefix: str, rows, k, r, v, q, qd, *, rho, t, env, depth0, dim: int) -> RigidBlock:
    """The rigid body whose entries of p are ``{prefix}body.*`` (:meth:`.rigid_body.RigidParameters.from_layout`) at
    the node of position ``r`` and velocity ``v`` (tuples of SX), its node's coordinates at ``rows`` of q and its
    orientation at ``k``: :func:`.rigid_body.rigid_body`'s terms (Lagrange's equations, energies, CG and rate).
    ``P`` the body's section parameters (virtual masses, weight in water, drag: Wang 1971 eq. 16, 32-35)."""
    k = list(k)
    Mb, fb, Kb, Vb, r_cg, v_cg, om = rigid_body(P, RigidParameters.from_layout(layout, prefix, dim), layout.symbol,
                                                rho, t, env, depth0, dim)(ca.vertcat(*r), ca.vertcat(*v), q[k], qd[k],
                                                                          layout.symbol, t)
    return RigidBlock(rows=tuple(rows), k=tuple(k), M=Mb, f=fb, K=Kb, V=Vb, r_cg=r_cg, v_cg=v_cg, omega=om, a=q[k],
                      ad=qd[k])


def assemble(M, f, f_static, blocks, n_rot: int) -> tuple:
    """(M, f, f_static) of the node coordinates widened by the ``n_rot`` orientation coordinates and every body's
    block (:class:`RigidBlock`) added on its node's and orientation's rows; ``f_static`` (the statics' own right-hand
    side) may be None."""
    if not n_rot:
        return M, f, f_static
    M = ca.diagcat(M, ca.SX.zeros(n_rot, n_rot))
    f = ca.vertcat(f, ca.SX.zeros(n_rot))
    if f_static is not None:
        f_static = ca.vertcat(f_static, ca.SX.zeros(n_rot))
    for blk in blocks:
        rows = list(blk.rows) + list(blk.k)
        for a in range(len(rows)):
            f[rows[a]] += blk.f[a]
            if f_static is not None:
                f_static[rows[a]] += blk.f[a]
            for b in range(len(rows)):
                M[rows[a], rows[b]] += blk.M[a, b]
    return M, f, f_static


def node_acceleration(blk: RigidBlock, M_node, f_node, dim: int) -> tuple:
    """(a_node, a_rot): the attachment node's acceleration (dim entries) and the orientation's (its coordinates'
    second derivatives), from the node's block M_node, f_node of the lines' terms plus the body's: the plane's 3 x 3
    by :func:`.segmented_element.block_solve`, space's 7 x 7 by CasADi's ``solve`` (QR)."""
    n = len(blk.k)
    Mj = ca.diagcat(M_node, ca.SX.zeros(n, n)) + blk.M
    fj = ca.vertcat(f_node, ca.SX.zeros(n)) + blk.f
    ab = block_solve(Mj, fj) if dim == 2 else ca.solve(Mj, fj)
    return tuple(ab[c] for c in range(dim)), [ab[dim + m] for m in range(n)]


def rigid_outputs(blk: RigidBlock, dim: int) -> tuple:
    """(values, names) of the body's outputs: :data:`RIGID_OUTPUTS` (pitch and rate, rad, rad/s; the CG's x, y and
    rates, m, m/s), in space also :data:`RIGID_OUTPUTS_3D` (roll, yaw of :func:`.rigid_body.attitude` and rates, the
    CG's z and rate, the body-axis angular velocity, the unit quaternion)."""
    a, ad, r_cg, v_cg, om = blk.a, blk.ad, blk.r_cg, blk.v_cg, blk.omega
    ang = {name: (value, ca.jtimes(value, a, ad)) for name, value in attitude(a).items()}
    out = [*ang["theta_b"], r_cg[0], v_cg[0], r_cg[1], v_cg[1]]
    names = list(RIGID_OUTPUTS)
    if dim == 3:
        out += [*ang["roll_b"], *ang["yaw_b"], r_cg[2], v_cg[2], *[om[c] for c in range(3)],
                *[a[c] / ca.norm_2(a) for c in range(4)]]
        names += list(RIGID_OUTPUTS_3D)
    return out, names
