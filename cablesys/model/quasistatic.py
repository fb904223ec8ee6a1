"""The quasi-static stretch model: Wang's swing dynamics with the stiff axial mode eliminated.

Singular perturbation of Wang (1971) eq. 47-48. When the axial natural frequency
omega_ax = sqrt(k / (M_bv + M_c/3)) lies far above every forcing frequency, the stretch u
follows the tension: its equation is kept with u'' = u' = 0 (the inertia and Voigt damping of
the stretch itself dropped, eq. 46 and 54), while the swing keeps all its terms, including the
cable and body inertia that load the spring through M_u,phi phi''. With s the slow (angle)
coordinates and u the stretches,

    M_ss(s, u) s'' = f_s(s, u, s', u' = 0, e)                     (swing rows of eq. 47-48)
    f_u(s, u, s', u' = 0, e) - M_us(s, u) s'' = 0                 (stretch rows, u'' = 0)

The second line is solved for u by Newton's method (unrolled, with the exact AD Jacobian, from
the zero-tension length: the equation is nearly linear, -k u plus terms that change with the
length only through u / l), so the model is an ODE in (s, s') alone whose fastest time scale
is the swing. The tension is the constraint force k u that holds the stretch equation. The
error of the reduction is O((omega / omega_ax)^2): a spring with mass driven at omega
responds by 1 / (1 - (omega / omega_ax)^2) more than its quasi-static tension.

In three dimensions (Wang 1971 p. 32, "allow the cable to swing out of the vertical plane") the slow
coordinates are both angles of Wang's 3-D cable, (phi, phi_z), and the fast one its stretch u: the same
code, the split by the coordinates' labels (a planar scene builds the planar model; ``numerics.dimensions
= 3`` forces the 3-D one, whose answer on a planar scene is the planar one).

A scene with ``cable.segments = N > 1`` gets the same reduction of the segmented cable
(:mod:`.element_coordinates`: the node model of :mod:`.segmented` in the coordinates (phi_k, u_k)
of its elements, Wang's p. 33 "each segment has two degrees of freedom", and (phi_k, phi_z_k, u_k) in
3-D: slow both angles of every element, fast its stretch). Its fast modes are the
N axial modes of the elements, the lowest near Wang's omega_ax and the others higher, all
undamped unless C_I > 0 (eq. 46): with eps = omega / omega_ax the system is
singularly perturbed (the stretch rows are M_uu u'' + ... = -k_e u + ..., k_e ~ 1/eps^2), and
Tikhonov's theorem gives the slow manifold u = u*(s, s', e) + O(eps^2) on which the bowing,
swing and string modes live (their frequencies stay far below omega_ax where the reduction is
used). The element stretches are solved by the chord method with the element stiffness
k_e = (AE)_r / h_r for Jacobian (:func:`chord_iterations`): the rows are -k_e u plus terms that
depend on u only through the element lengths, so each iteration gains a factor T / AE. The
tension of element k is the node model's element tension at the solved stretch (the constraint
force), so ``element_tension[k]``, ``tension_top`` and ``tension_bottom`` come out of the node
model's ``outputs``. N = 1 stays Wang's model above, exactly.

The model has the interface of :class:`~cablesys.model.build.CableModel` (``dynamics``,
``ode``, ``outputs`` with the 2-DOF labels, ``energy``), so ``simulate`` and the linear layer
run it unchanged. It carries no slack switch: a quasi-static stretch cannot go slack
(``cable_force`` is a constant 1); :func:`least_tension_margin` lets the caller check.
"""

from __future__ import annotations

import dataclasses

import casadi as ca
import numpy as np

from ..scene import Scene
from .build import CableModel, build_model
from .element_coordinates import (
    ElementModel,
    build_element_model,
    element_stiffness,
    hanging_stretch,
)
from .store import stored_model

MAX_NEWTON_ITERATIONS = 6
CHORD_TOLERANCE = 1e-4


def segmented(scene: Scene) -> bool:
    """Whether ``scene`` divides a section into elements (then the reduction is of the segmented cable)."""
    return any(sec.cable.segments > 1 for sec in scene.sections)


