r"""Particular solutions of Kennedy & Strahan (1981) eq. 5-16: real order and exact complex order.

The bounded solution of eq. 5 is ``v = z^nu J_{-nu}(b_o z)`` (eq. 8a with A = 0, p. 10),
regular at the zero-tension point ``z = 0``.  Written in ``s = z^2 = a + b xi`` it is
an entire function of ``s`` (no branch cuts):

    z^nu J_{-nu}(b_o z) = (b_o/2)^{-nu} / Gamma(1-nu) * 0F1(; q; x),
    q = 1 - nu = (c + 2 i beta omega)/b,   x = -b_o^2 s/4 = (omega^2 - i omega d) s / b^2,

so with the tow-point condition v(xi=0) = 1 (eq. 6b, 15)

    v(xi) = 0F1(; q; x(xi)) / 0F1(; q; x(0))                    (exact, complex order)
    v(xi) = (z/a^{1/2})^{-p} J_p(b_o z) / J_p(b_o a^{1/2})      (eq. 16, real order p = c/b - 1)

The real-order form is the exact one with ``q`` replaced by its real part ``c/b = 1 + p``
(the eq. 8b approximation).

Why a hand-written series: ``scipy.special.hyp0f1`` and ``scipy.special.jv`` take only a
real order/parameter, and ``mpmath.hyp0f1`` (exact, arbitrary precision) costs ~150 us a
point, i.e. ~6 s for a 200 x 200 grid.  The 0F1 power series is summed here vectorized
over the whole grid in complex128 with the cancellation it suffers measured term by term
(``sum |t_k| / |sum t_k|``); points whose estimated relative error exceeds ``tol`` are
recomputed with ``mpmath.hyp0f1``, so the result is exact to ``tol`` everywhere.
"""

from __future__ import annotations

import logging
import math

import numpy as np
import scipy.special as sc

from ..errors import SolverError
from .equation import Coefficients

__all__ = ["hyp0f1_complex", "exact_solution", "real_order_solution", "mpmath_solution",
           "ode_residual"]

log = logging.getLogger(__name__)

_EPS = np.finfo(float).eps


def hyp0f1_complex(q, x, *, max_terms: int = 5000):
    """Vectorized ``0F1(; q; x)`` and ``d/dx 0F1(; q; x)`` for complex ``q`` and ``x``.

    Power series ``sum_k x^k / ((q)_k k!)`` (DLMF 16.2.1), derivative
    ``sum_k x^k / ((q)_{k+1} k!)`` (DLMF 16.3.1).  Returns ``(F, dF, relerr)`` with
    ``relerr = eps * sum|t_k| / |F|`` the rounding-error estimate from cancellation.
    """
    q = np.asarray(q, dtype=complex)
    x = np.asarray(x, dtype=complex)
    q, x = np.broadcast_arrays(q, x)
    if np.any((q.real <= 0) & (np.abs(q.imag) < 1e-12) & (np.abs(q.real - np.round(q.real)) < 1e-12)):
        raise SolverError("0F1(; q; x) undefined for q = 0, -1, -2, ...")
    t = np.ones_like(x)
    F = t.copy()
    dF = t / q
    abssum = np.ones(x.shape)
    ax = np.abs(x)
    k_min = int(np.ceil(np.sqrt(ax.max()))) + 2 if ax.size else 0
    for k in range(max_terms):
        t = t * x / ((q + k) * (k + 1))
        F += t
        dF += t / (q + k + 1)
        at = np.abs(t)
        abssum += at
        if k >= k_min and np.all(at <= _EPS * 1e-2 * abssum):
            break
    else:
        raise SolverError(f"0F1 series did not converge in {max_terms} terms (max |x| = {ax.max():.3g})")
    with np.errstate(divide="ignore", invalid="ignore"):
        relerr = _EPS * abssum / np.abs(F)
    return F, dF, relerr


def _mp_hyp0f1(q, x, dps: int = 30, derivative: bool = True):
    import mpmath  # optional: exact fallback and benchmark baseline

    with mpmath.workdps(dps):
        f = complex(mpmath.hyp0f1(complex(q), complex(x)))
        if not derivative:
            return f, None
        return f, complex(mpmath.hyp0f1(complex(q) + 1, complex(x))) / complex(q)


