"""The 3-D seabed checks of ``ends_checks.py`` (node model in space, :mod:`cablesys.model.segmented_seabed`): a planar
mooring forced through the 3-D equations, the same mooring turned about the vertical, a line lying across a sloped bed
held or slid by its lateral friction, a line resting on the bed in space and the energy of a line bouncing on it (see
that study's docstring for the keys)."""

from __future__ import annotations

import dataclasses

import numpy as np

from cablesys.model import build_model
from cablesys.scene import Anchor, Body, Cable, Numerics, Seabed, Sinusoid, TopMotion, single_section_scene
from cablesys.scene.components import Environment
from cablesys.statics.catenary import segmented_steady
from cablesys.time_domain.run import simulate

# the chain of ends_checks.py: 300 m, w = 1300 N/m, EA = 50 MN, d = 0.1 m, 150 kg/m, fairlead 100 m above a flat bed
LENGTH, W, EA, DEPTH, DIAMETER, MASS = 300.0, 1300.0, 5e7, 100.0, 0.1, 150.0
K_BED, C_BED = 3e6, 3e5        # MoorDyn's default bed: Pa/m, Pa s/m
BODY = Body(weight=0.0, mass_x=1.0, mass_y=1.0)


def chain(n: int, length: float = LENGTH, **kw) -> Cable:
    return Cable(length=length, ae=EA, diameter=DIAMETER, mass_per_length=MASS, weight_per_length=W, segments=n, **kw)


def mooring(n: int, *, bearing_deg: float = 0.0, span: float = 250.0, slope_deg: float = 0.0, friction_axial=0.3,
            friction_lateral=0.6, surge: float = 3.0, heave: float = 1.0, duration: float = 30.0,
            dimensions: int | None = 3, rtol: float = 1e-10):
    """A mooring line from a fairlead at the top, moved in surge (along the line's horizontal direction) and heave at
    0.6 rad/s, to an anchor ``span`` m away on the bed ``DEPTH`` m below, the line's vertical plane at ``bearing_deg``
    from +x towards +z, the bed sloping by ``slope_deg`` along the line (its heading the bearing). At bearing 0 and
    ``dimensions`` None a planar scene; otherwise every x-z vector of the planar scene turned by the bearing."""
    g = np.radians(bearing_deg)
    planar = dimensions is None and bearing_deg == 0.0
    bed_depth = DEPTH + span * np.tan(np.radians(slope_deg))
    return single_section_scene(
        cable=chain(n), body=BODY,
        anchor=Anchor(x=span * np.cos(g), y=bed_depth, z=None if planar else span * np.sin(g)),
        seabed=Seabed(depth=DEPTH, slope_deg=slope_deg, heading_deg=None if planar else bearing_deg, stiffness=K_BED,
                      damping=C_BED, friction_axial=friction_axial, friction_lateral=friction_lateral),
        top_motion=TopMotion(x=(Sinusoid(amplitude=surge * np.cos(g), frequency=0.6),),
                             y=(Sinusoid(amplitude=heave, frequency=0.6),),
                             z=() if planar else (Sinusoid(amplitude=surge * np.sin(g), frequency=0.6),)),
        numerics=Numerics(duration=duration, output_step=0.5, model="as-built", rtol=rtol, atol=rtol,
                          dimensions=dimensions))


def _nodes(rec, dim: int) -> np.ndarray:
    """Free node positions of a run, (node, axis, time)."""
    X = np.asarray(rec.states)
    n = X.shape[0] // (2 * dim)
    return X[:dim * n].reshape(n, dim, -1)


