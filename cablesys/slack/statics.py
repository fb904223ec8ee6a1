"""Static equilibrium of a lumped-mass extensible cable with point masses.

Model (why lumped masses): the cable is cut into straight elastic bars of
unstretched length L0_e joined at nodes that carry half of each adjacent
bar's weight and mass plus any point mass placed there. Point masses sit
exactly on nodes, the stiffness and mass matrices are block tridiagonal
(sparse) and the frequencies converge as h^2 (the string limit of the chain
is omega_k = (2/h) c sin(k pi h / 2L)), which makes Richardson extrapolation
clean.

Equilibrium minimizes the potential energy (principle of minimum potential
energy; Griffin & Rosenthal 1985 section 6 treat the attached masses as
point loads):

    V(x, z) = sum_e EA / (2 L0_e) (l_e - L0_e)^2 + sum_i W_i z_i,

solved as an NLP with CasADi + IPOPT (:func:`solve_equilibrium`). The
Hessian of V at the minimum is the in-plane stiffness matrix used by
:mod:`cablesys.slack.vibration`. An independent exact route for the same
discrete equations, shooting on the support force (H, V_A) through the
statically determinate chain, is :func:`solve_equilibrium_shooting`; the
two agree to solver tolerance (tests).
"""

from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass, field

import casadi as ca
import numpy as np
import scipy.optimize

from ..errors import SolverError
from ..model.cable_model import FunctionCache
from .results import Equilibrium
from .scene import SlackScene, _buoyancy_and_added

log = logging.getLogger(__name__)

#: above this element count the NLP starts from a solved coarse chain
COARSE_LIMIT = 200


@dataclass(frozen=True, kw_only=True)
class Discretization:
    """Node data of the lumped-mass chain (arrays have one entry per node or element).

    s: unstretched arc length of each node from A (m); L0: element lengths (m);
    weight: nodal weight in the medium (N); mass: nodal physical mass (kg);
    added_transverse: nodal added mass of the cable, acting normal to the
    cable only (kg); added_isotropic: added mass of point masses (kg);
    mass_nodes: node index of each point mass, in scene order; functions: the CasADi
    energy, Hessian and NLP of this element count (:class:`~cablesys.model.FunctionCache`,
    shared by the statics and the modes of one solve, and between solves given one cache).
    """

    s: np.ndarray
    L0: np.ndarray
    weight: np.ndarray
    mass: np.ndarray
    added_transverse: np.ndarray
    added_isotropic: np.ndarray
    mass_nodes: tuple[int, ...]
    functions: FunctionCache = field(default_factory=FunctionCache, repr=False)

    @property
    def n_elements(self) -> int:
        return len(self.L0)


def discretize(scene: SlackScene, n_elements: int | None = None, cache: FunctionCache | None = None) -> Discretization:
    """Uniform nodes in unstretched arc length plus one node at each point mass.

    ``cache`` (default: a new one) keeps the CasADi functions of each element count.
    """
    n = int(n_elements or scene.n_elements)
    L = scene.cable.length
    s = np.linspace(0.0, L, n + 1)
    tol = 1e-9 * L
    extra = [pm.position for pm in scene.masses if np.min(np.abs(s - pm.position)) > tol]
    s = np.unique(np.concatenate([s, extra]))
    L0 = np.diff(s)
    g = scene.gravity
    w, ma = scene.cable.weight_and_added_mass(scene.medium, g)
    m = scene.cable.mass_per_length
    half = np.zeros(len(s))
    half[:-1] += L0 / 2
    half[1:] += L0 / 2
    weight, mass, added_t = w * half, m * half, ma * half
    added_i = np.zeros(len(s))
    nodes = []
    for pm in scene.masses:
        i = int(np.argmin(np.abs(s - pm.position)))
        nodes.append(i)
        wp, ap = _buoyancy_and_added(pm.mass, pm.specific_gravity, pm.added_mass_factor,
                                     scene.medium, g, "mass")
        weight[i] += wp
        mass[i] += pm.mass
        added_i[i] += ap
    return Discretization(s=s, L0=L0, weight=weight, mass=mass, added_transverse=added_t,
                          added_isotropic=added_i, mass_nodes=tuple(nodes), functions=FunctionCache() if cache is None else cache)


