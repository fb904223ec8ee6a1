"""The straight cable and the N-element cable against the continuous cable, in closed form.

A linear estimate of the error of Wang's straight cable and of the segmented cable with N elements
against the converged (continuous) cable, from quantities the scene gives. The cable's small motion
about its static line splits into two one-dimensional problems (Irvine 1981, "Cable Structures",
ch. 3-4; Wang 1971 eq. 17-25 for the straight cable's two directions):

- transverse: a taut string whose tension grows linearly toward the top by the cable's weight in
  water (the hanging chain, :func:`hanging_string`; Wang's straight cable has the mean tension),
  mass m_v per length with the added mass (Wang eq. 23-24), normal drag;
- axial: a rod, stiffness AE (+ i omega C_I, Voigt, Wang eq. 46), mass m per length, tangential
  friction.

Each is driven at the top by the part of the top motion along (or normal to) the static cable and
carries the body (virtual mass, drag) at its lower end. In a 3-D scene the static cable lies in the vertical
plane of the flow (:func:`~.indicators.relative_flow`, heading beta; the plane x-y without a flow): the top's
surge and sway are turned into that plane and across it, and the motion across it drives a second string, the
same string with the drag slope about the flow across the flow, half of that along it (the cross-flow drag
|v_n| v_n about v_n = U e_1 has the slopes 2 |U| along e_1 and |U| along e_2). With w(s) e^{i omega t}, k^2 = (m omega^2 -
i omega c) / S (S = T or AE), the continuous member's end forces are exact (the dynamic stiffness
of a string/rod; e.g. Clough & Penzien, "Dynamics of Structures", ch. 19):

    F_top  = (S/L) (b W_s - a W_b),     F_body = (S/L) (a W_s - b W_b),
    a = kL / sin kL,  b = kL cot kL,

and the body obeys -M omega^2 W_b + i omega c_b W_b = F_body. Wang's straight cable is the
Rayleigh-Ritz model with the linear shape (consistent mass: the kinetic energy of eq. 22-25
integrates the straight line), i.e. one linear finite element; the segmented cable is N linear
elements with the mass lumped half to each node (:mod:`cablesys.model.segmented`) and the drag shared
by virtual work. Both are solved in the same complex arithmetic; their differences from the
continuous member are the estimates. The drag enters as the equivalent linear damping of the
harmonic (describing-function) balance, c = (8 / 3 pi) 1/2 rho C_D A |V| (Roberts & Spanos,
"Random Vibration and Statistical Linearization", ch. 5; Borgman 1967), plus the slope
rho C_D A |U| of the drag about a current U, with |V| from the response itself (fixed point).

What this leaves out (said in :mod:`.estimate`): the static bow under current, slack, and the
start-up transients of slow modes that a time-domain comparison over a finite window contains.
"""

from __future__ import annotations

import cmath
import dataclasses
import functools
import math

import numpy as np
from scipy.linalg.lapack import zgtsv

from ..scene import Scene
from .indicators import relative_flow, top_phasors

K_HARMONIC = 8.0 / (3.0 * math.pi)   # describing function of |v| v for v = V sin(theta)
FIXED_POINT_ITERATIONS = 12
FIXED_POINT_TOLERANCE = 1e-9         # step in log |W_b| at which the drag's fixed point has converged
VARYING = 1e-3                       # relative change of the tension along a string below which it is uniform


@dataclasses.dataclass(frozen=True)
class Member:
    """One direction of one section: a string (transverse) or a rod (axial) with an end mass."""

    length: float          # m
    stiffness: complex     # T (string, N) or AE + i omega C_I (rod, N)
    mass: float            # per unit length (kg/m)
    drag: float            # 1/2 rho C_D d (normal) or 1/2 rho C_t pi d (tangential), kg/m^2
    end_mass: float        # body virtual mass in this direction (kg)
    end_drag: float        # 1/2 rho C_D A of the body in this direction (kg/m)
    current: float         # steady relative flow normal to the member (m/s), 0 for the rod
    gradient: float = 0.0  # dS/ds, stiffness growth per metre toward the top (string: weight in water along it, N/m)

    def varies(self) -> bool:
        """True when the stiffness changes along the member by more than VARYING (a hanging string)."""
        return abs(self.gradient) * self.length > VARYING * abs(self.stiffness)

    def end_stiffness(self) -> tuple[float, float]:
        """(top, bottom) stiffness of a varying member (the mean +- gradient L / 2)."""
        half = 0.5 * self.gradient * self.length
        return self.stiffness.real + half, self.stiffness.real - half