def exact_solution(coef: Coefficients, xi, omega, *, tol: float = 1e-9, derivative: bool = False):
    """Exact complex-order particular solution v(xi; omega), v(0) = 1 (eq. 8a, 6b).

    ``xi`` and ``omega`` broadcast against each other; returns ``v`` (and ``dv/dxi``
    if ``derivative``).  Points where the series loses more than ``tol`` are
    recomputed with mpmath.
    """
    xi = np.asarray(xi, dtype=float)
    omega = np.asarray(omega, dtype=float)
    xi_b, om_b = np.broadcast_arrays(xi, omega)
    q = coef.q(om_b)
    x = coef.x_arg(xi_b, om_b)
    # the tow-point normalization depends on omega only: sum it once per omega
    F0, _, err0 = hyp0f1_complex(coef.q(omega), coef.x_arg(0.0, omega))
    F0 = np.broadcast_to(F0, xi_b.shape).copy()
    err0 = np.broadcast_to(err0, xi_b.shape)
    x0 = coef.x_arg(np.zeros_like(xi_b), om_b)
    F, dF, err = (np.array(a) for a in hyp0f1_complex(q, x))   # 0-d arrays stay assignable
    bad = (err > tol) | (err0 > tol) | ~np.isfinite(F) | ~np.isfinite(F0)
    if np.any(bad):
        n = int(bad.sum())
        log.info("0F1 series: %d of %d points lose > %g, recomputed with mpmath", n, bad.size, tol)
        for idx in map(tuple, np.argwhere(bad)):
            F[idx], dF[idx] = _mp_hyp0f1(q[idx], x[idx])
            F0[idx], _ = _mp_hyp0f1(q[idx], x0[idx])
    v = F / F0
    if not derivative:
        return v
    dxdxi = (om_b**2 - 1j * om_b * coef.d) / coef.b
    return v, dF * dxdxi / F0


def real_order_solution(coef: Coefficients, xi, omega, *, derivative: bool = False):
    """Report's real-order solution, Kennedy & Strahan (1981) eq. 16 (order p = c/b - 1).

    Evaluated as ``w^{-p} J_p(w)`` with ``w = b_o z`` (eq. 5, 11a) via
    ``scipy.special.jv``; principal branches of ``w^{-p}`` and ``J_p(w)`` cancel, so
    the result is the entire function ``0F1(; 1+p; -w^2/4)`` up to a constant.
    """
    xi = np.asarray(xi, dtype=float)
    omega = np.asarray(omega, dtype=float)
    xi_b, om_b = np.broadcast_arrays(xi, omega)
    p = coef.p
    bo = np.sqrt(4.0 * om_b * (1j * coef.d - om_b) / coef.b**2 + 0j)     # eq. 5
    z = np.sqrt(coef.a + coef.b * xi_b + 0j)
    z0 = np.sqrt(coef.a + 0j)
    w, w0 = bo * z, bo * z0

    def g(w_, order):
        # w^-order J_order(w); the w -> 0 limit is 2^-order / Gamma(order + 1)
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            val = w_ ** (-order) * sc.jv(order, w_)
        small = np.abs(w_) < 1e-8
        return np.where(small, 2.0 ** (-order) / sc.gamma(order + 1.0), val)

    g0 = g(w0, p)
    v = g(w, p) / g0
    if not derivative:
        return v
    # d/dw [w^-p J_p(w)] = -w^-p J_{p+1}(w) (DLMF 10.6.6); dw/dxi = bo * b / (2 z)
    # combined: d/dxi = -(bo^2 b / 2) w^-(p+1) J_{p+1}(w)
    dv = -(bo**2 * coef.b / 2.0) * g(w, p + 1.0) / g0
    return v, dv


def mpmath_solution(coef: Coefficients, xi, omega, *, dps: int = 20):
    """Exact solution point by point with ``mpmath.hyp0f1`` (slow reference/baseline)."""
    xi = np.asarray(xi, dtype=float)
    omega = np.asarray(omega, dtype=float)
    xi_b, om_b = np.broadcast_arrays(xi, omega)
    out = np.empty(xi_b.shape, dtype=complex)
    f0 = {}
    for idx in np.ndindex(xi_b.shape):
        w = float(om_b[idx])
        q = complex(coef.q(w))
        if w not in f0:
            f0[w], _ = _mp_hyp0f1(q, complex(coef.x_arg(0.0, w)), dps, derivative=False)
        f, _ = _mp_hyp0f1(q, complex(coef.x_arg(xi_b[idx], w)), dps, derivative=False)
        out[idx] = f / f0[w]
    return out


def ode_residual(coef: Coefficients, xi, omega, v, dv, d2v):
    """Residual of the eq. 4 ODE, ``(a+b xi) v'' + (c + 2 i beta omega) v' + (i omega d - omega^2) v``."""
    xi = np.asarray(xi, dtype=float)
    return ((coef.a + coef.b * xi) * d2v + (coef.c + 2j * coef.beta * omega) * dv
            + (1j * omega * coef.d - omega**2) * v)

