"""Assemble the CasADi model of a scene: Lagrangian -> M(q) q'' = f -> functions.

The chain of sections (Wang 1971 p. 32-33) is built from the one-section pieces of
:mod:`section`; one section is exactly Wang's 2-DOF model. The top motion enters
through the exogenous vector e = (t, x_s, y_s, x_s', y_s', x_s'', y_s'').

A 3-D scene (``scene.three_d``; Wang 1971 p. 32, "allow the cable to swing out of the vertical
plane") is built by the same code with each angle phi joined by its out-of-plane angle phi_z,
the sway z_s in e (:data:`.top_motion.EXO_LABELS_3D`) and the outputs ``OUTPUT_NAMES_3D``.
"""

from __future__ import annotations

import casadi as ca

from ..errors import ParameterError
from ..scene import Scene
from .cable_model import CableModel
from .lagrange import lagrange_equations, virtual_work
from .params import ParameterLayout, environment_symbols, section_prefix
from .section import SectionParameters, dot as _dot, section_terms
from .segmented import build_segmented_model
from .signals import EXO_LABELS, OUTPUT_NAMES
from .store import stored_model
from .system import build_system_model
from .top_motion import EXO_LABELS_3D, symbolic_type, top_motion_function


# a section's outputs in 3-D: the planar ones, then the out-of-plane angle phi_z (rad) and its rate and the
# body's sway z_b (m, from the top's mean position) and its rate
OUTPUT_NAMES_3D = OUTPUT_NAMES + ("phi_z", "phi_z_rate", "z_b", "z_b_rate")


def _coordinates(n: int, angles: str, three_d: bool = False):
    """Symbols and labels of q: per section (phi_i, u_i), or a shared phi and u_1..u_n.

    In 3-D every angle phi has its out-of-plane partner phi_z (``phi_z``, ``phi_z_2``; shared
    when phi is), after it: (phi, phi_z, u) for one section.
    """
    sfx = (lambda i: "") if n == 1 else (lambda i: f"_{i + 1}")
    pair = (lambda i: (f"phi{sfx(i)}", f"phi_z{sfx(i)}")) if three_d else (lambda i: (f"phi{sfx(i)}",))
    if angles == "shared" or n == 1:
        labels = pair(0) if n == 1 else (("phi", "phi_z") if three_d else ("phi",))
        labels += tuple(f"u{sfx(i)}" for i in range(n))
    else:
        labels = tuple(x for i in range(n) for x in pair(i) + (f"u{sfx(i)}",))
    q = ca.SX.sym("q", len(labels))
    qd = ca.SX.sym("qd", len(labels))
    idx = {lbl: k for k, lbl in enumerate(labels)}

    def pick(vec, i):
        """(phi, u) of section i, or (phi, u, phi_z) in 3-D."""
        get = lambda name: vec[idx[name]] if name in idx else vec[idx[f"{name}{sfx(i)}"]]
        return (get("phi"), get("u")) + ((get("phi_z"),) if three_d else ())
    return q, qd, labels, pick, sfx


