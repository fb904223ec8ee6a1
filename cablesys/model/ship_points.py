"""Where a further point of the ship is: a second prescribed point of a system of lines (a crane tip beside a davit, a
second boom), moved with the ship at its arm Delta from the first prescribed point (the tow point, whose motion is the
top's: z, z', z'').

The arm is held in the scene's axes on a course whose heading holds, swung round with the ship's heading on a circle
(:func:`turned`), and turned by a vessel's small rotation theta at its lever arm (:func:`swing`, a 6-DOF motion RAO);
:func:`ship_point` adds them to the top's motion.
"""

from __future__ import annotations

import casadi as ca


def ship_point(arm, top, z0=None, theta=None, axes=()) -> tuple:
    """(r, v, a) of the point at ``arm`` Delta (dim entries, m): the top's motion ``top`` = (z, z', z'') plus the arm,
    swung round with the ship's heading on a circle when ``z0`` (the tow point at the start) is given (:func:`turned`),
    plus theta x Delta, its rate and acceleration when the vessel's rotation ``theta`` = (theta, theta', theta'') about
    the node ``axes`` is given (:func:`swing`)."""
    dim = len(arm)
    z, zd, zdd = top
    off = turned(arm, z, zd, zdd, z0) if z0 is not None else (tuple(arm), (0.0,) * dim, (0.0,) * dim)
    if theta is not None:
        off = tuple(tuple(o[c] + sw[c] for c in range(dim)) for o, sw in zip(off, (swing(th, arm, axes) for th in theta)))
    return tuple(tuple(base[c] + o[c] for c in range(dim)) for base, o in zip(top, off))


def swing(theta, arm, axes) -> tuple:
    """theta x Delta (m, node frame): the displacement of a point of the vessel at ``arm`` Delta (its mean position
    from the first prescribed point, dim entries) under the vessel's small rotation ``theta`` about the node ``axes``
    (rad; (z,) in the plane, where theta x Delta = (-theta_z Delta_y, theta_z Delta_x)); Faltinsen 1990 ch. 3, the
    rigid-body displacement eta_r x r in the node frame (:mod:`cablesys.scene.vessel`). Linear in theta: its rate and
    acceleration are the same map of theta's."""
    th = dict(zip(axes, (theta[m] for m in range(len(axes)))))
    wx, wy, wz = (th.get(c, 0.0) for c in "xyz")
    dx, dy, dz = (list(arm) + [0.0])[:3]
    return (wy * dz - wz * dy, wz * dx - wx * dz, wx * dy - wy * dx)[:len(arm)]


def turned(arm, z, zd, zdd, z0) -> tuple:
    """(Q(psi) Delta, its rate, its acceleration) (m, node frame): a point of a ship turning on a circle about the
    vertical through its centre (the origin, :class:`cablesys.scene.track.Track`) at ``arm`` Delta from the tow point
    when the run starts (its mean position, in the scene's axes), swung round with the ship's heading: psi(t) the angle
    the tow point has turned about the centre since the start, from its position ``z`` (rate ``zd``, acceleration
    ``zdd``) and its start ``z0``, Q(psi) the rotation about the upward vertical,
    Q(psi) (x, y, z) = (x cos psi - z sin psi, y, x sin psi + z cos psi), psi' = (x z' - z x') / rho^2 and
    psi'' = (x z'' - z x'') / rho^2 - 2 psi' (x x' + z z') / rho^2 (rho^2 = x^2 + z^2); d/dt Q Delta =
    psi' (-(Q Delta)_z, 0, (Q Delta)_x) (the rigid rotation Omega x r of the steady turn, Wang 1971 p. 32)."""
    x, zz, x0, zz0 = z[0], z[2], z0[0], z0[2]
    # a tow point at the centre (the statics' straight tow, in the tow point's frame) turns nothing: psi = 0
    off = (x * x + zz * zz) * (x0 * x0 + zz0 * zz0) > 1e-12
    rho2 = ca.if_else(off, x * x + zz * zz, 1.0)
    norm = ca.if_else(off, ca.sqrt((x * x + zz * zz) * (x0 * x0 + zz0 * zz0)), 1.0)
    c = ca.if_else(off, (x0 * x + zz0 * zz) / norm, 1.0)
    s = ca.if_else(off, (x0 * zz - zz0 * x) / norm, 0.0)
    w = ca.if_else(off, (x * zd[2] - zz * zd[0]) / rho2, 0.0)
    wd = ca.if_else(off, (x * zdd[2] - zz * zdd[0]) / rho2 - 2.0 * w * (x * zd[0] + zz * zd[2]) / rho2, 0.0)
    qx, qz = arm[0] * c - arm[2] * s, arm[0] * s + arm[2] * c
    return ((qx, arm[1], qz), (-w * qz, 0.0, w * qx), (-wd * qz - w * w * qx, 0.0, wd * qx - w * w * qz))
