"""Kennedy & Strahan (1981) eq. 3 coefficients against the dimensional physics."""

import math

import numpy as np
import pytest

from cablesys.errors import ParameterError
from cablesys.towed.equation import REPORT_SEA_TRIAL, REPORT_TYPICAL, Coefficients, TowedCable


def dimensional_coefficients(cable: TowedCable, rho=1025.0):
    """Per-unit-length coefficients of the dimensional eq. 1, built from forces (not from eq. 3)."""
    d = cable.diameter
    M = rho * math.pi * d**2 / 4.0                       # added mass
    m = M * (1.0 / cable.beta - 1.0)                     # cable mass from beta = M/(M+m)
    U, L = cable.speed, cable.length
    f_t = 0.5 * rho * math.pi * d * cable.c_t * U**2     # tangential friction per length
    T_drogue = 2.0 * cable.c_t_drogue * M * U**2

    def tension(x):
        return f_t * (L - x) + T_drogue

    k_n = 0.5 * rho * d * cable.c_n * U                  # linear normal drag / relative cross-flow
    return dict(M=M, m=m, tension=tension, dTdx=-f_t, k_n=k_n)


@pytest.mark.parametrize("kw", [dict(length=1190.0, speed=5.0, **REPORT_SEA_TRIAL), REPORT_TYPICAL,
                                dict(length=50.0, speed=1.3, diameter=0.03, c_t=0.004, c_n=0.5,
                                     c_t_drogue=0.0, beta=0.8)])
def test_coefficients_follow_from_the_dimensional_equation(kw):
    cable = TowedCable(**kw)
    co = cable.coefficients()
    dim = dimensional_coefficients(cable)
    M, m, U, L = dim["M"], dim["m"], cable.speed, cable.length
    scale = (M + m) * U**2 / L**2                        # divides eq. 1 after x = L xi, t = L tau / U
    for xi in (0.0, 0.37, 1.0):
        # y_xx: M U^2 - T(x)
        assert (M * U**2 - dim["tension"](xi * L)) / L**2 / scale == pytest.approx(co.a + co.b * xi, rel=1e-12)
    # y_x = eta_xi / L: -T'(x) + k_n U ; y_t = (U/L) eta_tau: k_n ; y_xt = (U/L^2) eta_xi_tau: 2 M U
    assert (-dim["dTdx"] + dim["k_n"] * U) / L / scale == pytest.approx(co.c, rel=1e-12)
    assert dim["k_n"] * U / L / scale == pytest.approx(co.d, rel=1e-12)
    assert 2 * M * U * (U / L**2) / scale == pytest.approx(2 * co.beta, rel=1e-12)


def test_derived_quantities():
    cable = TowedCable(length=1190.0, speed=5.0, **REPORT_SEA_TRIAL)
    co = cable.coefficients()
    assert co.c == pytest.approx(co.b + co.d, rel=1e-14)
    assert co.p == pytest.approx(cable.c_n / (math.pi * cable.c_t), rel=1e-12)         # eq. 8c
    # zero tension of the lengthened cable L* = L + d_c c_t'/c_t (report p. 10), up to the U^2 term
    assert co.xi_turn == pytest.approx(1 + (2 * cable.c_t_drogue - 1) / (2 * cable.c_t * cable.eps))
    assert co.xi_turn * cable.length == pytest.approx(cable.length + cable.diameter * cable.c_t_drogue / cable.c_t,
                                                      rel=1e-3)
    # omega = 2 pi f L / U
    assert cable.omega(1e-3) == pytest.approx(2 * math.pi * 1e-3 * 1190 / 5)
    assert np.isclose(co.order_ratio(10.0), 2 * 0.5 * 10 / (co.b * co.p))
    assert co.nu(3.0) == pytest.approx(1 - (co.c + 2j * co.beta * 3.0) / co.b)


@pytest.mark.parametrize("field,value", [("length", 0.0), ("speed", -5.0), ("diameter", float("nan")),
                                         ("c_n", -0.1), ("beta", 1.5), ("c_t_drogue", -1.0)])
def test_bad_cable_inputs_name_the_field(field, value):
    kw = dict(length=1000.0, speed=5.0)
    kw[field] = value
    with pytest.raises(ParameterError) as err:
        TowedCable(**kw)
    assert err.value.field == field


def test_coefficients_validated():
    with pytest.raises(ParameterError, match="coefficients.b"):
        Coefficients(a=-1.0, b=-2.0, c=1.0, d=1.0, beta=0.5)
