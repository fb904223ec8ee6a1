"""Transfer function, phase velocity and c* of a towed cable (Kennedy & Strahan (1981) eq. 26-27).

``H(xi, omega) = v(xi; omega) / v(0; omega) = |H| exp(-i psi)`` (eq. 26): cross-track
motion at ``xi`` per unit tow-point motion.  ``psi`` is the phase lag, unwrapped
along the cable from ``psi(0) = 0``.  Phase velocity ``c = omega / psi'(xi)`` (eq. 27a);
the measurable ``c* = omega xi / psi(xi)`` between the tow point and ``xi`` (eq. 27b);
both in units of U.  At low frequency ``c* -> 1 + 1/p`` (eq. 14, "water pulley").
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from ..errors import ParameterError
from ..results import ResultBase, timed
from .bessel import exact_solution, mpmath_solution, real_order_solution
from .equation import Coefficients

__all__ = [
    "SOLUTIONS",
    "TransferGrid",
    "c_star",
    "fine_xi",
    "phase_lag",
    "phase_velocity",
    "transfer_function",
    "transfer_grid",
    "water_pulley_c_star",
]


def _bvp(coef, xi, omega):
    from .bvp import bvp_solution
    return bvp_solution(coef, xi, omega)


# The solution routes of eq. 3 (one protocol whatever the route): name -> v(coef, xi, omega),
# the complex amplitude along the cable with v(0) = 1, broadcasting xi and omega (nondimensional).
# A user route is any callable with that signature, passed as ``method=`` (as scipy's solve_ivp
# takes an OdeSolver class): no registration, no global state.
SOLUTIONS = {
    "exact": exact_solution,            # complex order, 0F1 series (+ mpmath where lossy)
    "real": real_order_solution,        # report's eq. 16, real order p
    "mpmath": mpmath_solution,          # complex order, arbitrary precision, slow
    "bvp": _bvp,                        # independent shooting solution of the ODE
}


def _method(method):
    if callable(method):
        return method
    try:
        return SOLUTIONS[method]
    except (KeyError, TypeError):
        raise ParameterError("method", method, f"must be one of {sorted(SOLUTIONS)} or a callable "
                             "v(coef, xi, omega) with v(0) = 1") from None


def _check_xi(xi):
    xi = np.asarray(xi, dtype=float)
    if np.any(~np.isfinite(xi)) or np.any(xi < 0):
        raise ParameterError("xi", xi.min() if xi.size else xi, "must be finite and >= 0")
    return xi


def _check_omega(omega):
    omega = np.asarray(omega, dtype=float)
    if np.any(~np.isfinite(omega)) or np.any(omega <= 0):
        raise ParameterError("omega", omega.min() if omega.size else omega, "must be finite and > 0")
    return omega


def transfer_function(coef: Coefficients, xi, omega, method: str = "exact"):
    """Complex ``H(xi, omega)`` (Kennedy & Strahan (1981) eq. 26); xi, omega broadcast.

    Parameters
    ----------
    coef : Coefficients
        Nondimensional coefficients of eq. 3 (:meth:`TowedCable.coefficients`).
    xi : array_like
        Position along the cable, x / L (0 at the tow point).
    omega : array_like
        Nondimensional angular frequency, omega L / U (> 0).
    method : str or callable, optional
        Route to the solution (:data:`SOLUTIONS`): 'exact' (complex order, 0F1 series), 'real'
        (the report's real order, eq. 16), 'mpmath' (arbitrary precision), 'bvp' (shooting),
        or a callable ``v(coef, xi, omega)`` with ``v(0) = 1``.

    Returns
    -------
    ndarray of complex
        H = eta(xi) / eta(0), broadcast shape of ``xi`` and ``omega``.
    """
    return _method(method)(coef, _check_xi(xi), _check_omega(omega))


def fine_xi(xi_max: float, omega_max: float, n_min: int = 65) -> np.ndarray:
    """xi grid from the tow point fine enough to unwrap the phase lag (steps << pi)."""
    # |psi'| <~ omega (c >~ 1): 8 points per radian keeps unwrap steps far below pi
    n = max(n_min, int(np.ceil(8.0 * omega_max * xi_max)) + 1)
    return np.linspace(0.0, xi_max, n)


def phase_lag(coef: Coefficients, xi, omega, method: str = "exact", n_min: int = 65):
    """Unwrapped phase lag ``psi(xi, omega) = -arg H`` (eq. 26), shape (len(xi), len(omega)).

    The phase is unwrapped along a fine xi grid from the tow point (psi(0) = 0).

    Parameters
    ----------
    coef : Coefficients
        Nondimensional coefficients of eq. 3 (:meth:`TowedCable.coefficients`).
    xi : array_like
        Position along the cable, x / L (0 at the tow point).
    omega : array_like
        Nondimensional angular frequency, omega L / U (> 0).
    method : str or callable, optional
        Route to the solution (:data:`SOLUTIONS`): 'exact' (complex order, 0F1 series), 'real'
        (the report's real order, eq. 16), 'mpmath' (arbitrary precision), 'bvp' (shooting),
        or a callable ``v(coef, xi, omega)`` with ``v(0) = 1``.
    n_min : int, optional
        Least number of points of the fine unwrapping grid.

    Returns
    -------
    ndarray
        psi (rad), shape (len(xi), len(omega)).
    """
    xi = np.atleast_1d(_check_xi(xi))
    omega = np.atleast_1d(_check_omega(omega))
    fine = np.unique(np.concatenate([fine_xi(float(xi.max()), float(omega.max()), n_min), xi]))
    H = _method(method)(coef, fine[:, None], omega[None, :])
    psi = -np.unwrap(np.angle(H), axis=0)
    idx = np.searchsorted(fine, xi)
    return psi[idx]


def c_star(coef: Coefficients, xi, omega, method: str = "exact"):
    """``c* = omega xi / psi(xi)`` (Kennedy & Strahan (1981) eq. 27b), shape (len(xi), len(omega)).

    At ``xi = 0`` the limit is the local phase velocity (eq. 27a).

    Parameters
    ----------
    coef : Coefficients
        Nondimensional coefficients of eq. 3 (:meth:`TowedCable.coefficients`).
    xi : array_like
        Position along the cable, x / L (0 at the tow point).
    omega : array_like
        Nondimensional angular frequency, omega L / U (> 0).
    method : str or callable, optional
        Route to the solution (:data:`SOLUTIONS`): 'exact' (complex order, 0F1 series), 'real'
        (the report's real order, eq. 16), 'mpmath' (arbitrary precision), 'bvp' (shooting),
        or a callable ``v(coef, xi, omega)`` with ``v(0) = 1``.

    Returns
    -------
    ndarray
        c* in units of the tow speed U, shape (len(xi), len(omega)).
    """
    xi = np.atleast_1d(_check_xi(xi))
    omega = np.atleast_1d(_check_omega(omega))
    psi = phase_lag(coef, xi, omega, method)
    with np.errstate(divide="ignore", invalid="ignore"):
        cs = omega[None, :] * xi[:, None] / psi
    at0 = xi == 0
    if np.any(at0):
        cs[at0] = phase_velocity(coef, 0.0, omega)[None, :]
    return cs


def phase_velocity(coef: Coefficients, xi, omega):
    """Local phase velocity ``c = omega / psi'(xi)`` (Kennedy & Strahan (1981) eq. 27a).

    ``psi' = -Im(v'/v)`` from the exact solution and its derivative.

    Parameters
    ----------
    coef : Coefficients
        Nondimensional coefficients of eq. 3 (:meth:`TowedCable.coefficients`).
    xi : array_like
        Position along the cable, x / L (0 at the tow point).
    omega : array_like
        Nondimensional angular frequency, omega L / U (> 0).

    Returns
    -------
    ndarray
        c in units of the tow speed U.
    """
    xi = _check_xi(xi)
    omega = _check_omega(omega)
    v, dv = exact_solution(coef, xi, omega, derivative=True)
    return omega / (-np.imag(dv / v))


def water_pulley_c_star(coef: Coefficients) -> float:
    """Low-frequency limit ``c* = 1 + 1/p`` (Kennedy & Strahan (1981) eq. 14).

    Parameters
    ----------
    coef : Coefficients
        Nondimensional coefficients of eq. 3 (:meth:`TowedCable.coefficients`).

    Returns
    -------
    float
        c* in units of the tow speed U.
    """
    return 1.0 + 1.0 / coef.p


@dataclass(frozen=True, kw_only=True)
class TransferGrid(ResultBase):
    """H and c* on a (xi, omega) grid; arrays have shape (len(xi), len(omega)).

    Nondimensional: xi = x/L along the cable, omega in units of U/L (Kennedy & Strahan (1981) eq. 5)."""

    xi: np.ndarray
    omega: np.ndarray
    H: np.ndarray
    c_star: np.ndarray
    method: str
    success: bool = True
    message: str = ""
    stats: dict = field(default_factory=dict)

    VARIABLES: ClassVar[dict] = {"xi": ("1", "position along the cable x/L (0 at the tow point)"),
                                 "omega": ("1", "nondimensional angular frequency omega L/U"),
                                 "H_abs": ("1", "|H|, transfer function magnitude (eq. 26)"),
                                 "H_phase": ("rad", "arg H (eq. 26)"),
                                 "c_star": ("1", "nondimensional mean phase velocity c* (eq. 27b)")}

    def to_xarray(self):
        """Labelled ``xarray.Dataset`` with dims (xi, omega)."""
        import xarray as xr

        return xr.Dataset(
            {"H_abs": (("xi", "omega"), np.abs(self.H)),
             "H_phase": (("xi", "omega"), np.angle(self.H)),
             "c_star": (("xi", "omega"), self.c_star)},
            coords={"xi": self.xi, "omega": self.omega},
            attrs={"method": self.method, "source": "Kennedy & Strahan (1981) eq. 26-27"})


@timed
def transfer_grid(coef: Coefficients, xi, omega, method: str = "exact") -> TransferGrid:
    """H (eq. 26) and c* (eq. 27b) over a grid; ``xi`` must start at 0 and be fine
    enough (steps of psi < pi) for unwrapping directly along it.

    Parameters
    ----------
    coef : Coefficients
        Nondimensional coefficients of eq. 3 (:meth:`TowedCable.coefficients`).
    xi : array_like
        Increasing positions x / L starting at 0.
    omega : array_like
        Nondimensional angular frequency, omega L / U (> 0).
    method : str or callable, optional
        Route to the solution (:data:`SOLUTIONS`): 'exact' (complex order, 0F1 series), 'real'
        (the report's real order, eq. 16), 'mpmath' (arbitrary precision), 'bvp' (shooting),
        or a callable ``v(coef, xi, omega)`` with ``v(0) = 1``.

    Returns
    -------
    TransferGrid
        H and c* with dims (xi, omega).
    """
    xi = np.asarray(_check_xi(xi), dtype=float)
    omega = np.asarray(_check_omega(omega), dtype=float)
    if xi.ndim != 1 or omega.ndim != 1 or xi[0] != 0.0 or np.any(np.diff(xi) <= 0):
        raise ParameterError("xi", xi[:3], "must be a 1-D increasing grid starting at 0")
    H = _method(method)(coef, xi[:, None], omega[None, :])
    psi = -np.unwrap(np.angle(H), axis=0)
    with np.errstate(divide="ignore", invalid="ignore"):
        cs = omega[None, :] * xi[:, None] / psi
    cs[0] = phase_velocity(coef, 0.0, omega)
    return TransferGrid(xi=xi, omega=omega, H=H, c_star=cs,
                        method=method if isinstance(method, str) else getattr(method, "__name__", repr(method)))
