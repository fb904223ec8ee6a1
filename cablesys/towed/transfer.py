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
    "TowedResponse",
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


def _points(xi, omega):
    """Checked ``xi`` and ``omega`` broadcast to one shape (NumPy rules), as float arrays."""
    xi, omega = _check_xi(xi), _check_omega(omega)
    try:
        xi_b, om_b = np.broadcast_arrays(xi, omega)
    except ValueError:
        raise ParameterError("xi, omega", f"shapes {xi.shape} and {omega.shape}",
                             "must broadcast against each other (NumPy rules)") from None
    return np.array(xi_b, dtype=float), np.array(om_b, dtype=float)


def _route_name(method) -> str:
    return method if isinstance(method, str) else getattr(method, "__name__", repr(method))


def _phase_lag(coef, xi_b, om_b, method, n_min: int = 65):
    """psi at broadcast points: unwrapped from the tow point along a fine xi grid per distinct omega."""
    route = _method(method)
    xs, ws = xi_b.ravel(), om_b.ravel()
    if xs.size == 0:
        return np.zeros(xi_b.shape)
    w_unique, w_index = np.unique(ws, return_inverse=True)
    fine = np.unique(np.concatenate([fine_xi(float(xs.max()), float(w_unique.max()), n_min), xs]))
    H = route(coef, fine[:, None], w_unique[None, :])
    psi = -np.unwrap(np.angle(H), axis=0)
    return psi[np.searchsorted(fine, xs), w_index.ravel()].reshape(xi_b.shape)


def _phase_velocity(coef, xi_b, om_b):
    v, dv = exact_solution(coef, xi_b, om_b, derivative=True)
    return om_b / (-np.imag(dv / v))


@timed
def transfer_function(coef: Coefficients, xi, omega, method: str = "exact") -> "TowedResponse":
    """Complex ``H(xi, omega)`` (Kennedy & Strahan (1981) eq. 26) at broadcast points.

    Parameters
    ----------
    coef : Coefficients
        Nondimensional coefficients of eq. 3 (:meth:`TowedCable.coefficients`).
    xi : float or array_like
        Position along the cable, x / L (0 at the tow point).
    omega : float or array_like
        Nondimensional angular frequency, omega L / U (> 0); broadcast against ``xi`` (NumPy rules).
    method : str or callable, optional
        Route to the solution (:data:`SOLUTIONS`): 'exact' (complex order, 0F1 series), 'real'
        (the report's real order, eq. 16), 'mpmath' (arbitrary precision), 'bvp' (shooting),
        or a callable ``v(coef, xi, omega)`` with ``v(0) = 1``.

    Returns
    -------
    TowedResponse
        ``H`` = eta(xi) / eta(0) (complex, nondimensional) on the broadcast shape of ``xi`` and
        ``omega`` (0-d for two scalars), with those points.
    """
    xi_b, om_b = _points(xi, omega)
    H = np.broadcast_to(_method(method)(coef, xi_b, om_b), xi_b.shape).astype(complex)
    return TowedResponse(xi=xi_b, omega=om_b, H=H, method=_route_name(method))


#: Most points of the phase-unwrapping grid along the cable (8 per radian of omega xi): with one
#: complex value per point and frequency this bounds the memory a transfer grid allocates.
MAX_XI_POINTS = 1_000_000
#: Largest nondimensional frequency omega L / U the unwrapping grid resolves (1.25e5).
MAX_OMEGA_ND = (MAX_XI_POINTS - 1) / 8.0


def fine_xi(xi_max: float, omega_max: float, n_min: int = 65) -> np.ndarray:
    """xi grid from the tow point fine enough to unwrap the phase lag (steps << pi).

    Raises ParameterError when ``omega_max * xi_max`` would need more than ``MAX_XI_POINTS`` points.
    """
    # |psi'| <~ omega (c >~ 1): 8 points per radian keeps unwrap steps far below pi
    need = 8.0 * float(omega_max) * float(xi_max)
    if not need <= MAX_XI_POINTS - 1:
        raise ParameterError("omega L/U", float(omega_max),
                             f"must be <= {MAX_OMEGA_ND:.6g} at xi = {float(xi_max):.6g} (the phase lag is unwrapped "
                             f"on 8 points per radian along the cable, at most {MAX_XI_POINTS} points): "
                             "a shorter cable, a lower frequency or a higher tow speed")
    n = max(n_min, int(np.ceil(need)) + 1)
    return np.linspace(0.0, xi_max, n)


