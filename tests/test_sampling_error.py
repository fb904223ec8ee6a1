"""The sampling error of a variance and of 2 sigma from one finite record (cablesys.linear.sampling).

Checked against many synthetic records of known spectrum (the spread of the estimates over the records
matches the formula within the spread's own sampling error), and the formula for a Gaussian process
against Bendat & Piersol's continuum form (2 pi / T) int S^2 d omega, an independent route.
"""

import numpy as np
import pytest

from cablesys.errors import ParameterError
from cablesys.linear.sampling import (
    gaussian_mean_square_variance,
    log_ratio_error,
    mean_square_covariance,
    significant_amplitude_error,
)
from cablesys.linear.spectra import jonswap
from cablesys.scene.sea import SeaSpectrum

T, DT = 300.0, 0.5          # record length and sampling step (s): Nyquist 2 pi rad/s, above the sea band x 2


def _records(omega, z, n_records, rng, *, rayleigh=False, duration=T):
    """Mean squares of ``n_records`` records y = sum_k Re(z_k e^{i(omega_k t + eps_k)}), uniform phases
    (and Rayleigh amplitudes), sampled at DT on [0, duration); one row per response in ``z``."""
    t = np.arange(0.0, duration, DT) + 0.5 * DT
    E = np.exp(1j * np.outer(omega, t))
    g = np.exp(1j * rng.uniform(0, 2 * np.pi, (n_records, omega.size)))
    if rayleigh:
        g *= np.sqrt(rng.exponential(1.0, g.shape))
    return [np.mean(np.real((g * zk) @ E) ** 2, axis=1) for zk in z]


def _within(sample, predicted, k=3.0):
    """|spread of the records - formula| <= k standard errors of the records' spread (estimated from them)."""
    n = sample.size
    d2 = (sample - sample.mean()) ** 2
    var = d2.sum() / (n - 1)
    se = np.sqrt(np.var(d2, ddof=1) / n)          # standard error of the sample variance
    return abs(var - predicted) <= k * se, var, predicted, se


def test_sea_realisation_variance_and_two_sigma_spread_match_the_formula():
    sea = SeaSpectrum(kind="jonswap", hs=2.5, tp=9.0, gamma=3.3, n_components=100)
    w, a, _ = sea.components()
    # a response with a resonance in the band (an SDOF at 0.8 rad/s, 20 % damping) as well as the elevation
    h = 1.0 / (1 - (w / 0.8) ** 2 + 2j * 0.2 * w / 0.8)
    rng = np.random.default_rng(7)
    m_eta, m_y = _records(w, [a + 0j, a * h], 4000, rng)
    for z, m in ((a + 0j, m_eta), (a * h, m_y)):
        mean = 0.5 * np.sum(np.abs(z) ** 2)
        assert m.mean() == pytest.approx(mean, rel=0.01)
        V = mean_square_covariance(z, z, w, T)
        ok, *vals = _within(m, V)
        assert ok, vals
        # 2 sigma: the records' standard deviation against the first-order error, within 3 standard errors of it
        two_sigma = 2 * np.sqrt(m)
        s, s_pred = two_sigma.std(ddof=1), significant_amplitude_error(mean, V)
        assert abs(s - s_pred) <= 3 * s / np.sqrt(2 * (m.size - 1)), (s, s_pred)
    # the ratio of the two 2 sigma from one realisation: the common sea cancels in part. The formula is first order
    # in the relative errors: the records' first-order statistic d(ln rho) = (dm_y / m_y - dm_eta / m_eta) / 2
    # matches it within its sampling error; ln rho itself spreads a little more at these large errors (27 % and
    # 21 % on the mean squares): within 10 %
    ma, mb = 0.5 * np.sum(a**2), 0.5 * np.sum(np.abs(a * h) ** 2)
    pred = log_ratio_error(ma, mb, mean_square_covariance(a, a, w, T), mean_square_covariance(a * h, a * h, w, T),
                           mean_square_covariance(a * h, a, w, T))
    first_order = 0.5 * (m_y / mb - m_eta / ma)
    ok, *vals = _within(first_order, pred**2)
    assert ok, vals
    assert 0.5 * np.log(m_y / m_eta).std(ddof=1) == pytest.approx(pred, rel=0.1)
    v_y = mean_square_covariance(a * h, a * h, w, T)
    assert pred < significant_amplitude_error(mb, v_y) / (2 * np.sqrt(mb))


def test_gaussian_process_matches_bendat_and_piersol():
    """A Gaussian sea (Rayleigh amplitudes on a grid fine enough not to repeat within the record): the formula, the
    continuum (2 pi / T) int S^2 and the spread of many records agree."""
    duration = 600.0
    w = np.linspace(0.3, 2.5, 801)
    dw = w[1] - w[0]
    assert 2 * np.pi / dw > 3 * duration
    S = jonswap(w, 2.5, 9.0, 3.3)
    z = np.sqrt(2 * S * dw) + 0j
    V = mean_square_covariance(z, z, w, duration, random_amplitudes=True)
    V_bp = gaussian_mean_square_variance(w, S, duration)
    assert V == pytest.approx(V_bp, rel=0.02)
    (m,) = _records(w, [z], 800, np.random.default_rng(3), rayleigh=True, duration=duration)
    ok, *vals = _within(m, V_bp)
    assert ok, vals
    # the same sea with the deterministic amplitudes cablesys uses varies less over a record than a Gaussian one
    assert mean_square_covariance(z, z, w, duration) < V


def test_bad_input_is_refused():
    with pytest.raises(ParameterError, match="duration"):
        mean_square_covariance(np.ones(3), np.ones(3), np.array([1.0, 2.0, 3.0]), 0.0)
    with pytest.raises(ParameterError, match="za, zb"):
        mean_square_covariance(np.ones(2), np.ones(3), np.array([1.0, 2.0, 3.0]), 10.0)
