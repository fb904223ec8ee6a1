"""Complementary solution of Kennedy & Strahan (1981): eigenfrequencies and damping time (eq. 17-25).

With v(xi=0) = 0 (eq. 17a) the bounded solution ``z^-p J_p(b_o z)`` needs
``b_o a^{1/2} = delta_n``, the zeros of ``J_p`` (eq. 18).  With ``b_o^2 = (4 omega/b^2)(i d - omega)``
(eq. 5) this is the quadratic ``omega^2 - i d omega + delta_n^2 b^2/(4 a) = 0`` whose roots are
(eq. 19-20a, with ``a = beta (1 - D)``, ``D = 2 c_t eps + 2 c_t'``)

    omega_n = (i d/2) [1 -+ (1 - (delta_n/p)^2 / (beta (D - 1)))^{1/2}] .

Only eigenfrequencies that keep the order nearly real are admissible (eq. 8b, tested as
eq. 20b): ``|Im nu| / p = 2 beta |omega_n| / (b p) <= tol``.  For ``beta (D-1) >> 1`` the
slow root is ``omega_n ~ i (eps c_n / 2 pi) (delta_n/p)^2 / (D - 1)`` (eq. 21) and the
damping time is ``tau_0 = 1 / Im omega_1`` (eq. 23); the report takes ``delta_1 ~ p`` and gets
``t_0 = 2 pi (D - 1) d_c / (c_n U)`` (eq. 24-25).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np
import scipy.special as sc
from scipy.optimize import brentq, root

from ..errors import ParameterError, SolverError, require_positive
from ..results import ResultBase, timed
from .bessel import hyp0f1_complex
from .equation import Coefficients, TowedCable

__all__ = [
    "Eigenfrequencies",
    "bessel_zeros",
    "damping_time",
    "eigenfrequencies",
    "exact_eigenfrequency",
    "modes",
]


def bessel_zeros(p: float, n: int) -> np.ndarray:
    """First ``n`` positive zeros of ``J_p`` for real ``p > -1`` (scipy.special.jv + brentq).

    ``scipy.special.jn_zeros`` covers integer orders only.  The first zero lies in
    ``(p, sqrt(2 (p+1)(p+3)))`` (Watson, cited in Kennedy & Strahan (1981) p. 16); later
    zeros are bracketed by sign changes on a grid finer than their spacing (~pi).
    """
    require_positive("p + 1", p + 1.0)
    if n < 1:
        raise ParameterError("n", n, "must be >= 1")
    x_hi = math.sqrt(2.0 * (p + 1.0) * (p + 3.0)) + (n + 1) * math.pi
    x = np.linspace(1e-6, x_hi, int(40 * x_hi) + 10)
    j = sc.jv(p, x)
    idx = np.nonzero(np.sign(j[:-1]) * np.sign(j[1:]) < 0)[0][:n]
    if idx.size < n:
        raise SolverError(f"found only {idx.size} zeros of J_{p:g} below {x_hi:.3g}")
    return np.array([brentq(lambda t: sc.jv(p, t), x[i], x[i + 1], xtol=1e-14) for i in idx])


@dataclass(frozen=True, kw_only=True)
class Eigenfrequencies(ResultBase):
    """Complex nondimensional eigenfrequencies (eq. 20a): ``slow`` (- root) and ``fast`` (+ root).

    ``ratio_*`` = 2 beta |omega| / (b p) is the eq. 8b/20b measure; ``valid_*`` = ratio <= tol.
    """

    delta: np.ndarray
    slow: np.ndarray
    fast: np.ndarray
    ratio_slow: np.ndarray
    ratio_fast: np.ndarray
    valid_slow: np.ndarray
    valid_fast: np.ndarray
    tol: float
    success: bool = True
    message: str = ""
    stats: dict = field(default_factory=dict)

    VARIABLES: ClassVar[dict] = {
        "delta": ("1", "zero of J_p (eq. 19)"), "slow": ("1", "slow eigenfrequency omega L/U (eq. 20a, - root)"),
        "fast": ("1", "fast eigenfrequency omega L/U (eq. 20a, + root)"),
        "ratio_slow": ("1", "eq. 20b measure 2 beta |omega| / (b p), slow"),
        "ratio_fast": ("1", "eq. 20b measure 2 beta |omega| / (b p), fast"), "mode": ("1", "mode number")}

    def summary(self) -> dict:
        """Eigenfrequencies (nondimensional, omega L / U; complex as real/imag) with their eq. 20b test.

        Returns
        -------
        dict
            JSON-able.
        """
        def c(w):
            return {"real": float(w.real), "imag": float(w.imag)}
        return {**super().summary(), "modes": [
            {"delta": float(d), "slow": c(ws), "fast": c(wf), "valid_slow": bool(vs), "valid_fast": bool(vf)}
            for d, ws, wf, vs, vf in zip(self.delta, self.slow, self.fast, self.valid_slow, self.valid_fast)]}

    def to_xarray(self):
        """Eigenfrequencies and validity measures on dimension ``mode`` (complex frequencies kept complex).

        Returns
        -------
        xarray.Dataset
        """
        import xarray as xr
        return xr.Dataset({k: ("mode", getattr(self, k)) for k in ("delta", "slow", "fast", "ratio_slow", "ratio_fast")},
                          coords={"mode": np.arange(1, len(self.delta) + 1)}, attrs={"tol": self.tol})


@timed
def modes(coef: Coefficients, n: int = 5, *, tol: float = 0.1) -> Eigenfrequencies:
    """First ``n`` pairs of natural (complementary) modes' eigenfrequencies, Kennedy & Strahan (1981) eq. 18-20a.

    The towed model's counterpart of :func:`cablesys.modes` and :func:`cablesys.slack.modes`;
    each root carries the eq. 20b test of its validity.

    Parameters
    ----------
    coef : Coefficients
        Nondimensional coefficients of eq. 3 (:meth:`TowedCable.coefficients`).
    n : int, optional
        Number of mode pairs.
    tol : float, optional
        Largest eq. 20b ratio 2 beta |omega| / (b p) for which a root is called valid.

    Returns
    -------
    Eigenfrequencies
        Complex nondimensional eigenfrequencies omega L / U (slow and fast roots).
    """
    require_positive("tol", tol)
    if isinstance(n, bool) or int(n) != n or n < 1:
        raise ParameterError("n", n, "must be an integer >= 1 (number of mode pairs)")
    p = coef.p
    if p <= 0:
        raise ParameterError("p", p, "real order p = c/b - 1 must be > 0 (eq. 8c)")
    delta = bessel_zeros(p, n)
    # omega^2 - i d omega + delta^2 b^2/(4 a) = 0   (eq. 18 with eq. 5)
    disc = np.sqrt(-coef.d**2 - delta**2 * coef.b**2 / coef.a + 0j)
    w1 = 0.5 * (1j * coef.d - disc)
    w2 = 0.5 * (1j * coef.d + disc)
    slow, fast = (w1, w2) if abs(w1[0]) <= abs(w2[0]) else (w2, w1)
    rs = 2.0 * coef.beta * np.abs(slow) / (coef.b * p)
    rf = 2.0 * coef.beta * np.abs(fast) / (coef.b * p)
    return Eigenfrequencies(delta=delta, slow=slow, fast=fast, ratio_slow=rs, ratio_fast=rf,
                            valid_slow=rs <= tol, valid_fast=rf <= tol, tol=tol)


def eigenfrequencies(coef: Coefficients, n: int = 5, *, tol: float = 0.1) -> Eigenfrequencies:
    """Deprecated name of :func:`modes` (the verb the three models share).

    Parameters
    ----------
    coef : Coefficients
        Nondimensional coefficients of eq. 3.
    n : int, optional
        Number of mode pairs.
    tol : float, optional
        Largest eq. 20b ratio for a valid root.

    Returns
    -------
    Eigenfrequencies
        As :func:`modes`.
    """
    warnings.warn("cablesys.towed.eigenfrequencies is deprecated: use cablesys.towed.modes", DeprecationWarning,
                  stacklevel=2)
    return modes(coef, n, tol=tol)


def damping_time(cable: TowedCable, *, zero: str = "report") -> float:
    """Damping time t_0 (s) of the slowest mode (Kennedy & Strahan (1981) eq. 23-25).

    ``zero="report"``: the report's ``delta_1 ~ p`` and eq. 25, ``2 pi (D-1) d_c / (c_n U)``;
    ``zero="bessel"``: the true first zero of ``J_p`` in the eq. 19 root;
    ``zero="exact"``: the complex-order eigenfrequency (:func:`exact_eigenfrequency`).

    Parameters
    ----------
    cable : TowedCable
        The towed cable (SI).
    zero : str, optional
        'report', 'bessel' or 'exact' (see above).

    Returns
    -------
    float
        t_0 (s).
    """
    coef = cable.coefficients()
    if zero == "report":
        return 2.0 * math.pi * (cable.drag_term - 1.0) * cable.diameter / (cable.c_n * cable.speed)
    if zero == "bessel":
        w = modes(coef, 1).slow[0]
    elif zero == "exact":
        w = exact_eigenfrequency(coef, 1)
    else:
        raise ParameterError("zero", zero, "must be 'report', 'bessel' or 'exact'")
    if w.imag <= 0:
        raise SolverError(f"slowest mode omega = {w} is not damped")
    return cable.time_scale() / w.imag          # eq. 23, tau = U t / L


def exact_eigenfrequency(coef: Coefficients, n: int = 1) -> complex:
    """Slow eigenfrequency with the exact complex order: ``0F1(; q(omega); x(0, omega)) = 0``.

    Newton-type root (scipy.optimize.root) started from the real-order eq. 19 value.

    Parameters
    ----------
    coef : Coefficients
        Nondimensional coefficients of eq. 3 (:meth:`TowedCable.coefficients`).
    n : int, optional
        Mode number (1 = slowest).

    Returns
    -------
    complex
        Nondimensional eigenfrequency omega L / U (Im > 0: damped).
    """
    w0 = modes(coef, n).slow[n - 1]

    def g(w):
        q = (coef.c + 2j * coef.beta * w) / coef.b
        x0 = (w**2 - 1j * w * coef.d) * coef.a / coef.b**2
        F, _, _ = hyp0f1_complex(q, x0)
        return complex(F)

    scale = abs(g(complex(0.5 * w0))) or 1.0

    def fun(u):
        val = g(complex(u[0], u[1])) / scale
        return [val.real, val.imag]

    sol = root(fun, [w0.real, w0.imag], method="hybr", options={"xtol": 1e-12})
    if not sol.success:
        raise SolverError(f"exact eigenfrequency search failed near {w0}: {sol.message}")
    return complex(sol.x[0], sol.x[1])
