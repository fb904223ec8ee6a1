"""Locating taut/slack switches and snap loads (Wang 1971 eq. 54: F_bc may not fall below TENS).

We do not rely on CasADi's experimental zero-crossing events (in CasADi 3.6-3.8 IDAS ignores
them and CVODES fires in one direction only). Instead the simulator integrates each
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

from ..results import SnapLoad
from .failures import ode_jacobian

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


class EventLocator:
    """Switch and snap-load location for :class:`~cablesys.time_domain.run.Simulator` (a mixin).

    Uses the simulator's ``_advance``, ``_call``, ``_dense``, ``_gap_and_rate``, ``_gap_rates``
    and ``model``.
    """

    DENSE = 32     # points of the dense grid used to bracket a switch inside one interval

    def _dense_states(self, x, t_a, h, pm):
        """States at t_a + h * (0, 1/DENSE, ..., 1) from one integrator call."""
        Xd = np.array(self._call(self._dense, x0=x, p=np.concatenate([pm, [t_a, h]]))["xf"])
        if not np.all(np.isfinite(Xd)):
            raise FloatingPointError("nonfinite")
        return np.column_stack([x, Xd]), t_a + h * np.linspace(0.0, 1.0, self.DENSE + 1)

    def _rates_at(self, X, T, pm):
        G = self._gap_rates(X, T[None, :], np.tile(pm[:, None], (1, T.size)))   # CasADi maps over columns
        return [np.array(v) for v in G]

    def _refine(self, X, T, j, pm, i, which: int):
        """Root of derivative ``which`` (0: g, 1: dg/dt) of section i in [T[j-1], T[j]]."""
        x0, t0 = X[:, j - 1], T[j - 1]

        def fun(t):
            xt = self._advance(x0, t0, t - t0, pm) if t > t0 else x0
            vals = self._gap_rates(xt, t, pm)
            return float(np.array(vals[which])[i, 0]), float(np.array(vals[which + 1])[i, 0])
        G = self._rates_at(X[:, j - 1:j + 1], T[j - 1:j + 1], pm)
        return newton_bracketed(fun, T[j - 1], T[j], G[which][i, 0], G[which][i, 1],
                                   1e-13 * max(1.0, abs(T[j])))

    def _first_event(self, xa, t_a, xb, t_b, pm, mode):
        """Earliest located switch in (t_a, t_b] as (time, section), or None."""
        G, D, _ = self._rates_at(np.column_stack([xa, xb]), np.array([t_a, t_b]), pm)
        suspects = [i for i in range(len(mode))
                    if first_bad_interval(G[i:i + 1], D[i:i + 1], [t_b - t_a], mode[i:i + 1] == 1.0) is not None]
        if not suspects:
            return None
        X, T = self._dense_states(xa, t_a, t_b - t_a, pm)
        G, D, _ = self._rates_at(X, T, pm)
        found = [(t, i) for i in suspects if (t := self._locate(X, T, G, D, pm, mode, i)) is not None]
        return min(found) if found else None

    def _locate(self, X, T, G, D, pm, mode, i):
        """First crossing of section i on the dense grid (X, T), refined; None if there is none."""
        slack = mode[i:i + 1] == 1.0
        sign = -1.0 if slack[0] else 1.0
        lo = 0                                   # search intervals (T[lo], T[lo+1]], ...
        while lo < T.size - 1:
            j = first_bad_interval(G[i:i + 1, lo:], D[i:i + 1, lo:], np.diff(T[lo:]), slack)
            if j is None:
                return None
            j += lo
            if sign * G[i, j] < -1e-12 * max(1.0, abs(G[i, j - 1]), abs(G[i, j])):
                return self._refine(X, T, j, pm, i, 0)          # bracketed by the dense points
            if T[j] - T[j - 1] > 1e-9 * max(1.0, abs(T[j])):   # a dip between dense points: look closer
                sub = self._first_event(X[:, j - 1], T[j - 1], X[:, j], T[j], pm, mode)
                if sub is not None and sub[1] == i:
                    return sub[0]
            lo = j
        return None

    def _snap(self, x, t_star, pm, i_sec, t_end):
        """First tension maximum after section ``i_sec`` went taut at ``t_star`` (dg/dt = 0, d2g/dt2 < 0)."""
        J = np.array(ode_jacobian(self.model)(x, t_star, pm))
        iu = self.model.q_labels.index(self.model.label("u", i_sec))
        w2 = max(-J[self.model.nq + iu, iu], 1e-12)
        window = min(t_end - t_star, 2.0 * np.pi / np.sqrt(w2))      # within one stretch period
        if window <= 0:
            return None
        try:
            X, T = self._dense_states(x, t_star, window, pm)
            _, D, _ = self._rates_at(X, T, pm)
            j = next((j for j in range(1, T.size) if D[i_sec, j - 1] > 0 >= D[i_sec, j]), None)
            if j is None:
                return None
            t_pk = self._refine(X, T, j, pm, i_sec, 1)
            x_pk = self._advance(X[:, j - 1], T[j - 1], t_pk - T[j - 1], pm) if t_pk > T[j - 1] else X[:, j - 1]
        except (RuntimeError, FloatingPointError):
            return None
        g = float(np.array(self._gap_and_rate(x_pk, t_pk, pm)[0])[i_sec, 0])
        tens = pm[self.model.layout.section_index(i_sec, "cable.tension_floor")]
        return SnapLoad(time=float(t_pk), section=i_sec, tension=g + float(tens))
