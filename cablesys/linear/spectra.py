"""Response spectra, significant amplitudes and the Gaussian slack probability.

One-sided spectra S(omega) in m^2 s/rad over circular frequency omega (rad/s); the sea
spectra themselves (``jonswap``, ``pierson_moskowitz``) live in :mod:`cablesys.scene.spectra`.
"""

from __future__ import annotations

import math

import numpy as np

from .. import statistics as st
from ..scene.spectra import jonswap, pierson_moskowitz

__all__ = ["jonswap", "pierson_moskowitz", "response_spectrum", "significant_amplitude", "slack_probability",
           "spectral_moment"]


def spectral_moment(omega, S, order: int = 0) -> float:
    """m_n = int w^n S(w) dw (trapezoid on the given grid): :func:`cablesys.statistics.moment`."""
    return st.moment(omega, S, order)


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
    return st.significant_amplitude(math.sqrt(max(spectral_moment(omega, S, 0), 0.0)))


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
    return st.gaussian_probability_below(tension_floor, mean_tension, std_tension)
