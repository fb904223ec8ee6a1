"""Short-term statistics of a response, each defined once: from a time series and from a spectrum.

Pure numpy (a bottom-layer module). For a zero-mean stationary Gaussian process with one-sided
spectrum S(omega) and moments m_n = int omega^n S d omega:

* standard deviation sigma = sqrt(m0) (of a series: the population standard deviation of the samples);
* significant amplitude A_s = 2 sigma: the mean of the highest third of the amplitudes of a narrow-band
  Gaussian process, whose amplitudes are Rayleigh distributed (Longuet-Higgins 1952; H_s = 4 sqrt(m0) is the
  double amplitude, Bai & Jin, Marine Structural Design, sec. 2.2.5). It is 2 sigma for every signal, so the time and frequency
  domain agree by construction; a sinusoid of amplitude A has A_s = sqrt(2) A, and its amplitude
  (half the peak-to-peak) is :func:`half_range`;
* mean zero-up-crossing period T_z = 2 pi sqrt(m0 / m2) (Rice 1944; DNV-RP-C205 eq. 3.5.4.4); of a series, the
  mean time between the located up-crossings of its mean, undefined (None, with the reason) for a series that
  does not vary above its resolution or crosses its mean fewer than twice;
* most probable largest excursion above the mean over an exposure D: the mode of the largest of N = D / T_z
  Rayleigh peaks, sigma sqrt(2 ln N) (Ochi 1973; DNV-RP-C205 sec. 3.5.11.3), 0 when N <= 1;
* max / min: the sampled extremes of the window; they bound each other (max >= min) and bound the most probable
  extremes only when an exposure says so (the verdict takes the larger);
* settled: the amplitude (half peak-to-peak) of the first and second half of a window differ by no more than a
  relative tolerance or an absolute floor in the quantity's unit (:data:`FLOORS`), so a constant response
  (amplitude 0) is settled.

Tensions (``nonnegative=True``): a rope carries no compression, so no tension statistic is below 0 N. A series
that falls below 0 is reported at 0 with the time it spent there (``slack_time_s``), and a Gaussian most
probable minimum below 0 is reported as 0 with the Gaussian probability of a slack instant
P(T < 0) = Phi(-mean / sigma) (``slack_probability``) and a ``note``.
"""

from __future__ import annotations

import math

import numpy as np

KEYS = ("max", "min", "mean", "std", "amplitude", "significant_amplitude", "zero_upcrossing_period_s",
        "most_probable_max", "most_probable_min")

# resolution of a response in its SI unit: variations below it are numerical noise, not a response
FLOORS = {"m": 1e-6, "m/s": 1e-6, "rad": 1e-6, "rad/s": 1e-6, "N": 1e-3, "N/s": 1e-3, "1": 1e-9}
ROUNDOFF = 1e-9        # relative resolution of any series: variations below ROUNDOFF x max|y| are round-off


def resolution(y, floor: float = 0.0) -> float:
    """The smallest variation of ``y`` taken as a response: max(floor, ROUNDOFF x max|y|) (unit of ``y``)."""
    y = np.asarray(y, float)
    return max(float(floor), ROUNDOFF * float(np.max(np.abs(y))) if y.size else 0.0)


WINDOW_PERIODS = 5     # forcing periods in the statistics window of a settled periodic response


def window(time, period: float | None = None, ramp_s: float = 0.0, n_periods: int = WINDOW_PERIODS) -> tuple:
    """The statistics window [t0, t1] (s) of a run, and how it was chosen: the one window of a run's summary
    (statistics, amplitudes, the model ladder's error checks and its settling note).

    The window holds the settled forced response: it ends at the last time and starts at the latest of

    * the end of the smooth start (``ramp_s`` after the first time): the ramp's reduced amplitudes are not the
      forced response;
    * the middle of the run: the start-up transient from the initial state decays over the first half (a run
      of a damped system is judged on its second half; a build-up still under way there shows as a change of
      the amplitudes between the window's halves, :func:`settled`);
    * ``n_periods`` forcing periods before the end (the longest ``period``, s; None for no periodic forcing):
      5 periods give each half of the window 2.5 periods, enough for the amplitude (half the peak-to-peak, one
      period of a periodic response suffices) to be compared between the halves, while a long run keeps its
      window on the most settled part.

    A short run still gets a window: when less than ``least`` = min(one period, half the run) (no period:
    10 % of the run) follows the ramp, the window is the last ``least`` seconds, ramp included, and ``how``
    says so.

    Returns
    -------
    (float, float, str)
        t0, t1 (s) and the rule that set t0.
    """
    t = np.asarray(time, float)
    first, last = float(t[0]), float(t[-1])
    span = last - first
    after_ramp, middle = first + max(float(ramp_s or 0.0), 0.0), first + 0.5 * span
    start, how = middle, "the second half of the run"
    if after_ramp > start:
        start, how = after_ramp, f"after the smooth start ({float(ramp_s):.4g} s)"
    if period and last - n_periods * period > start:
        start, how = last - n_periods * period, f"the last {n_periods} forcing periods ({period:.4g} s)"
    least = min(period, 0.5 * span) if period else 0.1 * span
    if last - start < least:
        start = last - least
        how = (f"the last {'forcing period' if period and least == period else 'half' if period else '10 %'} "
               f"of the run, inside the smooth start ({float(ramp_s):.4g} s): too short to settle")
    return start, last, how


