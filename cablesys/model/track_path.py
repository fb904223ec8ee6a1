"""A towing ship's path in the horizontal plane as a CasADi expression of time (:class:`cablesys.scene.track.Track`).

The tow point runs at the speed U along a path of pieces, each of length l_k and constant signed curvature kappa_k
(0: a straight; +-1/R: an arc to port / starboard), from the origin with heading psi_0; the arc length is s = U t.
Along piece k, entered at s = S_k at the point P_k with heading psi_k, the position at sigma = s - S_k is the
chord of the arc (a circle's chord, do Carmo, Differential Geometry of Curves and Surfaces, 1976, sec. 1-5: a
plane curve of constant curvature):

    P(sigma) = P_k + sigma sinc(kappa sigma / 2) (cos(psi_k + kappa sigma / 2), sin(psi_k + kappa sigma / 2)),
    psi(sigma) = psi_k + kappa sigma,                 sinc(u) = sin(u) / u,

one formula for a straight (kappa = 0: sinc = 1, the chord the straight itself) and an arc, so that whether a leg
is straight or bent is a value of the parameter vector, not the model's structure. (x, z) are the plane's
coordinates, psi from +x towards +z. P_{k+1}, psi_{k+1} and S_{k+1} are those at sigma = l_k (symbolic sums of
the pieces before). Before t = 0 the point runs straight along psi_0 (the ship towed straight up to the start);
after the last piece straight on along its end heading, or, with a cycle of pieces whose headings sum to zero (a
zig-zag), the cycle repeats: with sigma_c the arc length past the legs, n = floor(sigma_c / S_c) whole cycles
(S_c the cycle's length) have moved the point by n D (D the cycle's displacement) and it is sigma_c - n S_c into
the next. The piece is selected by ``if_else`` on s (O(number of pieces) per evaluation; a path has few).

Velocity and acceleration are the exact t-derivatives by AD (``top_motion_function``): U (cos psi, sin psi) and
U^2 kappa (-sin psi, cos psi). The position is C1 and the acceleration steps where kappa does. The node model
needs no smoothing there: its equations of motion take the top's position and velocity (the elements' stretch,
damping and drag, :mod:`.segmented`), which are continuous, so its right-hand side is continuous in t and an
adaptive integrator steps through a join with its t-derivative's jump; the acceleration enters only the top
tension's lumped half element (an output, which steps with it, as the half element's inertia does).
"""

from __future__ import annotations

import casadi as ca

#: |u| below which sinc(u) is its Taylor series 1 - u^2/6 + u^4/120 - u^6/5040 (truncation u^8/9! < 3e-30)
SINC_SERIES = 1e-3


def sinc(u):
    """sin(u) / u, and its series near u = 0 (both branches finite, so their derivatives are too)."""
    small = ca.fabs(u) < SINC_SERIES
    us = ca.if_else(small, 1.0, u)
    u2 = u * u
    return ca.if_else(small, 1.0 - u2 / 6.0 * (1.0 - u2 / 20.0 * (1.0 - u2 / 42.0)), ca.sin(us) / us)


def _along(P, psi, sigma, kappa):
    """The point and heading at ``sigma`` along a piece of curvature ``kappa`` entered at ``P`` with ``psi``."""
    half = 0.5 * kappa * sigma
    chord = sigma * sinc(half)
    return (P[0] + chord * ca.cos(psi + half), P[1] + chord * ca.sin(psi + half)), psi + kappa * sigma


def _ends(pieces, P, psi):
    """Start points, headings and arc lengths of ``pieces`` ((length, curvature) pairs) entered at ``P``, ``psi``;
    the last entries are the end's."""
    points, headings, starts, s = [P], [psi], [0.0], 0.0
    for length, kappa in pieces:
        P, psi = _along(P, psi, length, kappa)
        s = s + length
        points.append(P)
        headings.append(psi)
        starts.append(s)
    return points, headings, starts


def _select(s, pieces, points, headings, starts, after=None):
    """The position at arc length ``s`` (from the pieces' start) on ``pieces``, ``after(s)`` past their end (None: the
    last piece's formula continued, for the rounding of s at a cycle's end)."""
    last = len(pieces) if after is not None else len(pieces) - 1
    out = after(s) if after is not None else _along(points[last], headings[last], s - starts[last], pieces[last][1])[0]
    for k in reversed(range(last)):
        P, _ = _along(points[k], headings[k], s - starts[k], pieces[k][1])
        out = tuple(ca.if_else(s < starts[k + 1], P[c], out[c]) for c in range(2))
    return out


def path_position(t, speed, heading, legs, cycle=()):
    """(x, z) of the tow point at time ``t`` (m; SX).

    Parameters
    ----------
    t : casadi.SX
        Time (s).
    speed, heading : casadi.SX
        U (m/s) and psi_0 (rad, from +x towards +z).
    legs, cycle : sequence of (SX, SX)
        (length (m), signed curvature (1/m, + to port)) of the pieces followed once from t = 0, then of the cycle
        repeated without end (its headings must sum to zero); no cycle: straight on after the legs.

    Returns
    -------
    tuple of casadi.SX
        (x_s, z_s).
    """
    s = speed * t
    origin = (0.0 * s, 0.0 * s)
    points, headings, starts = _ends(legs, origin, heading)
    end_P, end_psi, end_s = points[-1], headings[-1], starts[-1]
    if cycle:
        c_points, c_headings, c_starts = _ends(cycle, (0.0 * s, 0.0 * s), end_psi)
        D, S_c = c_points[-1], c_starts[-1]

        def after(sig):
            sc = sig - end_s
            n = ca.floor(sc / S_c)
            inside = _select(sc - n * S_c, cycle, c_points, c_headings, c_starts)
            return tuple(end_P[c] + n * D[c] + inside[c] for c in range(2))
    else:
        def after(sig):
            return _along(end_P, end_psi, sig - end_s, 0.0)[0]
    ahead = _select(s, legs, points, headings, starts, after)
    before, _ = _along(origin, heading, s, 0.0)
    return tuple(ca.if_else(s < 0.0, before[c], ahead[c]) for c in range(2))


def track_symbols(track, sym):
    """(speed, heading, legs, cycle) of ``track`` (:class:`cablesys.scene.track.Track`, not a circle) as entries of the
    parameter vector, ``sym(label)`` giving the symbol (labels of ``Track.parameter_items``); a straight track in the
    x-y plane has the heading 0, not a parameter."""
    legs, cycle = track.pieces()
    pieces = lambda name, ps: [(sym(f"top_motion.track.{name}[{j}].length"), sym(f"top_motion.track.{name}[{j}].curvature"))
                               for j in range(len(ps))]
    heading = 0.0 if track.in_plane else sym("top_motion.track.heading")
    return sym("top_motion.track.speed"), heading, pieces("legs", legs), pieces("cycle", cycle)
