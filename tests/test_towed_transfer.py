"""Transfer function, c* and phase velocity (Kennedy & Strahan (1981) eq. 14, 26-27)."""

import numpy as np
import pytest

from cablesys.errors import ParameterError
from cablesys.towed.equation import REPORT_SEA_TRIAL, REPORT_TYPICAL, TowedCable
from cablesys.towed.transfer import (c_star, phase_lag, phase_velocity, transfer_function,
                                     transfer_grid, water_pulley_c_star)

SEA = TowedCable(length=1190.0, speed=5.0, **REPORT_SEA_TRIAL).coefficients()
TYP = TowedCable(**REPORT_TYPICAL).coefficients()


@pytest.mark.parametrize("coef", [SEA, TYP], ids=["sea", "typical"])
def test_low_frequency_water_pulley_limit(coef):
    """c* -> 1 + 1/p and |H| -> 1 as omega -> 0 (eq. 12-14), at every xi."""
    xi = np.array([0.25, 0.5, 1.0])
    cs = c_star(coef, xi, np.array([1e-3])).c_star
    assert cs == pytest.approx(water_pulley_c_star(coef), rel=1e-5)
    assert np.abs(transfer_function(coef, xi, 1e-3).H) == pytest.approx(1.0, abs=1e-4)
    # and the report's statement that typical p > 10 makes c* near 1 does not hold here: p ~ 5-9
    assert 1.1 < water_pulley_c_star(coef) < 1.25


def test_amplitude_falls_and_phase_speed_rises_with_frequency():
    """Low-pass cable (Fig. 6) and dispersive, faster string-like waves (Fig. 7)."""
    om = np.linspace(0.1, 30.0, 40)
    H = np.abs(transfer_function(SEA, 1.0, om).H)
    cs = c_star(SEA, 1.0, om).c_star
    assert np.all(np.diff(H) < 0) and H[-1] < 0.01
    assert np.all(np.diff(cs) > 0)
    # c* larger near the tow point than at the end (report p. 22)
    both = c_star(SEA, np.array([0.1, 1.0]), np.array([15.0])).c_star
    assert both[0] > both[1]


def test_c_star_consistent_with_local_phase_velocity():
    """c* over a short reach equals the local phase velocity (eq. 27a vs 27b)."""
    om = np.array([2.0, 10.0])
    local = phase_velocity(SEA, 0.0, om).phase_velocity
    short = c_star(SEA, np.array([1e-4]), om).c_star
    assert short == pytest.approx(local, rel=1e-3)
    # psi(xi) is the integral of omega / c(xi)
    xi = np.linspace(0, 1, 401)
    integral = np.trapezoid(om[1] / phase_velocity(SEA, xi, om[1]).phase_velocity, xi)
    assert phase_lag(SEA, 1.0, om[1]).phase_lag == pytest.approx(integral, rel=1e-5)


def test_grid_matches_independent_routes():
    """The grid against routes that share none of its code: shooting and the local phase velocity."""
    xi = np.linspace(0.0, 1.0, 120)
    om = np.linspace(0.1, 25.0, 30)
    g = transfer_grid(SEA, xi, om)
    assert g.H.shape == (120, 30) and g.c_star.shape == (120, 30)
    assert g.H[0] == pytest.approx(np.ones(30), abs=1e-15)          # H = eta(xi)/eta(0)
    # H from a shooting solution of the same boundary-value problem (scipy solve_ivp, bvp.py)
    for k in (0, 12, 29):
        assert g.H[[60, 119], k] == pytest.approx(transfer_function(SEA, xi[[60, 119]], om[k], method="bvp").H,
                                                  rel=1e-9)
    # c* (eq. 27b) from the grid's unwrapped phase = omega / int_0^1 omega / c dxi with the local
    # phase velocity c (eq. 27a, from v'/v): two definitions, one number
    fine = np.linspace(0.0, 1.0, 801)
    for k in (3, 17, 29):
        psi = np.trapezoid(om[k] / phase_velocity(SEA, fine, om[k]).phase_velocity, fine)
        assert g.c_star[-1, k] == pytest.approx(om[k] / psi, rel=2e-6)
    ds = g.to_xarray()
    assert ds["H_abs"].dims == ("xi", "omega")
    assert ds["c_star"].attrs["units"] == "1" and "27b" in ds["c_star"].attrs["long_name"]