def _energy_functions(n: int, cache: FunctionCache | None = None):
    """CasADi potential energy V(w; p), its gradient and Hessian for n elements.

    w = [x_1..x_{n-1}, z_1..z_{n-1}] (interior nodes); p = [EA, xB, zB,
    L0_1..L0_n, W_1..W_{n-1}]. Vectorized SX so that 2000 elements build fast.
    """
    return (FunctionCache() if cache is None else cache).get(f"energy_{n}", lambda: _build_energy(n))


def _build_energy(n: int):
    w = ca.SX.sym("w", 2 * (n - 1))
    p = ca.SX.sym("p", 3 + n + (n - 1))
    EA, xB, zB = p[0], p[1], p[2]
    L0 = p[3:3 + n]
    W = p[3 + n:]
    x = ca.vertcat(0, w[: n - 1], xB)
    z = ca.vertcat(0, w[n - 1:], zB)
    dx = x[1:] - x[:-1]
    dz = z[1:] - z[:-1]
    le = ca.sqrt(dx ** 2 + dz ** 2)
    V = ca.sum1(EA / (2 * L0) * (le - L0) ** 2) + ca.dot(W, w[n - 1:])
    H, grad = ca.hessian(V, w)
    fV = ca.Function("V", [w, p], [V])
    fH = ca.Function("K", [w, p], [H])
    return w, p, V, fV, fH


def _nlp_solver(n: int, max_iter: int, tol: float, cache: FunctionCache):
    return cache.get(f"nlp_{n}_{max_iter}_{tol!r}", lambda: _build_nlp(n, max_iter, tol, cache))


def _build_nlp(n: int, max_iter: int, tol: float, cache: FunctionCache):
    w, p, V, _, _ = _energy_functions(n, cache)
    # objective scaled by 1 / (total weight * chord) so that IPOPT's tolerance
    # is relative: the scale is an extra parameter
    scale = ca.SX.sym("scale")
    opts = {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes",
            "ipopt.max_iter": max_iter, "ipopt.tol": tol}
    return ca.nlpsol("slack_statics", "ipopt",
                     {"x": w, "p": ca.vertcat(p, scale), "f": V * scale}, opts)


def _params(scene: SlackScene, d: Discretization) -> np.ndarray:
    return np.concatenate([[scene.cable.ae, scene.span, scene.rise], d.L0, d.weight[1:-1]])


def parabola_guess(scene: SlackScene, d: Discretization) -> np.ndarray:
    """Initial shape: a parabola below the chord whose inextensible length is L.

    Sag from L = c (1 + 8/3 (sag/c)^2) (Griffin & Rosenthal 1985, length of
    eq. 1), capped at half the length; nodes placed at their arc length s
    along the parabola (so the bars start near their unstretched length).
    """
    c, L = scene.chord, scene.cable.length
    sag = c * math.sqrt(max(3.0 / 8.0 * (L / c - 1.0), 1e-6))
    sag = min(sag, 0.5 * L)
    t = np.linspace(0.0, 1.0, 4001)
    u, v = t * c, 4 * sag * t * (1 - t)
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(u), np.diff(v)))])
    tn = np.interp(d.s / L * arc[-1], arc, t)
    th = scene.inclination
    e_c = np.array([math.cos(th), math.sin(th)])
    e_n = np.array([math.sin(th), -math.cos(th)])  # below the chord
    xy = np.outer(tn * c, e_c) + np.outer(4 * sag * tn * (1 - tn), e_n)
    return np.concatenate([xy[1:-1, 0], xy[1:-1, 1]])


def _equilibrium_from_nodes(scene, d, x, z, method, iterations, seconds, message) -> Equilibrium:
    dx, dz = np.diff(x), np.diff(z)
    le = np.hypot(dx, dz)
    tension = scene.cable.ae * (le - d.L0) / d.L0
    if np.any(tension <= 0.0):
        i = int(np.argmin(tension))
        raise SolverError(f"statics ({method}): element {i} is in compression "
                          f"(T = {tension[i]:.4g} N); the equilibrium found is not a hanging cable. "
                          "Try more elements or a smaller sag.")
    return Equilibrium(scene=scene, s=d.s.copy(), x=x, z=z, tension=tension, discretization=d,
                       method=method, iterations=iterations, seconds=seconds, message=message)


