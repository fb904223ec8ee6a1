"""Prescribed top motion x_s(t), y_s(t) and its first two derivatives, as a CasADi function.

Sinusoids a sin(omega t + phase) (Wang 1971, "an arbitrary number of sinusoidal functions")
plus an optional sampled series (the report's "non-periodic motions") interpolated by the
not-a-knot cubic B-spline through the samples (the spline of ``scipy.interpolate.
make_interp_spline``). The samples stay parameters: the spline coefficients solve the sparse
banded collocation system A c = samples inside the function (A from ``BSpline.design_matrix``),
and CasADi's ``bspline`` evaluates the spline from 4 coefficients at a time. That primitive
exists for MX only, so a scene with a series gets MX functions (``symbolic_type``).
"""

from __future__ import annotations

import casadi as ca
import numpy as np
from scipy.interpolate import BSpline, make_interp_spline


def symbolic_type(scene):
    """ca.SX for sinusoids only; ca.MX when a sampled series needs the B-spline primitive."""
    return ca.MX if scene.top_motion.series is not None else ca.SX


def _collocation(times):
    """Knots of the interpolating cubic spline and its (sparse) collocation matrix."""
    t = np.asarray(times, float)
    knots = make_interp_spline(t, np.zeros_like(t), k=3).t
    A = BSpline.design_matrix(t, knots, 3).tocsc()
    return knots, ca.DM(A)


def top_motion_function(scene, layout) -> ca.Function:
    """``top(t, p) -> (t, x_s, y_s, x_s', y_s', x_s'', y_s'')`` for the scene's top motion."""
    S = symbolic_type(scene)
    t = S.sym("t")
    p = S.sym("p", len(layout))
    sym = lambda label: p[layout.index(label)]
    pos = []
    for axis in ("x", "y"):
        s = 0
        for k in range(len(getattr(scene.top_motion, axis))):
            a, w, ph = (sym(f"top_motion.{axis}[{k}].{n}") for n in ("amplitude", "frequency", "phase"))
            s = s + a * ca.sin(w * t + ph)
        pos.append(s if isinstance(s, S) else S(s))
    series = scene.top_motion.series
    if series is not None:
        knots, A = _collocation(series.times)
        lo, hi = series.times[0], series.times[-1]
        tc = ca.fmin(ca.fmax(t, lo), hi)     # held at the end values outside the sampled span
        for j, axis in enumerate(("x", "y")):
            samples = ca.vertcat(*(sym(f"top_motion.series.{axis}[{k}]") for k in range(len(series.times))))
            coef = ca.solve(A, samples, "csparse")
            pos[j] = pos[j] + ca.bspline(tc, coef, [list(knots)], [3], 1, {})
    pos = ca.vertcat(*pos)
    vel = ca.jacobian(pos, t)
    acc = ca.jacobian(vel, t)
    return ca.Function("top", [t, p], [ca.vertcat(t, pos, vel, acc)], ["t", "p"], ["e"])
