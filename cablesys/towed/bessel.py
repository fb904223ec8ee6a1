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

Why hand-written numerics: ``scipy.special.hyp0f1`` and ``scipy.special.jv`` take only a
real order/parameter, and ``mpmath.hyp0f1`` (exact, arbitrary precision) costs ~0.5 ms a
point, i.e. ~20 s for a 200 x 200 grid.  Here, vectorized over the whole grid in complex128:

1. the 0F1 power series (DLMF 16.2.1), with the cancellation it suffers measured term by
   term (``eps * sum|t_k| / |sum t_k|``);
2. where that loses more than ``tol`` (large ``|x|``): ``0F1(; q; x) = Gamma(q) x^((1-q)/2)
   I_{q-1}(2 sqrt x)`` (DLMF 10.39.9) with Hankel's large-argument expansion of ``I_nu``
   (DLMF 10.40.1), valid for complex order; used only where ``Re 2 sqrt x >= 12`` (the
   dropped ``exp(-z)`` branch is below 1e-10 relative) and the expansion has converged;
3. anything left is recomputed with ``mpmath.hyp0f1``,

so the result is exact to ``tol`` everywhere (tests compare with mpmath).
"""

from __future__ import annotations

import logging

import numpy as np
import scipy.special as sc

from ..errors import SolverError
from .equation import Coefficients

__all__ = ["hyp0f1_complex", "hyp0f1_exact", "exact_solution", "real_order_solution", "mpmath_solution",
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


def _hankel_sum(nu, z, max_terms: int = 60):
    """``sum_k (-1)^k a_k(nu) / z^k`` of DLMF 10.40.1 and a converged flag (vectorized)."""
    mu = 4.0 * nu**2
    term = np.ones_like(z)
    S = term.copy()
    ok = np.zeros(z.shape, dtype=bool)
    prev = np.full(z.shape, np.inf)
    for k in range(1, max_terms):
        term = -term * (mu - (2 * k - 1) ** 2) / (k * 8.0 * z)
        at = np.abs(term)
        grow = at > prev
        live = ~ok & ~grow
        S = np.where(live, S + term, S)
        ok |= live & (at < 1e-16 * np.abs(S))
        prev = np.where(live, at, 0.0)  # a growing term freezes the point (not converged)
        if np.all(ok | grow | (prev == 0.0)):
            break
    return S, ok


def _hyp0f1_asymptotic(q, x):
    """``ln 0F1(; q; x)``, ``0F1(; q+1; x) / 0F1(; q; x)`` and a validity flag, large ``|x|``.

    0F1(; q; x) = Gamma(q) x^((1-q)/2) I_{q-1}(2 sqrt x)   (DLMF 10.39.9), and
    I_nu(z) ~ e^z (2 pi z)^(-1/2) sum_k (-1)^k a_k(nu) / z^k   (DLMF 10.40.1);
    principal branches of sqrt and log keep the product on the entire function.
    """
    z = 2.0 * np.sqrt(x)
    S0, ok0 = _hankel_sum(q - 1.0, z)
    S1, ok1 = _hankel_sum(q, z)
    lnF = (sc.loggamma(q) + 0.5 * (1.0 - q) * np.log(x) + z - 0.5 * np.log(2 * np.pi * z)
           + np.log(S0))
    # 0F1(q+1)/0F1(q) = q x^(-1/2) I_q(z) / I_{q-1}(z)
    ratio = q / np.sqrt(x) * S1 / S0
    ok = ok0 & ok1 & (z.real >= 12.0)
    return lnF, ratio, ok


def hyp0f1_exact(q, x, *, tol: float = 1e-9):
    """``0F1(; q; x)`` and its x-derivative to relative ``tol``: series, asymptotic, mpmath."""
    q, x = np.broadcast_arrays(np.asarray(q, dtype=complex), np.asarray(x, dtype=complex))
    shape = x.shape
    q, x = q.ravel(), x.ravel()        # 1-D work arrays: a scalar point indexes like any other
    F, dF, err = (np.array(a) for a in hyp0f1_complex(q, x))
    bad = (err > tol) | ~np.isfinite(F) | ~np.isfinite(dF)
    if np.any(bad):
        lnF, ratio, ok = _hyp0f1_asymptotic(q[bad], x[bad])
        with np.errstate(over="ignore", invalid="ignore"):
            Fa = np.exp(lnF)
        ok &= np.isfinite(Fa)
        idx = np.flatnonzero(bad)
        F[idx[ok]] = Fa[ok]
        dF[idx[ok]] = (Fa * ratio / q[bad])[ok]
        rest = idx[~ok]
        if rest.size:
            log.info("0F1: %d of %d points neither series nor asymptotic to %g; mpmath",
                     len(rest), bad.size, tol)
        for i in rest:
            F[i], dF[i] = _mp_hyp0f1(q[i], x[i])
    return F.reshape(shape), dF.reshape(shape)


def exact_solution(coef: Coefficients, xi, omega, *, tol: float = 1e-9, derivative: bool = False):
    """Exact complex-order particular solution v(xi; omega), v(0) = 1 (eq. 8a, 6b).

    ``xi`` and ``omega`` broadcast against each other; returns ``v`` (and ``dv/dxi``
    if ``derivative``), accurate to ``tol`` relative (see :func:`hyp0f1_exact`).
    """
    xi = np.asarray(xi, dtype=float)
    omega = np.asarray(omega, dtype=float)
    xi_b, om_b = np.broadcast_arrays(xi, omega)
    # the tow-point normalization depends on omega only: evaluate it once per omega
    F0, _ = hyp0f1_exact(coef.q(omega), coef.x_arg(0.0, omega), tol=tol)
    F, dF = hyp0f1_exact(coef.q(om_b), coef.x_arg(xi_b, om_b), tol=tol)
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

