"""A towed scene analysed: transfer function, phase velocity, modes and damping time, in SI.

The dimensional face of the Kennedy & Strahan (1981) theory: the scene's angular frequencies
omega (rad/s) become the theory's omega L / U (eq. 2, tau = U t / L), and the theory's phase
velocities (in units of U) are also given in m/s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from ..errors import SolverError
from ..results import ResultBase, timed
from .eigen import Eigenfrequencies, damping_time, modes
from .equation import added_fluid_mass
from .scene import TowedScene
from .transfer import TOWED_VARIABLES, c_star, transfer_function, water_pulley_c_star

__all__ = ["TowedAnalysis", "analyze"]


@dataclass(frozen=True, kw_only=True)
class TowedAnalysis(ResultBase):
    """Response of a towed cable to tow-point motion, on (``xi``, ``omega``), SI where it has units.

    ``xi`` = x/L; ``omega`` (rad/s) and ``omega_nd`` = omega L / U; ``H`` complex transfer function
    (eq. 26); ``phase_lag`` psi (rad); ``c_star`` (eq. 27b) in units of U and ``c_star_m_s`` in
    m/s; ``coefficients`` the theory's c_t, c_n, c_t_drogue and beta the scene converted to;
    ``modes`` the complementary solution (eq. 18-20, nondimensional); ``damping_time_s`` t_0 (s)
    of the slowest mode from the true first zero of J_p (eq. 19, 23) and
    ``damping_time_report_s`` the report's closed form (eq. 25); ``tension_top`` and
    ``tension_bottom`` (N) the steady tensions at the tow point and the drogue.
    """

    scene: Any
    coefficients: dict
    xi: np.ndarray
    omega: np.ndarray
    omega_nd: np.ndarray
    H: np.ndarray
    phase_lag: np.ndarray
    c_star: np.ndarray
    modes: Eigenfrequencies
    damping_time_s: float
    damping_time_report_s: float
    water_pulley_c_star: float
    success: bool = True
    message: str = ""
    stats: dict = field(default_factory=dict)

    # the theory's labels, with omega dimensional here and its nondimensional value as omega_nd
    VARIABLES: ClassVar[dict] = {
        **TOWED_VARIABLES, "omega": ("rad/s", "angular frequency of the tow-point motion"),
        "omega_nd": TOWED_VARIABLES["omega"], "frequency": ("Hz", "frequency of the tow-point motion"),
        "c_star_m_s": ("m/s", "mean phase velocity c* (eq. 27b)")}

    @property
    def c_star_m_s(self) -> np.ndarray:
        """c* in m/s (c* U)."""
        return self.c_star * self.scene.speed

    @property
    def tension_top(self) -> float:
        """Steady tension at the tow point, N: ``T(0) = 2 M U^2 (c_t L/d_c + c_t')`` (eq. 1-3, 20a)."""
        c, cab = self.coefficients, self.scene.cable
        M = added_fluid_mass(self.scene.density, cab.diameter)
        return 2.0 * M * self.scene.speed**2 * (c["c_t"] * cab.length / cab.diameter + c["c_t_drogue"])

    @property
    def tension_bottom(self) -> float:
        """Steady tension at the drogue end, N: ``T(L) = 2 M U^2 c_t'`` (the drogue's drag)."""
        M = added_fluid_mass(self.scene.density, self.scene.cable.diameter)
        return 2.0 * M * self.scene.speed**2 * self.coefficients["c_t_drogue"]

    def static_tensions(self) -> dict:
        """{"tension_top", "tension_bottom"}: the steady tensions (N) the verdict judges against ``scene.limits``
        (:func:`cablesys.verdict.judge`)."""
        return {"tension_top": np.array([self.tension_top]), "tension_bottom": np.array([self.tension_bottom])}

    @property
    def frequency(self) -> np.ndarray:
        """Frequencies of the tow-point motion, Hz (omega / 2 pi)."""
        return self.omega / (2.0 * math.pi)

    def summary(self) -> dict:
        """Headline numbers: the theory's coefficients, damping times (s), modes and the far-end response.

        Returns
        -------
        dict
            JSON-able; ``far_end`` is |H| and c* (m/s) at the largest xi, at the lowest and highest omega.
        """
        k = int(np.argmax(self.xi))
        far = {"xi": float(self.xi[k]),
               "omega_rad_s": [float(self.omega[0]), float(self.omega[-1])],
               "H_abs": [float(abs(self.H[k, 0])), float(abs(self.H[k, -1]))],
               "c_star_m_s": [float(self.c_star_m_s[k, 0]), float(self.c_star_m_s[k, -1])]}
        return {**super().summary(), "tension_top_N": self.tension_top, "tension_bottom_N": self.tension_bottom,
                "coefficients": dict(self.coefficients),
                "modes": self.modes.summary()["modes"], "far_end": far}

    def to_xarray(self):
        """|H|, arg H, psi and c* on (``xi``, ``omega``) with omega in rad/s; omega_nd and frequency on omega.

        Returns
        -------
        xarray.Dataset
        """
        import xarray as xr
        dims = ("xi", "omega")
        return xr.Dataset(
            {"H_abs": (dims, np.abs(self.H)), "H_phase": (dims, np.angle(self.H)),
             "phase_lag": (dims, self.phase_lag), "c_star": (dims, self.c_star),
             "c_star_m_s": (dims, self.c_star_m_s)},
            coords={"xi": self.xi, "omega": self.omega, "omega_nd": ("omega", self.omega_nd),
                    "frequency": ("omega", self.frequency)},
            attrs={"source": "Kennedy & Strahan (1981) eq. 26-27", "damping_time_s": self.damping_time_s,
                   **{f"coefficient_{k}": float(v) for k, v in self.coefficients.items()}})

    def table(self) -> tuple[list[str], list[list[float]]]:
        """(header, rows) of the response, one row per (xi, omega): the CSV format, units in the header."""
        header = ["xi", "omega_rad_s", "frequency_hz", "omega_nd", "H_abs", "H_phase_rad", "phase_lag_rad",
                  "c_star", "c_star_m_s"]
        rows = []
        for i, x in enumerate(self.xi):
            for k, w in enumerate(self.omega):
                h = self.H[i, k]
                rows.append([float(x), float(w), float(self.frequency[k]), float(self.omega_nd[k]), float(abs(h)),
                             float(np.angle(h)), float(self.phase_lag[i, k]), float(self.c_star[i, k]),
                             float(self.c_star_m_s[i, k])])
        return header, rows


@timed
def analyze(scene: TowedScene) -> TowedAnalysis:
    """Transfer function, c*, modes and damping time of a towed scene (Kennedy & Strahan (1981)).

    The scene's C_t, C_n and drogue drag area are converted once
    (:func:`~cablesys.towed.equation.theory_coefficients`); the frequencies omega (rad/s) enter
    the theory as omega L / U.

    Parameters
    ----------
    scene : TowedScene
        The towed cable, its tow and the grid (SI).

    Returns
    -------
    TowedAnalysis
        The response on (xi, omega), modes and damping times; ``success`` False (with the
        reason) when the damping time cannot be computed (the response is kept).
    """
    cable = scene.towed_cable()
    coef = cable.coefficients()
    xi = np.asarray(scene.xi, dtype=float)
    omega = scene.omega()
    omega_nd = omega * cable.length / cable.speed      # eq. 2 (tau = U t / L), as TowedCable.omega
    grid = (xi[:, None], omega_nd[None, :])
    H = transfer_function(coef, *grid).H
    cs = c_star(coef, *grid)
    message = ""
    try:
        t0 = damping_time(cable, zero="bessel")
    except SolverError as err:
        t0, message = math.nan, f"damping time: {err}"
    return TowedAnalysis(scene=scene, coefficients=scene.coefficients(), xi=xi, omega=omega, omega_nd=omega_nd,
                         H=H, phase_lag=cs.phase_lag, c_star=cs.c_star, modes=modes(coef, scene.n_modes),
                         damping_time_s=float(t0), damping_time_report_s=float(damping_time(cable, zero="report")),
                         water_pulley_c_star=water_pulley_c_star(coef), success=not message, message=message)
