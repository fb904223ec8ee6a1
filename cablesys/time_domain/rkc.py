"""Runge-Kutta-Chebyshev (RKC), second order, s stages: an explicit method stable far along the negative real axis.

The segmented cable's Voigt damping C_I makes its shortest element modes overdamped: the ODE's spectrum
holds a real eigenvalue of about -4 C_I / (m l_e^2) (m mass per length, l_e = L / N), which grows as N^2
while every oscillatory eigenvalue stays bounded (the light-cage lift, 60 m of 30 mm wire, C_I 1e5 N s:
-6.7e3, -2.9e4, -1.2e5 1/s at N = 16, 32, 64, the largest imaginary part 435 1/s at each). Classical RK4
must keep h |lambda| <= 2.78 on that real eigenvalue, so its step falls as N^-2 and a run costs N^3. RKC's
stability region is a strip along the real axis of length beta(s) ~ 0.65 s^2, so s stages per step carry
a step s^2 / 4 times longer than one RK4 stage does: the cost of the damping grows as N instead of N^2.

The scheme (Sommeijer, Shampine & Verwer 1997, "RKC: an explicit solver for parabolic PDEs", J. Comput.
Appl. Math. 88, eq. 2.3-2.8; van der Houwen & Sommeijer 1980), with damping eps = 2/13:

    w0 = 1 + eps / s^2,  w1 = T_s'(w0) / T_s''(w0),  b_j = T_j''(w0) / T_j'(w0)^2 (b_0 = b_1 = b_2),
    a_j = 1 - b_j T_j(w0),
    Y_0 = y_n,  Y_1 = Y_0 + mu~_1 h F_0,                                       mu~_1 = b_1 w1
    Y_j = (1 - mu_j - nu_j) Y_0 + mu_j Y_{j-1} + nu_j Y_{j-2} + mu~_j h F(t_n + c_{j-1} h, Y_{j-1}) + gamma~_j h F_0,
          mu_j = 2 b_j w0 / b_{j-1},  nu_j = -b_j / b_{j-2},  mu~_j = 2 b_j w1 / b_{j-1},  gamma~_j = -a_{j-1} mu~_j,
    y_{n+1} = Y_s,   c_j = w1 T_j''(w0) / T_j'(w0) (j >= 2), c_1 = c_2 / T_2'(w0),

T_j the Chebyshev polynomials of the first kind. Its stability polynomial is R_s(z) = a_s + b_s T_s(w0 + w1 z).
"""

from __future__ import annotations

import functools

import numpy as np

from ..errors import ParameterError

EPS = 2.0 / 13.0          # the damping of the stability polynomial (Sommeijer et al. 1997)
MAX_STAGES = 200


@functools.lru_cache(maxsize=64)
def coefficients(s: int, eps: float = EPS) -> dict:
    """The RKC coefficients of ``s`` stages (s >= 2): ``w0``, ``w1``, ``a``, ``b``, ``mu``, ``nu``, ``mut``, ``gam``, ``c``
    (arrays indexed by stage 0..s; see the module docstring)."""
    s = int(s)
    if not 2 <= s <= MAX_STAGES:
        raise ParameterError("stages", s, f"RKC needs an integer number of stages in [2, {MAX_STAGES}]")
    w0 = 1.0 + eps / s**2
    T, dT, d2T = np.zeros(s + 1), np.zeros(s + 1), np.zeros(s + 1)
    T[0], T[1], dT[1] = 1.0, w0, 1.0
    for j in range(2, s + 1):                          # Chebyshev recurrences and their derivatives at w0
        T[j] = 2 * w0 * T[j - 1] - T[j - 2]
        dT[j] = 2 * T[j - 1] + 2 * w0 * dT[j - 1] - dT[j - 2]
        d2T[j] = 4 * dT[j - 1] + 2 * w0 * d2T[j - 1] - d2T[j - 2]
    w1 = dT[s] / d2T[s]
    b = np.zeros(s + 1)
    b[2:] = d2T[2:] / dT[2:] ** 2
    b[0] = b[1] = b[2]
    a = 1.0 - b * T
    mu, nu, mut, gam = (np.zeros(s + 1) for _ in range(4))
    mut[1] = b[1] * w1
    for j in range(2, s + 1):
        mu[j], nu[j] = 2 * b[j] * w0 / b[j - 1], -b[j] / b[j - 2]
        mut[j] = 2 * b[j] * w1 / b[j - 1]
        gam[j] = -a[j - 1] * mut[j]
    c = np.zeros(s + 1)
    c[2:] = w1 * d2T[2:] / dT[2:]
    c[1] = c[2] / (4 * w0)
    return {"w0": w0, "w1": w1, "a": a, "b": b, "mu": mu, "nu": nu, "mut": mut, "gam": gam, "c": c}


def amplification(z, s: int):
    """R_s(z) = a_s + b_s T_s(w0 + w1 z): the factor one step multiplies the mode exp(lambda t) by, z = h lambda."""
    k = coefficients(s)
    x = k["w0"] + k["w1"] * np.asarray(z, dtype=complex)
    t0, t1 = np.ones_like(x), x
    for _ in range(2, s + 1):
        t0, t1 = t1, 2 * x * t1 - t0
    return k["a"][s] + k["b"][s] * t1


def stages_for(h: float, eigenvalues, margin: float = 0.97) -> int | None:
    """The fewest stages s whose step h keeps every mode of the spectrum stable, |R_s(h lambda)| <= ``margin``
    where the mode is damped by more than that in one exact step (|exp(h lambda)| <= margin) and
    |R_s(h lambda)| <= 1 elsewhere, checked on every eigenvalue; None when no s <= MAX_STAGES does. (Inside its
    real interval R_s ripples up to ~1 - eps / 3 = 0.95: a stiff mode decays by at least that much a step, not as
    fast as exactly; the margin stays above the ripple.)"""
    z = h * np.asarray(eigenvalues, dtype=complex).ravel()
    bound = np.where(np.abs(np.exp(z)) <= margin, margin, 1.0 + 1e-9)
    s = max(2, int(np.ceil(np.sqrt(max(-z.real.min(), 0.0) / 0.65))) - 1)
    while s <= MAX_STAGES:
        if np.all(np.abs(amplification(z, s)) <= bound):
            return s
        s += 1
    return None


def step(f, x, t, h, s: int):
    """One RKC step of ``x' = f(x, t)`` from (x, t) over h with ``s`` stages (symbolic or numeric ``x``)."""
    k = coefficients(s)
    f0 = f(x, t)
    prev, cur = x, x + k["mut"][1] * h * f0
    for j in range(2, s + 1):
        nxt = ((1 - k["mu"][j] - k["nu"][j]) * x + k["mu"][j] * cur + k["nu"][j] * prev
               + k["mut"][j] * h * f(cur, t + k["c"][j - 1] * h) + k["gam"][j] * h * f0)
        prev, cur = cur, nxt
    return cur