def exact(mb: Member, omega: float, c: float, cb: float) -> tuple:
    """(W_b, F_body, F_top) per unit top amplitude of the continuous member (module docstring); a
    string whose tension grows toward the top (:meth:`Member.varies`) by :func:`hanging_string`."""
    if mb.varies():
        return hanging_string(mb, omega, c, cb)
    k = cmath.sqrt((mb.mass * omega**2 - 1j * omega * c) / mb.stiffness)
    x = k * mb.length
    if abs(x) < 1e-6:
        a, b = 1.0 + x * x / 6.0, 1.0 - x * x / 3.0
    else:
        a, b = x / cmath.sin(x), x * cmath.cos(x) / cmath.sin(x)
    s = mb.stiffness / mb.length
    wb = s * a / (s * b - mb.end_mass * omega**2 + 1j * omega * cb)
    return wb, s * (a - b * wb), s * (b - a * wb)


def hanging_string(mb: Member, omega: float, c: float, cb: float) -> tuple:
    """(W_b, F_body, F_top) of the continuous string whose tension grows linearly toward the top, T = T_b +
    g s (s up from the body, g the weight in water per length along it): the hanging chain of Irvine
    (1981, ch. 4; Bernoulli's). (T W')' + mu W = 0 with mu = m omega^2 - i omega c becomes Bessel's equation
    of order 0 in z = 2 sqrt(mu T) / g, so W = a H1_0(z) + b H2_0(z) and T W' = -(g z / 2)(a H1_1(z) +
    b H2_1(z)) (Hankel functions, exponentially scaled: each is normalised at the end where it is largest,
    so a strongly damped string does not overflow). W = 1 at the top; at the body
    Z_b W_b = T_b W'(0) (Z_b = -M omega^2 + i omega c_b); the top force is T_t W'(L).
    The uniform string's tension (the mean, :func:`exact`) puts the string modes of a cable weighing as
    much as its body off by tens of percent, and with them the elements' error near them."""
    from scipy.special import hankel1e, hankel2e
    t_top, t_bot = mb.end_stiffness()
    g = mb.gradient
    mu = mb.mass * omega**2 - 1j * omega * c
    zt, zb = 2.0 * cmath.sqrt(mu * t_top) / g, 2.0 * cmath.sqrt(mu * t_bot) / g
    # H1(z) = h1e(z) e^{iz}, H2(z) = h2e(z) e^{-iz}; with a = alpha e^{-i z1}, b = beta e^{i z2} the factors
    # are e^{i(z - z1)} and e^{-i(z - z2)}, at most 1 in size on [zb, zt] for (z1, z2) chosen by Im(zt - zb)
    z1, z2 = (zt, zb) if (zt - zb).imag <= 0 else (zb, zt)
    f1 = lambda z, v: complex(hankel1e(v, z)) * cmath.exp(1j * (z - z1))
    f2 = lambda z, v: complex(hankel2e(v, z)) * cmath.exp(-1j * (z - z2))
    zbody = -mb.end_mass * omega**2 + 1j * omega * cb
    # rows: W(zt) = 1; Z_b W(zb) + (g zb / 2) (alpha f1'(zb) + beta f2'(zb)) = 0, with T W' = -(g z / 2)(...)
    m11, m12 = f1(zt, 0), f2(zt, 0)
    m21 = zbody * f1(zb, 0) + 0.5 * g * zb * f1(zb, 1)
    m22 = zbody * f2(zb, 0) + 0.5 * g * zb * f2(zb, 1)
    det = m11 * m22 - m12 * m21
    alpha, beta = m22 / det, -m21 / det
    wb = alpha * f1(zb, 0) + beta * f2(zb, 0)
    return wb, zbody * wb, -0.5 * g * zt * (alpha * f1(zt, 1) + beta * f2(zt, 1))


CHAIN_OVERFLOW = 300.0   # |Re(n kappa)| above which cosh(n kappa) nears overflow: the banded solve instead