def planar_equivalence(n: int = 10, duration: float = 30.0, rtol: float = 1e-10) -> dict:
    """The planar mooring (friction 0.3 axial, 0.6 lateral, fairlead in surge and heave) against the same scene forced
    through the 3-D equations (``numerics.dimensions = 3``): the 3-D right-hand side at the planar run's states (z = 0)
    against the planar one (largest difference of the node accelerations over the run, and the largest sway
    acceleration, relative to the run's largest node acceleration), and the two runs at ``rtol`` (node positions, m; element tensions relative to the largest)."""
    sc2, sc3 = mooring(n, dimensions=None, duration=duration, rtol=rtol), mooring(n, duration=duration, rtol=rtol)
    m2, m3 = build_model(sc2), build_model(sc3)
    p2, p3 = m2.parameters(sc2), m3.parameters(sc3)
    r2, r3 = simulate(sc2, model=m2), simulate(sc3, model=m3)
    X2, t = np.asarray(r2.states), np.asarray(r2.time)
    k = X2.shape[0] // 4
    diff, sway, scale = 0.0, 0.0, 0.0
    for i in range(0, len(t), 2):
        q, v = X2[:2 * k, i].reshape(k, 2), X2[2 * k:, i].reshape(k, 2)
        x3 = np.concatenate([np.column_stack([q, np.zeros(k)]).ravel(), np.column_stack([v, np.zeros(k)]).ravel()])
        a2 = np.array(m2.ode(X2[:, i], t[i], p2)).ravel()[2 * k:].reshape(k, 2)
        a3 = np.array(m3.ode(x3, t[i], p3)).ravel()[3 * k:].reshape(k, 3)
        diff, sway = max(diff, float(np.max(np.abs(a3[:, :2] - a2)))), max(sway, float(np.max(np.abs(a3[:, 2]))))
        scale = max(scale, float(np.max(np.abs(a2))))
    rhs, sway = diff / scale, sway / scale
    q2, q3 = _nodes(r2, 2), _nodes(r3, 3)
    T2, T3 = r2.profiles["element_tension"], r3.profiles["element_tension"]
    return {"rhs_max_rel": rhs, "sway_acceleration_max_rel": sway,
            "run_positions_max_abs_m": float(np.max(np.abs(q3[:, :2] - q2))),
            "run_sway_max_abs_m": float(np.max(np.abs(q3[:, 2]))),
            "run_tension_max_rel": float(np.max(np.abs(T3 - T2)) / np.max(np.abs(T2))),
            "friction_max_N": float(np.max(np.abs(r2.profiles["seabed_friction"]))),
            "N": n, "duration_s": duration, "success": bool(r2.success and r3.success)}


def rotated(bearing_deg: float = 35.0, n: int = 10, duration: float = 30.0, slope_deg: float = 3.0,
            rtol: float = 1e-10) -> dict:
    """The mooring on a bed sloping 3 degrees along the line, in the plane (3-D equations, bearing 0) and turned by
    ``bearing_deg`` about the vertical (anchor, fairlead motion and the slope's heading turned): its static state and
    run are the turned ones. Largest node-position difference after turning back (m), of the static state and of the
    run, and the largest relative difference of the element tensions (a rotation leaves them unchanged)."""
    g = np.radians(bearing_deg)
    turn = np.array([[np.cos(g), 0.0, -np.sin(g)], [0.0, 1.0, 0.0], [np.sin(g), 0.0, np.cos(g)]])
    runs, statics = [], []
    for b in (0.0, bearing_deg):
        sc = mooring(n, bearing_deg=b, slope_deg=slope_deg, duration=duration, rtol=rtol)
        model = build_model(sc)
        statics.append(segmented_steady(model, model.parameters(sc)).q.reshape(-1, 3))
        runs.append(simulate(sc, model=model))
    q0, q1 = _nodes(runs[0], 3), _nodes(runs[1], 3)
    back = np.einsum("ij,njt->nit", turn, q0)
    T0, T1 = runs[0].profiles["element_tension"], runs[1].profiles["element_tension"]
    return {"static_max_abs_m": float(np.max(np.abs(statics[0] @ turn.T - statics[1]))),
            "run_max_abs_m": float(np.max(np.abs(back - q1))),
            "run_tension_max_rel": float(np.max(np.abs(T1 - T0)) / np.max(np.abs(T0))),
            "bearing_deg": bearing_deg, "slope_deg": slope_deg, "N": n, "duration_s": duration,
            "success": bool(runs[0].success and runs[1].success)}