def window_mask(time, t0: float, t1: float) -> np.ndarray:
    """The samples of ``time`` in [t0, t1] (s), with a relative slack of 1e-9 for round-off in the ends."""
    t = np.asarray(time, float)
    eps = 1e-9 * max(1.0, abs(t1))
    return (t >= t0 - eps) & (t <= t1 + eps)


def significant_amplitude(sigma: float) -> float:
    """A_s = 2 sigma (unit of sigma): the mean of the highest third of the Rayleigh amplitudes of a narrow-band
    Gaussian process (Longuet-Higgins 1952; H_s = 4 sqrt(m0), Bai & Jin, Marine Structural Design, sec. 2.2.5)."""
    return 2.0 * float(sigma)


def half_range(y) -> float:
    """Half the peak-to-peak of ``y`` (its unit): the amplitude of a periodic response."""
    y = np.asarray(y, float)
    return 0.5 * float(np.ptp(y)) if y.size else 0.0


def crossing_times(t, y, level: float) -> np.ndarray:
    """Times (s) of the up-crossings of ``level`` (y[k] < level <= y[k+1]), located by linear interpolation."""
    t, y = np.asarray(t, float), np.asarray(y, float)
    k = np.flatnonzero((y[:-1] < level) & (y[1:] >= level))
    return t[k] + (level - y[k]) / (y[k + 1] - y[k]) * (t[k + 1] - t[k])


def zero_upcrossing_period(t, y, floor: float = 0.0) -> tuple[float | None, str]:
    """Mean zero-up-crossing period T_z (s) of a sampled series and, when undefined, why.

    Parameters
    ----------
    t, y : array_like
        Sample times (s) and values.
    floor : float
        Absolute resolution of ``y`` (its unit, :data:`FLOORS`): a series whose standard deviation is not above
        :func:`resolution` does not oscillate and has no T_z.

    Returns
    -------
    (float or None, str)
        The mean time between the first and last located up-crossings of the mean over the whole cycles
        between them, and "" ; or None and the reason.
    """
    y = np.asarray(y, float)
    res = resolution(y, floor)
    if y.size < 3 or not float(np.std(y)) > res:
        return None, f"no T_z: the series does not vary above its resolution {res:.3g}"
    times = crossing_times(t, y, float(np.mean(y)))
    if times.size < 2:
        return None, f"no T_z: {times.size} up-crossing(s) of the mean in the window (two are needed)"
    return float(times[-1] - times[0]) / (times.size - 1), ""


def spectral_zero_upcrossing_period(m0: float, m2: float) -> float | None:
    """T_z = 2 pi sqrt(m0 / m2) (s) of a spectrum with moments m0, m2 (Rice 1944; DNV-RP-C205 eq. 3.5.4.4);
    None when m0 or m2 is not positive (no response)."""
    return 2 * math.pi * math.sqrt(m0 / m2) if m0 > 0 and m2 > 0 else None


def rayleigh_mpm(sigma: float, tz: float | None, duration: float) -> float:
    """Most probable largest excursion above the mean, sigma sqrt(2 ln(D / T_z)) (Rayleigh peaks; Ochi 1973;
    DNV-RP-C205 sec. 3.5.11.3).

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
        The mode of the largest of N = D / T_z Rayleigh peaks (0 when N <= 1 or T_z is undefined).
    """
    if tz is None or not (sigma > 0 and tz > 0 and duration > 0) or not math.isfinite(tz):
        return 0.0
    n = duration / tz
    return sigma * math.sqrt(2.0 * math.log(n)) if n > 1 else 0.0