def test_bad_inputs():
    with pytest.raises(ParameterError, match="omega"):
        transfer_function(SEA, 0.5, 0.0)
    with pytest.raises(ParameterError, match="xi"):
        transfer_function(SEA, -0.1, 1.0)
    with pytest.raises(ParameterError, match="method"):
        transfer_function(SEA, 0.5, 1.0, method="magic")
    with pytest.raises(ParameterError, match="xi"):
        transfer_function(SEA, 1.5, 1.0, method="bvp")          # beyond the zero-tension point


def test_a_user_solution_route_is_a_callable():
    """As solve_ivp takes an OdeSolver class, method= takes any v(coef, xi, omega) with v(0) = 1."""
    from cablesys.towed.bessel import real_order_solution

    calls = []

    def mine(coef, xi, omega):
        calls.append(np.shape(xi))
        return real_order_solution(coef, xi, omega)

    xi, om = np.linspace(0.0, 1.0, 65), np.array([0.5, 2.0])
    assert transfer_function(SEA, 0.7, 2.0, method=mine).H == transfer_function(SEA, 0.7, 2.0, method="real").H
    g = transfer_grid(SEA, xi, om, method=mine)
    assert calls and g.method == "mine"
    with pytest.raises(ParameterError, match="callable"):
        transfer_function(SEA, 0.5, 1.0, method=3)


FUNCTIONS = {"H": transfer_function, "phase_lag": phase_lag, "c_star": c_star, "phase_velocity": phase_velocity}


@pytest.mark.parametrize("name", sorted(FUNCTIONS))
def test_scalars_and_arrays_give_the_same_numbers(name):
    """Each point asked alone (two floats) equals the same point inside a broadcast call, to 1e-12.

    The omega grid reaches 60, where the 0F1 series hands over to the asymptotic expansion
    (a scalar point there goes through the same code); xi includes the tow point (c* -> eq. 27a).
    """
    xi = np.array([0.0, 0.3, 1.0])
    om = np.array([0.5, 4.0, 20.0, 60.0])
    grid = getattr(FUNCTIONS[name](SEA, xi[:, None], om[None, :]), name)
    assert grid.shape == (3, 4)
    for i, x in enumerate(xi):
        line = getattr(FUNCTIONS[name](SEA, x, om), name)
        assert line.shape == (4,)
        for k, w in enumerate(om):
            one = getattr(FUNCTIONS[name](SEA, float(x), float(w)), name)
            assert np.ndim(one) == 0
            assert abs(one - grid[i, k]) <= 1e-12 * max(1.0, abs(one)), (x, w)
            assert abs(line[k] - grid[i, k]) <= 1e-12 * max(1.0, abs(one)), (x, w)


def test_broadcast_pairs_are_points_not_a_grid():
    """Equal-length xi and omega are paired point by point (NumPy broadcasting), labelled on ``point``."""
    xi, om = np.array([0.2, 0.9]), np.array([1.0, 2.0])
    pairs = c_star(SEA, xi, om)
    assert pairs.c_star.shape == (2,)
    assert pairs.c_star[1] == pytest.approx(float(c_star(SEA, 0.9, 2.0).c_star), rel=1e-12)
    ds = pairs.to_xarray()
    assert ds["c_star"].dims == ("point",) and list(ds["omega"].values) == [1.0, 2.0]
    assert ds["omega"].attrs["units"] == "1" and "omega L/U" in ds["omega"].attrs["long_name"]
    assert ds["phase_lag"].attrs["units"] == "rad"
    with pytest.raises(ParameterError, match="broadcast"):
        transfer_function(SEA, np.array([0.1, 0.2, 0.3]), np.array([1.0, 2.0]))
