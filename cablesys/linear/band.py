"""The frequency band of an RAO: every natural frequency and every forcing frequency, with margin."""

from __future__ import annotations

import math

import numpy as np

from ..scene.sea import user_count


def forcing_frequencies(scene) -> dict:
    """{label: omega (rad/s)} of the scene's forcing: each distinct user sinusoid frequency, and for a
    sea its peak 2 pi / T_p and the ends of its band."""
    out = {}
    top = scene.top_motion
    freqs = sorted({round(s.frequency, 10) for ax in ("x", "y")
                    for s in getattr(top, ax)[:user_count(top, ax)] if s.amplitude != 0.0})
    for w in freqs:
        out[f"forcing {w:.3g} rad/s (T = {2 * math.pi / w:.3g} s)"] = w
    sea = top.spectrum
    if sea is not None:
        lo, hi = sea.band()
        out[f"sea peak {sea.omega_peak:.3g} rad/s (T_p = {sea.tp:.3g} s)"] = sea.omega_peak
        out["sea band low"] = lo
        out["sea band high"] = hi
    return out


def default_band(natural, forcing, *, margin: float = 3.0, n: int = 400, omega_max: float | None = None) -> np.ndarray:
    """Frequencies from min/margin to max x margin over the natural and forcing frequencies;
    logarithmically spaced when that spans a decade or more, else linear.

    Parameters
    ----------
    natural, forcing : iterable of float
        Natural and forcing frequencies (rad/s); non-finite and non-positive ones are ignored.
    margin : float
        Factor below the smallest and above the largest.
    n : int
        Number of frequencies.
    omega_max : float, optional
        Fixed upper end (the lower end is then omega_max / n when no frequency is known).
    """
    ws = [float(w) for w in list(natural) + list(forcing) if np.isfinite(w) and w > 0]
    if not ws:
        hi = omega_max or 10.0
        return np.linspace(hi / n, hi, n)
    lo = min(ws) / margin
    hi = omega_max or max(ws) * margin
    if hi <= lo:
        lo = hi / n
    if hi / lo >= 10.0:
        return np.geomspace(lo, hi, n)
    return np.linspace(lo, hi, n)


RELEVANT_FACTOR = 10.0    # modes above this multiple of the highest forcing frequency are not excited by it


def relevant_modes(natural, forcing, factor: float = RELEVANT_FACTOR) -> list:
    """The natural frequencies (rad/s) a forced response can excite: those up to ``factor`` x the highest forcing
    frequency (all of them without forcing; the lowest always). A segmented cable's element stretch modes lie
    decades above the forcing: they set no band and no plot."""
    ws = sorted(float(w) for w in natural if np.isfinite(w) and w > 0)
    fs = [float(w) for w in forcing if np.isfinite(w) and w > 0]
    if not fs or not ws:
        return ws
    top = factor * max(fs)
    return [w for k, w in enumerate(ws) if k == 0 or w <= top]
