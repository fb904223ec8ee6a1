"""Sampling error of a variance (and of 2 sigma) estimated from one finite record of a random sea response.

A record of length T gives the mean square m^ = (1/T) int_0^T y^2 dt, an estimate of sigma^2 with a
random error. For a stationary Gaussian process of one-sided spectrum S(omega) (rad/s) and T much
longer than its correlation time, Var[m^] = (2/T) int R(tau)^2 d tau (Isserlis: Cov[y(t)^2, y(s)^2] =
2 R(s - t)^2) = (2 pi / T) int_0^inf S(omega)^2 d omega (Parseval), i.e. the normalized random error
eps = 1 / sqrt(B_s T) with the statistical bandwidth B_s = (int G df)^2 / int G^2 df in Hz (Bendat &
Piersol, "Random Data", 4th ed. 2010, sec. 8.2.2 and 8.2.3): :func:`gaussian_mean_square_variance`.

cablesys realises a sea as a sum of sinusoids (:mod:`cablesys.scene.sea`): y(t) = sum_k Re(z_k
e^{i(omega_k t + eps_k)}), deterministic amplitudes, independent uniform phases eps_k. Over a record
longer than 2 pi / d_omega its components are resolved and the estimate varies less than a Gaussian
process's; :func:`mean_square_covariance` is the exact covariance over the phases of two such
responses driven by the same sea (the baseline and the designed cable in the same realisation), for
which the Gaussian value is the limit of many components (then each pair (j, k) term below tends to
the double integral of S S' sinc^2, which is the Parseval form above).

With F(nu) = (1/T) int_{t0}^{t0+T} e^{i nu t} dt (|F| = |sinc(nu T / 2)|) and p_k = z^a_k conj(z^b_k):
    m^ = sum_{j,k} 1/2 Re(w_j conj(w_k) F(omega_j - omega_k)) + 1/2 Re(w_j w_k F(omega_j + omega_k)),
    w_k = z_k e^{i eps_k}; terms with different phase combinations are uncorrelated and
    Cov(Re(A e^{iu}), Re(B e^{iu})) = Re(A conj(B)) / 2 for u uniform, so
    Cov[m^a, m^b] = sum_{j<k} 1/2 |F(omega_j - omega_k)|^2 Re(p_j conj(p_k))
                  + sum_{j<k} 1/2 |F(omega_j + omega_k)|^2 Re(p_j p_k) + sum_k 1/8 |F(2 omega_k)|^2 Re(p_k^2).
With Rayleigh amplitudes as well (w_k = z_k g_k, g_k complex normal, E|g|^2 = 1: a Gaussian process
on the grid) the diagonal adds sum_k |p_k|^2 / 4 and the last sum doubles.

2 sigma^ = 2 sqrt(m^): its relative error is half that of m^ (first order), and the error of the
ratio of two 2 sigma^ from one realisation is Var[ln rho] = (V_aa / m_a^2 + V_bb / m_b^2 - 2 V_ab /
(m_a m_b)) / 4: the common sea cancels in part. Both are first order in the relative errors of the
mean squares; at errors of 20-30 % on them ln rho spreads up to about 10 % more than stated
(tests/test_sampling_error.py), at the 5-10 % of a few hundred seconds of sea much less.
"""

from __future__ import annotations

import numpy as np

from ..errors import ParameterError


def _check(omega, duration) -> np.ndarray:
    omega = np.asarray(omega, float)
    if omega.ndim != 1 or omega.size < 1 or not np.all(np.isfinite(omega)) or np.any(omega <= 0):
        raise ParameterError("omega", omega.shape, "a 1-D array of positive frequencies (rad/s)")
    if not (np.isfinite(duration) and duration > 0):
        raise ParameterError("duration", duration, "a positive record length (s)")
    return omega


def mean_square_covariance(za, zb, omega, duration: float, *, random_amplitudes: bool = False) -> float:
    """Cov[m^a, m^b] (unit of y_a y_b, squared) of the mean squares over one record of ``duration`` s of
    y_a = sum_k Re(za_k e^{i(omega_k t + eps_k)}) and y_b likewise with the same phases (module docstring).

    Parameters
    ----------
    za, zb : array_like of complex
        Complex amplitudes of the components of the two responses (e.g. transfer times wave amplitude).
    omega : array_like
        Component frequencies (rad/s), positive.
    duration : float
        Record length T (s).
    random_amplitudes : bool, optional
        Rayleigh amplitudes too (a Gaussian process on the grid), not the sea's deterministic ones.

    Returns
    -------
    float
    """
    omega = _check(omega, duration)
    za, zb = np.asarray(za, complex), np.asarray(zb, complex)
    if za.shape != omega.shape or zb.shape != omega.shape:
        raise ParameterError("za, zb", (za.shape, zb.shape), f"one complex amplitude per frequency ({omega.size})")
    p = za * np.conj(zb)

    def F2(nu):                                   # |F(nu)|^2 = sinc^2(nu T / 2); numpy's sinc is sin(pi x)/(pi x)
        return np.sinc(nu * duration / (2 * np.pi)) ** 2

    upper = np.triu(np.ones((omega.size, omega.size), bool), 1)
    diff = F2(omega[:, None] - omega[None, :]) * np.real(p[:, None] * np.conj(p[None, :]))
    summ = F2(omega[:, None] + omega[None, :]) * np.real(p[:, None] * p[None, :])
    diag = (0.25 if random_amplitudes else 0.125) * float(np.sum(F2(2 * omega) * np.real(p ** 2)))
    out = 0.5 * float(np.sum(diff[upper]) + np.sum(summ[upper])) + diag
    if random_amplitudes:
        out += 0.25 * float(np.sum(np.abs(p) ** 2))
    return out


def gaussian_mean_square_variance(omega, S, duration: float) -> float:
    """Var[m^] = (2 pi / T) int_0^inf S(omega)^2 d omega of a stationary Gaussian process (Bendat & Piersol
    2010 sec. 8.2.2; module docstring), T much longer than the correlation time. ``S``: one-sided spectrum
    (unit^2 s/rad) on the grid ``omega`` (rad/s), trapezoidal rule."""
    omega = _check(omega, duration)
    S = np.asarray(S, float)
    if S.shape != omega.shape:
        raise ParameterError("S", S.shape, f"one value per frequency ({omega.size})")
    return 2 * np.pi / duration * float(np.trapezoid(S ** 2, omega))


def significant_amplitude_error(m: float, variance: float) -> float:
    """Standard error (same unit as 2 sigma) of 2 sqrt(m^) for mean square m (first order: d(2 sqrt m) = dm /
    sqrt m)."""
    return float(np.sqrt(max(variance, 0.0)) / np.sqrt(m)) if m > 0 else float("nan")


def log_ratio_error(m_a: float, m_b: float, v_aa: float, v_bb: float, v_ab: float) -> float:
    """Standard error of ln(sqrt(m^b / m^a)), the log of the ratio of two 2 sigma^ from one realisation
    (module docstring)."""
    v = (v_aa / m_a**2 + v_bb / m_b**2 - 2 * v_ab / (m_a * m_b)) / 4.0
    return float(np.sqrt(max(v, 0.0)))
