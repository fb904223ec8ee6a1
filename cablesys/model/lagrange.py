"""Lagrange's equations by automatic differentiation (Wang 1971 eq. 8-9).

For generalized coordinates q and prescribed coordinates z(t) (the top motion),
d/dt(dL/dq') - dL/dq = Q gives M(q) q'' = f(q, q', z, z', z'', t) with

    M = d2L/dq'2,
    f = dL/dq + Q - (d2L/dq' dq) q' - (d2L/dq' dz) z' - (d2L/dq' dz') z''.

Generalized forces come from virtual work: a force F at a point whose velocity is v(q')
contributes (dv/dq')^T F (Wang 1971 eq. 37, 43, 45 are special cases).
"""

from __future__ import annotations

import casadi as ca


def lagrange_equations(L, Q, q, qd, z, zd, zdd):
    """Return (M, f) with M q'' = f for the Lagrangian ``L`` and generalized forces ``Q``."""
    p = ca.gradient(L, qd)
    M = ca.jacobian(p, qd)
    f = (ca.gradient(L, q) + Q
         - ca.mtimes(ca.jacobian(p, q), qd)
         - ca.mtimes(ca.jacobian(p, z), zd)
         - ca.mtimes(ca.jacobian(p, zd), zdd))
    return M, f


def virtual_work(point_forces, qd):
    """Sum of (dv/dq')^T F over ``point_forces`` = [(v, F), ...] with v, F 2-vectors."""
    Q = ca.SX.zeros(qd.shape[0])
    for v, F in point_forces:
        Q += ca.mtimes(ca.jacobian(ca.vertcat(*v), qd).T, ca.vertcat(*F))
    return Q
