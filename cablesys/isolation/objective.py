"""Symbolic objective and constraints of the isolation design, differentiable end to end.

Chain of CasADi expressions of the normalized design vector x (no finite differences):

1. p(x): the scene's parameter vector with the decision variables inserted (``problem.py``).
2. Steady state q_0(p): ``casadi.rootfinder`` (Newton) on the static residual f(q, 0, 0, p) = 0
   of the model (Wang 1971 eq. 47-48 with all rates zero). Its derivative is the implicit-
   function-theorem one, dq_0/dp = -(df/dq)^-1 df/dp, provided by CasADi.
3. Linearization about q_0 by the model's own AD Jacobians (``cablesys.linear.linearization``):
   M dq'' + C dq' + K dq = F0 z + F1 z' + F2 z'', y = Cq dq + Cv dq' + D0 z + D1 z' + D2 z''.
4. Transfer on a fixed frequency grid in real arithmetic: with Z = K - w^2 M + i w C (dJ included),
   [[Re Z, -Im Z], [Im Z, Re Z]] [Re Q; Im Q] = [Re F; Im F] for the buoy input z = (1, i) a
   (the top follows the surface orbit of Wang 1971 eq. 26 at x = 0, as in
   :mod:`cablesys.linear.stochastic`).
5. Response variances sigma^2 = int |Y(w)|^2 S(w) dw (trapezoid on the grid), the significant
   amplitude 2 sigma (Longuet-Higgins 1952), or the band RMS of the RAO.

The quadratic drag (eq. 32-45) has zero slope about a still-water equilibrium, so its
equivalent linearization comes from the Gaussian equivalent linearization
(:func:`cablesys.linear.stochastic.stochastic_response`): dJ = E[dr/dxi] - dr/dxi(q_0), the
drag damping C_eq *and* the drag excitation by the top velocity (dr/dz', the cable segments
move with the top) plus the small geometric averaging of K and M. Choice made here: dJ is a
*parameter* of the NLP, held fixed during one solve and updated between solves until the
design and dJ agree (an outer fixed-point iteration, ``solve.py``). Reason: making it
self-consistent inside the NLP would need the expected drag Jacobian E[dr/dxi] as a
symbolic function of the response covariance (a Gaussian expectation of |v| v per drag
element, a quadrature in 3 n_q + 6 dimensions in the library) plus the standard deviations
as extra variables and equality constraints; the held matrix keeps the NLP small and its
gradient exact for the problem it solves, and the fixed point is checked on convergence.
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from ..linear.linearization import functions, xi_blocks
from ..linear.spectra import jonswap
from ..linear.steady import static_residual
from ..linear.stochastic import BUOY
from ..model import CableModel
from ..model.design_variables import linear_map
from .problem import DesignSettings

# constraint rows: (kind, section index); kinds below
CONSTRAINT_KINDS = ("slack", "peak_tension", "static_strain")


def _trapezoid_weights(w: np.ndarray) -> np.ndarray:
    d = np.diff(w)
    out = np.zeros_like(w)
    out[:-1] += d / 2
    out[1:] += d / 2
    return out


def complex_solve(A, B, fr, fi):
    """(A + iB)(x_r + i x_i) = f_r + i f_i for small SX matrices, in real arithmetic.

    Gaussian elimination without pivoting on the complex matrix (an n x n complex elimination is
    about a quarter of the work of the equivalent 2n x 2n real QR that ``casadi.solve`` builds).
    The pivots are the successive Schur complements of the dynamic stiffness
    K - w^2 M + i w C; with every coordinate damped (C_eq > 0 on its diagonal) their imaginary
    parts do not vanish, so no pivoting is needed; ``test_design_objective`` checks the result
    against the stochastic linearization's own complex solve."""
    n = A.shape[0]
    ar = [[A[i, j] for j in range(n)] for i in range(n)]
    ai = [[B[i, j] for j in range(n)] for i in range(n)]
    br, bi = [fr[i] for i in range(n)], [fi[i] for i in range(n)]
    for k in range(n):
        den = ar[k][k] ** 2 + ai[k][k] ** 2
        inv_r, inv_i = ar[k][k] / den, -ai[k][k] / den
        for i in range(k + 1, n):
            mr = ar[i][k] * inv_r - ai[i][k] * inv_i
            mi = ar[i][k] * inv_i + ai[i][k] * inv_r
            for j in range(k + 1, n):
                ar[i][j], ai[i][j] = (ar[i][j] - (mr * ar[k][j] - mi * ai[k][j]),
                                      ai[i][j] - (mr * ai[k][j] + mi * ar[k][j]))
            br[i], bi[i] = br[i] - (mr * br[k] - mi * bi[k]), bi[i] - (mr * bi[k] + mi * br[k])
    xr, xi = [None] * n, [None] * n
    for k in reversed(range(n)):
        sr, si = br[k], bi[k]
        for j in range(k + 1, n):
            sr, si = sr - (ar[k][j] * xr[j] - ai[k][j] * xi[j]), si - (ar[k][j] * xi[j] + ai[k][j] * xr[j])
        den = ar[k][k] ** 2 + ai[k][k] ** 2
        xr[k] = (sr * ar[k][k] + si * ai[k][k]) / den
        xi[k] = (si * ar[k][k] - sr * ai[k][k]) / den
    return ca.vertcat(*xr), ca.vertcat(*xi)