def _end_forces(momenta, ext, M, f, q, qd, z, zd, zdd):
    """Forces of every section's cable on its body and on its top point, as ((Fx, Fy), (Fx, Fy)).

    Momentum balances with dP/dt taken along the motion by AD, q'' = M^-1 f (Wang 1971 eq. 47-48):
    - on the body: M_bv a_b - W_b - D_b - F_below (eq. 16, 32-35), F_below the force of the next
      section's cable on its top point (this body; zero for the lowest): the cable tension at the
      body end. Hanging at rest it is W_b plus everything hanging below the body, whereas the
      spring force F_bc = k u (eq. 54, the ``tension_mid`` output) adds W_c/2 to it: the uniform
      stretch makes k u the mean tension of the cable, at rest the tension at mid-length;
    - on the top point of section i: sum over the cables and bodies below of W + D - dP/dt, with
      weights in water (eq. 12, 15), drag (eq. 32-35, 42, 44) and momenta of the virtual masses of
      the kinetic energy (eq. 16, 22-25). Spring, Voigt damper and slack rule (eq. 46, 54) are
      internal and cancel. Hanging at rest it is W_b + W_c.
    The outputs are the magnitudes, signed by the axial component (negative: the straight cable
    pushes, i.e. a real cable would be slack there).
    """
    qdd = ca.solve(M, f)

    def rate(P):
        Pv = ca.vertcat(*P)
        return (ca.mtimes(ca.jacobian(Pv, q), qd) + ca.mtimes(ca.jacobian(Pv, qd), qdd)
                + ca.mtimes(ca.jacobian(Pv, z), zd) + ca.mtimes(ca.jacobian(Pv, zd), zdd))
    dim = len(momenta[0][0])                      # 2 in the plane, 3 in space
    out, below = [], [0.0] * dim
    for (P, P_b), (F, F_b) in zip(reversed(momenta), reversed(ext)):
        dP, dP_b = rate(P), rate(P_b)
        # ``below`` is still the pull of the section below on this body (its top-point force; 0 for the last)
        out_body = tuple(dP_b[j] - F_b[j] - below[j] for j in range(dim))
        below = [below[j] + F[j] - dP[j] for j in range(dim)]
        out.append((out_body, tuple(below)))
    return list(reversed(out))


def build_model(scene: Scene) -> CableModel:
    """Build the CasADi functions for ``scene``'s structure (values go in through ``p``).

    With compilation enabled (the default; ``CABLESYS_COMPILE=0`` disables it) a structure
    built before, by this or another process, is loaded from the disk cache instead
    (:mod:`.store`, faster than building it: ``studies/bench_start.py``), and ``model.cache`` is attached to
    the disk index of its compiled functions (:class:`cablesys.compiled.DerivedStore`), so a
    second start loads the compiled DAE without building it. ``model.build_info`` says which
    (``stored``: loaded from disk; ``build_s``: seconds spent here; ``structure_key``).

    Wang's 2-DOF model (one section; Wang 1971 eq. 8-9, 15, 25, 37-46) or the chain of sections
    (p. 32-33) by Lagrange's equations from energies and virtual work; a scene with
    ``segments > 1`` in a section's cable gets the segmented cable (:mod:`.segmented`), and a system of lines
    joined at points that is not a chain (``scene.system``) the node model of a graph of lines (:mod:`.system`).

    Parameters
    ----------
    scene : Scene
        Any scene of the structure wanted (its values only fix the parameter layout).

    Returns
    -------
    CableModel
        SX functions ``dynamics``, ``ode``, ``top``, ``outputs``, ``energy``, ``cable_force`` and the
        labelled parameter layout (``model.parameters(scene)`` gives the numbers, SI units).
    """
    return stored_model(scene, "build_model", lambda: _build(scene))