def solve_equilibrium(scene: SlackScene, *, n_elements: int | None = None,
                      guess: np.ndarray | None = None, max_iter: int = 200,
                      tol: float = 1e-9, cache: FunctionCache | None = None) -> Equilibrium:
    """Minimize the potential energy with CasADi nlpsol('ipopt').

    Returns the equilibrium (its ``discretization`` is the element layout). ``guess`` is an initial
    w vector (e.g. a neighbouring solution in a sweep); default the parabola.
    Raises SolverError if IPOPT does not converge.

    Parameters
    ----------
    scene : SlackScene
        The slack-cable scene (SI).
    n_elements : int, optional
        Lumped-mass elements (default from the scene).
    guess : ndarray, optional
        Initial free-node coordinates (x then z, m).
    max_iter : int, optional
        IPOPT iteration limit.
    tol : float, optional
        IPOPT tolerance.
    cache : FunctionCache, optional
        Keeps the NLP and energy functions per element count: pass one cache to solves that
        repeat an element count (a sweep) so the NLP is built once. Default: a new cache.

    Returns
    -------
    Equilibrium
        Static shape (m) with element tensions (N); ``discretization`` holds the element layout
        that :func:`cablesys.slack.modes` needs.
    """
    d = discretize(scene, n_elements, cache)
    n = d.n_elements
    t0 = time.perf_counter()
    solver = _nlp_solver(n, int(max_iter), float(tol), d.functions)
    if guess is not None:
        w0 = np.asarray(guess, float)
    elif int(n_elements or scene.n_elements) > COARSE_LIMIT:
        # two-level start: solve a coarse chain, interpolate its shape in s
        # (its O(h^2)-close) so that IPOPT needs a few Newton steps, not ~90
        eqc = solve_equilibrium(scene, n_elements=COARSE_LIMIT, max_iter=max_iter, tol=tol, cache=d.functions)
        w0 = np.concatenate([np.interp(d.s[1:-1], eqc.s, eqc.x), np.interp(d.s[1:-1], eqc.s, eqc.z)])
    else:
        w0 = parabola_guess(scene, d)
    scale = 1.0 / (float(np.sum(d.weight)) * scene.chord)
    sol = solver(x0=w0, p=np.append(_params(scene, d), scale))
    stats = solver.stats()
    dt = time.perf_counter() - t0
    if not stats.get("success", False):
        raise SolverError(f"statics NLP did not converge: IPOPT says '{stats.get('return_status')}' "
                          f"after {stats.get('iter_count')} iterations (max_iter = {max_iter}) "
                          f"for span = {scene.span:g} m, rise = {scene.rise:g} m, L = {scene.cable.length:g} m, "
                          f"{n} elements. Nearly coincident or near-vertical supports and a specific gravity near "
                          "1 are hard for it: try more elements or max_iter, or a slightly different geometry.")
    w = np.asarray(sol["x"]).ravel()
    x = np.concatenate([[0.0], w[: n - 1], [scene.span]])
    z = np.concatenate([[0.0], w[n - 1:], [scene.rise]])
    log.info("statics NLP: %d elements, %d iterations, %.3f s", n, stats.get("iter_count", -1), dt)
    return _equilibrium_from_nodes(scene, d, x, z, "nlp-ipopt", int(stats.get("iter_count", -1)), dt, "")


def _chain_ends(HV: np.ndarray, d: Discretization, EA: float):
    """March from A: element e carries (H, V_A + sum of nodal weights before it)."""
    H, VA = HV
    Vz = VA + np.concatenate([[0.0], np.cumsum(d.weight[1:-1])])
    T = np.hypot(H, Vz)
    stretch = d.L0 * (1.0 + T / EA) / T       # l_e / T_e (Hooke's law)
    return np.cumsum(H * stretch), np.cumsum(Vz * stretch)


def _elastic_parabola_tension(W: float, c: float, L: float, EA: float) -> float:
    """Chord tension of an elastic parabola: W c / (8 sag) with L(1 + H/EA) = c (1 + 8/3 (sag/c)^2).

    Griffin & Rosenthal (1985) eq. 1 and its length; used only as a starting
    guess (brentq on log H, the residual is monotone in H).
    """
    def res(logH):
        H = math.exp(logH)
        Ls = L * (1.0 + H / EA)
        sag = c * math.sqrt(max(3.0 / 8.0 * (Ls / c - 1.0), 1e-30))
        return math.log(W * c / (8.0 * sag)) - logH
    lo, hi = math.log(W * 1e-3), math.log(max(W, EA) * 10.0)
    return math.exp(scipy.optimize.brentq(res, lo, hi))


