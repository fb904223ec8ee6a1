"""Horizontal-vertical force interaction (Kennedy & Strahan (1981) eq. 28-39 and Appendix B).

A cable at horizontal angle ``theta`` to the flow and steady depression ``phi`` has unit
tangent ``(sin th cos ph, cos th cos ph, sin ph)`` (eq. 28); the normal relative flow
``U_N = U - (U.c) c`` has ``|U_N|^2 = U^2 (1 - cos^2 th cos^2 ph)`` (eq. 32), and the
quadratic normal force ``R |U_N/U|^2 n`` (eq. 33-35, ``R = (rho/2) c_n d_c U^2``) has the
cross-track component (eq. 36)

    (F_N)_x = -R cos th cos^2 ph sin th (1 - cos^2 th cos^2 ph)^{1/2},

against ``-R cos th sin^2 th`` for a level cable (eq. 37).  Their ratio is the amplification
(eq. 38) ``A = cos^2 ph (1 - cos^2 th cos^2 ph)^{1/2} / sin th``, used as ``c_n* = A c_n`` (eq. 39).

A is singular at ``theta = 0`` only because the force changes from ``theta^2`` to ``theta``
dependence.  Appendix B averages ``|F_x|`` over a zero-mean Gaussian ``theta`` of rms
``sigma`` (eq. B-3, B-4); at small angles (B-2) this gives (eq. B-5)

    A_eff = sqrt(2/pi) cos^2 ph sin ph / sigma .
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import quad

from ..errors import ParameterError, require_positive, require_range

__all__ = ["amplification", "normal_force_x", "effective_amplification",
           "effective_amplification_exact", "rms_angle_for"]


def _angles(theta, phi):
    theta = np.asarray(theta, dtype=float)
    phi = np.asarray(phi, dtype=float)
    if np.any(~np.isfinite(theta)) or np.any(theta <= 0) or np.any(theta > math.pi / 2):
        raise ParameterError("theta", theta, "must be in (0, pi/2] rad")
    if np.any(~np.isfinite(phi)) or np.any(phi < 0) or np.any(phi >= math.pi / 2):
        raise ParameterError("phi", phi, "must be in [0, pi/2) rad")
    return theta, phi


def normal_force_x(theta, phi):
    """Cross-track normal force per R, ``(F_N)_x / R`` (Kennedy & Strahan (1981) eq. 36)."""
    theta = np.asarray(theta, dtype=float)
    phi = np.asarray(phi, dtype=float)
    c2 = np.cos(theta) ** 2 * np.cos(phi) ** 2
    return -np.cos(theta) * np.cos(phi) ** 2 * np.sin(theta) * np.sqrt(1.0 - c2)


def amplification(theta, phi):
    """``A(theta, phi)`` of Kennedy & Strahan (1981) eq. 38 (angles in rad).

    Parameters
    ----------
    theta : array_like
        Horizontal angle of the cable to the flow (rad), 0 < theta <= pi/2.
    phi : array_like
        Steady depression angle (rad), 0 <= phi < pi/2.

    Returns
    -------
    ndarray
        A (1): the cross-track normal force of the inclined cable over that of a level cable
        (eq. 36 / eq. 37), so that c_n* = A c_n (eq. 39).
    """
    theta, phi = _angles(theta, phi)
    return np.cos(phi) ** 2 * np.sqrt(1.0 - np.cos(theta) ** 2 * np.cos(phi) ** 2) / np.sin(theta)


def effective_amplification(sigma, phi):
    """Small-angle Gaussian average ``sqrt(2/pi) cos^2 phi sin phi / sigma`` (eq. B-5).

    Parameters
    ----------
    sigma : array_like
        RMS horizontal angle (rad), > 0.
    phi : array_like
        Depression angle (rad).

    Returns
    -------
    ndarray
        A_eff (1), the Gaussian-averaged amplification of eq. B-5.
    """
    sigma = np.asarray(sigma, dtype=float)
    if np.any(~np.isfinite(sigma)) or np.any(sigma <= 0):
        raise ParameterError("sigma", sigma, "rms horizontal angle must be > 0 (rad)")
    _, phi = _angles(np.full_like(sigma, 0.1), phi)
    return math.sqrt(2.0 / math.pi) * np.cos(phi) ** 2 * np.sin(phi) / sigma


def effective_amplification_exact(sigma: float, phi: float) -> float:
    """``E|F_x(theta, phi)| / E|F_x(theta, 0)|`` for ``theta ~ N(0, sigma^2)`` (eq. B-3, B-4),
    with the full eq. 36 force (no small-angle step), by scipy.integrate.quad."""
    sigma = require_positive("sigma", sigma, "rad")
    phi = require_range("phi", phi, 0.0, math.pi / 2, "rad", hi_open=True)
    top = min(10.0 * sigma, math.pi / 2)

    def mean_abs(ph):
        val, _ = quad(lambda t: abs(normal_force_x(t, ph)) * math.exp(-0.5 * (t / sigma) ** 2),
                      0.0, top, limit=200, epsabs=0.0, epsrel=1e-10)
        return val

    return mean_abs(phi) / mean_abs(0.0)


def rms_angle_for(A: float, phi: float) -> float:
    """rms horizontal angle sigma (rad) giving effective amplification ``A`` by eq. B-5."""
    A = require_positive("A", A)
    phi = require_range("phi", phi, 0.0, math.pi / 2, "rad", lo_open=True, hi_open=True)
    return math.sqrt(2.0 / math.pi) * math.cos(phi) ** 2 * math.sin(phi) / A