@functools.lru_cache(maxsize=64)
def drag_shares(points: int = 0) -> tuple[float, float]:
    """(diagonal, off-diagonal) of an element's drag matrix per c h: the drag at ``points`` mid-points
    of equal parts of the element with the velocity interpolated linearly and the force shared by virtual
    work, sum over s_k = (k + 1/2) / points of ((1 - s_k)^2, s_k (1 - s_k)) / points, as the segmented model
    evaluates it (:func:`cablesys.model.segmented.drag_points`); 0: exact integration (1/3, 1/6), the
    continuous limit. One point per element gives (1/4, 1/4): the rule changes with N (10 points per
    section shared among the elements), and with it the error, which then converges unevenly in N."""
    if points <= 0:
        return 1.0 / 3.0, 1.0 / 6.0
    s = (np.arange(points) + 0.5) / points
    return float(np.sum((1 - s) ** 2) / points), float(np.sum(s * (1 - s)) / points)


def elements(mb: Member, omega: float, c: float, cb: float, n: int, *, consistent: bool, points: int = 0) -> tuple:
    """(W_b, F_body, F_top) per unit top amplitude of ``n`` linear elements: consistent mass for
    Wang's straight cable (n = 1), lumped mass for the segmented cable; drag shared by virtual work.

    Every element alike, the free nodes obey o w_{k-1} + 2 d w_k + o w_{k+1} = 0 (d = D00 = D11,
    o = D01 = D10 of the element's dynamic stiffness D = K - omega^2 M + i omega C), a linear recurrence
    with w_k = cosh(k kappa) + B sinh(k kappa) / sinh(kappa), cosh(kappa) = -d / o, w_0 = 1 at the top
    and the body node o w_{n-1} + (d + Z_b) w_n = 0 (Z_b = -M omega^2 + i omega c_b). With
    cosh((n-1) kappa) = cosh(n kappa) cosh(kappa) - sinh(n kappa) sinh(kappa) this gives, with S_n =
    sinh(n kappa) / sinh(kappa),

        W_b = o / (o cosh(n kappa) - Z_b S_n),   F_body = Z_b W_b (the body's own balance),
        F_top = d + o w_1 = o B,   B = (o sinh(kappa) sinh(n kappa) - Z_b cosh(n kappa)) / (Z_b S_n - o cosh(n kappa)),

    free of the cancellations of the stiffness in d + o w (the forces are small differences of k / h
    terms). cosh(kappa) - 1 = -(d + o) / o is formed without the stiffness (d + o = -omega^2 m h / 2 +
    i omega c h / 2 for either mass), so kappa stays accurate as k h -> 0. Constant cost in n (the
    estimate tabulates n up to 128: choosing is part of the user's wait); near overflow
    (|Re(n kappa)| > CHAIN_OVERFLOW) the tridiagonal system is solved (:func:`elements_banded`)."""
    if mb.varies() and not consistent:
        return elements_banded(mb, omega, c, cb, n, consistent=consistent, points=points)
    h = mb.length / n
    k_el = mb.stiffness / h
    o_m = mb.mass * h / 6.0 if consistent else 0.0        # off-diagonal mass: consistent (m h / 6) or lumped
    o = -k_el - omega**2 * o_m + 1j * omega * c * h * drag_shares(points)[1]
    delta = -(-omega**2 * mb.mass * h / 2.0 + 1j * omega * c * h / 2.0) / o      # cosh(kappa) - 1
    kappa = 2.0 * cmath.asinh(cmath.sqrt(delta / 2.0))
    if abs((n * kappa).real) > CHAIN_OVERFLOW:
        return elements_banded(mb, omega, c, cb, n, consistent=consistent, points=points)
    sk, ch, sh = cmath.sinh(kappa), cmath.cosh(n * kappa), cmath.sinh(n * kappa)
    s_n = sh / sk if sk != 0 else complex(n)
    zb = -mb.end_mass * omega**2 + 1j * omega * cb
    den = zb * s_n - o * ch
    wb = -o / den
    return wb, zb * wb, o * (o * sk * sh - zb * ch) / den


