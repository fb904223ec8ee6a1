"""Sea spectra, response spectra, significant amplitudes and the Gaussian slack probability.

One-sided spectra S(omega) in m^2 s/rad over circular frequency omega (rad/s).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.stats import norm

from ..errors import ParameterError, require_finite


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


def spectral_moment(omega, S, order: int = 0) -> float:
    """m_n = int w^n S(w) dw (trapezoid on the given grid)."""
    omega = np.asarray(omega, float)
    return float(np.trapezoid(omega**order * np.asarray(S, float), omega))


def response_spectrum(transfer, S) -> np.ndarray:
    """S_y(w) = |H(w)|^2 S(w) for a transfer H per unit sea amplitude (first axis omega)."""
    H = np.asarray(transfer)
    shape = (-1,) + (1,) * (H.ndim - 1)
    return np.abs(H) ** 2 * np.asarray(S, float).reshape(shape)


def significant_amplitude(omega, S) -> float:
    """2 sqrt(m0): the mean of the highest third of amplitudes of a narrow-band Gaussian
    process (Longuet-Higgins 1952; Hs = 4 sqrt(m0) is the double amplitude).

    Parameters
    ----------
    omega : array_like
        Angular frequencies (rad/s).
    S : array_like
        One-sided spectrum of the quantity on ``omega`` (unit^2 s/rad).

    Returns
    -------
    float
        Significant amplitude (unit of the quantity).
    """
    return 2.0 * math.sqrt(max(spectral_moment(omega, S, 0), 0.0))


def slack_probability(mean_tension: float, std_tension: float, tension_floor: float) -> float:
    """P(T < TENS) for Gaussian tension N(mean, std^2) (Wang 1971 eq. 54 floor; Gaussian assumption).

    Parameters
    ----------
    mean_tension : float
        Mean tension (N).
    std_tension : float
        Standard deviation of the tension (N).
    tension_floor : float
        TENS, the tension below which the cable is slack (N).

    Returns
    -------
    float
        Probability in [0, 1].
    """
    if std_tension <= 0:
        return float(mean_tension < tension_floor)
    return float(norm.cdf((tension_floor - mean_tension) / std_tension))