def gaussian_probability_below(level: float, mean: float, sigma: float) -> float:
    """P(X < level) of a Gaussian X ~ N(mean, sigma^2) (a step at the mean when sigma = 0)."""
    if not sigma > 0:
        return float(mean < level)
    return 0.5 * math.erfc((mean - level) / (sigma * math.sqrt(2.0)))


def amplitude_change(first: float, second: float, floor: float = 0.0, scale: float | None = None) -> float:
    """Relative change of an amplitude between two halves of a window: |a2 - a1| / max(a1, a2) (or / ``scale``, a
    normalization shared by several amplitudes), and 0 when the change is within the absolute ``floor`` (the unit
    of the amplitudes, :data:`FLOORS`): a change of a zero or round-off amplitude is no change."""
    d = abs(float(second) - float(first))
    return 0.0 if d <= floor else d / (scale if scale else max(abs(first), abs(second)))


def settled(t, y, rtol: float = 1e-3, floor: float = 0.0) -> tuple[bool, float]:
    """Whether ``y`` has settled over the window ``t``: its amplitudes (:func:`half_range`) over the first and
    second half change by no more than ``rtol`` (:func:`amplitude_change`, absolute ``floor`` in the unit of y).

    Returns
    -------
    (bool, float)
        Settled, and the relative change.
    """
    t, y = np.asarray(t, float), np.asarray(y, float)
    if t.size < 4:
        return True, 0.0
    mid = 0.5 * (t[0] + t[-1])
    change = amplitude_change(half_range(y[t <= mid]), half_range(y[t >= mid]), resolution(y, floor))
    return change <= rtol, change


def bound_extremes(stats: dict, fallback: dict, floor: float | None = 0.0) -> tuple[dict, list]:
    """Extremes that bound each other: every ``<k>_min`` at least ``floor`` (None: no floor) and every pair with
    ``<k>_max`` < ``<k>_min`` replaced by the ``fallback`` pair (e.g. a finest run's own sampled extremes, which
    bound each other), amplitudes at least 0.

    For records whose extremes are not sampled but computed (a Richardson extrapolation of max and min
    separately can cross them).

    Returns
    -------
    (dict, list)
        A copy of ``stats``, and the base names ``k`` whose pair was replaced.
    """
    out, crossed = dict(stats), []
    for key in stats:
        if key.endswith("_amplitude"):
            out[key] = max(out[key], 0.0)
        if key.endswith("_min") and floor is not None:
            out[key] = max(out[key], floor)
    for key in stats:
        if key.endswith("_max") and key[:-4] + "_min" in stats:
            lo = key[:-4] + "_min"
            if out[key] < out[lo]:
                out[key], out[lo] = fallback[key], fallback[lo]
                crossed.append(key[:-4])
    return out, crossed


def flagged_intervals(t, flags) -> list[tuple[float, float]]:
    """The intervals (s) of the runs of flagged samples: from the first flagged sample of a run to the first
    unflagged one after it (the last time when the run lasts to the end). Their total length is the sum of the
    sample steps that start at a flagged sample: the time spent slack resolved to the output step."""
    t, f = np.asarray(t, float), np.asarray(flags, bool)
    if not f.any():
        return []
    edge = np.diff(np.concatenate([[0], f.astype(np.int8), [0]]))
    starts, ends = np.flatnonzero(edge == 1), np.flatnonzero(edge == -1)
    return [(float(t[a]), float(t[min(b, t.size - 1)])) for a, b in zip(starts, ends)]


