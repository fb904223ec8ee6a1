"""Prescribed top motion x_s(t), y_s(t) and its first two derivatives, as a CasADi function.

Sinusoids a sin(omega t + phase) (Wang 1971, "an arbitrary number of sinusoidal functions")
plus an optional sampled series interpolated by a cubic B-spline through the samples (the
report's "non-periodic motions"). The sample values stay parameters: the B-spline
coefficients are a fixed linear map of them, computed once from the basis matrix.
"""

from __future__ import annotations

import casadi as ca
import numpy as np


def _spline_through(times):
    """A cubic B-spline interpolant on ``times`` and the matrix mapping samples to coefficients."""
    grid = [float(v) for v in times]
    spline = ca.interpolant("series", "bspline", [grid], 1, {})
    n = len(grid)
    basis = np.zeros((n, n))
    for j in range(n):
        unit = np.zeros(n)
        unit[j] = 1.0
        basis[:, j] = [float(spline(tk, unit)) for tk in grid]
    return spline, np.linalg.inv(basis)


def top_motion_function(scene, layout) -> ca.Function:
    """``top(t, p) -> (t, x_s, y_s, x_s', y_s', x_s'', y_s'')`` for the scene's top motion."""
    t = ca.SX.sym("t")
    pos = []
    for axis in ("x", "y"):
        s = 0
        for k in range(len(getattr(scene.top_motion, axis))):
            a, w, ph = (layout.sym(f"top_motion.{axis}[{k}].{n}") for n in ("amplitude", "frequency", "phase"))
            s = s + a * ca.sin(w * t + ph)
        pos.append(s)
    series = scene.top_motion.series
    if series is not None:
        spline, to_coef = _spline_through(series.times)
        lo, hi = series.times[0], series.times[-1]
        tc = ca.fmin(ca.fmax(t, lo), hi)     # held at the end values outside the sampled span
        for j, axis in enumerate(("x", "y")):
            samples = ca.vertcat(*(layout.sym(f"top_motion.series.{axis}[{k}]") for k in range(len(series.times))))
            pos[j] = pos[j] + spline(tc, ca.mtimes(ca.DM(to_coef), samples))
    pos = ca.vertcat(*[ca.SX(v) if not isinstance(v, ca.SX) else v for v in pos])
    vel = ca.jacobian(pos, t)
    acc = ca.jacobian(vel, t)
    return ca.Function("top", [t, layout.symbol], [ca.vertcat(t, pos, vel, acc)], ["t", "p"], ["e"])