def solve_equilibrium_shooting(scene: SlackScene, *, n_elements: int | None = None) -> Equilibrium:
    """Exact equilibrium of the same chain by shooting on (H, V_A) (scipy.optimize.root).

    The chain is statically determinate: node balance gives element forces
    (H, V_A + sum W_i), Hooke's law their lengths; the two unknowns close
    the chord. Used as an independent check of the NLP and for fast sweeps. Returns the
    :class:`Equilibrium` (``method`` 'shooting', ``iterations`` the residual evaluations).
    """
    d = discretize(scene, n_elements)
    t0 = time.perf_counter()
    x, z, nfev = shooting_nodes(scene, d)
    return _equilibrium_from_nodes(scene, d, x, z, "shooting", nfev, time.perf_counter() - t0, "")


def shooting_nodes(scene: SlackScene, d: Discretization):
    """Node positions (x, z, m; supports included) of the chain ``d`` at rest by shooting on (H, V_A), and
    the residual evaluations: :func:`solve_equilibrium_shooting` on any node layout."""
    EA = scene.cable.ae
    Wtot = float(np.sum(d.weight[1:-1]))
    c, L = scene.chord, scene.cable.length
    try:   # the elastic parabola's start fails for chords near vertical or near zero: a solver failure
        H0 = _elastic_parabola_tension(Wtot * math.cos(scene.inclination), c, L, EA) * math.cos(scene.inclination)
        VA0 = -Wtot / 2 + H0 * scene.rise / max(scene.span, 1e-9)
    except (ValueError, OverflowError, ZeroDivisionError) as err:
        raise SolverError(f"statics shooting: no starting tension from the elastic parabola ({err}) for span = "
                          f"{scene.span:g} m, rise = {scene.rise:g} m, L = {L:g} m; this chord is outside the "
                          "shooting route's reach (use the NLP, solve_equilibrium)") from None

    def res(v):
        X, Z = _chain_ends(np.array([math.exp(v[0]), v[1]]), d, EA)
        return [(X[-1] - scene.span) / c, (Z[-1] - scene.rise) / c]

    where = f"for span = {scene.span:g} m, rise = {scene.rise:g} m, L = {L:g} m"
    for method in ("hybr", "lm"):   # Powell hybrid first, Levenberg-Marquardt as a fallback
        try:
            with np.errstate(over="ignore", invalid="ignore"):
                sol = scipy.optimize.root(res, [math.log(H0), VA0], method=method, options={"xtol": 1e-13})
        except OverflowError as err:      # the tension iterate exp(log H) left the floating-point range
            raise SolverError(f"statics shooting ({method}): the horizontal tension iterate overflowed ({err}) "
                              f"{where}; use the NLP, solve_equilibrium") from None
        if np.max(np.abs(sol.fun)) <= 1e-9:
            break
    if np.max(np.abs(sol.fun)) > 1e-9:
        raise SolverError(f"statics shooting did not converge {where}: {sol.message}")
    X, Z = _chain_ends(np.array([math.exp(sol.x[0]), sol.x[1]]), d, EA)
    x = np.concatenate([[0.0], X[:-1], [scene.span]])
    z = np.concatenate([[0.0], Z[:-1], [scene.rise]])
    return x, z, int(sol.nfev)


def stiffness_inplane(eq: Equilibrium, d: Discretization):
    """In-plane stiffness: the CasADi Hessian of V at equilibrium (scipy CSC matrix)."""
    n = d.n_elements
    _, _, _, _, fH = _energy_functions(n, d.functions)
    w = np.concatenate([eq.x[1:-1], eq.z[1:-1]])
    K = fH(w, _params(eq.scene, d))
    return _casadi_to_csc(K)


def _casadi_to_csc(M):
    import scipy.sparse as sp
    sps = M.sparsity()
    colind = np.asarray(sps.colind())
    row = np.asarray(sps.row())
    data = np.asarray(M.nonzeros(), float)
    return sp.csc_matrix((data, row, colind), shape=(M.size1(), M.size2()))
