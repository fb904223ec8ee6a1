"""Particular solutions: exact complex order (0F1), report's real order (eq. 16), shooting, mpmath."""

import math

import numpy as np
import pytest
import scipy.special as sc

from cablesys.towed.bessel import (exact_solution, hyp0f1_complex, hyp0f1_exact, mpmath_solution,
                                   ode_residual, real_order_solution)
from cablesys.towed.bvp import bvp_solution
from cablesys.towed.equation import REPORT_SEA_TRIAL, REPORT_TYPICAL, TowedCable

SEA = TowedCable(length=1190.0, speed=5.0, **REPORT_SEA_TRIAL).coefficients()
TYP = TowedCable(**REPORT_TYPICAL).coefficients()
SHORT = TowedCable(length=150.0, speed=5.0, **REPORT_SEA_TRIAL).coefficients()


@pytest.mark.parametrize("coef", [SEA, TYP, SHORT], ids=["sea", "typical", "short"])
@pytest.mark.parametrize("omega", [0.3, 4.0, 25.0])
def test_exact_solution_satisfies_the_ode(coef, omega):
    """(a+b xi) v'' + (c + 2 i beta omega) v' + (i omega d - omega^2) v = 0 (eq. 4 in eq. 3)."""
    xi = np.linspace(0.0, 1.0, 23)
    q = coef.q(omega)
    x = coef.x_arg(xi, omega)
    dx = (omega**2 - 1j * omega * coef.d) / coef.b
    F0, _, _ = hyp0f1_complex(q, coef.x_arg(0.0, omega))
    v = hyp0f1_exact(q, x)[0] / F0
    dv = hyp0f1_exact(q + 1, x)[0] / q * dx / F0                       # DLMF 16.3.1
    d2v = hyp0f1_exact(q + 2, x)[0] / (q * (q + 1)) * dx**2 / F0
    res = ode_residual(coef, xi, omega, v, dv, d2v)
    scale = (np.abs((coef.a + coef.b * xi) * d2v) + np.abs((coef.c + 2j * coef.beta * omega) * dv)
             + np.abs((1j * omega * coef.d - omega**2) * v))
    assert np.max(np.abs(res) / scale) < 1e-10
    assert exact_solution(coef, 0.0, omega) == pytest.approx(1.0, abs=1e-14)   # eq. 6b


@pytest.mark.parametrize("coef", [SEA, TYP, SHORT], ids=["sea", "typical", "short"])
def test_exact_agrees_with_independent_shooting_solution(coef):
    xi = np.linspace(0.0, 1.0, 11)[:, None]
    om = np.array([0.2, 2.0, 8.0, 30.0])[None, :]
    ve = exact_solution(coef, xi, om)
    vb = bvp_solution(coef, xi, om)
    assert np.max(np.abs(ve - vb) / np.abs(ve)) < 1e-8


def test_bounded_at_the_zero_tension_point():
    """The regular solution stays finite at xi* (eq. 6b boundedness); shooting agrees there too."""
    xs = SEA.xi_turn
    ve = exact_solution(SEA, np.array([xs - 1e-9, xs]), 5.0)
    vb = bvp_solution(SEA, np.array([xs - 1e-9, xs]), 5.0)
    assert np.all(np.isfinite(ve)) and abs(ve[1]) < 1.0
    assert abs(ve[1] - vb[1]) < 1e-8


def test_exact_agrees_with_mpmath_including_the_asymptotic_branch():
    # c_n = 3 makes |x| large (~2500 at omega = 20): series loses > 1e-9, Hankel branch takes over
    big = TowedCable(length=1190.0, speed=5.0, **{**REPORT_SEA_TRIAL, "c_n": 3.0}).coefficients()
    for coef in (SEA, big):
        xi = np.array([0.0, 0.3, 0.7, 1.0])[:, None]
        om = np.array([0.5, 7.0, 20.0])[None, :]
        ve = exact_solution(coef, xi, om)
        vm = mpmath_solution(coef, xi, om)
        assert np.max(np.abs(ve - vm) / np.abs(vm)) < 1e-9
    q, x = big.q(20.0), big.x_arg(0.0, 20.0)
    assert hyp0f1_complex(q, x)[2] > 1e-9          # the series alone would not do


def test_real_order_form_equals_scipy_hyp0f1_with_real_parameter():
    """Eq. 16 via jv equals 0F1(; 1+p; x) / 0F1(; 1+p; x0) (scipy.special.hyp0f1, real parameter)."""
    xi = np.linspace(0.0, 1.0, 9)[:, None]
    om = np.array([0.5, 5.0, 15.0])[None, :]
    vr = real_order_solution(SEA, xi, om)
    ref = sc.hyp0f1(1 + SEA.p, SEA.x_arg(xi, om)) / sc.hyp0f1(1 + SEA.p, SEA.x_arg(0.0, om))
    assert np.max(np.abs(vr - ref) / np.abs(ref)) < 1e-10
    v, dv = real_order_solution(SEA, xi, om, derivative=True)
    h = 1e-6
    fd = (real_order_solution(SEA, xi + h, om) - real_order_solution(SEA, xi - h, om)) / (2 * h)
    assert np.max(np.abs(dv - fd) / np.abs(dv)) < 1e-6


@pytest.mark.parametrize("coef", [SEA, TYP, SHORT], ids=["sea", "typical", "short"])
def test_real_order_close_to_exact_where_eq8b_holds(coef):
    """Dropping Im q = 2 beta omega / b (eq. 8b) changes ln H by ~ (beta omega/b) |ln((a+b)/a)|."""
    xi = np.array([1.0])
    for om in (0.5, 3.0, 10.0):
        ve = exact_solution(coef, xi, om)[0]
        vr = real_order_solution(coef, xi, om)[0]
        est = coef.beta * om / coef.b * abs(math.log(abs((coef.a + coef.b) / coef.a)))
        rel = abs(vr - ve) / abs(ve)
        assert coef.order_ratio(om) < 0.1
        assert rel < 3 * est + 1e-12
        assert rel > 1e-6               # and they are genuinely different solutions (accuracy ~1e-10)