def parameter_map(model: CableModel, variables: tuple):
    """(x -> p) as an SX Function of (x, p_base): the variables' values v.value(x_j) replace their parameters (times
    each target's factor), through the one linear map of :func:`cablesys.model.design_variables.linear_map`."""
    x = ca.SX.sym("x", len(variables))
    pb = ca.SX.sym("p_base", len(model.layout))
    keep, B = linear_map(model.layout, np.ones(len(model.layout)), variables)     # keep: 0 at every target, else 1
    theta = ca.vertcat(*[v.value(x[j]) for j, v in enumerate(variables)])
    p = keep * pb + ca.mtimes(ca.DM(B), theta)
    return ca.Function("design_parameters", [x, pb], [p], ["x", "p_base"], ["p"])


def static_rootfinder(model: CableModel) -> ca.Function:
    """Newton rootfinder q_0(q_guess, p) of the model's static residual (differentiable; the
    residual is the one :func:`cablesys.linear.steady.steady_state` solves, built once per model)."""
    return model.cache.get("design_steady", lambda: ca.rootfinder(
        "design_steady", "newton", static_residual(model), {"abstol": 1e-12, "max_iter": 50, "error_on_fail": False}))


def _frequency_response_squared(nq: int, ny: int, nz: int) -> ca.Function:
    """SX function (M, C, K, F0, F1, F2, Cq, Cv, D0, D1, D2, w) -> |Y(w)|^2 of the outputs for the
    buoy input z = (1, i) (step 4 of the module docstring, real arithmetic)."""
    mats = [ca.SX.sym(name, *shape) for name, shape in (
        ("M", (nq, nq)), ("C", (nq, nq)), ("K", (nq, nq)), ("F0", (nq, nz)), ("F1", (nq, nz)), ("F2", (nq, nz)),
        ("Cq", (ny, nq)), ("Cv", (ny, nq)), ("D0", (ny, nz)), ("D1", (ny, nz)), ("D2", (ny, nz)))]
    w = ca.SX.sym("w")
    M, C, K, F0, F1, F2, Cq, Cv, D0, D1, D2 = mats
    dr, di = np.real(BUOY), np.imag(BUOY)
    A, B = K - w**2 * M, w * C
    Fr = ca.mtimes(F0, dr) - w * ca.mtimes(F1, di) - w**2 * ca.mtimes(F2, dr)
    Fi = ca.mtimes(F0, di) + w * ca.mtimes(F1, dr) - w**2 * ca.mtimes(F2, di)
    Qr, Qi = complex_solve(A, B, Fr, Fi)
    Yr = ca.mtimes(Cq, Qr) - w * ca.mtimes(Cv, Qi) + ca.mtimes(D0, dr) - w * ca.mtimes(D1, di) - w**2 * ca.mtimes(D2, dr)
    Yi = ca.mtimes(Cq, Qi) + w * ca.mtimes(Cv, Qr) + ca.mtimes(D0, di) + w * ca.mtimes(D1, dr) - w**2 * ca.mtimes(D2, di)
    return ca.Function("design_response_w", [*mats, w], [Yr**2 + Yi**2])