@timed
def phase_lag(coef: Coefficients, xi, omega, method: str = "exact", n_min: int = 65) -> "TowedResponse":
    """Unwrapped phase lag ``psi(xi, omega) = -arg H`` (Kennedy & Strahan (1981) eq. 26), rad.

    The phase is unwrapped along a fine xi grid from the tow point (psi(0) = 0), one grid for
    all points, so a point's value does not depend on the others asked with it.

    Parameters
    ----------
    coef : Coefficients
        Nondimensional coefficients of eq. 3 (:meth:`TowedCable.coefficients`).
    xi : float or array_like
        Position along the cable, x / L (0 at the tow point).
    omega : float or array_like
        Nondimensional angular frequency, omega L / U (> 0); broadcast against ``xi`` (NumPy rules).
    method : str or callable, optional
        Route to the solution (:data:`SOLUTIONS`): 'exact' (complex order, 0F1 series), 'real'
        (the report's real order, eq. 16), 'mpmath' (arbitrary precision), 'bvp' (shooting),
        or a callable ``v(coef, xi, omega)`` with ``v(0) = 1``.
    n_min : int, optional
        Least number of points of the fine unwrapping grid.

    Returns
    -------
    TowedResponse
        ``phase_lag`` psi (rad) on the broadcast shape of ``xi`` and ``omega``.
    """
    xi_b, om_b = _points(xi, omega)
    psi = _phase_lag(coef, xi_b, om_b, method, n_min)
    return TowedResponse(xi=xi_b, omega=om_b, phase_lag=psi, method=_route_name(method))


@timed
def c_star(coef: Coefficients, xi, omega, method: str = "exact") -> "TowedResponse":
    """``c* = omega xi / psi(xi)`` (Kennedy & Strahan (1981) eq. 27b) at broadcast points.

    At ``xi = 0`` the limit is the local phase velocity (eq. 27a).

    Parameters
    ----------
    coef : Coefficients
        Nondimensional coefficients of eq. 3 (:meth:`TowedCable.coefficients`).
    xi : float or array_like
        Position along the cable, x / L (0 at the tow point).
    omega : float or array_like
        Nondimensional angular frequency, omega L / U (> 0); broadcast against ``xi`` (NumPy rules).
    method : str or callable, optional
        Route to the solution (:data:`SOLUTIONS`): 'exact' (complex order, 0F1 series), 'real'
        (the report's real order, eq. 16), 'mpmath' (arbitrary precision), 'bvp' (shooting),
        or a callable ``v(coef, xi, omega)`` with ``v(0) = 1``.

    Returns
    -------
    TowedResponse
        ``c_star`` in units of the tow speed U and the ``phase_lag`` psi (rad) it came from, on
        the broadcast shape of ``xi`` and ``omega``.
    """
    xi_b, om_b = _points(xi, omega)
    psi = _phase_lag(coef, xi_b, om_b, method)
    with np.errstate(divide="ignore", invalid="ignore"):
        cs = np.asarray(om_b * xi_b / psi, dtype=float)
    at0 = xi_b == 0
    if np.any(at0):
        cs[at0] = _phase_velocity(coef, xi_b[at0], om_b[at0])
    return TowedResponse(xi=xi_b, omega=om_b, phase_lag=psi, c_star=cs, method=_route_name(method))


@timed
def phase_velocity(coef: Coefficients, xi, omega) -> "TowedResponse":
    """Local phase velocity ``c = omega / psi'(xi)`` (Kennedy & Strahan (1981) eq. 27a).

    ``psi' = -Im(v'/v)`` from the exact solution and its derivative.

    Parameters
    ----------
    coef : Coefficients
        Nondimensional coefficients of eq. 3 (:meth:`TowedCable.coefficients`).
    xi : float or array_like
        Position along the cable, x / L (0 at the tow point).
    omega : float or array_like
        Nondimensional angular frequency, omega L / U (> 0); broadcast against ``xi`` (NumPy rules).

    Returns
    -------
    TowedResponse
        ``phase_velocity`` c in units of the tow speed U, on the broadcast shape.
    """
    xi_b, om_b = _points(xi, omega)
    return TowedResponse(xi=xi_b, omega=om_b, phase_velocity=_phase_velocity(coef, xi_b, om_b), method="exact")


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