def as_tension(stats: dict, t=None, raw=None) -> dict:
    """``stats`` of a tension with no value below 0 N (module docstring): the slack time of the ``raw`` series
    (:func:`flagged_intervals` of its samples at or below 0), the Gaussian slack probability, clipped extremes and
    a note."""
    out = dict(stats)
    notes = []
    if raw is not None:
        out["slack_time_s"] = sum(b - a for a, b in flagged_intervals(t, np.asarray(raw, float) <= 0.0))
        low = float(np.min(raw))
        if low < 0.0:
            notes.append(f"the series fell to {low:.4g} (a rope carries no compression): counted as 0, "
                         f"slack for {out['slack_time_s']:.3g} s")
    out["slack_probability"] = gaussian_probability_below(0.0, stats["mean"], stats["std"])
    if stats["most_probable_min"] is not None and stats["most_probable_min"] < 0.0:
        notes.append(f"the Gaussian most probable minimum {stats['most_probable_min']:.4g} is below 0: reported as 0; "
                     f"the cable goes slack (Gaussian P(T < 0) = {out['slack_probability']:.3g})")
    for k in ("max", "min", "most_probable_max", "most_probable_min"):
        out[k] = None if out[k] is None else max(float(out[k]), 0.0)
    if notes:
        out["note"] = "; ".join(notes)
    return out


def time_domain(t, y, duration: float | None = None, *, floor: float = 0.0, nonnegative: bool = False) -> dict:
    """Statistics of a sampled series ``y(t)`` (same unit as ``y``; periods in s), as the module docstring
    defines them.

    Parameters
    ----------
    t, y : array_like
        Sample times (s) and values over the statistics window.
    duration : float, optional
        Exposure for the most probable extremes (s); default: the window length.
    floor : float
        Absolute resolution of ``y`` in its unit (:data:`FLOORS`).
    nonnegative : bool
        A tension (module docstring): the statistics are of max(y, 0), nothing is reported below 0, and
        ``slack_time_s``, ``slack_probability`` (and a ``note`` when y fell below 0) are added.

    Returns
    -------
    dict
        ``max, min, mean, std, amplitude`` (half the peak-to-peak), ``significant_amplitude`` (2 std),
        ``zero_upcrossing_period_s`` (None without it, ``zero_upcrossing_note`` saying why),
        ``most_probable_max`` and ``most_probable_min`` (mean +- sigma sqrt(2 ln(D / T_z)); the mean for a series
        that does not vary above its resolution, None for one that varies without a T_z).
    """
    t, raw = np.asarray(t, float), np.asarray(y, float)
    y = np.maximum(raw, 0.0) if nonnegative else raw          # a rope's tension: compression counts as slack (0)
    mean, std = float(np.mean(y)), float(np.std(y))
    span = float(t[-1] - t[0]) if len(t) > 1 else 0.0
    tz, why = zero_upcrossing_period(t, y, floor)
    mpm = rayleigh_mpm(std, tz, duration or span)
    out = {"max": float(np.max(y)), "min": float(np.min(y)), "mean": mean, "std": std, "amplitude": half_range(y),
           "significant_amplitude": significant_amplitude(std), "zero_upcrossing_period_s": tz,
           "most_probable_max": mean + mpm, "most_probable_min": mean - mpm}
    if why:
        out["zero_upcrossing_note"] = why
        if std > resolution(y, floor):      # it varies, but not as a process with a period: no Rayleigh extremes
            out["most_probable_max"] = out["most_probable_min"] = None
    return as_tension(out, t, raw) if nonnegative else out


def moment(omega, S, order: int = 0) -> float:
    """m_n = int omega^n S(omega) d omega (trapezoid, :func:`numpy.trapezoid`)."""
    omega = np.asarray(omega, float)
    return float(np.trapezoid(omega**order * np.asarray(S, float), omega))


def frequency_domain(omega, S, duration: float, mean: float = 0.0, *, nonnegative: bool = False) -> dict:
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
    nonnegative : bool
        A tension: a most probable minimum below 0 is reported as 0 with ``slack_probability`` and a ``note``.

    Returns
    -------
    dict
        The keys of :func:`time_domain` but ``amplitude`` (a sampled half peak-to-peak); ``max``/``min`` are the
        most probable extremes.
    """
    m0, m2 = moment(omega, S, 0), moment(omega, S, 2)
    std = math.sqrt(max(m0, 0.0))
    tz = spectral_zero_upcrossing_period(m0, m2)
    mpm = rayleigh_mpm(std, tz, duration)
    out = {"max": mean + mpm, "min": mean - mpm, "mean": mean, "std": std,
           "significant_amplitude": significant_amplitude(std), "zero_upcrossing_period_s": tz,
           "most_probable_max": mean + mpm, "most_probable_min": mean - mpm}
    if tz is None:
        out["zero_upcrossing_note"] = "no T_z: the spectrum has no positive m0 and m2"
    return as_tension(out) if nonnegative else out


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
