"""Closed-form elastic catenaries, the checks of the node model's statics (:mod:`cablesys.statics.catenary`).

- :func:`elastic_catenary`: a line hanging from its top with a body's weight and a horizontal force at its lower end
  (Irvine 1981, eq. 2.17-2.18);
- :func:`seabed_catenary`: a mooring line from an anchor on a flat seabed, part of it on the bed with Coulomb
  friction; :func:`seabed_catenary_span` the fairlead span that lays a given length on the bed.
"""

from __future__ import annotations

import numpy as np

from ..errors import SolverError


def elastic_catenary(s, *, weight_per_length, ea, horizontal, bottom_weight):
    """Elastic catenary hanging from its top, loaded at its lower end (closed form).

    Arc length ``s`` (unstretched) is measured up from the lower end, where the cable carries a
    vertical force ``bottom_weight`` and a horizontal force ``horizontal`` (H > 0). With V(s) =
    W_b + w s and T = sqrt(H^2 + V^2) (Irvine 1981, Cable Structures, eq. 2.17-2.18 rearranged):

        x(s) = H s / EA + (H / w) [asinh(V(s)/H) - asinh(W_b/H)],
        z(s) = (W_b s + w s^2 / 2) / EA + (1 / w) [T(s) - T(0)],

    the horizontal and vertical offsets of the point at s from the lower end.

    Parameters
    ----------
    s : array
        Unstretched arc length from the lower end (m).
    weight_per_length, ea, horizontal, bottom_weight : float
        w (N/m), EA (N, per unstretched length), H (N), W_b (N).

    Returns
    -------
    (numpy.ndarray, numpy.ndarray, numpy.ndarray)
        x(s), z(s) (m) and the tension T(s) (N).
    """
    s = np.asarray(s, float)
    w, H, Wb = weight_per_length, horizontal, bottom_weight
    V = Wb + w * s
    T = np.hypot(H, V)
    x = H * s / ea + H / w * (np.arcsinh(V / H) - np.arcsinh(Wb / H))
    zz = (Wb * s + 0.5 * w * s**2) / ea + (T - np.hypot(H, Wb)) / w
    return x, zz, T


def seabed_catenary(*, length, weight_per_length, ea, span, height, friction=0.0):
    """The elastic mooring-line catenary with seabed contact and friction (closed form).

    A uniform line of unstretched length L, weight in water w per unit length and axial stiffness
    EA runs from an anchor on a flat, rigid seabed to a fairlead ``span`` X horizontally and
    ``height`` Z above it. Along the bed (arc length s from the anchor, 0 <= s <= L_B) the tension is
    T(s) = max(H - mu w (L_B - s), 0): the line was laid by pulling its fairlead away, the friction
    mu w per unit length acting towards the anchor; the suspended part (arc sigma = s - L_B from the
    touchdown point, V = w sigma) is Irvine's elastic catenary with zero slope at touchdown (Irvine
    1981, Cable Structures, eq. 2.17-2.18; the same assembly as MAP++'s and MoorDyn's catenary
    with seabed friction, Jonkman 2007, NREL/TP-500-41958, sec. 2.2):

        x(s) = s + (1/EA) int_0^s T ds                                  (on the bed)
        x(L_B + sigma) = x(L_B) + (H/w) asinh(w sigma / H) + H sigma / EA
        z(L_B + sigma) = (H/w) [sqrt(1 + (w sigma / H)^2) - 1] + w sigma^2 / (2 EA),

    with L_B = L - V_F / w. When V_F > w L the line does not touch: V_A = V_F - w L and
    x(s) = (H/w)[asinh(V(s)/H) - asinh(V_A/H)] + H s / EA, z(s) = (H/w)[sqrt(1 + (V(s)/H)^2) -
    sqrt(1 + (V_A/H)^2)] + (V_A s + w s^2/2) / EA, V(s) = V_A + w s. (H, V_F) solve
    x(L) = X, z(L) = Z (scipy.optimize.root).

    Parameters
    ----------
    length, weight_per_length, ea : float
        L (m), w (N/m), EA (N).
    span, height : float
        X, Z (m) of the fairlead from the anchor (Z > 0 up).
    friction : float
        mu, the seabed friction coefficient along the line (>= 0).

    Returns
    -------
    dict
        ``H``, ``V_F`` (N) at the fairlead; ``H_A``, ``V_A`` (N, up) at the anchor; ``L_B`` (m) on the
        bed; ``touchdown_x`` (m); ``shape(s) -> (x, z, T)`` for unstretched arc s from the anchor.
    """
    from scipy.optimize import root

    L, w, EA, X, Z, mu = length, weight_per_length, ea, span, height, friction

    def bed(s, H, L_B):
        """x offset and tension on the bed at arc s <= L_B."""
        s0 = max(L_B - H / (mu * w), 0.0) if mu > 0 else 0.0
        sp = np.maximum(s - s0, 0.0)
        integral = H * sp - mu * w * (L_B * sp - 0.5 * (np.maximum(s, s0) ** 2 - s0**2))
        return s + integral / EA, np.maximum(H - mu * w * (L_B - s), 0.0)

    def shape(s, H, VF):
        s = np.asarray(s, float)
        L_B = L - VF / w
        if L_B <= 0:                                     # not touching
            VA = VF - w * L
            V = VA + w * s
            x = H / w * (np.arcsinh(V / H) - np.arcsinh(VA / H)) + H * s / EA
            z = H / w * (np.hypot(1, V / H) - np.hypot(1, VA / H)) + (VA * s + 0.5 * w * s**2) / EA
            return x, z, np.hypot(H, V)
        xb, Tb = bed(np.minimum(s, L_B), H, L_B)
        sig = np.maximum(s - L_B, 0.0)
        x = xb + H / w * np.arcsinh(w * sig / H) + H * sig / EA
        z = H / w * (np.hypot(1, w * sig / H) - 1) + 0.5 * w * sig**2 / EA
        return x, z, np.where(s <= L_B, Tb, np.hypot(H, w * sig))

    def residual(v):
        H, VF = np.exp(v[0]), v[1]
        x, z, _ = shape(L, H, VF)
        return [(x - X) / L, (z - Z) / L]

    # start: the inextensible catenary's estimate (Peyrot & Goulois 1979, as used by MAP++)
    lam = 0.2 if L <= np.hypot(X, Z) else np.sqrt(3 * ((L**2 - Z**2) / X**2 - 1)) if L**2 - Z**2 > X**2 else 1e6
    H0 = max(abs(w * X / (2 * lam)), 1e-3 * w * L)
    V0 = 0.5 * w * (Z / np.tanh(lam) + L)
    for scale in (1.0, 0.1, 10.0, 0.01, 100.0):        # hybr from the estimate, then from H0 scaled
        sol = root(residual, [np.log(H0 * scale), V0], method="hybr", options={"xtol": 1e-15})
        res = float(max(abs(np.array(residual(sol.x)))))
        if res < 1e-12:
            break
    if not res < 1e-12:                 # judged by the residual (hybr may stop at xtol on the root itself)
        raise SolverError(f"seabed catenary not solved: {sol.message} (residual {res:.3g})")
    H, VF = float(np.exp(sol.x[0])), float(sol.x[1])
    L_B = max(L - VF / w, 0.0)
    H_A = max(H - mu * w * L_B, 0.0) if L_B > 0 else H
    V_A = 0.0 if L_B > 0 else VF - w * L
    return dict(H=H, V_F=VF, H_A=H_A, V_A=V_A, L_B=L_B, touchdown_x=float(shape(L_B, H, VF)[0]),
                shape=lambda s: shape(s, H, VF))


