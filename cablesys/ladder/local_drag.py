"""The string with its drag linearized element by element: the second linearization of the estimate.

:mod:`.continuum` gives the whole string one equivalent damping, from the mean of its end speeds. Where
the forcing nears a string mode (omega / omega_string ~ 0.5-1, the random heavy cables) the string bulges
between its ends and its drag follows the local speed, so each element here gets the describing function
of its own speed amplitude, c = (8 / 3 pi) 1/2 rho C_D d |V| (+ the current's slope; Roberts & Spanos,
"Random Vibration and Statistical Linearization", ch. 5, applied per element), a fixed point on the node
amplitudes. With the segmented model's drag points (:func:`cablesys.model.segmented.drag_points`) |V| is
taken at each point from the complex velocity interpolated there (:func:`_solve`): where the nodes differ
in phase, as in a drag-controlled travelling wave, one mid-point sees less speed than the mean of its
nodes' amplitudes and damps the element less. The continuous string is its limit: N = REFERENCE_N and
N / 2 elements with the exact drag shares, extrapolated (Richardson, second order).

Against time-domain runs: the 1000 m wire surged and heaved 1 m at T = 10 s (settled, 100-120 s), body
surge x_b at N = 4 / 5 / 6 (two drag points per element) 0.0071 / 0.0107 / 0.0150 m here against 0.0074 /
0.0113 / 0.0157 measured, at N = 7 / 8 / 10 / 20 (one) 0.0324 / 0.0301 / 0.0266 / 0.0242 against 0.0345 /
0.0318 / 0.0275 / 0.0235 (surge alone 0.0340 / - / 0.0266 / 0.0244); the mean node amplitude per element
gave 0.0056 / 0.0071 / 0.0111 and 0.0244 / 0.0240 / 0.0237 / 0.0236 (tests/test_ladder_settling.py: a
500 m wire). The random heavy cables (tight, vs N = 32), body error at N = 2 / 3 / 4 / 6 / 8: heavy-1
0.55 / 0.13 / 0.038 / 0.011 / 0.16 % here against 0.97 / 0.21 / 0.014 / 0.009 / 0.091 % measured,
heavy-2 1.45 / 0.45 / 0.17 / 0.066 / 0.017 % against 1.68 / 0.49 / 0.21 / 0.076 / 0.008 %. On the Dale
scene at 2 omega_n the one-damping string is the closer (0.81 / 0.37 / 0.32 % against 0.88 / 0.38 /
0.31 % at N = 2 / 3 / 4): neither linearization holds everywhere, so :mod:`.estimate` states the larger
of the two.
"""

from __future__ import annotations

import math

import numpy as np

from ..scene import Scene
from .continuum import (
    K_HARMONIC,
    Member,
    across,
    drag_shares,
    members,
    respond,
    solve_tridiagonal,
    top_components,
)

REFERENCE_N = 256           # elements of the extrapolated continuous string
ITERATIONS = 40             # fixed-point iterations at most
TOLERANCE = 1e-6            # largest relative change of a node amplitude at which the fixed point stops


