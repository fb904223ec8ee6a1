"""Complementary solution: eigenfrequencies (eq. 18-21), eq. 20b test, damping time (eq. 23-25)."""

import math

import numpy as np
import pytest
import scipy.special as sc

from cablesys.errors import ParameterError
from cablesys.towed.bessel import hyp0f1_complex
from cablesys.towed.eigen import (bessel_zeros, damping_time, modes,
                                  exact_eigenfrequency)
from cablesys.towed.equation import REPORT_SEA_TRIAL, REPORT_TYPICAL, TowedCable

TYPICAL = TowedCable(**REPORT_TYPICAL)


def test_bessel_zeros():
    assert bessel_zeros(3.0, 4) == pytest.approx(sc.jn_zeros(3, 4), rel=1e-12)
    z = bessel_zeros(8.912, 3)
    assert np.abs(sc.jv(8.912, z)).max() < 1e-12
    assert 8.912 < z[0] < math.sqrt(2 * 9.912 * 11.912)          # Watson's interval (report p. 16)


def test_damping_time_report_typical_values():
    """t_0 ~ 150 s with the report's delta_1 ~ p (eq. 25): 2 pi (D - 1) d_c / (c_n U)."""
    t0 = damping_time(TYPICAL, zero="report")
    assert t0 == pytest.approx(2 * math.pi * (489 - 1) * 0.01 / (0.07 * 3.0), rel=1e-12)
    assert 140.0 < t0 < 155.0
    # the true first zero of J_p (delta_1 ~ 1.49 p, not p) shortens it by (delta_1/p)^2
    t_bessel = damping_time(TYPICAL, zero="bessel")
    p = TYPICAL.coefficients().p
    d1 = bessel_zeros(p, 1)[0]
    assert t_bessel == pytest.approx(t0 / (d1 / p) ** 2, rel=0.01)   # eq. 21 vs eq. 19 exact root
    # and the exact complex-order eigenvalue barely moves it (eq. 8b holds for the slow mode)
    assert damping_time(TYPICAL, zero="exact") == pytest.approx(t_bessel, rel=0.01)


def test_eigenfrequencies_solve_eq18_and_pass_eq20b_only_for_the_slow_root():
    co = TYPICAL.coefficients()
    e = modes(co, 4)
    for w_set in (e.slow, e.fast):
        bo2 = 4 * w_set / co.b**2 * (1j * co.d - w_set)                 # eq. 5
        assert np.sqrt(bo2 * co.a + 0j) == pytest.approx(e.delta, rel=1e-10)   # eq. 18 (principal root)
    assert np.all(e.slow.imag > 0)                                       # damped (eq. 22)
    assert np.all(e.valid_slow) and not np.any(e.valid_fast)
    # eq. 21 small-parameter form for the slow root
    eq21 = co.d / 4 * (e.delta / co.p) ** 2 / (co.beta * (TYPICAL.drag_term - 1))
    assert e.slow.imag == pytest.approx(eq21, rel=0.01)


def test_exact_eigenfrequency_is_a_zero_of_the_exact_solution():
    co = TYPICAL.coefficients()
    w = exact_eigenfrequency(co, 1)
    q = (co.c + 2j * co.beta * w) / co.b
    F, _, _ = hyp0f1_complex(q, (w**2 - 1j * w * co.d) * co.a / co.b**2)
    F_scale, _, _ = hyp0f1_complex(q, (0.5 * w) ** 2 * co.a / co.b**2)
    assert abs(F) < 1e-8 * abs(F_scale)
    assert w.imag > 0


def test_bad_inputs():
    with pytest.raises(ParameterError):
        bessel_zeros(2.0, 0)
    with pytest.raises(ParameterError, match="zero"):
        damping_time(TYPICAL, zero="guess")
    sea = TowedCable(length=1190.0, speed=5.0, **REPORT_SEA_TRIAL)
    assert damping_time(sea, zero="report") > damping_time(sea, zero="bessel") > 0
