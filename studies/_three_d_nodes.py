"""The node model (segmented cable, :mod:`cablesys.model.segmented`) in three dimensions: the checks of
``studies/three_d_checks.py`` for it, beside Wang's straight cable's.

- :func:`planar_equivalence`: planar scenes divided into N elements, run by the 3-D node equations
  (``numerics.dimensions = 3``: nodes (x, y, z)) against the planar node model: right-hand side and outputs
  at random in-plane states, and a fixed-step run (the same RK4 steps in both);
- :func:`rotation_invariance`: a 3-D scene (current turning with depth, a wave with a heading, surge + sway +
  heave) and the same scene turned about the vertical: at random node states (turned node by node) the
  accelerations turn and the scalars (tensions, stretches) are equal; over a fixed-step run the node
  positions turn;
- :func:`chain_modes`: the hanging chain (no body weight, a stiff cable): the out-of-plane modes of the 3-D
  node model's linearization (:func:`cablesys.linear.linearization.linearize`) against the in-plane ones of
  the planar node model, and both against the continuous chain's omega_k = (j_0k / 2) sqrt(w / (m_t L))
  (Bernoulli's hanging chain, Irvine 1981 ch. 4: j_0k the zeros of the Bessel function J_0, w the weight in water and
  m_t the mass plus added mass per length, eq. 23), with the observed order of convergence in N;
- :func:`energy_drift`: no drag, no damping, the top at rest, a 3-D swing (the cable turned in the x-y plane
  and started with a sway velocity): max |E - E_0| over the motion's energy, many pendulum periods.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from scipy.special import jn_zeros

from cablesys.linear.linearization import linearize
from cablesys.linear.modal import modes
from cablesys.model import build_model
from cablesys.scene import Body, Numerics, single_section_scene
from cablesys.statics.steady import steady_state
from cablesys.time_domain.initial import initial_state
from cablesys.time_domain.run import simulate


def divided(sc, n: int):
    """``sc`` with every section's cable divided into ``n`` elements."""
    return dataclasses.replace(sc, sections=tuple(dataclasses.replace(s, cable=dataclasses.replace(s.cable, segments=n))
                                                  for s in sc.sections))


def _nodes(v, dim):
    return np.asarray(v, float).reshape(-1, dim)


def _lift(x2):
    """A planar node state (x, y per node; positions then velocities) as a 3-D one with z = 0."""
    n = len(x2) // 2
    q, v = _nodes(x2[:n], 2), _nodes(x2[n:], 2)
    z = np.zeros((len(q), 1))
    return np.concatenate([np.hstack([q, z]).ravel(), np.hstack([v, z]).ravel()])


def _drop(x3):
    """The in-plane entries of a 3-D node vector (and the largest out-of-plane one)."""
    n = len(x3) // 2
    q, v = _nodes(x3[:n], 3), _nodes(x3[n:], 3)
    return np.concatenate([q[:, :2].ravel(), v[:, :2].ravel()]), float(np.max(np.abs(np.r_[q[:, 2], v[:, 2]])))


def _drop_rows(states3):
    """The in-plane rows of 3-D node states (states x time), and the largest out-of-plane entry."""
    n = states3.shape[0] // 3
    keep = [k for k in range(states3.shape[0]) if k % 3 != 2]
    return states3[keep], float(np.max(np.abs(states3[2::3]))) if n else 0.0


