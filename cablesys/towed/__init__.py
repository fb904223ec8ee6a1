"""Towed cables: the Kennedy & Strahan (1981) transverse linear theory, solved exactly.

scene (``TowedScene``, ``load_towed_scene``: the cable's C_t, C_n in the Wang scene's names) ->
``analyze`` -> :class:`TowedAnalysis` (H, c*, modes, damping time; omega in rad/s), as
``cablesys.slack``'s scene -> analyze; the theory's own functions below take its nondimensional
coefficients (:meth:`TowedCable.coefficients`) and omega L / U.

equation     nondimensional coefficients of eq. 3 (derivation in its docstring); theory_coefficients, the
             one conversion of C_t, C_n and a drogue's drag area to c_t, c_n, c_t' and beta
scene        the towed scene file ([cable], [environment], [towed]) and its validation
analysis     analyze(scene) -> TowedAnalysis, SI
bessel       particular solutions: exact complex order (0F1) and the report's real order (eq. 16)
bvp          independent shooting solution of the same boundary-value problem (solve_ivp)
mol          the PDE in time: method of lines + CasADi CVODES; forced H and slowest mode
transfer     H(xi, omega) (eq. 26), phase velocity (eq. 27a), c* (eq. 27b), water pulley (eq. 14): each
             returns a TowedResponse (the result protocol) at xi and omega broadcast together
eigen        complementary solution: modes (eigenfrequencies, eq. 18-21), validity (eq. 20b), t_0 (eq. 23-25)
interaction  horizontal-vertical amplification A(theta, phi) (eq. 38) and its Gaussian average (App. B)
runs         sea-trial runs: CSV reading with row/column errors, model per run, c_n fits
plots        plot_response: |H| and c* against frequency
cli          the `cablesys towed` sub-command (SCENE.toml or RUNS.csv)
"""

from ..lazy import lazy_exports

# public name -> module that defines it, imported on first use (cablesys.lazy)
_EXPORTS = {
    "TowedAnalysis": ".analysis",
    "analyze": ".analysis",
    "TowedScene": ".scene",
    "TowedSceneCable": ".scene",
    "load_towed_scene": ".scene",
    "theory_coefficients": ".equation",
    "plot_response": ".plots",
    "Eigenfrequencies": ".eigen",
    "damping_time": ".eigen",
    "eigenfrequencies": ".eigen",
    "exact_eigenfrequency": ".eigen",
    "modes": ".eigen",
    "REPORT_SEA_TRIAL": ".equation",
    "REPORT_TYPICAL": ".equation",
    "Coefficients": ".equation",
    "TowedCable": ".equation",
    "amplification": ".interaction",
    "effective_amplification": ".interaction",
    "forced_response": ".mol",
    "slowest_mode": ".mol",
    "fit_normal_drag": ".runs",
    "model_runs": ".runs",
    "RunsResponse": ".runs",
    "read_runs": ".runs",
    "TowedResponse": ".transfer",
    "TransferGrid": ".transfer",
    "c_star": ".transfer",
    "phase_lag": ".transfer",
    "phase_velocity": ".transfer",
    "transfer_function": ".transfer",
    "transfer_grid": ".transfer",
    "water_pulley_c_star": ".transfer",
}

__all__ = ["Coefficients", "Eigenfrequencies", "REPORT_SEA_TRIAL", "REPORT_TYPICAL", "RunsResponse", "TowedAnalysis",
           "TowedCable", "TowedResponse", "TowedScene", "TowedSceneCable", "TransferGrid", "amplification", "analyze",
           "c_star", "damping_time", "effective_amplification", "exact_eigenfrequency", "fit_normal_drag",
           "forced_response", "load_towed_scene", "model_runs", "modes", "phase_lag", "phase_velocity",
           "plot_response", "read_runs", "slowest_mode", "theory_coefficients", "transfer_function", "transfer_grid",
           "water_pulley_c_star"]

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, __all__)
