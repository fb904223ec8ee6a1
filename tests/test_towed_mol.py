"""Time-domain method of lines (CasADi CVODES) against the exact solution and eigenfrequency."""

import numpy as np
import pytest

from cablesys.errors import ParameterError
from cablesys.towed.bessel import exact_solution
from cablesys.towed.eigen import exact_eigenfrequency
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
    # the damping time this implies is well below the report's 146 s for its typical values
    if coef is TYP:
        t0 = TowedCable(**REPORT_TYPICAL).time_scale() / slowest_mode(coef, 80).imag
        assert 60.0 < t0 < 72.0


def test_mol_inputs():
    with pytest.raises(ParameterError):
        mol_matrix(SEA, 2)
    with pytest.raises(ParameterError, match="omega"):
        forced_response(SEA, 0.0, [1.0])
    with pytest.raises(ParameterError, match="xi"):
        forced_response(SEA, 1.0, [2.0], n=20)
