"""Time-domain method of lines (CasADi CVODES) against the exact solution and eigenfrequency."""

import numpy as np
import pytest

from cablesys.errors import ParameterError
from cablesys.towed.bessel import exact_solution
from cablesys.towed.eigen import damping_time, exact_eigenfrequency
from cablesys.towed.equation import REPORT_SEA_TRIAL, REPORT_TYPICAL, TowedCable
from cablesys.towed.mol import forced_response, mol_matrix, slowest_mode

SEA = TowedCable(length=1190.0, speed=5.0, **REPORT_SEA_TRIAL).coefficients()
TYP = TowedCable(**REPORT_TYPICAL).coefficients()


def test_forced_pde_run_converges_to_the_exact_transfer_function():
    xi = np.array([0.5, 1.0])
    exact = exact_solution(SEA, xi, 3.0)
    e50 = np.abs(forced_response(SEA, 3.0, xi, n=50) - exact).max()
    e100 = np.abs(forced_response(SEA, 3.0, xi, n=100) - exact).max()
    assert e100 < 2e-4
    assert 3.0 < e50 / e100 < 5.5            # second-order finite differences


@pytest.mark.parametrize("coef", [SEA, TYP], ids=["sea", "typical"])
def test_slowest_mode_converges_to_the_exact_complex_order_eigenfrequency(coef):
    w_exact = exact_eigenfrequency(coef)
    e40 = abs(slowest_mode(coef, 40) - w_exact)
    e80 = abs(slowest_mode(coef, 80) - w_exact)
    assert e80 < 2e-3 * abs(w_exact)
    assert e40 / e80 > 3.0
    # the damping time it implies (eq. 23) agrees with the real-order theory's: the first zero
    # of J_p in eq. 19 (an independent route: Bessel zeros and a quadratic, no discretization),
    # and both lie below the report's upper bound (t_0)max of eq. 25, "~ 150 seconds" for these
    # typical values (Kennedy & Strahan 1981, the text after eq. 25)
    if coef is TYP:
        cable = TowedCable(**REPORT_TYPICAL)
        t0 = cable.time_scale() / slowest_mode(coef, 80).imag
        assert t0 == pytest.approx(damping_time(cable, zero="bessel"), rel=0.01)
        assert t0 == pytest.approx(damping_time(cable, zero="exact"), rel=2e-3)
        assert damping_time(cable, zero="report") == pytest.approx(150.0, rel=0.05)
        assert t0 < damping_time(cable, zero="report")


def test_mol_inputs():
    with pytest.raises(ParameterError):
        mol_matrix(SEA, 2)
    with pytest.raises(ParameterError, match="omega"):
        forced_response(SEA, 0.0, [1.0])
    with pytest.raises(ParameterError, match="xi"):
        forced_response(SEA, 1.0, [2.0], n=20)
