"""Towed cables: the Kennedy & Strahan (1981) transverse linear theory, solved exactly.

equation     nondimensional coefficients of eq. 3 (derivation in its docstring)
bessel       particular solutions: exact complex order (0F1) and the report's real order (eq. 16)
bvp          independent shooting solution of the same boundary-value problem (solve_ivp)
mol          the PDE in time: method of lines + CasADi CVODES; forced H and slowest mode
transfer     H(xi, omega) (eq. 26), phase velocity (eq. 27a), c* (eq. 27b), water pulley (eq. 14)
eigen        complementary solution: eigenfrequencies (eq. 18-21), validity (eq. 20b), t_0 (eq. 23-25)
interaction  horizontal-vertical amplification A(theta, phi) (eq. 38) and its Gaussian average (App. B)
runs         sea-trial runs: CSV reading with row/column errors, model per run, c_n fits
cli          the `cablesys towed` sub-command
"""

from .equation import Coefficients, TowedCable, REPORT_SEA_TRIAL, REPORT_TYPICAL
from .transfer import (transfer_function, c_star, phase_velocity, phase_lag,
                       water_pulley_c_star, transfer_grid, TransferGrid)

__all__ = ["Coefficients", "TowedCable", "REPORT_SEA_TRIAL", "REPORT_TYPICAL",
           "transfer_function", "c_star", "phase_velocity", "phase_lag",
           "water_pulley_c_star", "transfer_grid", "TransferGrid"]