def _static_strain(scene: Scene) -> float:
    """The largest static strain T_top / AE over the sections, hanging (Wang 1971 eq. 12, 46)."""
    eps, below = 0.0, 0.0
    for sec in reversed(scene.sections):
        below += sec.body.weight + sec.cable.total_weight
        eps = max(eps, abs(below) / sec.cable.ae)
    return eps


def newton_iterations(scene: Scene) -> int:
    """Newton iterations for the stretch: each squares the relative error, which starts near the
    static strain eps = T_top / AE (the residual is -k u plus terms that vary with u only through
    the length), so n iterations leave about eps^(2^n); we ask for 1e-12."""
    eps = _static_strain(scene)
    n = 1
    while eps ** (2 ** n) > 1e-12 and n < MAX_NEWTON_ITERATIONS:
        n += 1
    return n


def chord_iterations(scene: Scene) -> int:
    """Chord iterations for the element stretches (the segmented reduction): u <- u + r / k_e with the
    element stiffness k_e = (AE)_r / h_r for Jacobian. The residual is -k_e u plus terms that change
    with u only through the element lengths (relative size eps = T / AE) and the centripetal and
    drag terms (smaller still where the reduction holds), so each iteration multiplies the error by
    about eps. The start, the hanging stretch, is off by the dynamic part of the tension (a fraction
    <= 1 of the tension in a taut cable), so n iterations leave a relative tension error <= eps^n; we
    ask for :data:`CHORD_TOLERANCE`, 100x under the ladder's tightest default tolerance (1 % body
    motion). Dale (eps = 3e-5): one iteration; 300 m steel wire (eps = 2e-4): two."""
    eps = max(_static_strain(scene), 1e-300)
    n = 1
    while eps ** n > CHORD_TOLERANCE and n < MAX_NEWTON_ITERATIONS:
        n += 1
    return n


def default_iterations(scene: Scene) -> int:
    """Iterations of the stretch solve of :func:`build_quasistatic`: Newton's for Wang's cable,
    the chord method's for a segmented one."""
    return chord_iterations(scene) if segmented(scene) else newton_iterations(scene)


def _split(full: CableModel):
    slow = [i for i, lbl in enumerate(full.q_labels) if lbl.startswith("phi")]
    fast = [i for i, lbl in enumerate(full.q_labels) if lbl.startswith("u")]
    return slow, fast


def _assemble(n, slow, fast, s_vals, u_vals):
    out = [None] * n
    for k, i in enumerate(slow):
        out[i] = s_vals[k]
    for k, i in enumerate(fast):
        out[i] = u_vals[k]
    return ca.vertcat(*out)