def _build(scene: Scene) -> CableModel:
    """The symbolic build of :func:`build_model`."""
    if getattr(scene, "system", None) is not None:       # lines joined at points: a graph of lines
        return build_system_model(scene)
    if any(s.cable.segments > 1 for s in scene.sections):   # N straight elements per section
        return build_segmented_model(scene)
    if getattr(scene, "winch", None) is not None:
        raise ParameterError("cable.segments", 1, "must be >= 2 with [winch]: the winch acts on the node model "
                             "(segmented); Wang's straight cable here has a fixed length (model/winch.py is its "
                             "2-DOF winch, for the control door)")
    layout = ParameterLayout.from_scene(scene)
    p = layout.symbol
    n = len(scene.sections)
    space = scene.three_d                               # Wang 1971 p. 32: out of the vertical plane
    dim = 3 if space else 2
    q, qd, q_labels, pick, sfx = _coordinates(n, scene.angles, space)
    e = ca.SX.sym("e", len(EXO_LABELS_3D if space else EXO_LABELS))
    t, z, zd, zdd = e[0], e[1:1 + dim], e[1 + dim:1 + 2 * dim], e[1 + 2 * dim:1 + 3 * dim]
    env_p = environment_symbols(layout, scene)          # Wang 1971 eq. 26-28 inputs
    rho, depth0 = env_p["density"], env_p["top_depth"]

    top_r = (z[0], depth0 + z[1]) + ((z[2],) if space else ())
    top_v = tuple(zd[j] for j in range(dim))
    K = V = 0
    forces, Q_direct = [], ca.SX.zeros(len(q_labels))
    out, gaps, momenta, ext, axes = [], [], [], [], []
    for i, sec in enumerate(scene.sections):
        P = SectionParameters.from_layout(layout, section_prefix(n, i), sec.body.is_sphere, space)
        phi, u, *theta = pick(q, i)
        phid, ud, *thetad = pick(qd, i)
        T = section_terms(P, top_r, top_v, phi, u, phid, ud, t=t, env=env_p, rho=rho,
                          n_segments=scene.numerics.drag_segments,
                          theta=theta[0] if space else None, thetad=thetad[0] if space else None)
        K, V = K + T["K"], V + T["V"]
        forces += T["point_forces"]
        Q_direct += ca.jacobian(u, q).T * T["Q_u"]      # eq. 46 acts on this section's stretch
        # phi: Wang's cable is straight (body at top + l e_t, eq. 10), so its angle is the chord's angle;
        # tension_mid: the spring force F_bc with the slack floor (eq. 46, 54), the tension of the uniform stretch
        out.append([phi, phid, u, ud, T["r_b"][0], T["v_b"][0], T["r_b"][1] - depth0, T["v_b"][1], T["tension"]])
        if space:
            out[-1] += [theta[0], thetad[0], T["r_b"][2], T["v_b"][2]]
        momenta.append((T["momentum"], T["body_momentum"]))
        axes.append(T["e_t"])
        ext.append((T["external_force"], T["body_external_force"]))
        gaps.append(T["F_bc"] - P.tens)
        top_r, top_v = T["r_b"], T["v_b"]

    Q = virtual_work(forces, qd) + Q_direct
    M, f = lagrange_equations(K - V, Q, q, qd, z, zd, zdd)
    for i, (bottom, top_force) in enumerate(_end_forces(momenta, ext, M, f, q, qd, z, zd, zdd)):
        # magnitudes, negative when the force pushes along the cable (compression: slack, eq. 54)
        e_t = axes[i]
        pull_body = -_dot(bottom, e_t)
        pull_top = _dot(top_force, e_t)
        row = [ca.sign(pull_body) * ca.sqrt(_dot(bottom, bottom)), ca.sign(pull_top) * ca.sqrt(_dot(top_force, top_force))]
        out[i] = out[i][:9] + row + out[i][9:]          # the OUTPUT_NAMES order, then the 3-D outputs
    out = [y for row in out for y in row]
    x = ca.vertcat(q, qd)
    dynamics = ca.Function("dynamics", [q, qd, e, p], [M, f], ["q", "qd", "e", "p"], ["M", "f"])
    top = top_motion_function(scene, layout)
    S = symbolic_type(scene)
    xs, ts, ps = S.sym("x", x.shape[0]), S.sym("t"), S.sym("p", p.shape[0])
    M_t, f_t = dynamics(xs[: len(q_labels)], xs[len(q_labels):], top(ts, ps), ps)
    ode = ca.Function("ode", [xs, ts, ps], [ca.vertcat(xs[len(q_labels):], ca.solve(M_t, f_t))],
                      ["x", "t", "p"], ["xdot"])
    output_labels = tuple(f"{name}{sfx(i)}" for i in range(n) for name in (OUTPUT_NAMES_3D if space else OUTPUT_NAMES))
    outputs = ca.Function("outputs", [x, e, p], [ca.vertcat(*out)], ["x", "e", "p"], ["y"])
    energy = ca.Function("energy", [x, e, p], [K, V], ["x", "e", "p"], ["K", "V"])
    cable_force = ca.Function("cable_force", [x, p], [ca.vertcat(*gaps)], ["x", "p"], ["gap"])
    slack_index = tuple(layout.index(f"{section_prefix(n, i)}slack") for i in range(n))
    return CableModel(layout=layout, n_sections=n, angles=scene.angles, q_labels=q_labels,
                      output_labels=output_labels, dynamics=dynamics, ode=ode, top=top,
                      outputs=outputs, energy=energy, cable_force=cable_force, slack_index=slack_index,
                      symbolic=S)