# the line laid across a sloped bed: 20 m of the chain along x, the bed sloping down towards +z
SLIDE_L, SLIDE_N, SLIDE_EA, SLIDE_VS, SLIDE_RHO = 20.0, 10, 1e6, 0.01, 1025.0


def slide_time(v, *, slope_deg: float, mu: float, added_mass_factor: float = 1.0):
    """Time (s) for a node of a line lying along a bed's contour to reach the down-slope speed v (m/s) from rest under
    its weight's down-slope part w sin(a) against the regularised lateral friction mu w cos(a) tanh(v / v_s)
    (:mod:`cablesys.model.segmented_seabed`), per unit length m_e v' = A - B tanh(v / v_s), m_e = m + gamma rho pi d^2 / 4
    (the sliding is normal to the line: its added mass moves, Wang 1971 eq. 23): with u = v / v_s,
    t = m_e v_s / (A^2 - B^2) [A u + B ln((A cosh u - B sinh u) / A)] (d/du of the bracket is (A^2 - B^2) / (A - B tanh u)).
    For B > A (tan a < mu) the speed tends to the creep speed v_s atanh(A / B) of the regularisation, where t -> inf:
    the friction holds the line but for that creep; for A > B it slides, accelerating at (A - B) / m_e."""
    a = np.radians(slope_deg)
    A, B = W * np.sin(a), mu * W * np.cos(a)
    m_e = MASS + added_mass_factor * SLIDE_RHO * np.pi * DIAMETER ** 2 / 4
    u = np.asarray(v, float) / SLIDE_VS
    # A cosh u - B sinh u = e^u [(A - B) + (A + B) e^(-2u)] / 2, its logarithm without overflow
    log = u + np.log(((A - B) + (A + B) * np.exp(-2.0 * u)) / (2.0 * A))
    return m_e * SLIDE_VS / (A * A - B * B) * (A * u + B * log)


def slide_speed(t, *, slope_deg: float, mu: float) -> np.ndarray:
    """The down-slope speed (m/s) at times t (s) of :func:`slide_time`, inverted by SciPy's brentq (t(v) increases
    from 0, towards infinity at the creep speed when the friction holds)."""
    from scipy.optimize import brentq
    a = np.radians(slope_deg)
    A, B = np.sin(a), mu * np.cos(a)
    top = SLIDE_VS * np.arctanh(A / B) * (1 - 1e-15) if B > A else 1e3
    f = lambda v, ti: slide_time(v, slope_deg=slope_deg, mu=mu) - ti
    return np.array([0.0 if ti <= 0 else top if f(top, ti) <= 0 else brentq(f, 0.0, top, args=(ti,), xtol=1e-15,
                                                                              rtol=1e-14) for ti in t])