def _stretch_solution(full: CableModel, slow, fast, s, sd, e, p, iterations: int, start=None, stiffness=None):
    """(u, s'', M_ss, f_s, u'): the stretch satisfying the u-rows with u'' = u' = 0, and its rate along the motion.

    Wang's cable (``stiffness`` None): Newton with the exact AD Jacobian from the zero-tension length.
    Elements: the chord method u <- u + r / k_e from ``start`` (both SX of p), one evaluation of the
    rows per iteration (no AD through the N x N solve: 9x fewer operations at N = 4); s'', M_ss and
    f_s are those of the last iterate before the update, off by O(eps^iterations)."""
    n = full.nq
    ns, nf = len(slow), len(fast)
    u_sym = ca.SX.sym("u", nf)
    q = _assemble(n, slow, fast, [s[k] for k in range(ns)], [u_sym[k] for k in range(nf)])
    qd = _assemble(n, slow, fast, [sd[k] for k in range(ns)], [0.0] * nf)
    M, f = full.dynamics(q, qd, e, p)
    M_ss, M_us = M[slow, slow], M[fast, slow]
    sdd = ca.solve(M_ss, f[slow])
    r = f[fast] - ca.mtimes(M_us, sdd)                      # stretch rows with u'' = 0
    # u' along the motion comes from dr/dt at fixed u (the implicit-function theorem: dr/du u' = -dr/dt),
    # one forward AD sweep (shared by CSE) instead of AD through the unrolled iterations; e = (t, z, z', z'')
    # with z of 2 entries in the plane, 3 in space (top_motion.EXO_LABELS_3D)
    dim = (e.numel() - 1) // 3
    zd, zdd = e[1 + dim:1 + 2 * dim], e[1 + 2 * dim:1 + 3 * dim]
    r_t = ca.jtimes(r, ca.vertcat(s, sd, e), ca.vertcat(sd, sdd, 0.0, zd, zdd, ca.DM.zeros(dim)))
    if stiffness is not None:
        rows = ca.Function("rows", [u_sym, s, sd, e, p], [r, sdd, M_ss, f[slow]])
        u = start
        for _ in range(iterations):
            u_last = u
            r_u, sdd_u, M_s, f_s = rows(u, s, sd, e, p)
            u = u + r_u / stiffness
        # the chord's Jacobian, -k_e, at the last iterate: u' = (dr/dt at fixed u) / k_e to O(eps)
        ud = ca.Function("rows_rate", [u_sym, s, sd, e, p], [r_t])(u_last, s, sd, e, p) / stiffness
        return u, sdd_u, M_s, f_s, ud
    J = ca.jacobian(r, u_sym)
    newton = ca.Function("newton", [u_sym, s, sd, e, p], [u_sym - ca.solve(J, r)])
    u = ca.SX.zeros(nf) if start is None else start          # default: zero-tension length (eq. 1)
    for _ in range(iterations):
        u = newton(u, s, sd, e, p)
    M_s, f_s, sdd_s = (ca.substitute(v, u_sym, u) for v in (M_ss, f[slow], sdd))
    # the exact Jacobian at the converged stretch, an nf x nf solve (the heave scene's outputs 15.5k -> ~4k operations)
    ud = ca.Function("rows_rate", [u_sym, s, sd, e, p], [-ca.solve(J, r_t)])(u, s, sd, e, p)
    return u, sdd_s, M_s, f_s, ud


def build_quasistatic(scene: Scene, *, full: CableModel | None = None,
                      iterations: int | None = None) -> CableModel:
    """The quasi-static stretch model of ``scene`` (same parameters ``p`` as :func:`build_model`).

    Parameters
    ----------
    scene : Scene
        Any scene Wang's model accepts (one section or a chain); with ``cable.segments = N > 1``
        the segmented cable of N elements per section (its stretches quasi-static).
    full : CableModel, optional
        The model reduced, if already built: Wang's 2-DOF model, or an
        :class:`~.element_coordinates.ElementModel` (default: built from ``scene``).
    iterations : int, optional
        Iterations of the stretch solve (default :func:`default_iterations`: Newton's for Wang's
        cable, the chord method's for elements).

    Returns
    -------
    CableModel
        ``q_labels`` are the angles only (``phi[k]`` per element for N > 1; with ``phi_z``, ``phi_z[k]`` in 3-D);
        ``outputs`` has the
        labels of the model reduced (2-DOF, or the segmented profiles ``element_tension[k]``...; the
        stretch rate is the quasi-static one, du/dt along the motion without the top jerk); ``kind``
        is ``"quasi-static"``; for N > 1 an ``ElementModel`` with ``elements`` and ``n_elements``.
    """
    iterations = iterations or default_iterations(scene)
    # a structure built before is loaded from the disk cache (model/store.py), like build_model's
    return stored_model(scene, "build_quasistatic", lambda: _build_quasistatic(scene, full, iterations), (iterations,))


