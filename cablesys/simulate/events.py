"""Locating taut/slack switches and snap loads (Wang 1971 eq. 54: F_bc may not fall below TENS).

We do not rely on CasADi's experimental zero-crossing events (casadi issue 4393: IDAS
ignores them, CVODES fires in one direction only). Instead the simulator integrates each
mode (taut or slack, a parameter of the same compiled function) smoothly and checks the
switching function g = F_bc - TENS at the output times and, between them, on a cubic Hermite
interpolant built from g and dg/dt (which catches short excursions between output times).
A suspected crossing is bracketed on a dense grid from one integrator call, then refined by
a safeguarded Newton iteration whose derivative dg/dt comes from automatic differentiation;
each iterate integrates only from the nearest dense point. Snap loads (the first tension
maximum after going taut) are located the same way on dg/dt = 0 with d2g/dt2.
"""

from __future__ import annotations

import numpy as np

HERMITE_SAMPLES = np.linspace(0.0, 1.0, 33)[1:]


def hermite(ga, gb, da, db, h, s):
    """Cubic Hermite interpolant of g on [0, h] at fractions ``s`` (g values and slopes at the ends)."""
    h00 = 2 * s**3 - 3 * s**2 + 1
    h10 = s**3 - 2 * s**2 + s
    h01 = -2 * s**3 + 3 * s**2
    h11 = s**3 - s**2
    return h00 * ga + h10 * h * da + h01 * gb + h11 * h * db


def first_bad_interval(G, D, h, slack, tol_rel: float = 1e-12):
    """Index j >= 1 of the first interval (t_{j-1}, t_j] where any section leaves its mode, or None.

    Taut: g must stay >= -tol; slack: g (the unclamped F_bc - TENS) must stay <= tol, checked at
    the Hermite samples of every interval (the interval end included) at once.

    ``G``, ``D``: (n_sections, n_times) values of g and dg/dt; ``h``: (n_times - 1,) interval
    lengths; ``slack``: (n_sections,) booleans.
    """
    sign = np.where(np.asarray(slack, bool), -1.0, 1.0)[:, None, None]
    ga, gb, da, db = G[:, :-1, None], G[:, 1:, None], D[:, :-1, None], D[:, 1:, None]
    vals = sign * hermite(ga, gb, da, db, np.asarray(h)[None, :, None], HERMITE_SAMPLES[None, None, :])
    tol = tol_rel * np.maximum(1.0, np.maximum(np.abs(ga), np.abs(gb)))
    bad = np.any(vals < -tol, axis=(0, 2))
    idx = np.nonzero(bad)[0]
    return int(idx[0]) + 1 if idx.size else None


def newton_bracketed(fun, a: float, b: float, fa: float, fb: float, xtol: float, maxiter: int = 60):
    """Root of ``fun`` in [a, b] (fa, fb of opposite sign); ``fun(t) -> (f, df/dt)``.

    Newton steps from the better end, bisection whenever a step leaves the bracket or
    does not shrink it fast enough (hand-written because each evaluation is an integrator
    call that returns the derivative for free; scipy's brentq would need 5-10x more calls).
    """
    if fa == 0.0:
        return a
    if fb == 0.0:
        return b
    t = a if abs(fa) < abs(fb) else b
    f, df = fun(t)
    for _ in range(maxiter):
        step_ok = df != 0.0 and np.isfinite(df)
        t_new = t - f / df if step_ok else 0.5 * (a + b)
        if not (a < t_new < b):
            t_new = 0.5 * (a + b)
        if abs(t_new - t) < xtol:
            return t_new
        t = t_new
        f, df = fun(t)
        if f == 0.0:
            return t
        if np.sign(f) == np.sign(fa):
            a, fa = t, f
        else:
            b = t
        if b - a < xtol:
            return 0.5 * (a + b)
    return t
