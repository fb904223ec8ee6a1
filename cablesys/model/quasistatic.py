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

The model has the interface of :class:`~cablesys.model.build.CableModel` (``dynamics``,
``ode``, ``outputs`` with the 2-DOF labels, ``energy``), so ``simulate`` and the linear layer
run it unchanged. It carries no slack switch: a quasi-static stretch cannot go slack
(``cable_force`` is a constant 1); :func:`least_tension_margin` lets the caller check.
"""

from __future__ import annotations

import dataclasses

import casadi as ca

from ..scene import Scene
from .build import CableModel, build_model
from .store import stored_model

MAX_NEWTON_ITERATIONS = 6


def newton_iterations(scene: Scene) -> int:
    """Newton iterations for the stretch: each squares the relative error, which starts near the
    static strain eps = T_top / AE (the residual is -k u plus terms that vary with u only through
    the length), so n iterations leave about eps^(2^n); we ask for 1e-12."""
    eps, below = 0.0, 0.0
    for sec in reversed(scene.sections):
        below += sec.body.weight + sec.cable.total_weight
        eps = max(eps, abs(below) / sec.cable.ae)
    n = 1
    while eps ** (2 ** n) > 1e-12 and n < MAX_NEWTON_ITERATIONS:
        n += 1
    return n


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


def _stretch_solution(full: CableModel, slow, fast, s, sd, e, p, iterations: int):
    """(u, s'', M_ss, f_s): the stretch satisfying the u-rows with u'' = u' = 0, by Newton."""
    n = full.nq
    ns, nf = len(slow), len(fast)
    u_sym = ca.SX.sym("u", nf)
    q = _assemble(n, slow, fast, [s[k] for k in range(ns)], [u_sym[k] for k in range(nf)])
    qd = _assemble(n, slow, fast, [sd[k] for k in range(ns)], [0.0] * nf)
    M, f = full.dynamics(q, qd, e, p)
    M_ss, M_us = M[slow, slow], M[fast, slow]
    sdd = ca.solve(M_ss, f[slow])
    r = f[fast] - ca.mtimes(M_us, sdd)                      # stretch rows with u'' = 0
    step = ca.solve(ca.jacobian(r, u_sym), r)
    newton = ca.Function("newton", [u_sym, s, sd, e, p], [u_sym - step])
    u = ca.SX.zeros(nf)                                      # zero-tension length (eq. 1)
    for _ in range(iterations):
        u = newton(u, s, sd, e, p)
    M_s, f_s, sdd_s = (ca.substitute(v, u_sym, u) for v in (M_ss, f[slow], sdd))
    return u, sdd_s, M_s, f_s


def build_quasistatic(scene: Scene, *, full: CableModel | None = None,
                      iterations: int | None = None) -> CableModel:
    """The quasi-static stretch model of ``scene`` (same parameters ``p`` as :func:`build_model`).

    Parameters
    ----------
    scene : Scene
        Any scene Wang's model accepts (one section or a chain).
    full : CableModel, optional
        The 2-DOF model of the scene, if already built.
    iterations : int, optional
        Newton iterations for the stretch (default :func:`newton_iterations`).

    Returns
    -------
    CableModel
        ``q_labels`` are the angles only; ``outputs`` has the 2-DOF labels (the stretch rate is
        the quasi-static one, du/dt along the motion without the top jerk); ``kind`` is
        ``"quasi-static"``.
    """
    iterations = iterations or newton_iterations(scene)
    # a structure built before is loaded from the disk cache (model/store.py), like build_model's
    return stored_model(scene, "build_quasistatic", lambda: _build_quasistatic(scene, full, iterations), (iterations,))


def _build_quasistatic(scene: Scene, full: CableModel | None, iterations: int) -> CableModel:
    """The symbolic build of :func:`build_quasistatic`."""
    if full is None:          # always Wang's straight cable, whatever the scene's segments
        secs = tuple(dataclasses.replace(sec, cable=dataclasses.replace(sec.cable, segments=1)) for sec in scene.sections)
        full = build_model(dataclasses.replace(scene, sections=secs))
    slow, fast = _split(full)
    ns = len(slow)
    n = full.nq
    q_labels = tuple(full.q_labels[i] for i in slow)
    s, sd = ca.SX.sym("q", ns), ca.SX.sym("qd", ns)
    e = ca.SX.sym("e", 7)
    p = ca.SX.sym("p", len(full.layout))
    u, sdd, M_s, f_s = _stretch_solution(full, slow, fast, s, sd, e, p, iterations)
    dynamics = ca.Function("dynamics", [s, sd, e, p], [M_s, f_s], ["q", "qd", "e", "p"], ["M", "f"])

    # u' along the motion: du/dt = du/ds s' + du/ds' s'' + du/dz z' + du/dz' z'' (the jerk and the
    # explicit time dependence of waves are left out: they are higher order in omega / omega_ax)
    z, zd, zdd = e[1:3], e[3:5], e[5:7]
    ud = (ca.mtimes(ca.jacobian(u, s), sd) + ca.mtimes(ca.jacobian(u, sd), sdd)
          + ca.mtimes(ca.jacobian(u, z), zd) + ca.mtimes(ca.jacobian(u, zd), zdd))
    x_full = ca.vertcat(_assemble(n, slow, fast, [s[k] for k in range(ns)], [u[k] for k in range(len(fast))]),
                        _assemble(n, slow, fast, [sd[k] for k in range(ns)], [ud[k] for k in range(len(fast))]))
    x = ca.vertcat(s, sd)
    outputs = ca.Function("outputs", [x, e, p], [full.outputs(x_full, e, p)], ["x", "e", "p"], ["y"])
    K, V = full.energy(x_full, e, p)
    energy = ca.Function("energy", [x, e, p], [K, V], ["x", "e", "p"], ["K", "V"])
    cable_force = ca.Function("cable_force", [x, p], [ca.DM.ones(full.n_sections)], ["x", "p"], ["gap"])

    S = full.symbolic
    xs, ts, ps = S.sym("x", 2 * ns), S.sym("t"), S.sym("p", len(full.layout))
    M_t, f_t = dynamics(xs[:ns], xs[ns:], full.top(ts, ps), ps)
    ode = ca.Function("ode", [xs, ts, ps], [ca.vertcat(xs[ns:], ca.solve(M_t, f_t))], ["x", "t", "p"], ["xdot"])
    return dataclasses.replace(full, q_labels=q_labels, dynamics=dynamics, ode=ode, outputs=outputs,
                               energy=energy, cable_force=cable_force, kind="quasi-static")


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
