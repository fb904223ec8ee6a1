"""Short-term statistics (cablesys/statistics.py): closed forms and the Rayleigh most probable maximum
against time-domain maxima over many seeds of a linear response (RAO superposition)."""

import math

import numpy as np
import pytest

from cablesys import statistics as st
from cablesys.scene.sea import SeaSpectrum


def test_sine_statistics_closed_form():
    """a sin(w t): std a/sqrt(2), up-crossing period 2 pi / w, significant amplitude 2 std = sqrt(2) a,
    amplitude (half the peak-to-peak) a."""
    t = np.linspace(0, 200, 20001)
    s = st.time_domain(t, 3.0 + 2.0 * np.sin(0.5 * np.pi * t))
    assert s["mean"] == pytest.approx(3.0, abs=1e-3)
    assert s["std"] == pytest.approx(2.0 / math.sqrt(2), rel=1e-3)
    assert s["zero_upcrossing_period_s"] == pytest.approx(4.0, rel=0.01)
    assert s["significant_amplitude"] == pytest.approx(2.0 * math.sqrt(2), rel=1e-3)
    assert s["amplitude"] == pytest.approx(2.0, rel=1e-3)
    assert s["max"] == pytest.approx(5.0, abs=1e-6)


def test_spectral_moments_of_a_narrow_band():
    """S concentrated at w0: T_z = 2 pi / w0; sigma^2 = area."""
    w = np.linspace(0.9, 1.1, 2001)
    S = np.where(np.abs(w - 1.0) < 0.005, 1.0, 0.0)
    f = st.frequency_domain(w, S, duration=3600.0, mean=2.0)
    assert f["std"] == pytest.approx(math.sqrt(0.01), rel=0.01)
    assert f["zero_upcrossing_period_s"] == pytest.approx(2 * math.pi, rel=1e-3)
    n = 3600.0 / f["zero_upcrossing_period_s"]
    assert f["most_probable_max"] == pytest.approx(2.0 + f["std"] * math.sqrt(2 * math.log(n)))
    assert st.rayleigh_mpm(1.0, 10.0, 5.0) == 0.0


@pytest.mark.slow
def test_most_probable_maximum_matches_maxima_over_seeds():
    """Linear oscillator (omega_n = 1 rad/s, zeta = 0.2) in a Pierson-Moskowitz sea: the most probable
    maximum from the response spectrum is the mode of the largest peak over D, so about e^-1 = 37 % of
    the seeds' maxima fall below it (Gumbel limit of the largest Rayleigh peak), within the binomial
    scatter of 120 seeds (3 sigma = 0.13). (A lightly damped oscillator is dominated by a few
    components of the realisation, which is then not Gaussian: the test keeps the response broad.); and the spectral and time-domain T_z, sigma agree."""
    wn, zeta, duration, n_seeds = 1.0, 0.2, 900.0, 120
    t = np.arange(0.0, duration, 0.5)
    below, tds, fds = 0, [], None
    for seed in range(n_seeds):
        sea = SeaSpectrum(kind="pierson-moskowitz", hs=2.0, tp=7.0, n_components=200, seed=seed,
                          omega_min=0.4, omega_max=2.5)
        w, a, e = sea.components()
        H = 1.0 / (1 - (w / wn) ** 2 + 2j * zeta * w / wn)
        y = (np.abs(H) * a) @ np.sin(w[:, None] * t[None, :] + (e + np.angle(H))[:, None])
        if fds is None:      # the target response spectrum on a fine grid
            wf = np.linspace(0.4, 2.5, 4000)
            Hf = 1.0 / (1 - (wf / wn) ** 2 + 2j * zeta * wf / wn)
            fds = st.frequency_domain(wf, np.abs(Hf) ** 2 * sea.density(wf), duration)
        below += y.max() < fds["most_probable_max"]
        tds.append(st.time_domain(t, y))
    frac = below / n_seeds
    assert abs(frac - math.exp(-1)) < 3 * math.sqrt(math.exp(-1) * (1 - math.exp(-1)) / n_seeds)
    assert np.mean([s["std"] for s in tds]) == pytest.approx(fds["std"], rel=0.05)
    assert np.mean([s["zero_upcrossing_period_s"] for s in tds]) == pytest.approx(fds["zero_upcrossing_period_s"], rel=0.05)
    assert np.mean([s["most_probable_max"] for s in tds]) == pytest.approx(fds["most_probable_max"], rel=0.05)