def solve_tridiagonal(off: np.ndarray, diag: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """x of the symmetric tridiagonal system (``off`` below and above ``diag``): LAPACK zgtsv (Gaussian
    elimination with partial pivoting), ~1 us at these sizes where scipy.linalg.solve_banded's checks and
    wrapping cost ~14 us, and the estimate solves ~10^3 of them per choice."""
    if len(diag) == 1:
        return rhs / diag
    *_, x, info = zgtsv(off, diag, off, rhs)
    if info != 0:
        raise np.linalg.LinAlgError(f"singular tridiagonal system (zgtsv info {info})")
    return x


def elements_banded(mb: Member, omega: float, c: float, cb: float, n: int, *, consistent: bool,
                    points: int = 0) -> tuple:
    """:func:`elements` by a banded solve of the node equations (any attenuation), each element with the
    stiffness at its mid-point (a string whose tension grows toward the top: :meth:`Member.varies`;
    the consistent single element keeps the mean, Wang's straight cable)."""
    h = mb.length / n
    d_m, o_m = (mb.mass * h / 3.0, mb.mass * h / 6.0) if consistent else (mb.mass * h / 2.0, 0.0)
    d_c, o_c = drag_shares(points)
    dd = -omega**2 * d_m + 1j * omega * c * h * d_c           # D00 = D11 = k + dd of each element
    od = -omega**2 * o_m + 1j * omega * c * h * o_c           # D01 = D10 = -k + od
    # nodes 1..n free (n: the body), node 0 the top moving with amplitude 1: a tridiagonal system solved
    # banded in O(n): node j gets D11 of element j - 1 and D00 of element j, the body node D11 of the last
    # element and its own mass and drag; node 1 is driven by D10 of element 0 x 1
    zb = -mb.end_mass * omega**2 + 1j * omega * cb
    varying = mb.varies() and not consistent
    if varying:
        t_top, t_bot = mb.end_stiffness()
    if n <= SCALAR_MAX:
        k = ([(t_top + (t_bot - t_top) * ((j + 0.5) / n)) / h for j in range(n)] if varying
             else [mb.stiffness / h] * n)
        return _chain_scalar([kj + dd for kj in k], [od - kj for kj in k], zb)
    if varying:
        k = (t_top + (t_bot - t_top) * (np.arange(n) + 0.5) / n) / h + 0j     # element k from the top
    else:
        k = np.full(n, mb.stiffness / h, dtype=complex)
    d, o = k + dd, od - k
    diag = np.empty(n, complex)
    diag[:-1] = d[:-1] + d[1:]
    diag[-1] = d[-1] + zb
    f = np.zeros(n, complex)
    f[0] = -o[0]
    w = solve_tridiagonal(o[1:], diag, f)
    return w[-1], zb * w[-1], d[0] + o[0] * w[0]


SCALAR_MAX = 16      # elements up to which the node equations are eliminated in Python scalars (below)


def _chain_scalar(d: list, o: list, zb: complex) -> tuple:
    """:func:`elements_banded`'s (W_b, F_body, F_top) for a few elements, by eliminating the node equations
    from the body up (the continued fraction of the chain's impedances: Z_n = d_n + Z_b, Z_j = d_j + d_j+1 -
    o_j+1^2 / Z_j+1, the top node driven by -o_0): at n <= SCALAR_MAX ~4x cheaper than the LAPACK call's
    array set-up, and the estimate solves ~60 such chains per choice (Dale)."""
    n = len(d)
    z = [0j] * n
    z[-1] = d[-1] + zb
    for j in range(n - 2, -1, -1):
        z[j] = d[j] + d[j + 1] - o[j + 1] * o[j + 1] / z[j + 1]
    w0 = w = -o[0] / z[0]
    for j in range(1, n):
        w = -o[j] * w / z[j]
    return w, zb * w, d[0] + o[0] * w0


def respond(mb: Member, omega: float, top: complex, model: str, n: int = 1, points: int = 0) -> tuple:
    """(W_b, F_body, F_top) for top amplitude ``top`` (m); ``model`` "exact", "wang" or "segmented".

    The drag's equivalent damping follows the member's own response: a fixed point of the body
    amplitude, a = |W_b(a)|, solved in x = log a for R(x) = log|W_b(e^x)| - x = 0: one geometric relaxation
    step (at a drag-controlled resonance |W_b| ~ 1 / c ~ 1 / |W_b|, where plain substitution alternates
    between two values; the geometric mean lands on the root), then secant steps (superlinear: the
    relaxation alone gains only a factor ~2 per step away from resonance), relaxation again whenever a
    secant step is not usable; until the step is below FIXED_POINT_TOLERANCE."""
    if top == 0 or omega <= 0:
        return 0j, 0j, 0j

    def evaluate(x):
        amp = math.exp(x)
        v_b, v_c = omega * amp, omega * 0.5 * (abs(top) + amp)
        c = mb.drag * (K_HARMONIC * v_c + 2.0 * mb.current)
        cb = mb.end_drag * (K_HARMONIC * v_b + 2.0 * mb.current)
        r = (exact(mb, omega, c, cb) if model == "exact"
             else elements(mb, omega, c, cb, n, consistent=(model == "wang"), points=points))
        return r, math.log(max(abs(r[0] * top), 1e-300)) - x

    x = math.log(abs(top))
    r, res = evaluate(x)
    prev = None
    for _ in range(FIXED_POINT_ITERATIONS):
        step = 0.5 * res                                       # geometric relaxation
        if prev is not None and res != prev[1]:
            secant = -res * (x - prev[0]) / (res - prev[1])
            if math.isfinite(secant) and abs(secant) <= 2.0 * abs(res) + 1e-12:
                step = secant
        prev = (x, res)
        x += step
        r, res = evaluate(x)
        if abs(step) <= FIXED_POINT_TOLERANCE:
            break
    return tuple(v * top for v in r)


def members(scene: Scene, omega: float, angle: float) -> list[tuple[Member, Member]]:
    """(transverse string, axial rod) per section about the static line at ``angle`` from the vertical.

    A lower section's body and everything below it hang from the section's end: their virtual mass
    is the end mass (a bound: the lower sections move with it)."""
    env = scene.environment
    rho = env.density
    u_rel = abs(relative_flow(scene)[0])
    st, ct = math.sin(angle), math.cos(angle)
    out = []
    secs = list(scene.sections)
    for i, sec in enumerate(secs):
        c, b = sec.cable, sec.body
        below_w = sum(s.body.weight + s.cable.total_weight for s in secs[i + 1:])
        below_m = sum(s.body.mass_x + s.cable.total_mass for s in secs[i + 1:])
        tension = max(below_w + b.weight + 0.5 * c.total_weight, 1e-12)     # mean along the section
        m_n = c.mass_per_length + c.added_mass_factor * rho * math.pi * c.diameter**2 / 4     # eq. 23-24
        m_bn = b.mass_x * ct**2 + b.mass_y * st**2 + below_m
        m_bt = b.mass_x * st**2 + b.mass_y * ct**2 + below_m
        # the tension grows toward the top by the weight in water along the cable (a heavy cable: string
        # modes of the hanging chain, :func:`hanging_string`), bounded so that the body end stays taut
        grad = min(max(c.weight_per_length * ct, 0.0), 1.8 * tension / c.length)
        string = Member(c.length, complex(tension), m_n, 0.5 * rho * c.cd_normal * c.diameter, m_bn,
                        0.5 * rho * b.drag_area_normal, u_rel * ct, grad)
        rod = Member(c.length, complex(c.ae, omega * c.internal_damping), c.mass_per_length,
                     0.5 * rho * c.ct_tangential * math.pi * c.diameter, m_bt, 0.5 * rho * b.drag_area_tangential, 0.0)
        out.append((string, rod))
    return out


def top_components(scene: Scene) -> list[tuple[float, complex, complex, complex]]:
    """(omega, X_s, Y_s, Z_s) per forcing frequency: the complex top amplitudes, a sin(wt + ph) = Re(-i a e^{i ph}
    e^{iwt}), with surge and sway turned into the flow's vertical plane (X_s along the heading beta of
    :func:`~.indicators.relative_flow`, Z_s across it: :func:`~.indicators.top_phasors`); Z_s = 0 in the plane."""
    return top_phasors(scene, relative_flow(scene)[1])


def forcing_members(scene: Scene, angle: float, forcing=None) -> list:
    """[(omega, X_s, Y_s, Z_s, :func:`members`)] per forcing component: what :func:`response` needs of the scene,
    built once for the many responses of one estimate (``parts``)."""
    comps = top_components(scene) or [(w, a + 0j, a + 0j, 0j) for w, a in (forcing or [])]
    return [(omega, xs, ys, zs, members(scene, omega, angle)) for omega, xs, ys, zs in comps]


def across(string: Member) -> Member:
    """The string of the motion across the flow's plane (3-D): the same string, its drag slope about the flow half
    of that along it (module docstring)."""
    return dataclasses.replace(string, current=0.5 * string.current)


def response(scene: Scene, angle: float, model: str, n: int = 1, forcing=None, parts=None) -> dict:
    """Body amplitudes |x_b|, |y_b| (m) and end-force amplitudes (N) summed over the forcing components.

    Parameters
    ----------
    scene : Scene
        The scene.
    angle : float
        Static angle of the cable from the vertical (rad), :func:`~cablesys.ladder.indicators.static_angle`.
    model : {"exact", "wang", "segmented"}
        The continuous cable, the straight cable (one consistent element), N lumped elements.
    n : int, optional
        Elements per section of the segmented cable.
    forcing : list of (omega, amplitude), optional
        Used (in both directions) when the top motion has no sinusoids (a series, waves).
    parts : list, optional
        :func:`forcing_members` of the same scene, angle and forcing (built here when omitted).

    Returns
    -------
    dict
        ``x_b``, ``y_b`` (m), ``force_body``, ``force_top`` (N, the largest over sections, axial); in 3-D
        (sway, or a flow off the x axis) also ``z_b``, the body amplitudes then along the flow's plane and across
        it (:func:`top_components`).
    """
    from ..model.segmented import drag_points
    st, ct = math.sin(angle), math.cos(angle)
    points = 0 if model == "exact" else drag_points(scene, n)       # the models' own drag quadrature
    out = {"x_b": 0.0, "y_b": 0.0, "force_body": 0.0, "force_top": 0.0}
    for omega, xs, ys, zs, pairs in (parts if parts is not None else forcing_members(scene, angle, forcing)):
        top_t, top_n = xs * st + ys * ct, xs * ct - ys * st      # along and normal to the static line
        for string, rod in pairs:
            wb, _, _ = respond(string, omega, top_n, model, n, points)
            ub, fb, ft = respond(rod, omega, top_t, model, n, points)
            out["x_b"] = max(out["x_b"], abs(ub * st + wb * ct))
            out["y_b"] = max(out["y_b"], abs(ub * ct - wb * st))
            out["force_body"] = max(out["force_body"], abs(fb))
            out["force_top"] = max(out["force_top"], abs(ft))
            if zs != 0:                     # across the flow's plane: the string alone (no tension to first order)
                out["z_b"] = max(out.get("z_b", 0.0), abs(respond(across(string), omega, zs, model, n, points)[0]))
    return out


def relative_errors(got: dict, ref: dict, largest_tension: float) -> dict:
    """{"body", "tension"} of ``got`` against ``ref`` as :mod:`.metrics` measures them: amplitude
    differences relative to the larger reference amplitude, force differences relative to the
    largest tension."""
    keys = [k for k in ("x_b", "y_b", "z_b") if k in ref]
    a_ref = max(max(ref[k] for k in keys), 1e-300)
    body = max(abs(got.get(k, 0.0) - ref[k]) for k in keys) / a_ref
    tension = max(abs(got[k] - ref[k]) for k in ("force_body", "force_top")) / max(largest_tension, 1e-300)
    return {"body": float(body), "tension": float(tension)}


def string_travel_time(mb: Member) -> float:
    """Time (s) a transverse wave takes from the top to the body along the string ``mb``: the integral of
    ds / c(s), c = sqrt(T(s) / m_v) (m_v with the added mass, Wang 1971 eq. 23-24). For the hanging
    string, T = T_b + g s (:meth:`Member.varies`), this is 2 sqrt(m_v) (sqrt(T_top) - sqrt(T_b)) / g
    (Irvine 1981, ch. 4: the hanging chain); for the uniform string L sqrt(m_v / T)."""
    t = mb.stiffness.real
    if not mb.varies():
        return mb.length * math.sqrt(mb.mass / t)
    t_top, t_bot = mb.end_stiffness()
    return 2.0 * math.sqrt(mb.mass) * (math.sqrt(t_top) - math.sqrt(t_bot)) / mb.gradient
