"""Independent numerical particular solution: the BVP of Kennedy & Strahan (1981) eq. 6 by shooting.

The bounded solution is the one regular at the zero-tension point ``xi* = -a/b``, the
free end of the "lengthened cable" that replaces the drogue (report p. 10).  With
``sigma = xi* - xi`` (so ``a + b xi = -b sigma``) the eq. 4 ODE reads

    b sigma v_ss + (c + 2 i beta omega) v_s - (i omega d - omega^2) v = 0 .

Boundedness of ``v''`` at ``sigma = 0`` forces ``q v_s(0) = r v(0)`` with
``q = (c + 2 i beta omega)/b``, ``r = (i omega d - omega^2)/b``; differentiating once more,
``(1 + q) v_ss(0) = r v_s(0)``.  These two Taylor terms start the solution at a small
``sigma_0``; ``scipy.integrate.solve_ivp`` (DOP853, complex) integrates the ODE toward the
tow point, and the result is scaled so that ``v(xi = 0) = 1`` (eq. 6b).  The unwanted
solution ``~ sigma^(1-q)`` (``Re(1-q) = -p < 0``) decays in the direction of integration,
so the shooting is stable.  No Bessel or hypergeometric function is used.

(``solve_bvp`` with its singular-term option ``S`` was tried first: when it converges it
agrees to 1e-10, but its mesh refinement next to the singular end exceeds any node budget
for about half of the frequencies, so it is not used.)
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from ..errors import ParameterError, SolverError
from .equation import Coefficients

__all__ = ["bvp_solution", "shoot_from_zero_tension"]


def shoot_from_zero_tension(coef: Coefficients, omega: float, sigma_eval, *, rtol: float = 1e-11):
    """Regular solution with ``v(sigma=0) = 1`` at ``sigma_eval`` (strictly ascending), and v_s."""
    xs = coef.xi_turn
    if not xs > 0:
        raise ParameterError("coefficients.a", coef.a, "need a < 0 (tension at the tow point "
                             "exceeding the fluid-inertia term) for the shooting route")
    q = complex(coef.q(omega))
    r = (1j * omega * coef.d - omega**2) / coef.b
    # start where the neglected cubic Taylor term is ~1e-13 relative
    s0 = min(1e-4 * xs, 1e-4 / max(abs(r), 1.0))
    v1 = r / q
    v2 = r * v1 / (1.0 + q)
    y0 = np.array([1.0 + v1 * s0 + 0.5 * v2 * s0**2, v1 + v2 * s0], dtype=complex)

    def rhs(sigma, y):
        return np.array([y[1], (r * y[0] - q * y[1]) / sigma])

    sigma_eval = np.asarray(sigma_eval, dtype=float)
    v = 1.0 + v1 * sigma_eval + 0.5 * v2 * sigma_eval**2       # Taylor start, used below s0
    dv = v1 + v2 * sigma_eval
    far = sigma_eval > s0
    if np.any(far):
        sol = solve_ivp(rhs, (s0, float(sigma_eval[far].max())), y0, method="DOP853",
                        t_eval=sigma_eval[far], rtol=rtol, atol=1e-300)
        if not sol.success:
            raise SolverError(f"shooting failed for omega = {omega:g}: {sol.message}")
        v[far], dv[far] = sol.y[0], sol.y[1]
    return v, dv


def bvp_solution(coef: Coefficients, xi, omega, *, rtol: float = 1e-11):
    """v(xi; omega) with v(0) = 1 from the shooting solution; xi, omega broadcast, xi <= xi*."""
    xi = np.asarray(xi, dtype=float)
    omega = np.asarray(omega, dtype=float)
    xi_b, om_b = np.broadcast_arrays(xi, omega)
    xs = coef.xi_turn
    if np.any(xi_b > xs):
        raise ParameterError("xi", float(xi_b.max()),
                             f"must be <= xi* = -a/b = {xs:.4g} for the shooting route")
    out = np.empty(xi_b.shape, dtype=complex)
    for om in np.unique(om_b):
        sel = om_b == om
        xis = xi_b[sel]
        sig = np.unique(np.concatenate([xs - xis, [xs]]))     # include the tow point
        v, _ = shoot_from_zero_tension(coef, float(om), sig, rtol=rtol)
        v_tow = v[-1]
        out[sel] = v[np.searchsorted(sig, xs - xis)] / v_tow
    return out