def _random_states(model, p, rng, count, dim):
    """States near the equilibrium: node positions moved by O(0.3 m) (out of the plane too in 3-D), rates O(0.3)."""
    q0 = steady_state(model, p).q
    out = []
    for _ in range(count):
        q = q0 + rng.normal(scale=0.3, size=q0.size) * (np.tile([1, 0.02, 1][:dim], q0.size // dim))
        out.append(np.concatenate([q, rng.normal(scale=0.3, size=q0.size)]))
    return out


def planar_equivalence(planar_scenes, quick: bool, n_el: int = 4) -> dict:
    """Largest differences between the planar node model and the 3-D node equations on planar scenes."""
    rng = np.random.default_rng(11)
    worst_abs, worst_rel, cases = 0.0, 0.0, {}
    for base in planar_scenes:
        sc = divided(base, n_el)
        sc3 = sc.with_numerics(dimensions=3)
        m2, m3 = build_model(sc), build_model(sc3)
        p2, p3 = m2.parameters(sc), m3.parameters(sc3)
        rows3 = [m3.output_labels.index(lb) for lb in m2.output_labels]
        d_abs = d_rel = out_of_plane = 0.0
        for x2 in _random_states(m2, p2, rng, 3 if quick else 10, 2):
            x3 = _lift(x2)
            for t in (0.0, 7.3):
                f2 = np.array(m2.ode(x2, t, p2)).ravel()
                f3, f3z = _drop(np.array(m3.ode(x3, t, p3)).ravel())
                y2 = np.array(m2.outputs(x2, m2.top(t, p2), p2)).ravel()
                y3 = np.array(m3.outputs(x3, m3.top(t, p3), p3)).ravel()[rows3]
                out_of_plane = max(out_of_plane, f3z)
                for a, b in ((f2, f3), (y2, y3)):
                    d_abs = max(d_abs, float(np.max(np.abs(a - b))))
                    d_rel = max(d_rel, float(np.max(np.abs(a - b)) / max(np.max(np.abs(a)), 1.0)))
        # the same start (the planar equilibrium, z = 0): the run compares the equations, not two statics solves
        # (those agree to the statics' tolerance: ``equilibrium_max_abs_m``)
        q2, q3 = steady_state(m2, p2).q, steady_state(m3, p3).q
        x0 = initial_state(sc, m2, p2)
        run = sc.with_numerics(duration=2.0 if quick else 10.0, steps_per_output=40)
        r2 = simulate(run, model=m2, method="rk", x0=x0)
        r3 = simulate(run.with_numerics(dimensions=3), model=m3, method="rk", x0=_lift(x0))
        # the run: states (node positions m, velocities m/s) absolute; every output normwise relative,
        # max|a - b| / max(max|a|, 1), but the element tensions' rates, reported apart: T' holds the
        # nodes' accelerations times C_I / h (eq. 46), so it amplifies the states' rounding (1e-11 m)
        # by the axial stiffness (k_e / m ~ 1e5 s^-2): its difference is the output's condition, not the equations'
        series = [lb for lb in m2.output_labels if lb in r2.data]
        a2 = [np.asarray(r2[lb]) for lb in series] + [np.asarray(r2.profiles[k]) for k in sorted(r2.profiles)]
        a3 = [np.asarray(r3[lb]) for lb in series] + [np.asarray(r3.profiles[k]) for k in sorted(r2.profiles)]
        rate = sorted(r2.profiles).index("element_tension_rate") + len(series)
        normwise = [float(np.max(np.abs(a - b)) / max(float(np.max(np.abs(a))), 1.0)) for a, b in zip(a2, a3)]
        s2, (s3, s3z) = np.asarray(r2.states), _drop_rows(np.asarray(r3.states))
        run_abs = float(np.max(np.abs(s2 - s3)))
        run_rel = max(v for k, v in enumerate(normwise) if k != rate)
        run_out = max([s3z, float(np.max(np.abs(r3.profiles["node_z"])))]
                      + [float(np.max(np.abs(np.asarray(r3[lb])))) for lb in r3.data if lb.startswith(("z_b", "phi_z"))])
        cases[sc.name] = {"elements_per_section": n_el, "equations_max_abs": d_abs, "equations_max_rel": d_rel,
                          "equations_out_of_plane_max_abs": out_of_plane, "run_max_abs": run_abs,
                          "equilibrium_max_abs_m": float(np.max(np.abs(_lift(np.r_[q2, q2])[:q3.size] - q3))),
                          "run_max_rel": run_rel, "run_out_of_plane_max_abs": run_out,
                          "run_tension_rate_max_rel": normwise[rate],
                          "three_d_q_labels": list(m3.q_labels[:6])}
        worst_abs = max(worst_abs, run_abs, run_out, out_of_plane)
        worst_rel = max(worst_rel, d_rel, run_rel)
    return {"run_max_abs": worst_abs, "max_rel": worst_rel, "cases": cases}


def _turn_nodes(alpha, v, rotate):
    """A node vector (x, y, z per node) turned node by node about the vertical."""
    return np.concatenate([rotate(alpha, r) for r in _nodes(v, 3)])


def rotation_invariance(scene, rotated_scene, rotate, quick: bool, alpha: float = math.radians(35.0),
                        n_el: int = 4) -> dict:
    """Largest difference between the node model's answer turned by ``alpha`` and the turned scene's answer."""
    sc = divided(scene, n_el)
    sr = rotated_scene(sc, alpha)
    m, mt = build_model(sc), build_model(sr)
    p, pr = m.parameters(sc), mt.parameters(sr)
    lab = m.output_labels
    scal = [k for k, lb in enumerate(lab) if lb.startswith(("u", "tension", "chord_stretch", "element_"))]
    vec = lambda y, name: np.array([y[lab.index(f"{ax}{name}")] for ax in ("x_b", "y_b", "z_b")])
    rng = np.random.default_rng(5)
    worst = worst_rel = 0.0
    nq = m.nq
    for x in _random_states(m, p, rng, 3 if quick else 10, 3):
        xr = np.concatenate([_turn_nodes(alpha, x[:nq], rotate), _turn_nodes(alpha, x[nq:], rotate)])
        for t in (0.0, 5.1):
            f, fr = np.array(m.ode(x, t, p)).ravel(), np.array(mt.ode(xr, t, pr)).ravel()
            acc, acc_r = f[nq:], fr[nq:]
            worst_rel = max(worst_rel, float(np.max(np.abs(_turn_nodes(alpha, acc, rotate) - acc_r)) / np.max(np.abs(acc))))
            y = np.array(m.outputs(x, m.top(t, p), p)).ravel()
            yr = np.array(mt.outputs(xr, mt.top(t, pr), pr)).ravel()
            worst_rel = max(worst_rel, float(np.max(np.abs(y[scal] - yr[scal]) / np.maximum(np.abs(y[scal]), 1.0))))
            for name in ("", "_rate"):
                worst = max(worst, float(np.max(np.abs(rotate(alpha, vec(y, name)) - vec(yr, name)))))
    run = dict(duration=3.0 if quick else 20.0, steps_per_output=40)
    r = simulate(sc.with_numerics(**run), model=m, method="rk")
    rr = simulate(sr.with_numerics(**run), model=mt, method="rk")
    pos = np.stack([np.asarray(r.profiles[f"node_{ax}"]) for ax in "xyz"], axis=-1)      # time x node x axis
    pos_r = np.stack([np.asarray(rr.profiles[f"node_{ax}"]) for ax in "xyz"], axis=-1)
    turned = np.einsum("ij,tnj->tni", np.array([rotate(alpha, e) for e in np.eye(3)]).T, pos)
    run_pos = float(np.max(np.abs(turned - pos_r)))
    ten = lambda res: [np.asarray(res["tension_top"]), np.asarray(res["tension_bottom"]),
                       np.asarray(res.profiles["element_tension"])]
    run_t = max(float(np.max(np.abs(a - b)) / np.max(np.abs(a))) for a, b in zip(ten(r), ten(rr)))
    return {"equations_max_abs": worst, "equations_max_rel": worst_rel, "run_position_max_abs_m": run_pos,
            "run_tension_max_rel": run_t, "alpha_deg": math.degrees(alpha), "elements": n_el,
            "node_excursion_m": float(np.max(np.ptp(pos, axis=0)))}


def chain_scene(n_el: int, three_d: bool):
    """A 50 m chain hanging from a fixed top, its end free (a weightless body of 1 mg), stiff, no current."""
    from three_d_checks import wire
    cable = wire(length=50.0, ae=4.0e7, segments=n_el, cd_normal=0.0, ct_tangential=0.0)
    body = Body(weight=0.0, mass_x=1e-6, mass_y=1e-6, mass_z=1e-6 if three_d else None,
                drag_area_normal=0.0, drag_area_tangential=0.0)
    return single_section_scene(cable=cable, body=body, numerics=Numerics(model="as-built", dimensions=3 if three_d else None))


def _transverse(md, axis: int, dim: int, count: int):
    """The lowest ``count`` mode frequencies whose shapes move mostly along ``axis`` (0 x, 2 z) of the nodes."""
    shapes = np.asarray(md.shapes)
    frac = np.array([np.sum(shapes[axis::dim, k] ** 2) / np.sum(shapes[:, k] ** 2) for k in range(shapes.shape[1])])
    w = np.asarray(md.omega_undamped)[frac > 0.5]
    return np.sort(w)[:count]


def chain_modes(quick: bool, n_modes: int = 3) -> dict:
    """Out-of-plane against in-plane modes of the hanging chain, and both against the Bessel-J0 closed form."""
    ns = (8, 16) if quick else (8, 16, 32)
    sc = chain_scene(ns[0], False)
    c = sc.cable
    rho = sc.environment.density
    m_t = c.mass_per_length + c.added_mass_factor * rho * math.pi * c.diameter**2 / 4       # eq. 23
    exact = jn_zeros(0, n_modes) / 2 * math.sqrt(c.weight_per_length / (m_t * c.length))
    rows, equal = [], 0.0
    for n in ns:
        s2, s3 = chain_scene(n, False), chain_scene(n, True)
        m2, m3 = build_model(s2), build_model(s3)
        w_in = _transverse(modes(linearize(m2, m2.parameters(s2))), 0, 2, n_modes)
        md3 = modes(linearize(m3, m3.parameters(s3)))
        w_out, w_in3 = _transverse(md3, 2, 3, n_modes), _transverse(md3, 0, 3, n_modes)
        equal = max(equal, float(np.max(np.abs(w_out / w_in - 1))), float(np.max(np.abs(w_in3 / w_in - 1))))
        rows.append({"elements": n, "omega_out_of_plane": w_out.tolist(), "omega_in_plane": w_in.tolist(),
                     "rel_err_vs_bessel": (np.abs(w_out / exact - 1)).tolist()})
    errs = np.array([r["rel_err_vs_bessel"] for r in rows])
    order = (np.log2(errs[:-1] / errs[1:])).tolist()
    return {"out_of_plane_vs_in_plane_max_rel": equal, "omega_bessel": exact.tolist(), "by_elements": rows,
            "observed_order": order, "vs_bessel_rel_err_finest": float(np.max(errs[-1]))}


def energy_drift(quick: bool, n_el: int = 3) -> dict:
    """max |E - E_0| / (E_0 - E_rest) of a 3-D swing of the node model, drag and damping off, top at rest."""
    from three_d_checks import pendulum_scene
    sc = divided(pendulum_scene(ae=3e5, weight=2e4, mass=3000.0, cable_mass=True,
                                numerics=Numerics(duration=1.0, output_step=0.05, model="as-built", dimensions=3)), n_el)
    m = build_model(sc)
    p = m.parameters(sc)
    q_rest = steady_state(m, p).q
    nodes = _nodes(q_rest, 3)
    a = 0.4                                    # the straight cable turned by 0.4 rad in the x-y plane (Wang's phi)
    depth = nodes[:, 1]
    q0 = np.column_stack([-depth * math.sin(a), depth * math.cos(a), np.zeros(len(depth))])
    L = depth[-1]
    v0 = np.column_stack([np.zeros(len(depth)), np.zeros(len(depth)), 0.25 * depth])   # sway: 0.25 rad/s about x
    x0 = np.concatenate([q0.ravel(), v0.ravel()])
    period = 2 * math.pi * math.sqrt(L / 9.80665)
    n_per = 5 if quick else 100
    r = simulate(sc.with_numerics(duration=n_per * period, output_step=period / 8), model=m, x0=x0,
                 rtol=1e-10, atol=1e-10, max_num_steps=10**6)
    e0 = np.zeros(m.top.size1_out(0))
    energy = lambda x: sum(float(v) for v in m.energy(x, e0, p))
    E = np.array([energy(x) for x in np.asarray(r.states).T])
    E_rest = energy(np.concatenate([q_rest, np.zeros(m.nq)]))
    return {"drift_rel": float(np.max(np.abs(E - E[0])) / (E[0] - E_rest)), "periods": n_per, "elements": n_el,
            "motion_energy_J": float(E[0] - E_rest), "rtol": 1e-10,
            "z_b_amplitude_m": float(np.max(np.abs(np.asarray(r["z_b"]))))}