def lateral_slide(mu: float, slope_deg: float = 20.0, duration: float = 4.0, series: bool = False) -> dict:
    """A line of ``SLIDE_L`` m of the chain laid straight along x (zero tension) on a bed sloping ``slope_deg`` down
    towards +z (heading 90 degrees), its ends held (the top and an anchor on the bed), dropped from its nodes'
    static penetration with no drag: the middle node's down-slope speed against :func:`slide_speed`, the closed form of
    one node (the inner nodes slide together without stretching their elements, so the two end elements' tension
    reaches the middle only later). Returns the largest error of the speed (m/s) and of the displacement (m) against
    the closed form over the run, the last speed and displacement, the creep speed v_s atanh(tan a / mu) (m/s; NaN
    when the line slides) and the acceleration (A - B) / m_e (m/s^2; NaN when it holds); ``series``: also the run's
    (t, v) and the closed form's v."""
    from scipy.integrate import cumulative_trapezoid
    a = np.radians(slope_deg)
    scene = single_section_scene(
        cable=Cable(length=SLIDE_L, ae=SLIDE_EA, diameter=DIAMETER, mass_per_length=MASS, weight_per_length=W,
                    cd_normal=0.0, ct_tangential=0.0, segments=SLIDE_N),
        body=BODY, anchor=Anchor(x=SLIDE_L, y=0.0, z=0.0),
        seabed=Seabed(depth=DEPTH, slope_deg=slope_deg, heading_deg=90.0, stiffness=K_BED, damping=C_BED,
                      friction_axial=mu, friction_lateral=mu, friction_speed=SLIDE_VS),
        environment=Environment(top_depth=DEPTH, density=SLIDE_RHO),
        numerics=Numerics(duration=duration, output_step=0.05, model="as-built", rtol=1e-10, atol=1e-10))
    model = build_model(scene)
    n_in = np.array([0.0, np.cos(a), -np.sin(a)])               # into the bed (heading 90 degrees)
    sink = W * np.cos(a) / (K_BED * DIAMETER)                    # k d h delta = w h cos(a)
    h = SLIDE_L / SLIDE_N
    q0 = np.array([[j * h, 0.0, 0.0] + sink * n_in for j in range(1, SLIDE_N)]).ravel()
    rec = simulate(scene, model=model, x0=np.concatenate([q0, np.zeros_like(q0)]))
    X, t = np.asarray(rec.states), np.asarray(rec.time)
    nq = X.shape[0] // 2
    down = np.array([0.0, np.sin(a), np.cos(a)])                 # down the slope, in the bed
    mid = SLIDE_N // 2 - 1
    v = X[nq + 3 * mid:nq + 3 * mid + 3].T @ down
    s = (X[3 * mid:3 * mid + 3] - X[3 * mid:3 * mid + 3, :1]).T @ down
    v_cf = slide_speed(t, slope_deg=slope_deg, mu=mu)
    s_cf = cumulative_trapezoid(slide_speed(np.linspace(0, duration, 4001), slope_deg=slope_deg, mu=mu),
                                np.linspace(0, duration, 4001), initial=0.0)
    A, B = np.sin(a), mu * np.cos(a)
    m_e = MASS + SLIDE_RHO * np.pi * DIAMETER ** 2 / 4
    out = {"series": (t, v, v_cf)} if series else {}
    return out | {"speed_max_abs_err_m_s": float(np.max(np.abs(v - v_cf))),
            "displacement_max_abs_err_m": float(np.max(np.abs(s - np.interp(t, np.linspace(0, duration, 4001), s_cf)))),
            "speed_end_m_s": float(v[-1]), "displacement_end_m": float(s[-1]),
            "creep_speed_m_s": float(SLIDE_VS * np.arctanh(A / B)) if B > A else float("nan"),
            "acceleration_m_s2": float(W * (A - B) / m_e) if A > B else float("nan"),
            "tan_slope": float(np.tan(a)), "mu_lateral": mu, "duration_s": duration, "success": bool(rec.success)}


def resting(duration: float, n: int = 10, bearing_deg: float = 35.0, cross_deg: float = 60.0,
            slope_deg: float = 3.0) -> dict:
    """The mooring turned to ``bearing_deg``, its bed sloping ``slope_deg`` towards a heading ``cross_deg`` off the
    line's (so that the laid part lies across a slope and carries its down-slope weight by its curvature: the statics
    hold no lateral friction), no axial and 0.6 lateral friction, MoorDyn's default bed, the fairlead at rest: left from
    its static state for ``duration`` s. Returns the largest node displacement (m) and the largest lateral offset of
    the static line from the vertical plane through its ends (m: the slope's pull across it)."""
    g = np.radians(bearing_deg)
    sc = mooring(n, bearing_deg=bearing_deg, friction_axial=0.0, surge=0.0, heave=0.0, duration=duration)
    bed = dataclasses.replace(sc.seabed, slope_deg=slope_deg, heading_deg=bearing_deg + cross_deg)
    anchor = np.array(sc.anchor.position)
    anchor[1] = bed.bed_y(anchor[0], 0.0, anchor[2])
    sc = dataclasses.replace(sc, seabed=bed, anchor=Anchor(x=anchor[0], y=anchor[1], z=anchor[2]),
                             top_motion=TopMotion(),
                             numerics=dataclasses.replace(sc.numerics, output_step=5.0, rtol=1e-8, atol=1e-8))
    rec = simulate(sc)
    q = _nodes(rec, 3)
    across = np.array([-np.sin(g), 0.0, np.cos(g)])
    return {"drift_max_m": float(np.max(np.linalg.norm(q - q[:, :, :1], axis=1))),
            "static_offset_across_m": float(np.max(np.abs(q[:, :, 0] @ across))),
            "duration_s": duration, "N": n, "success": bool(rec.success)}