def _solve(mb: Member, omega: float, top: complex, n: int, points: int, start=None) -> tuple:
    """(W_b, node amplitudes) of :func:`chain`; ``start``: node amplitudes of another N (top to body), the
    first guess interpolated along the string (the fixed point moves little with N).

    ``points`` > 0: the drag acts at the segmented model's points s_k = (k + 1/2) / points of each element
    (:func:`cablesys.model.segmented.drag_points`), on the velocity interpolated there, (1 - s_k) w_j +
    s_k w_j+1, so each point's describing function takes the amplitude of that complex sum, not the
    mean of the node amplitudes: where adjacent nodes differ in phase (a travelling, drag-attenuated wave,
    phase k h per element) one midpoint sees less speed than its nodes, |cos(k h / 2)| of it, and the
    element is damped less (the segmented model's own drag, Roberts & Spanos ch. 5 applied per point); the
    force is shared by virtual work, ((1 - s_k)^2, s_k (1 - s_k), s_k^2) per point. ``points`` = 0 (the
    continuous limit's exact shares): the element's mean node amplitude."""
    h = mb.length / n
    if mb.varies():
        t_top, t_bot = mb.end_stiffness()
        k = (t_top + (t_bot - t_top) * (np.arange(n) + 0.5) / n) / h + 0j
    else:
        k = np.full(n, mb.stiffness / h, dtype=complex)
    d_c, o_c = drag_shares(points)
    s_k = (np.arange(points) + 0.5) / points if points > 0 else None
    if start is None:
        amp = np.full(n + 1, abs(top))                  # node amplitudes, 0 the top
    else:
        amp = np.interp(np.linspace(0.0, 1.0, n + 1), np.linspace(0.0, 1.0, len(start)), start)
    pts = None if s_k is None else (1 - s_k)[None, :] * amp[:-1, None] + s_k[None, :] * amp[1:, None]
    w = np.zeros(n, complex)
    mass = -omega**2 * mb.mass * h / 2.0
    for _ in range(ITERATIONS):
        cb = mb.end_drag * (K_HARMONIC * omega * amp[-1] + 2.0 * mb.current)
        if pts is None:
            c = mb.drag * (K_HARMONIC * omega * 0.5 * (amp[:-1] + amp[1:]) + 2.0 * mb.current)
            d0 = d1 = k + mass + 1j * omega * c * h * d_c
            o = -k + 1j * omega * c * h * o_c
        else:
            c = mb.drag * (K_HARMONIC * omega * pts + 2.0 * mb.current) * h / points      # per point, (n, points)
            d0 = k + mass + 1j * omega * (c @ (1 - s_k) ** 2)
            d1 = k + mass + 1j * omega * (c @ s_k**2)
            o = -k + 1j * omega * (c @ (s_k * (1 - s_k)))
        diag = np.empty(n, complex)
        diag[:-1] = d1[:-1] + d0[1:]
        diag[-1] = d1[-1] - mb.end_mass * omega**2 + 1j * omega * cb
        f = np.zeros(n, complex)
        f[0] = -o[0] * top
        w = solve_tridiagonal(o[1:], diag, f)
        new = np.sqrt(amp[1:] * np.maximum(np.abs(w), 1e-300))          # geometric relaxation (see respond)
        done = np.max(np.abs(new - amp[1:]) / np.maximum(new, 1e-300)) <= TOLERANCE
        amp[1:] = new
        if pts is not None:
            nodes = np.concatenate(([top], w))
            got = np.abs((1 - s_k)[None, :] * nodes[:-1, None] + s_k[None, :] * nodes[1:, None])
            new_pts = np.sqrt(pts * np.maximum(got, 1e-300))
            done = done and np.max(np.abs(new_pts - pts) / np.maximum(new_pts, 1e-300)) <= TOLERANCE
            pts = new_pts
        if done:
            break
    return complex(w[-1]), amp


def chain(mb: Member, omega: float, top: complex, n: int, points: int = 0, start=None) -> complex:
    """Body amplitude W_b (m) of ``n`` lumped string elements (each at its own tension, :meth:`Member.varies`)
    driven by ``top`` (m) at ``omega``, each element damped by the describing function of its own mean
    speed amplitude (module docstring); ``points``: the drag points per element
    (:func:`~.continuum.drag_shares`, 0: exact shares); ``start``: node amplitudes to start from."""
    if top == 0 or omega <= 0:
        return 0j
    return _solve(mb, omega, top, n, points, start)[0]


def reference(mb: Member, omega: float, top: complex) -> tuple:
    """(W_b, node amplitudes) of the continuous string with the local drag: :func:`chain` at REFERENCE_N
    and REFERENCE_N / 2 elements with exact drag shares, extrapolated as (4 W_N - W_N/2) / 3."""
    if top == 0 or omega <= 0:
        return 0j, None
    coarse, amp = _solve(mb, omega, top, REFERENCE_N // 2, 0)
    fine, amp = _solve(mb, omega, top, REFERENCE_N, 0, amp)
    return (4.0 * fine - coarse) / 3.0, amp


def body_responses(scene: Scene, angle: float, counts, points, forcing=None) -> tuple:
    """Body amplitudes {x_b, y_b} (m) with the strings' drag linearized element by element: (the continuous
    string's, {n: those of n elements with ``points(n)`` drag points each} for n in ``counts``); the rods as
    :func:`~.continuum.respond` (exact, or n lumped elements). Each element chain starts from the continuous
    string's node amplitudes."""
    comps = top_components(scene) or [(w, a + 0j, a + 0j, 0j) for w, a in (forcing or [])]
    st, ct = math.sin(angle), math.cos(angle)
    ref = {"x_b": 0.0, "y_b": 0.0}
    out = {n: {"x_b": 0.0, "y_b": 0.0} for n in counts}

    def add(d, ub, wb, wz=None):
        d["x_b"] = max(d["x_b"], abs(ub * st + wb * ct))
        d["y_b"] = max(d["y_b"], abs(ub * ct - wb * st))
        if wz is not None:
            d["z_b"] = max(d.get("z_b", 0.0), abs(wz))

    for omega, xs, ys, zs in comps:
        top_t, top_n = xs * st + ys * ct, xs * ct - ys * st
        for string, rod in members(scene, omega, angle):
            wb, amp = reference(string, omega, top_n)
            # 3-D: the motion across the flow's plane drives the same string, its drag slope across the flow
            side = across(string) if zs != 0 else None
            wz, amp_z = reference(side, omega, zs) if side is not None else (None, None)
            add(ref, respond(rod, omega, top_t, "exact")[0], wb, wz)
            for n in counts:
                p = points(n)
                add(out[n], respond(rod, omega, top_t, "segmented", n, p)[0], chain(string, omega, top_n, n, p, start=amp),
                    chain(side, omega, zs, n, p, start=amp_z) if side is not None else None)
    return ref, out