def seabed_catenary_span(*, length, weight_per_length, ea, height, seabed_length, friction=0.0) -> float:
    """The fairlead span X at which :func:`seabed_catenary` lays ``seabed_length`` L_B on the bed.

    The suspended arc sigma = L - L_B carries V_F = w sigma; H solves z(sigma) = Z (scipy brentq) and
    X = L_B + (1/EA) int_0^L_B T ds + (H/w) asinh(w sigma / H) + H sigma / EA (the formulas of
    :func:`seabed_catenary`). All in m, N, N/m.
    """
    from scipy.optimize import brentq

    L, w, EA, Z, L_B, mu = length, weight_per_length, ea, height, seabed_length, friction
    sig = L - L_B
    H = brentq(lambda H: H / w * (np.hypot(1, w * sig / H) - 1) + 0.5 * w * sig**2 / EA - Z,
               1e-9 * w * L, 1e9 * w * L, xtol=1e-12 * w * L, rtol=4 * np.finfo(float).eps)
    s0 = max(L_B - H / (mu * w), 0.0) if mu > 0 else 0.0
    on_bed = H * (L_B - s0) - mu * w * (L_B * (L_B - s0) - 0.5 * (L_B**2 - s0**2))
    return float(L_B + on_bed / EA + H / w * np.arcsinh(w * sig / H) + H * sig / EA)


def suspended_catenary(length: float, anchor, arcs) -> np.ndarray:
    """Points (x, y down) at arc lengths ``arcs`` from the top (0, 0) of the inextensible catenary of ``length``
    hanging between the top and ``anchor`` (x != 0): Y = a cosh((X - X0) / a) + C (Y up), a from
    sqrt(L^2 - dY^2) = 2 a sinh(h / (2 a)), X0 = h / 2 - a atanh(dY / L) (Irvine 1981, *Cable Structures*, ch. 1)."""
    from scipy.optimize import brentq
    h, dY = abs(float(anchor[0])), -float(anchor[1])
    target = np.sqrt(length**2 - dY**2) / h                       # 2 a sinh(h / 2a) / h = target > 1
    hi = 1.0                                   # sinh(u) / u grows from 1 at u = 0: double until it passes the target
    while np.sinh(hi) / hi < target:
        hi *= 2.0
    u = brentq(lambda u: np.sinh(u) / u - target, 1e-9, hi)        # u = h / (2 a)
    a = h / (2.0 * u)
    x0 = 0.5 * h - a * np.arctanh(dY / length)
    X = x0 + a * np.arcsinh(np.asarray(arcs, float) / a - np.sinh(x0 / a))
    Y = a * (np.cosh((X - x0) / a) - np.cosh(x0 / a))
    return np.column_stack([np.sign(anchor[0]) * X, -Y])