def bouncing(duration: float, n: int = 10, chord: float = 20.0, lift: float = 1.0, bow: float = 1.0,
             bearing_deg: float = 35.0, ea: float = 1e6, rtol: float = 1e-10) -> dict:
    """A soft rope between two points on a flat bed, its vertical plane at ``bearing_deg``, lifted into the arc
    y = -lift sin(pi s / chord) bowed sideways by bow sin(pi s / chord) at zero strain (nodes equally spaced along the
    3-D arc, the rope as long as it) and dropped: no drag, no friction, no contact damping, no internal damping (the
    planar ``ends_checks.bouncing`` in space). Returns the energy drift max |E(t) - E(0)| / (E(0) - E_rest) (E_rest: the
    rope lying straight at its static penetration) and the mid-node's number of contacts."""
    from scipy.integrate import cumulative_trapezoid

    g = np.radians(bearing_deg)
    xs = np.linspace(0.0, chord, 20001)
    shape = lambda x: np.column_stack([x, -lift * np.sin(np.pi * x / chord), bow * np.sin(np.pi * x / chord)])
    pts = shape(xs)
    s = cumulative_trapezoid(np.linalg.norm(np.gradient(pts, xs, axis=0), axis=1), xs, initial=0.0)
    arc = float(s[-1])
    turn = np.array([[np.cos(g), 0.0, -np.sin(g)], [0.0, 1.0, 0.0], [np.sin(g), 0.0, np.cos(g)]])
    cab = Cable(length=arc, ae=ea, diameter=DIAMETER, mass_per_length=MASS, weight_per_length=W, segments=n,
                cd_normal=0.0, ct_tangential=0.0)
    scene = single_section_scene(
        cable=cab, body=BODY, anchor=Anchor(x=chord * np.cos(g), y=0.0, z=chord * np.sin(g)),
        seabed=Seabed(depth=DEPTH, stiffness=K_BED, damping=0.0), environment=Environment(top_depth=DEPTH),
        numerics=Numerics(duration=duration, output_step=0.02, model="as-built", rtol=rtol, atol=rtol))
    model = build_model(scene)
    p = model.parameters(scene)
    q0 = (shape(np.interp(arc * np.arange(1, n) / n, s, xs)) @ turn.T).ravel()
    rec = simulate(scene, model=model, x0=np.concatenate([q0, np.zeros_like(q0)]))
    X, t = np.asarray(rec.states), np.asarray(rec.time)
    energy = lambda x, ti: sum(float(v) for v in model.energy(x, model.top(ti, p), p))
    E = np.array([energy(X[:, i], t[i]) for i in range(len(t))])
    sink = W / (K_BED * DIAMETER)                             # static penetration of a lying node
    q_rest = (np.column_stack([chord * np.arange(1, n) / n, np.full(n - 1, sink), np.zeros(n - 1)]) @ turn.T).ravel()
    E_rest = energy(np.concatenate([q_rest, 0 * q_rest]), 0.0)
    touching = X[3 * (n // 2 - 1) + 1] > 0.0                  # the mid node below the bed's surface (y = 0)
    return {"energy_drift_rel": float(np.max(np.abs(E - E[0])) / (E[0] - E_rest)),
            "contacts": int(np.sum(touching[1:] & ~touching[:-1])), "duration_s": duration,
            "sway_range_m": float(np.ptp(X[3 * (n // 2 - 1) + 2] * np.cos(g) - X[3 * (n // 2 - 1)] * np.sin(g))),
            "success": bool(rec.success), "reached_s": float(t[-1])}
