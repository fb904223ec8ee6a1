"""Sea elevation spectra (a description of the sea state, so part of the scene layer; numpy only).

One-sided spectra S(omega) in m^2 s/rad over circular frequency omega (rad/s).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ParameterError, require_finite

__all__ = ["jonswap", "pierson_moskowitz"]


def _check(hs: float, tp: float) -> tuple[float, float]:
    for name, v in (("spectrum.hs", hs), ("spectrum.tp", tp)):
        require_finite(name, v)
        if v <= 0:
            raise ParameterError(name, v, "must be > 0 (significant wave height in m, peak period in s)")
    return float(hs), float(tp)


def _check_omega(omega) -> np.ndarray:
    omega = np.atleast_1d(np.asarray(omega, float))
    if np.any(~np.isfinite(omega)) or np.any(omega <= 0):
        raise ParameterError("omega", f"min {np.min(omega)!r}", "spectral frequencies must be finite and > 0 rad/s")
    return omega


def pierson_moskowitz(omega, hs: float, tp: float) -> np.ndarray:
    """S(w) = 5/16 Hs^2 wp^4 w^-5 exp(-5/4 (wp/w)^4), wp = 2 pi / Tp (Pierson & Moskowitz 1964;
    DNV-RP-C205 eq. 3.5.5.1, written with Hs and Tp).

    Parameters
    ----------
    omega : array_like
        Angular frequencies (rad/s), > 0.
    hs : float
        Significant wave height H_s (m).
    tp : float
        Peak period T_p (s).

    Returns
    -------
    ndarray
        S(omega), one-sided (m^2 s/rad); its zeroth moment is H_s^2 / 16.
    """
    hs, tp = _check(hs, tp)
    w = _check_omega(omega)
    wp = 2 * math.pi / tp
    return 5.0 / 16.0 * hs**2 * wp**4 * w**-5 * np.exp(-1.25 * (wp / w) ** 4)


def jonswap(omega, hs: float, tp: float, gamma: float = 3.3) -> np.ndarray:
    """JONSWAP: A_gamma S_PM(w) gamma^exp(-(w - wp)^2 / (2 s^2 wp^2)), s = 0.07 (w <= wp) or 0.09,
    A_gamma = 1 - 0.287 ln gamma (Hasselmann et al. 1973; normalization of DNV-RP-C205 eq. 3.5.5.2-5).

    Parameters
    ----------
    omega : array_like
        Angular frequencies (rad/s), > 0.
    hs : float
        Significant wave height H_s (m).
    tp : float
        Peak period T_p (s).
    gamma : float, optional
        Peak enhancement factor (1 gives Pierson-Moskowitz).

    Returns
    -------
    ndarray
        S(omega), one-sided (m^2 s/rad).
    """
    hs, tp = _check(hs, tp)
    require_finite("spectrum.gamma", gamma)
    if not 1.0 <= gamma <= 7.0:
        raise ParameterError("spectrum.gamma", gamma, "peak-enhancement factor must be in [1, 7] (1 gives Pierson-Moskowitz)")
    w = _check_omega(omega)
    wp = 2 * math.pi / tp
    s = np.where(w <= wp, 0.07, 0.09)
    peak = gamma ** np.exp(-0.5 * ((w - wp) / (s * wp)) ** 2)
    return (1.0 - 0.287 * math.log(gamma)) * pierson_moskowitz(w, hs, tp) * peak