# nondimensional quantities of the towed theory: name -> (unit, long name); omega here is omega L / U
TOWED_VARIABLES = {"xi": ("1", "position along the cable x/L (0 at the tow point)"),
                   "omega": ("1", "nondimensional angular frequency omega L/U"),
                   "H_abs": ("1", "|H|, transfer function magnitude (eq. 26)"),
                   "H_phase": ("rad", "arg H (eq. 26)"),
                   "phase_lag": ("rad", "unwrapped phase lag psi = -arg H (eq. 26)"),
                   "c_star": ("1", "mean phase velocity c* over the tow speed U (eq. 27b)"),
                   "phase_velocity": ("1", "local phase velocity c over the tow speed U (eq. 27a)"),
                   "point": ("1", "point index")}


def _layout(xi: np.ndarray, omega: np.ndarray):
    """Dimensions and coordinates for values at broadcast points: (xi, omega) for an outer grid,
    one of them for a line, else a flat ``point`` dimension with xi and omega on it."""
    if xi.ndim == 2 and np.all(xi == xi[:, :1]) and np.all(omega == omega[:1, :]):
        return ("xi", "omega"), {"xi": xi[:, 0], "omega": omega[0]}, None
    x, w = xi.ravel(), omega.ravel()
    if x.size > 1 and np.all(x == x[0]) and np.unique(w).size == w.size:
        return ("omega",), {"omega": w, "xi": x[0]}, -1
    if x.size > 1 and np.all(w == w[0]) and np.unique(x).size == x.size:
        return ("xi",), {"xi": x, "omega": w[0]}, -1
    return ("point",), {"xi": ("point", x), "omega": ("point", w)}, -1


@dataclass(frozen=True, kw_only=True)
class TowedResponse(ResultBase):
    """Towed-cable response at points (xi, omega) broadcast together (Kennedy & Strahan (1981) eq. 26-27).

    Nondimensional throughout: ``xi`` = x/L, ``omega`` = omega L / U (eq. 2, 5), both on the
    broadcast shape; of ``H`` (complex, eq. 26), ``phase_lag`` (rad), ``c_star`` (eq. 27b) and
    ``phase_velocity`` (eq. 27a; both in units of the tow speed U) the ones the call computed are
    arrays of that shape, the others None.
    """

    xi: np.ndarray
    omega: np.ndarray
    method: str
    H: np.ndarray | None = None
    phase_lag: np.ndarray | None = None
    c_star: np.ndarray | None = None
    phase_velocity: np.ndarray | None = None
    success: bool = True
    message: str = ""
    stats: dict = field(default_factory=dict)

    VARIABLES: ClassVar[dict] = TOWED_VARIABLES

    def _values(self) -> dict:
        out = {}
        if self.H is not None:
            out["H_abs"], out["H_phase"] = np.abs(self.H), np.angle(self.H)
        for name in ("phase_lag", "c_star", "phase_velocity"):
            if getattr(self, name) is not None:
                out[name] = getattr(self, name)
        return out

    def summary(self) -> dict:
        """The points' shape and range and the computed quantities (value lists up to 50 points).

        Returns
        -------
        dict
            JSON-able (complex H as real/imag).
        """
        doc = {**super().summary(), "shape": list(self.xi.shape),
               "xi_range": [float(self.xi.min()), float(self.xi.max())] if self.xi.size else [],
               "omega_range": [float(self.omega.min()), float(self.omega.max())] if self.omega.size else [],
               "quantities": sorted(self._values())}
        if self.xi.size <= 50:
            doc["values"] = {k: np.ravel(v).tolist() for k, v in self._values().items()}
        return doc

    def to_xarray(self):
        """The computed quantities on (xi, omega), xi, omega or a flat ``point`` dimension.

        Returns
        -------
        xarray.Dataset
        """
        import xarray as xr
        dims, coords, flat = _layout(self.xi, self.omega)
        data = {k: (dims, np.ravel(v) if flat else v) for k, v in self._values().items()}
        return xr.Dataset(data, coords=coords,
                          attrs={"method": self.method, "source": "Kennedy & Strahan (1981) eq. 26-27"})


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

    VARIABLES: ClassVar[dict] = TOWED_VARIABLES

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
    cs[0] = _phase_velocity(coef, np.zeros_like(omega), omega)
    return TransferGrid(xi=xi, omega=omega, H=H, c_star=cs, method=_route_name(method))
