"""Independent numerical particular solution: the complex BVP of Kennedy & Strahan (1981) eq. 6.

The bounded solution is the one regular at the zero-tension point ``xi* = -a/b``,
the free end of the "lengthened cable" that replaces the drogue (report p. 10).
With ``sigma = xi* - xi`` (so ``a + b xi = -b sigma``) the eq. 4 ODE reads

    b sigma v_ss + (c + 2 i beta omega) v_s - (i omega d - omega^2) v = 0,

a first-order system ``y' = S y / sigma + f`` with ``y = (v, v_s)``,
``S = [[0, 0], [(i omega d - omega^2)/b, -q]]``, ``f = (v_s, 0)``, which is exactly
the singular-term form that ``scipy.integrate.solve_bvp`` handles (it enforces
``S y(0) = 0``: bounded ``v''`` at zero tension).  The other condition is
``v(xi = 0) = 1`` (eq. 6b).  No Bessel or hypergeometric function is used, so the
result checks both the exact and the real-order forms.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_bvp

from ..errors import ParameterError, SolverError
from .equation import Coefficients

__all__ = ["bvp_solution", "solve_particular_bvp"]


def solve_particular_bvp(coef: Coefficients, omega: float, *, tol: float = 1e-6,
                         nodes: int | None = None):
    """Solve the eq. 6 BVP for one real ``omega`` on ``0 <= xi <= xi*``.

    Returns the ``solve_bvp`` result; ``sol.sol(sigma)[0]`` is v at ``xi = xi* - sigma``.
    """
    xs = coef.xi_turn
    if not xs > 0:
        raise ParameterError("coefficients.a", coef.a, "need a < 0 (tension at the tow point "
                             "exceeding the fluid-inertia term) for the BVP route")
    q = complex(coef.q(omega))
    r = (1j * omega * coef.d - omega**2) / coef.b
    S = np.array([[0.0, 0.0], [r, -q]], dtype=complex)

    def fun(sigma, y):
        return np.vstack([y[1], np.zeros_like(y[1])])

    def bc(ya, yb):
        return np.array([r * ya[0] - q * ya[1], yb[0] - 1.0])

    n = nodes or int(max(200, 40 * omega * xs))
    sigma = np.linspace(0.0, xs, n)
    # guess: water-pulley wave exp(-i omega xi / c) decaying slowly (eq. 13-14)
    k = omega * coef.d / coef.c
    v0 = np.exp(-1j * k * (xs - sigma))
    y0 = np.vstack([v0, 1j * k * v0])
    sol = solve_bvp(fun, bc, sigma, y0, S=S, tol=tol, max_nodes=50000)
    if not sol.success:
        # the relative collocation residual is noisy next to the singular end; a
        # looser residual tol on a finer fixed mesh still gives v to ~1e-9 (tests)
        sigma = np.linspace(0.0, xs, 4 * n)
        v0 = np.exp(-1j * k * (xs - sigma))
        sol = solve_bvp(fun, bc, sigma, np.vstack([v0, 1j * k * v0]), S=S,
                        tol=max(tol, 1e-4), max_nodes=50000)
    if not sol.success:
        raise SolverError(f"solve_bvp failed for omega = {omega:g}: {sol.message}; "
                          "try more nodes or a looser tol")
    return sol


def bvp_solution(coef: Coefficients, xi, omega, *, tol: float = 1e-6):
    """v(xi; omega), v(0) = 1, from the collocation BVP; xi, omega broadcast, xi <= xi*."""
    xi = np.asarray(xi, dtype=float)
    omega = np.asarray(omega, dtype=float)
    xi_b, om_b = np.broadcast_arrays(xi, omega)
    if np.any(xi_b > coef.xi_turn):
        raise ParameterError("xi", float(xi_b.max()),
                             f"must be <= xi* = -a/b = {coef.xi_turn:.4g} for the BVP route")
    out = np.empty(xi_b.shape, dtype=complex)
    for om in np.unique(om_b):
        sel = om_b == om
        sol = solve_particular_bvp(coef, float(om), tol=tol)
        out[sel] = sol.sol(coef.xi_turn - xi_b[sel])[0]
    return out
