"""Locating taut/slack switches and snap loads (Wang 1971 eq. 54: F_bc may not fall below TENS).

We do not rely on CasADi's experimental zero-crossing events (casadi issue 4393: IDAS
ignores them, CVODES fires in one direction only). Instead the simulator integrates each
mode (taut or slack, a parameter of the same compiled function) smoothly, checks the
switching function g = F_bc - TENS at the output times and, between them, a cubic Hermite
interpolant of g built from g and dg/dt (which catches short excursions between output
times), and locates each crossing with Brent's method on g(integrate(x_a, t_a -> t)).
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import brentq

HERMITE_SAMPLES = np.linspace(0.0, 1.0, 33)[1:]


def hermite(ga, gb, da, db, h, s):
    """Cubic Hermite interpolant of g on [0, h] at fractions ``s`` (g values and slopes at the ends)."""
    h00 = 2 * s**3 - 3 * s**2 + 1
    h10 = s**3 - 2 * s**2 + s
    h01 = -2 * s**3 + 3 * s**2
    h11 = s**3 - s**2
    return h00 * ga + h10 * h * da + h01 * gb + h11 * h * db


def first_violation(ga, gb, da, db, h, slack: bool, tol: float):
    """Fraction in (0, 1] of the first point where g leaves the current mode, or None.

    Taut: g must stay >= -tol. Slack: g (the unclamped F_bc - TENS) must stay <= tol.
    """
    sign = -1.0 if slack else 1.0
    if sign * gb < -tol:
        end_bad = True
    else:
        end_bad = False
    vals = sign * hermite(ga, gb, da, db, h, HERMITE_SAMPLES)
    bad = np.nonzero(vals < -tol)[0]
    if bad.size:
        return float(HERMITE_SAMPLES[bad[0]])
    return 1.0 if end_bad else None


def locate_crossing(g_of_t, t_a: float, t_b: float, xtol: float):
    """Brent's method on a bracketing interval; returns the crossing time or None."""
    ga, gb = g_of_t(t_a), g_of_t(t_b)
    if ga == 0.0:
        return t_a
    if np.sign(ga) == np.sign(gb):
        return None
    return brentq(g_of_t, t_a, t_b, xtol=xtol, rtol=4 * np.finfo(float).eps, maxiter=200)


def locate_first_maximum(rate_of_t, t_start: float, dt: float, t_limit: float, xtol: float):
    """First time after ``t_start`` where ``rate_of_t`` turns from positive to negative."""
    t_prev, t = t_start, t_start
    while t < t_limit:
        t = min(t + dt, t_limit)
        if rate_of_t(t) < 0.0:
            return brentq(rate_of_t, t_prev, t, xtol=xtol, rtol=4 * np.finfo(float).eps, maxiter=200)
        t_prev = t
    return None
