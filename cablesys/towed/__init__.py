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

from .eigen import Eigenfrequencies, damping_time, eigenfrequencies, exact_eigenfrequency
from .equation import REPORT_SEA_TRIAL, REPORT_TYPICAL, Coefficients, TowedCable
from .interaction import amplification, effective_amplification
from .mol import forced_response, slowest_mode
from .runs import fit_normal_drag, model_runs, read_runs
from .transfer import TransferGrid, c_star, phase_lag, phase_velocity, transfer_function
from .transfer import transfer_grid, water_pulley_c_star

__all__ = ["REPORT_SEA_TRIAL", "REPORT_TYPICAL", "Coefficients", "Eigenfrequencies", "TowedCable", "TransferGrid",
           "amplification", "c_star", "damping_time", "effective_amplification", "eigenfrequencies",
           "exact_eigenfrequency", "fit_normal_drag", "forced_response", "model_runs", "phase_lag", "phase_velocity",
           "read_runs", "slowest_mode", "transfer_function", "transfer_grid", "water_pulley_c_star"]
