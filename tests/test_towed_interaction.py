"""Horizontal-vertical interaction: A(theta, phi) (eq. 36-38) and the Gaussian average (App. B)."""

import math

import numpy as np
import pytest

from cablesys.errors import ParameterError
from cablesys.towed.interaction import (amplification, effective_amplification,
                                        effective_amplification_exact, normal_force_x, rms_angle_for)


def normal_force_from_vectors(theta, phi):
    """x-component of R |U_N|^2/U^2 n_hat with U_N = U - (U.c) c (eq. 28-35), from the vectors."""
    c = np.array([math.sin(theta) * math.cos(phi), math.cos(theta) * math.cos(phi), math.sin(phi)])
    U = np.array([0.0, 1.0, 0.0])
    UN = U - (U @ c) * c
    return (UN @ UN) * UN[0] / np.linalg.norm(UN)


@pytest.mark.parametrize("theta,phi", [(0.05, 0.0), (0.05, 0.1), (0.3, 0.7), (1.2, 0.2)])
def test_eq36_from_vector_algebra(theta, phi):
    assert normal_force_x(theta, phi) == pytest.approx(normal_force_from_vectors(theta, phi), rel=1e-12)
    ratio = normal_force_from_vectors(theta, phi) / normal_force_from_vectors(theta, 0.0)
    assert amplification(theta, phi) == pytest.approx(ratio, rel=1e-12)      # eq. 38


def test_amplification_limits():
    assert amplification(0.2, 0.0) == pytest.approx(1.0, rel=1e-14)       # level cable
    th = np.radians([1.0, 2.0, 3.0])
    A = amplification(th, math.radians(6.0))
    assert np.all(np.diff(A) < 0) and A[0] > 2.29 > A[-1]   # report's A = 2.29 lies in this band


def test_gaussian_average_small_angle_form():
    phi = math.radians(6.0)
    for sig_deg in (0.05, 0.2):
        sig = math.radians(sig_deg)
        assert effective_amplification_exact(sig, phi) == pytest.approx(
            float(effective_amplification(sig, phi)), rel=0.02)
    # at sigma comparable to phi the small-angle form (B-5) underestimates the full average
    sig = math.radians(5.0)
    assert effective_amplification_exact(sig, phi) > 1.3 * float(effective_amplification(sig, phi))
    assert rms_angle_for(float(effective_amplification(0.01, phi)), phi) == pytest.approx(0.01)


def test_bad_angles():
    with pytest.raises(ParameterError, match="theta"):
        amplification(0.0, 0.1)
    with pytest.raises(ParameterError, match="phi"):
        amplification(0.1, math.pi / 2)
    with pytest.raises(ParameterError, match="sigma"):
        effective_amplification(-1.0, 0.1)
