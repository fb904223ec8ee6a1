"""Short-term statistics of a response: from a time series and from a spectrum, side by side.

Pure numpy (a bottom-layer module). For a zero-mean stationary Gaussian process with
one-sided spectrum S(omega) and moments m_n = int omega^n S d omega:

* standard deviation sigma = sqrt(m0); significant amplitude 2 sqrt(m0) (the mean of the
  highest third of amplitudes of a narrow-band process, Longuet-Higgins 1952);
* mean zero-up-crossing period T_z = 2 pi sqrt(m0 / m2) (Rice 1944; DNV-RP-C205 eq. 3.5.4.4);
* the peaks are Rayleigh distributed (narrow band), so the most probable largest of
  N = D / T_z peaks in a duration D is sigma sqrt(2 ln N) above the mean (Ochi 1973;
  DNV-RP-C205 sec. 3.5.11.3 "most probable largest": sqrt(2 ln N) for Rayleigh peaks).

The same numbers are estimated from a sampled series: sigma from the samples, T_z from the
counted mean up-crossings, significant amplitude from the highest third of the zero-crossing
cycle half-heights, and the most probable maximum with the counted T_z.
"""

from __future__ import annotations

import itertools
import math

import numpy as np

KEYS = ("max", "min", "mean", "std", "significant_amplitude", "zero_upcrossing_period_s",
        "most_probable_max", "most_probable_min")


def rayleigh_mpm(sigma: float, tz: float, duration: float) -> float:
    """Most probable largest excursion above the mean, sigma sqrt(2 ln(D / T_z)) (Rayleigh peaks).

    Parameters
    ----------
    sigma : float
        Standard deviation of the process (its unit).
    tz : float or None
        Mean zero-up-crossing period (s); None when undefined (no crossing).
    duration : float
        Duration D of the exposure (s).

    Returns
    -------
    float
        The mode of the largest of N = D / T_z Rayleigh peaks (0 when N <= 1).
    """
    if tz is None or not (sigma > 0 and tz > 0 and duration > 0) or not math.isfinite(tz):
        return 0.0
    n = duration / tz
    return sigma * math.sqrt(2.0 * math.log(n)) if n > 1 else 0.0


def upcrossings(y: np.ndarray, level: float) -> np.ndarray:
    """Indices k where y[k] < level <= y[k+1]."""
    y = np.asarray(y, float)
    return np.flatnonzero((y[:-1] < level) & (y[1:] >= level))


def time_domain(t, y, duration: float | None = None) -> dict:
    """Statistics of a sampled series ``y(t)`` (same unit as ``y``; periods in s).

    Parameters
    ----------
    t, y : array_like
        Sample times (s) and values over the statistics window.
    duration : float, optional
        Exposure for the most probable maximum (s); default: the window length.

    Returns
    -------
    dict
        ``max, min, mean, std, significant_amplitude`` (mean of the highest third of the
        cycle half-heights), ``zero_upcrossing_period_s`` (mean time between up-crossings of
        the mean; None without two crossings), ``most_probable_max`` and ``most_probable_min`` (mean +- sigma sqrt(2 ln N)).
    """
    t, y = np.asarray(t, float), np.asarray(y, float)
    mean, std = float(np.mean(y)), float(np.std(y))
    span = float(t[-1] - t[0]) if len(t) > 1 else 0.0
    idx = upcrossings(y, mean) if std > 0 else np.array([], int)
    if len(idx) >= 2:          # between the first and last up-crossing: whole cycles only
        tz = float(t[idx[-1]] - t[idx[0]]) / (len(idx) - 1)
    else:
        tz = span / len(idx) if len(idx) else None      # no crossing: undefined (JSON null)
    halves = [0.5 * (y[a:b + 1].max() - y[a:b + 1].min()) for a, b in itertools.pairwise(idx)]
    if halves:
        h = np.sort(halves)[::-1]
        sig = float(np.mean(h[:max(1, len(h) // 3)]))
    else:
        sig = 0.0
    mpm = rayleigh_mpm(std, tz, duration or span)
    return {"max": float(np.max(y)), "min": float(np.min(y)), "mean": mean, "std": std,
            "significant_amplitude": sig, "zero_upcrossing_period_s": tz,
            "most_probable_max": mean + mpm, "most_probable_min": mean - mpm}


def moment(omega, S, order: int = 0) -> float:
    """m_n = int omega^n S(omega) d omega (trapezoid)."""
    omega, S = np.asarray(omega, float), np.asarray(S, float)
    f = omega**order * S
    return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(omega)))


def frequency_domain(omega, S, duration: float, mean: float = 0.0) -> dict:
    """Statistics of a Gaussian process with one-sided spectrum ``S(omega)`` about ``mean``.

    Parameters
    ----------
    omega : array_like
        Circular frequencies (rad/s), increasing.
    S : array_like
        One-sided spectral density (unit^2 s/rad).
    duration : float
        Exposure D for the most probable extremes (s).
    mean : float
        Mean value (the static value of the response).

    Returns
    -------
    dict
        Same keys as :func:`time_domain`; ``max``/``min`` are the most probable extremes.
    """
    m0, m2 = moment(omega, S, 0), moment(omega, S, 2)
    std = math.sqrt(max(m0, 0.0))
    tz = 2 * math.pi * math.sqrt(m0 / m2) if m2 > 0 else None
    mpm = rayleigh_mpm(std, tz, duration)
    return {"max": mean + mpm, "min": mean - mpm, "mean": mean, "std": std, "significant_amplitude": 2 * std,
            "zero_upcrossing_period_s": tz, "most_probable_max": mean + mpm, "most_probable_min": mean - mpm}


def side_by_side(td: dict | None, fd: dict | None) -> dict:
    """{key: {"time_domain": v, "frequency_domain": v}} for the keys either has."""
    out = {}
    for k in KEYS:
        row = {}
        if td is not None and k in td:
            row["time_domain"] = td[k]
        if fd is not None and k in fd:
            row["frequency_domain"] = fd[k]
        if row:
            out[k] = row
    return out