def response_functions(model: CableModel, n_omega: int) -> ca.Function:
    """SX Function (q0, p, dJ, omega, wS, wband) -> (significant, band_rms, sigma of [y_b, tensions], mean tensions,
    static strains), for a frequency grid of ``n_omega`` points.

    ``dJ`` is added to the exact residual Jacobian dr/dxi at q0 (the held equivalent-drag part). ``omega`` is the
    grid (rad/s), ``wS`` the quadrature weights times the sea spectrum there (m^2 s), ``wband`` the normalized
    weights of the RAO band (:func:`sea_weights`): the sea and the band are arguments, so one function serves every
    sea state, band and grid of that size (the structure only, ``n_omega``, is part of its cache key)."""
    b = xi_blocks(model)
    n = model.n_sections
    nq = model.nq
    q0 = ca.SX.sym("q0", nq)
    p = ca.SX.sym("p", len(model.layout))
    d_jac = ca.SX.sym("dJ", nq, b["n"])
    omega = ca.SX.sym("omega", n_omega)
    w_s = ca.SX.sym("wS", n_omega)
    w_band = ca.SX.sym("wband", n_omega)
    xi = ca.vertcat(q0, ca.SX.zeros(b["n"] - nq))
    fns = functions(model)
    J = fns["jac"](xi, p) + d_jac
    y0, Jy = fns["out_jac"](xi, p)
    M, C, K = -J[:, b["qdd"]], -J[:, b["qd"]], -J[:, b["q"]]
    F0, F1, F2 = J[:, b["z"]], J[:, b["zd"]], J[:, b["zdd"]]
    rows = [model.output_index("y_b", n - 1)] + [model.output_index("tension_mid", i) for i in range(n)]
    Cq, Cv = Jy[rows, b["q"]], Jy[rows, b["qd"]]
    D0, D1, D2 = Jy[rows, b["z"]], Jy[rows, b["zd"]], Jy[rows, b["zdd"]]
    # one frequency's |Y|^2 as an SX function, built once and inlined at every grid frequency
    # (the same expression graph as writing it out per frequency, built in a fraction of the time)
    per_w = _frequency_response_squared(nq, len(rows), F0.shape[1])
    var = ca.SX.zeros(len(rows))
    band_ms = 0
    for k in range(n_omega):
        mag2 = per_w(M, C, K, F0, F1, F2, Cq, Cv, D0, D1, D2, omega[k])
        var += w_s[k] * mag2
        band_ms += w_band[k] * mag2[0]
    sigma = ca.sqrt(var)
    mean_t = ca.vertcat(*[y0[model.output_index("tension_mid", i)] for i in range(n)])
    strain = []
    for i in range(n):
        l_r, t_r, ae = (p[model.layout.section_index(i, f"cable.{name}")] for name in ("length", "tension_ref", "ae"))
        l_0 = l_r - t_r * l_r / ae                                                # eq. 1
        strain.append(q0[model.q_index("u", i)] / l_0)
    return ca.Function("design_response", [q0, p, d_jac, omega, w_s, w_band],
                       [2.0 * sigma[0], ca.sqrt(band_ms), sigma, mean_t, ca.vertcat(*strain)],
                       ["q0", "p", "dJ", "omega", "wS", "wband"],
                       ["significant", "band_rms", "sigma", "mean_tension", "static_strain"])


def sea_weights(settings: DesignSettings) -> tuple:
    """(omega, wS, wband) of :func:`response_functions` for ``settings``: the grid (rad/s), the trapezoid weights
    times the JONSWAP spectrum (hs, tp, gamma), and the band's normalized trapezoid weights."""
    omega = settings.omega
    wts = _trapezoid_weights(omega)
    band = (omega >= settings.band[0]) & (omega <= settings.band[1])
    return omega, wts * jonswap(omega, settings.hs, settings.tp, settings.gamma), wts * band / np.sum(wts * band)


def constraint_names(n: int) -> tuple:
    return tuple(f"{kind}_{i + 1}" for kind in CONSTRAINT_KINDS for i in range(n))


def nlp_functions(model: CableModel, settings: DesignSettings, variables: tuple, p_base: np.ndarray):
    """The NLP in MX: f(x; dJ), g(x; dJ) with g <= 0 meaning 'met', plus a report function.

    The NLP parameter vector is (dJ flattened column-major, q_guess of the rootfinder).

    Constraints per section i (normalized to order one):
      slack_i:         (TENS_i - (T_i - n_sigma sigma_Ti)) / T_i <= 0    (Wang 1971 eq. 54 floor)
      peak_tension_i:  (T_i + n_sigma sigma_Ti) / WLL_i - 1 <= 0
      static_strain_i: (u_0i / l_0i) / limit_i - 1 <= 0
    """
    n = model.n_sections
    nq = model.nq
    pmap = parameter_map(model, variables)
    rf = static_rootfinder(model)
    omega, w_s, w_band = sea_weights(settings)
    resp = model.cache.get(f"design_response {omega.size}", lambda: response_functions(model, omega.size))
    x = ca.MX.sym("x", len(variables))
    n_xi = xi_blocks(model)["n"]
    dj_flat = ca.MX.sym("dJ", nq * n_xi)
    q_guess = ca.MX.sym("q_guess", nq)
    p = pmap(x, ca.DM(p_base))
    q0 = rf(q_guess, p)
    significant, band_rms, sigma, mean_t, strain = resp(q0, p, ca.reshape(dj_flat, nq, n_xi), ca.DM(omega),
                                                        ca.DM(w_s), ca.DM(w_band))
    obj = significant if settings.objective == "significant" else band_rms
    tens = [float(p_base[k]) for k in model.layout.section_indices("cable.tension_floor")]
    g = ([(tens[i] - (mean_t[i] - settings.n_sigma * sigma[1 + i])) / mean_t[i] for i in range(n)]
         + [(mean_t[i] + settings.n_sigma * sigma[1 + i]) / settings.working_load[i] - 1 for i in range(n)]
         + [strain[i] / settings.strain_limit[i] - 1 for i in range(n)])
    g = ca.vertcat(*g)
    par = ca.vertcat(dj_flat, q_guess)
    report = ca.Function("design_report", [x, par], [obj, g, sigma, mean_t, strain, q0, p],
                         ["x", "par"], ["objective", "g", "sigma", "mean_tension", "static_strain", "q0", "p"])
    return x, par, obj, g, report