def _build_quasistatic(scene: Scene, full: CableModel | None, iterations: int) -> CableModel:
    """The symbolic build of :func:`build_quasistatic`."""
    if full is None:
        if segmented(scene):  # N elements per section: the node model in element coordinates
            full = build_element_model(scene)
        else:                 # Wang's straight cable
            full = build_model(scene)
    slow, fast = _split(full)
    ns = len(slow)
    n = full.nq
    q_labels = tuple(full.q_labels[i] for i in slow)
    s, sd = ca.SX.sym("q", ns), ca.SX.sym("qd", ns)
    e = ca.SX.sym("e", full.dynamics.size1_in(2))      # (t, z, z', z''): 7 entries in the plane, 10 in space
    p = ca.SX.sym("p", len(full.layout))
    # Wang's model starts Newton at the zero-tension length (its rows are smooth there); the elements'
    # tension law max(TENS, ...) (eq. 54) is flat below the floor, so they start from the hanging stretch
    elements = isinstance(full, ElementModel)
    start, stiffness = (hanging_stretch(scene, full.layout)(p), element_stiffness(scene, full.layout)(p)) if elements else (None, None)
    u, _, M_s, f_s, ud = _stretch_solution(full, slow, fast, s, sd, e, p, iterations, start, stiffness)
    opts = {"cse": True}    # the chord's or Newton's evaluations share many terms
    dynamics = ca.Function("dynamics", [s, sd, e, p], [M_s, f_s], ["q", "qd", "e", "p"], ["M", "f"], opts)

    # u' along the motion: du/dt = du/ds s' + du/ds' s'' + du/dz z' + du/dz' z'' (the jerk and the
    # explicit time dependence of waves are left out: they are higher order in omega / omega_ax):
    # ud from _stretch_solution
    x_full = ca.vertcat(_assemble(n, slow, fast, [s[k] for k in range(ns)], [u[k] for k in range(len(fast))]),
                        _assemble(n, slow, fast, [sd[k] for k in range(ns)], [ud[k] for k in range(len(fast))]))
    x = ca.vertcat(s, sd)
    outputs = ca.Function("outputs", [x, e, p], [full.outputs(x_full, e, p)], ["x", "e", "p"], ["y"], opts)
    K, V = full.energy(x_full, e, p)
    energy = ca.Function("energy", [x, e, p], [K, V], ["x", "e", "p"], ["K", "V"])
    # always taut (one per slack switch of the full model: Wang's per section, none for elements)
    cable_force = ca.Function("cable_force", [x, p], [ca.DM.ones(len(full.slack_index), 1)], ["x", "p"], ["gap"])

    S = full.symbolic
    xs, ts, ps = S.sym("x", 2 * ns), S.sym("t"), S.sym("p", len(full.layout))
    M_t, f_t = dynamics(xs[:ns], xs[ns:], full.top(ts, ps), ps)
    ode = ca.Function("ode", [xs, ts, ps], [ca.vertcat(xs[ns:], ca.solve(M_t, f_t))], ["x", "t", "p"], ["xdot"], opts)
    extra = {}
    if isinstance(full, ElementModel):    # its maps and node model are of the full coordinates: dropped
        extra = {"to_nodes": None, "from_nodes": None, "node_model": None, "name": "quasi-static"}
    return dataclasses.replace(full, q_labels=q_labels, dynamics=dynamics, ode=ode, outputs=outputs,
                               energy=energy, cable_force=cable_force, kind="quasi-static", **extra)


def axial_frequencies(scene: Scene) -> tuple:
    """omega_ax = sqrt(k / (M_bv,y + M_c / 3)) of each section hanging alone (rad/s): the stretch
    mode of Wang's model, a spring with the body and a third of the cable mass (eq. 22, 25)."""
    out = []
    below = 0.0
    for sec in reversed(scene.sections):
        c, b = sec.cable, sec.body
        below += b.mass_y
        out.append((c.spring_constant / (below + c.total_mass / 3.0)) ** 0.5)
        below += c.total_mass
    return tuple(reversed(out))


def least_tension_margin(result, scene: Scene) -> float:
    """The least tension above the floor over a quasi-static run (N): min over time of every
    element's tension (``element_tension[k]``, the constraint force of the segmented reduction),
    Wang's F_bc (``tension_mid``) and the body-end force, minus the largest tension floor TENS (eq. 54).
    A quasi-static stretch cannot go slack, so a margin <= 0 says the run left the model's validity
    (run the segmented rung instead).

    Parameters
    ----------
    result : TimeResult
        A run of a quasi-static model (any model with these outputs).
    scene : Scene
        Its scene (the floors).

    Returns
    -------
    float
        min(T) - TENS in N.
    """
    floor = max(s.cable.tension_floor for s in scene.sections)
    low = [float(np.min(result[k])) for k in ("tension_bottom", "tension_mid") if k in result.labels]
    profiles = getattr(result, "profiles", {}) or {}
    if "element_tension" in profiles:
        low.append(float(np.min(profiles["element_tension"])))
    return min(low) - floor
