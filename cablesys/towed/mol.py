"""Time-domain check of the Kennedy & Strahan (1981) PDE: method of lines with a CasADi integrator.

The PDE (eq. 3) ``eta_tt + 2 beta eta_xt + (a + b xi) eta_xx + c eta_x + d eta_t = 0`` is
discretized on the lengthened cable ``0 <= xi <= xi* = -a/b`` (report p. 10) with second-order
central differences; at ``xi*`` the tension vanishes, ``eta_xx`` drops out and both
characteristics leave the domain, so no boundary condition is imposed there (one-sided
differences instead).  States ``(eta_1..eta_N, w_1..w_N, s, k)`` with ``w = eta_t`` and a
harmonic oscillator ``s = sin(omega tau)``, ``k = cos(omega tau)`` driving the tow point
``eta_0 = s`` (eq. 6b).  The linear ODE ``x' = A x`` is integrated by CasADi (CVODES, BDF),
and the steady harmonic response at ``xi`` gives ``H`` independently of any Bessel function.
The eigenvalues of the free operator give the complementary modes (eq. 18-23).
"""

from __future__ import annotations

import numpy as np

from ..errors import ParameterError, SolverError
from .equation import Coefficients

__all__ = ["mol_matrix", "forced_response", "slowest_mode"]


def mol_matrix(coef: Coefficients, n: int, omega: float = 0.0):
    """``(A, xi)``: the (2n + 2) x (2n + 2) MOL matrix (last two rows: the forcing oscillator)
    and the node positions ``xi_1..xi_n`` (``xi_n = xi*``)."""
    if n < 4:
        raise ParameterError("n", n, "need at least 4 nodes")
    xs = coef.xi_turn
    if not xs > 0:
        raise ParameterError("coefficients.a", coef.a, "need a < 0 (zero-tension point downstream)")
    h = xs / n
    xi = h * np.arange(1, n + 1)
    m = 2 * n + 2
    A = np.zeros((m, m))
    E, W, S, K = 0, n, 2 * n, 2 * n + 1          # offsets of eta, w, and the oscillator rows

    def eta(j):          # column of eta_j (j = 0 is the tow point: eta_0 = s)
        return S if j == 0 else E + j - 1

    def w(j):            # column of w_j (w_0 = d s/dtau = omega k)
        return W + j - 1

    for j in range(1, n + 1):
        r = W + j - 1
        A[E + j - 1, w(j)] = 1.0                          # eta_t = w
        tension = coef.a + coef.b * xi[j - 1]
        if j < n:                                          # central differences
            d1 = {j - 1: -0.5 / h, j + 1: 0.5 / h}
            d2 = {j - 1: 1.0 / h**2, j: -2.0 / h**2, j + 1: 1.0 / h**2}
        else:                                              # one-sided at xi* (outflow, no BC)
            d1 = {j - 2: 0.5 / h, j - 1: -2.0 / h, j: 1.5 / h}
            d2 = {}
            tension = 0.0
        for i, cf in d1.items():
            A[r, eta(i)] += -coef.c * cf                   # - c eta_x
            if i == 0:
                A[r, K] += -2.0 * coef.beta * cf * omega   # - 2 beta w_x, w_0 = omega k
            else:
                A[r, w(i)] += -2.0 * coef.beta * cf
        for i, cf in d2.items():
            A[r, eta(i)] += -tension * cf                  # - (a + b xi) eta_xx
        A[r, w(j)] += -coef.d                              # - d eta_t
    A[S, K] = omega                                        # s' = omega k
    A[K, S] = -omega                                       # k' = -omega s
    return A, xi


def forced_response(coef: Coefficients, omega: float, xi_obs, *, n: int = 200, settle: float | None = None,
                    periods: int = 2, integrator: str = "cvodes"):
    """Complex ``H(xi_obs, omega)`` from a CasADi time integration started at rest.

    Integrates to ``settle + periods`` forcing periods (``settle`` defaults to 12 damping
    times of the slowest mode) and fits ``eta = Im[H exp(i omega tau)]`` over the last periods.

    Parameters
    ----------
    coef : Coefficients
        Nondimensional coefficients of eq. 3 (:meth:`TowedCable.coefficients`).
    omega : float
        Nondimensional forcing frequency omega L / U (> 0).
    xi_obs : array_like
        Observation points x / L within the discretized cable.
    n : int, optional
        Number of MOL nodes.
    settle : float, optional
        Nondimensional settling time before the fit.
    periods : int, optional
        Forcing periods fitted.
    integrator : str, optional
        CasADi integrator plugin ('cvodes', 'idas', ...).

    Returns
    -------
    ndarray of complex
        H at ``xi_obs``.
    """
    import casadi as ca

    if not omega > 0:
        raise ParameterError("omega", omega, "must be > 0")
    A, xi = mol_matrix(coef, n, omega)
    if settle is None:
        settle = 12.0 / slowest_mode(coef, n=max(40, n // 4)).imag
    period = 2 * np.pi / omega
    t_fit = settle + np.linspace(0.0, periods * period, 40 * periods + 1)
    x = ca.SX.sym("x", A.shape[0])
    F = ca.integrator("mol", integrator, {"x": x, "ode": ca.mtimes(ca.DM(A), x)}, 0.0, list(t_fit),
                      {"abstol": 1e-11, "reltol": 1e-10, "max_num_steps": 200000})
    x0 = np.zeros(A.shape[0])
    x0[-1] = 1.0                                            # k(0) = cos 0
    try:
        X = np.array(F(x0=x0)["xf"])
    except RuntimeError as err:
        raise SolverError(f"CasADi {integrator} failed on the MOL system: {err}") from None
    full = np.vstack([X[2 * n], X[:n]])                     # eta at xi = 0 (= s), xi_1..xi_n
    nodes = np.r_[0.0, xi]
    xi_obs = np.atleast_1d(np.asarray(xi_obs, dtype=float))
    if np.any(xi_obs < 0) or np.any(xi_obs > nodes[-1]):
        raise ParameterError("xi", xi_obs, f"must be in [0, xi* = {nodes[-1]:.4g}]")
    j = np.clip(np.searchsorted(nodes, xi_obs) - 1, 0, n - 1)
    wgt = (xi_obs - nodes[j]) / (nodes[j + 1] - nodes[j])      # linear interpolation, O(h^2)
    eta_obs = (1.0 - wgt)[:, None] * full[j] + wgt[:, None] * full[j + 1]
    basis = np.column_stack([np.sin(omega * t_fit), np.cos(omega * t_fit)])
    coefs, *_ = np.linalg.lstsq(basis, eta_obs.T, rcond=None)
    return coefs[0] + 1j * coefs[1]


def slowest_mode(coef: Coefficients, n: int = 200) -> complex:
    """Least-damped complementary eigenfrequency ``omega_1`` (eq. 22-23) from the MOL operator:
    ``eta ~ exp(i omega tau)`` so ``omega = -i lambda`` for each eigenvalue ``lambda`` of A.

    Parameters
    ----------
    coef : Coefficients
        Nondimensional coefficients of eq. 3 (:meth:`TowedCable.coefficients`).
    n : int, optional
        Number of MOL nodes.

    Returns
    -------
    complex
        omega_1 (nondimensional, Im > 0: damped).
    """
    A, _ = mol_matrix(coef, n)
    lam = np.linalg.eigvals(A[:2 * n, :2 * n])
    k = int(np.argmax(lam.real))
    if lam[k].real >= 0:
        raise SolverError(f"MOL operator has an undamped mode, lambda = {lam[k]}")
    return complex(-1j * lam[k])
