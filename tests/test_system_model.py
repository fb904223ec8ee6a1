"""The node model of a cable system (lines joined at points, cablesys.model.system): a chain built as a graph is the
chain's node model; a symmetric three-line mooring and a span with a clump weight hung from a junction against the
elastic catenary's closed form (second order in N); a bridle of two equal legs against the one doubled line; energy
conserved without drag and damping; the restoring force of the catenaries on a buoy pulled by a current."""

import math
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import root

sys.path.insert(0, str(Path(__file__).resolve().parent))
from energy_checks import energy_history  # noqa: E402

from cablesys.model import build_model  # noqa: E402
from cablesys.model.system import build_system_model  # noqa: E402
from cablesys.scene import Body, Cable, Scene, Section, TopMotion  # noqa: E402
from cablesys.scene.components import Numerics  # noqa: E402
from cablesys.scene.harmonics import Sinusoid  # noqa: E402
from cablesys.scene.system import Line, Point, System  # noqa: E402
from cablesys.statics.closed_forms import seabed_catenary  # noqa: E402
from cablesys.statics.system import system_steady  # noqa: E402

pytestmark = pytest.mark.filterwarnings("ignore")
RHO = 1025.0


def wire(n, **kw):
    return Cable(**{**dict(length=100.0, ae=2e6, diameter=0.02, mass_per_length=1.5, weight_per_length=12.0,
                           cd_normal=1.2, internal_damping=400.0, segments=n), **kw})


def as_graph(system: System, **kw) -> Scene:
    """A scene holding ``system`` as a graph even when it is a chain (which a Scene turns into sections): the chain's
    system set on a scene made from another system."""
    other = System(point=(Point(name="a", kind="prescribed"), Point(name="b", kind="fixed", x=1.0, y=1.0),
                          Point(name="c", kind="junction", body=Body(weight=1.0, mass_x=1.0, mass_y=1.0))),
                   line=(Line(name="x", start="a", end="c", section=(wire(2),)),
                         Line(name="y", start="c", end="b", section=(wire(2),))))
    scene = Scene(system=other, **kw)
    object.__setattr__(scene, "system", system)
    return scene


CLUMP = Body(weight=800.0, mass_x=120.0, mass_y=130.0, drag_area_normal=0.2, drag_area_tangential=0.2)
PKG = Body(weight=3000.0, mass_x=400.0, mass_y=450.0, mass_z=420.0, drag_area_normal=0.8, drag_area_tangential=0.5,
           axis_angle_deg=10.0)


def same_dynamics(m_c, m_g, p_c, p_g, x, times):
    """The graph model ``m_g``'s ode and energy are the chain model ``m_c``'s at the state x and each of ``times`` (to
    1e-12 relative); yields (t, the chain's outputs by label, the graph's) for the caller's outputs."""
    for t in times:
        f_c, f_g = np.array(m_c.ode(x, t, p_c)).ravel(), np.array(m_g.ode(x, t, p_g)).ravel()
        assert np.max(np.abs(f_g - f_c)) <= 1e-12 * np.max(np.abs(f_c))
        e = np.array(m_c.top(t, p_c)).ravel()
        np.testing.assert_allclose(np.array(m_g.energy(x, e, p_g), float), np.array(m_c.energy(x, e, p_c), float),
                                   rtol=1e-12)
        yield (t, dict(zip(m_c.output_labels, np.array(m_c.outputs(x, e, p_c)).ravel())),
               dict(zip(m_g.output_labels, np.array(m_g.outputs(x, e, p_g)).ravel())))


@pytest.mark.parametrize("space", [False, True])
def test_a_chain_built_as_a_graph_is_the_chains_node_model(space):
    """ship -> wire -> clump (junction) -> wire -> anchor in the plane, or -> package (free) swaying in 3-D: the graph
    model numbers the nodes as the chain's does, and its ode, energy and outputs are the chain's to round-off (the
    chain's tension_top / tension_bottom are the lines' tension_from / tension_to, x_b its points' x)."""
    motion = TopMotion(x=(Sinusoid(amplitude=1.0, frequency=0.6),), y=(Sinusoid(amplitude=0.5, frequency=0.6),),
                       z=(Sinusoid(amplitude=0.7, frequency=0.4),) if space else (), ramp_s=10.0)
    low = (Point(name="pkg", kind="body", body=PKG) if space else Point(name="anchor", kind="fixed", x=60.0, y=150.0))
    system = System(point=(Point(name="ship", kind="prescribed"), Point(name="clump", kind="junction", body=CLUMP), low),
                    line=(Line(name="upper", start="ship", end="clump", section=(wire(4),)),
                          Line(name="lower", start="clump", end=low.name, section=(wire(3, length=80.0),))))
    chain = Scene(system=system, top_motion=motion)
    assert chain.system is None and len(chain.sections) == 2         # the Scene makes it the chain of sections
    graph = as_graph(system, top_motion=motion)
    m_c, m_g = build_model(chain), build_system_model(graph)
    assert m_g.q_labels == m_c.q_labels and m_g.dim == (3 if space else 2)
    rng = np.random.default_rng(3)
    dim = m_c.dim
    x = rng.normal(size=2 * m_c.nq)
    x[:m_c.nq] += np.tile(np.r_[0.0, 40.0, 0.0][:dim], m_c.nq // dim) * np.repeat(np.arange(1, m_c.nq // dim + 1), dim)
    p_c, p_g = m_c.parameters(chain), m_g.parameters(graph)
    for _, y_c, y_g in same_dynamics(m_c, m_g, p_c, p_g, x, (0.7, 13.1)):
        pairs = {"tension_top_1": "line.upper.tension_from", "tension_bottom_1": "line.upper.tension_to",
                 "tension_top_2": "line.lower.tension_from", "tension_bottom_2": "line.lower.tension_to",
                 "x_b_1": "point.clump.x", "y_b_1": "point.clump.y", "y_b_rate_1": "point.clump.y_rate"}
        pairs.update({f"element_tension[{k}]": f"element_tension[{k}]" for k in range(7)})
        if space:
            pairs.update({"z_b_2": "point.pkg.z", "tension_bottom_2": "line.lower.tension_to"})
        for a, b in pairs.items():
            assert y_g[b] == pytest.approx(y_c[a], rel=1e-12, abs=1e-12), (a, b)


def mooring(n, *, ae=5e8, cd=0.0, damping=0.0, drag=0.0, duration=10.0, mass=4e4):
    """A submerged buoy (net buoyancy 300 kN) moored by three 160 m chains (500 N/m in water) to anchors 150 m from
    it at 120 deg and 100 m below the node frame's origin: no prescribed point, a 3-D scene."""
    pts = [Point(name="buoy", kind="body", body=Body(weight=-300e3, mass_x=mass, mass_y=mass, mass_z=mass,
                                                     drag_area_normal=drag, drag_area_tangential=drag))]
    lines = []
    for k in range(3):
        a = math.radians(120 * k)
        pts.append(Point(name=f"anchor{k}", kind="fixed", x=150 * math.cos(a), y=100.0, z=150 * math.sin(a)))
        lines.append(Line(name=f"leg{k}", start="buoy", end=f"anchor{k}",
                          section=(Cable(length=160.0, ae=ae, diameter=0.1, mass_per_length=60.0, weight_per_length=500.0,
                                         cd_normal=cd, ct_tangential=cd, internal_damping=damping, segments=n),)))
    return Scene(system=System(point=tuple(pts), line=tuple(lines)), numerics=Numerics(duration=duration, output_step=0.5))


def catenary_forces(bx, by, ea=5e8):
    """Horizontal force along x and vertical pull down on the buoy at (bx, by, 0) from the three elastic catenaries
    (closed form, cablesys.statics.closed_forms.seabed_catenary: each line hangs clear of the anchor's level), and
    each line's fairlead and anchor tension (N)."""
    fx, fv, ends = 0.0, 0.0, []
    for k in range(3):
        a = math.radians(120 * k)
        dx, dz = 150 * math.cos(a) - bx, 150 * math.sin(a)
        X = math.hypot(dx, dz)
        c = seabed_catenary(length=160.0, weight_per_length=500.0, ea=ea, span=X, height=100.0 - by)
        assert c["L_B"] == 0.0                       # suspended: the closed form without seabed contact
        fx += c["H"] * dx / X
        fv += c["V_F"]
        ends.append((math.hypot(c["H"], c["V_F"]), math.hypot(c["H_A"], c["V_A"])))
    return fx, fv, ends


def closed_form_buoy(force=0.0, ea=5e8):
    """The buoy's (x, y) where the catenaries balance its buoyancy and a horizontal ``force`` along +x (N)."""
    sol = root(lambda v: [(catenary_forces(*v, ea)[0] + force) / 1e3, (catenary_forces(*v, ea)[1] - 300e3) / 1e3],
               [0.0, 47.0], tol=1e-14)
    assert sol.success
    return sol.x


def test_a_symmetric_three_line_mooring_against_the_elastic_catenary():
    """The equilibrium is offset-free (the buoy above the anchors' centre) and its depth, every line's fairlead and
    anchor tension converge at second order in N to the elastic catenary's closed form (Richardson of N = 8, 16 within
    5e-7 of it)."""
    bx, by = closed_form_buoy()
    assert abs(bx) < 1e-9
    t_fair, t_anchor = catenary_forces(bx, by)[2][0]
    errors, values = [], []
    for n in (4, 8, 16):
        sc = mooring(n)
        m = build_model(sc)
        y = system_steady(m, m.parameters(sc)).outputs
        assert abs(y["point.buoy.x"]) < 1e-9 and abs(y["point.buoy.z"]) < 1e-9
        fair = [y[f"line.leg{k}.tension_from"] for k in range(3)]
        anchor = [y[f"line.leg{k}.tension_to"] for k in range(3)]
        assert np.ptp(fair) < 1e-6 * fair[0] and np.ptp(anchor) < 1e-6 * anchor[0]      # the three legs alike
        v = np.array([y["point.buoy.y"], fair[0], anchor[0]])
        values.append(v)
        errors.append(np.abs(v - [by, t_fair, t_anchor]) / [100.0, t_fair, t_anchor])
    order = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all((order > 1.9) & (order < 2.1)), order
    rich = (4 * values[2] - values[1]) / 3
    np.testing.assert_allclose(rich, [by, t_fair, t_anchor], rtol=5e-7)


def test_a_span_with_a_clump_weight_hung_from_a_junction_against_the_catenaries():
    """A crane (prescribed) and a post (fixed) joined by two wires meeting at a ring (junction), a clump weight hung
    from the ring by a third line, in the plane: the ring where the two elastic catenaries' pulls balance the ring, the
    drop line and the clump (closed form); the node model converges at second order in N."""
    w, ae, W_ring, W_clump, L_drop = 20.0, 5e6, 500.0, 4000.0, 20.0

    def scene(n):
        cab = lambda length: (Cable(length=length, ae=ae, diameter=0.024, mass_per_length=2.4, weight_per_length=w,
                                    segments=n),)
        return Scene(system=System(
            point=(Point(name="crane", kind="prescribed"), Point(name="post", kind="fixed", x=80.0, y=10.0),
                   Point(name="ring", kind="junction", body=Body(weight=W_ring, mass_x=60.0, mass_y=60.0)),
                   Point(name="clump", kind="body", body=Body(weight=W_clump, mass_x=500.0, mass_y=500.0))),
            line=(Line(name="left", start="crane", end="ring", section=cab(45.0)),
                  Line(name="right", start="ring", end="post", section=cab(45.0)),
                  Line(name="drop", start="ring", end="clump", section=cab(L_drop)))))

    def pulls(rx, ry):
        """(horizontal, vertical up) pull of the two span lines on the ring at (rx, ry): each an elastic catenary from
        the ring (its low end) up to its support."""
        out = np.zeros(2)
        for sx, sy in ((0.0, 0.0), (80.0, 10.0)):
            c = seabed_catenary(length=45.0, weight_per_length=w, ea=ae, span=abs(sx - rx), height=ry - sy)
            out += [c["H"] * np.sign(sx - rx), c["V_A"] if c["L_B"] == 0.0 else np.nan]
        return out
    hanging = W_ring + W_clump + w * L_drop        # the drop line hangs straight down: it pulls the clump and its weight
    sol = root(lambda v: (pulls(*v) - [0.0, hanging]) / 1e3, [37.0, 24.0], tol=1e-14)
    assert np.all(np.abs(pulls(*sol.x) - [0.0, hanging]) < 1e-9 * hanging)     # both suspended, pulling the ring up
    values = []
    for n in (4, 8, 16):
        sc = scene(n)
        m = build_model(sc)
        y = system_steady(m, m.parameters(sc)).outputs
        assert y["line.drop.tension_from"] == pytest.approx(W_clump + w * L_drop, rel=1e-9)   # exact for any N
        assert y["point.clump.x"] == pytest.approx(y["point.ring.x"], abs=1e-9)
        values.append(np.array([y["point.ring.x"], y["point.ring.y"]]))
    e = [np.abs(v - sol.x) for v in values]
    assert np.all(np.log2(e[0] / e[1]) > 1.8) and np.all(np.log2(e[1] / e[2]) > 1.8)
    np.testing.assert_allclose((4 * values[2] - values[1]) / 3, sol.x, atol=1e-6)


def test_a_bridle_of_two_equal_legs_is_the_doubled_line():
    """ship -> wire -> ring -> two equal legs -> package: at rest the same shape as the chain with one leg of twice the
    stiffness and weight, each leg carrying half its tension (parallel lines between the same two points)."""
    leg = Cable(length=30.0, ae=1e6, diameter=0.02, mass_per_length=1.0, weight_per_length=8.0, segments=3)
    double = Cable(length=30.0, ae=2e6, diameter=0.02, mass_per_length=2.0, weight_per_length=16.0, segments=3)
    ring = Body(weight=200.0, mass_x=20.0, mass_y=20.0)
    pkg = Body(weight=3000.0, mass_x=400.0, mass_y=400.0)
    bridle = Scene(system=System(
        point=(Point(name="ship", kind="prescribed"), Point(name="ring", kind="junction", body=ring),
               Point(name="pkg", kind="body", body=pkg)),
        line=(Line(name="main", start="ship", end="ring", section=(wire(4),)),
              Line(name="leg_a", start="ring", end="pkg", section=(leg,)),
              Line(name="leg_b", start="ring", end="pkg", section=(leg,)))))
    assert bridle.system is not None                   # two lines between the same points: not a chain
    chain = Scene(sections=(Section(cable=wire(4), body=ring), Section(cable=double, body=pkg)))
    mb, mc = build_model(bridle), build_model(chain)
    yb = system_steady(mb, mb.parameters(bridle)).outputs
    from cablesys.statics.steady import steady_state
    yc = steady_state(mc, mc.parameters(chain)).outputs
    assert yb["point.pkg.y"] == pytest.approx(yc["y_b_2"], rel=1e-10)
    assert yb["point.ring.y"] == pytest.approx(yc["y_b_1"], rel=1e-10)
    assert 2 * yb["line.leg_a.tension_to"] == pytest.approx(yc["tension_bottom_2"], rel=1e-10)
    assert yb["line.leg_a.tension_from"] == pytest.approx(yb["line.leg_b.tension_from"], rel=1e-12)


def test_energy_is_conserved_without_drag_and_damping():
    """The moored buoy (softer lines, 4 t) released 2 m off its equilibrium in still water, no drag, no Voigt damping:
    K + V (the model's own energy) drifts by less than 1e-6 of the swing energy over 100 s (about 14 periods of its
    surge)."""
    sc = mooring(4, ae=5e6, mass=4e3, duration=100.0)
    m = build_model(sc)
    p = m.parameters(sc)
    x_static = system_steady(m, p).x
    x0 = x_static.copy()
    x0[0] += 2.0
    r, E, swing = energy_history(sc, m, p, x0, x_static)
    crossings = np.sum(np.diff(np.sign(r["point.buoy.x"] - r["point.buoy.x"].mean())) != 0)
    assert crossings >= 20                             # at least 10 periods
    assert np.max(np.abs(E - E[0])) < 1e-6 * swing


def test_a_buoy_pulled_by_a_current_gets_the_catenaries_restoring_force():
    """A uniform current drags the buoy (sphere drag 1/2 rho C_D A U^2, the lines without drag): the node model's offset
    is where the closed-form catenaries' restoring force balances it (Richardson of N = 8, 16 within 1e-4 of the
    offset), and the restoring stiffness from the statics' finite difference between two currents is the closed form's."""
    cda = 25.0
    offsets = {}
    for U in (1.5, 2.0):
        force = 0.5 * RHO * cda * U * U
        bx, by = closed_form_buoy(force)
        got = []
        for n in (8, 16):
            sc = mooring(n, drag=cda).with_environment(current_depths=(0.0,), current_speeds=(U,))
            m = build_model(sc)
            y = system_steady(m, m.parameters(sc)).outputs
            assert abs(y["point.buoy.z"]) < 1e-9
            got.append(np.array([y["point.buoy.x"], y["point.buoy.y"]]))
        rich = (4 * got[1] - got[0]) / 3
        assert rich[0] == pytest.approx(bx, rel=1e-4) and rich[1] == pytest.approx(by, abs=5e-5)
        offsets[U] = (force, rich[0], bx)
    (f1, x1, c1), (f2, x2, c2) = offsets[1.5], offsets[2.0]
    assert (f2 - f1) / (x2 - x1) == pytest.approx((f2 - f1) / (c2 - c1), rel=1e-4)


@pytest.mark.parametrize("bearing", [None, 30.0])
def test_a_chain_wire_chain_mooring_line_is_todays_sections_with_weightless_joints(bearing):
    """One [[line]] of three sections from a fairlead to an anchor on a seabed with friction, in the graph model, and
    today's [[sections]] with [anchor] and [seabed] whose joints carry weightless bodies of 1e-9 kg: the same nodes,
    the same static state (1e-9 m), the same static forces (the laid-down friction) and ode (to the joints' masses).
    In the plane, and in space (``bearing``): the line's vertical plane turned 30 deg about the vertical, on a bed
    sloping 2 deg along it, the fairlead moved along the line and across it (the 3-D bed's normal, axial and lateral
    friction on a line's tangent from the elements on both sides of a node, as the chain's; axial friction 0.1, with
    which the laid part stays in tension to the anchor)."""
    from cablesys.scene import Anchor, Seabed
    from cablesys.statics.steady import steady_state
    chain = lambda n, length: Cable(length=length, ae=5e8, diameter=0.1, mass_per_length=60.0, weight_per_length=500.0,
                                    cd_normal=2.4, ct_tangential=0.4, segments=n)
    secs = (chain(4, 60.0), Cable(length=150.0, ae=2e8, diameter=0.08, mass_per_length=20.0, weight_per_length=150.0,
                                  cd_normal=1.2, segments=6), chain(8, 120.0))
    if bearing is None:
        bed = Seabed(depth=100.0, friction_axial=0.5, damping=1e5)
        end, motion = (280.0, 100.0, None), TopMotion(x=(Sinusoid(amplitude=2.0, frequency=0.5),), ramp_s=20.0)
    else:
        g, slope = math.radians(bearing), 2.0
        bed = Seabed(depth=100.0, friction_axial=0.1, friction_lateral=0.8, damping=1e5, slope_deg=slope,
                     heading_deg=bearing)
        end = (280.0 * math.cos(g), 100.0 + 280.0 * math.tan(math.radians(slope)), 280.0 * math.sin(g))
        motion = TopMotion(x=(Sinusoid(amplitude=2.0, frequency=0.5),), z=(Sinusoid(amplitude=1.0, frequency=0.5),),
                           ramp_s=20.0)
    graph = Scene(system=System(point=(Point(name="fairlead", kind="prescribed"),
                                       Point(name="anchor", kind="fixed", x=end[0], y=end[1], z=end[2])),
                                line=(Line(name="mooring", start="fairlead", end="anchor", section=secs),)),
                  seabed=bed, top_motion=motion)
    joint = Body(weight=0.0, mass_x=1e-9, mass_y=1e-9)
    old = Scene(sections=tuple(Section(cable=c, body=joint) for c in secs), anchor=Anchor(x=end[0], y=end[1], z=end[2]),
                seabed=bed, top_motion=motion)
    assert graph.system is not None and graph.sections == ()
    assert graph.three_d == old.three_d == (bearing is not None)
    m_g, m_o = build_model(graph), build_model(old)
    assert m_g.q_labels == m_o.q_labels
    p_g, p_o = m_g.parameters(graph), m_o.parameters(old)
    s_g, s_o = steady_state(m_g, p_g), steady_state(m_o, p_o)
    np.testing.assert_allclose(s_g.q, s_o.q, rtol=0, atol=1e-9)
    assert s_g.outputs["line.mooring.tension_from"] == pytest.approx(s_o.outputs["tension_top_1"], rel=1e-9)
    assert s_g.outputs["line.mooring.tension_to"] == pytest.approx(s_o.outputs["tension_bottom_3"], rel=1e-9)
    rng = np.random.default_rng(5)
    x = np.concatenate([s_o.q + rng.normal(size=s_o.q.size) * 0.05, rng.normal(size=s_o.q.size) * 0.1])
    f_g, f_o = (np.array(m.ode(x, 5.0, pp)).ravel() for m, pp in ((m_g, p_g), (m_o, p_o)))
    assert np.max(np.abs(f_g - f_o)) < 1e-10 * np.max(np.abs(f_o))
    z, e = np.zeros(s_o.q.size), np.zeros(m_o.dynamics.size1_in(2))
    np.testing.assert_array_equal(np.array(m_g.static_force(x[:z.size], z, e, p_g)),
                                  np.array(m_o.static_force(x[:z.size], z, e, p_o)))
    if bearing is not None:          # the bed's lateral friction acts on the perturbed line, the same in both
        y_g = dict(zip(m_g.output_labels, np.array(m_g.outputs(x, e, p_g)).ravel()))
        y_o = dict(zip(m_o.output_labels, np.array(m_o.outputs(x, e, p_o)).ravel()))
        lat = [k for k in y_o if k.startswith("seabed_friction_lateral[")]
        assert len(lat) == m_o.nq // 3 + 2 and max(abs(y_o[k]) for k in lat) > 1.0
        for k in lat:
            assert y_g[k] == pytest.approx(y_o[k], rel=1e-10, abs=1e-9), k


def test_a_buoy_held_by_two_lines_lying_on_the_seabed_against_the_catenary_with_friction():
    """A buoy (90 kN net buoyancy) held by two 240 m chains to anchors on the bed 190 m either side, friction 0.5: each
    line is the elastic catenary with seabed friction (closed form: its fairlead carries half the buoyancy, 150 m lie on
    the bed, the touchdown on a node at every N here); the buoy's depth converges to it at second order in N
    (N = 8, 16, 32 from the default guess; N = 64 by a run's start, which refines the state from coarser N when its
    first guess fails)."""
    from scipy.optimize import brentq
    from cablesys.scene import Seabed
    from cablesys.statics.system import system_initial_state
    L, w, ea, R, D, B, mu = 240.0, 500.0, 5e8, 190.0, 100.0, 90e3, 0.5

    def scene(n):
        cab = (Cable(length=L, ae=ea, diameter=0.1, mass_per_length=60.0, weight_per_length=w, segments=n),)
        return Scene(system=System(
            point=(Point(name="buoy", kind="body", body=Body(weight=-B, mass_x=1e4, mass_y=1e4)),
                   Point(name="west", kind="fixed", x=-R, y=D), Point(name="east", kind="fixed", x=R, y=D)),
            line=(Line(name="w", start="buoy", end="west", section=cab), Line(name="e", start="buoy", end="east",
                                                                             section=cab))),
            seabed=Seabed(depth=D, friction_axial=mu, stiffness=3e8))
    cat = lambda Z: seabed_catenary(length=L, weight_per_length=w, ea=ea, span=R, height=Z, friction=mu)
    Z = brentq(lambda Z: cat(Z)["V_F"] - B / 2, 60.0, 95.0, xtol=1e-13)
    assert cat(Z)["L_B"] == pytest.approx(150.0, rel=1e-9)
    errors = []
    for n in (8, 16, 32, 64):
        sc = scene(n)
        m = build_model(sc)
        p = m.parameters(sc)
        if n < 64:
            y = system_steady(m, p).outputs
            assert y["line.w.tension_from"] == pytest.approx(y["line.e.tension_from"], rel=1e-9)
            q = (y["point.buoy.x"], y["point.buoy.y"])
        else:
            q = system_initial_state(sc, m, p)[:2]
        assert abs(q[0]) < 1e-9
        errors.append(abs(q[1] - (D - Z)))
    order = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all((order > 1.7) & (order < 2.3)), order


def test_a_buoy_held_by_two_lines_lying_on_the_seabed_turned_about_the_vertical():
    """The buoy held by two chains lying on the bed (friction 0.5, 150 m laid each side), its anchors turned 30 deg
    about the vertical into a 3-D scene: the 3-D bed (normal contact and the laid-down friction along the lines'
    tangent projected on the bed) gives the planar statics, the buoy's depth and every line-end tension to 1e-9 and no
    sway beyond the statics' tolerance (rotation invariance)."""
    from cablesys.scene import Seabed
    L, w, R, D, B = 240.0, 500.0, 190.0, 100.0, 90e3

    def scene(bearing):
        cab = (Cable(length=L, ae=5e8, diameter=0.1, mass_per_length=60.0, weight_per_length=w, segments=8),)
        c, s = math.cos(math.radians(bearing or 0.0)), math.sin(math.radians(bearing or 0.0))
        z = (lambda v: None) if bearing is None else (lambda v: v)
        return Scene(system=System(
            point=(Point(name="buoy", kind="body", body=Body(weight=-B, mass_x=1e4, mass_y=1e4)),
                   Point(name="west", kind="fixed", x=-R * c, y=D, z=z(-R * s)),
                   Point(name="east", kind="fixed", x=R * c, y=D, z=z(R * s))),
            line=(Line(name="w", start="buoy", end="west", section=cab),
                  Line(name="e", start="buoy", end="east", section=cab))),
            seabed=Seabed(depth=D, friction_axial=0.5, stiffness=3e8, heading_deg=None if bearing is None else 0.0))
    out = {}
    for bearing in (None, 30.0):
        sc = scene(bearing)
        assert sc.three_d == (bearing is not None)
        m = build_model(sc)
        out[bearing] = system_steady(m, m.parameters(sc)).outputs
    plane, space = out[None], out[30.0]
    for k in ("point.buoy.y", "line.w.tension_from", "line.w.tension_to", "line.e.tension_from", "line.e.tension_to"):
        assert space[k] == pytest.approx(plane[k], rel=1e-9), k
    assert plane["line.w.tension_to"] < 0.2 * plane["line.w.tension_from"]       # the friction has taken most of it
    assert abs(space["point.buoy.x"]) < 1e-5 and abs(space["point.buoy.z"]) < 1e-5


def test_a_package_landed_at_the_end_of_a_graph_rests_on_its_footprint_as_the_chains():
    """ship -> wire -> clump (junction) -> wire -> package (body.bed_area = 2 m^2) on a seabed, the chain built as a
    graph and as today's sections: the same ode and static forces, and the package's node pressed 1 cm into the bed
    carries the contact law's k (d l / 2 + bed_area) delta (its footprint with its line's half element, MoorDyn's
    kBot per unit area)."""
    from cablesys.scene import Seabed
    pkg = Body(weight=3000.0, mass_x=400.0, mass_y=450.0, drag_area_normal=0.8, drag_area_tangential=0.5,
               axis_angle_deg=10.0, bed_area=2.0)
    system = System(point=(Point(name="ship", kind="prescribed"), Point(name="clump", kind="junction", body=CLUMP),
                           Point(name="pkg", kind="body", body=pkg)),
                    line=(Line(name="upper", start="ship", end="clump", section=(wire(4),)),
                          Line(name="lower", start="clump", end="pkg", section=(wire(3, length=80.0),))))
    bed = Seabed(depth=180.0, stiffness=3e6, friction_axial=0.4)
    chain, graph = Scene(system=system, seabed=bed), as_graph(system, seabed=bed)
    assert chain.system is None and graph.system is not None
    m_c, m_g = build_model(chain), build_system_model(graph)
    p_c, p_g = m_c.parameters(chain), m_g.parameters(graph)
    rng = np.random.default_rng(11)
    k = m_c.nq // 2
    y = np.r_[np.arange(1, 5) * 25.0, 100.0 + np.arange(1, 4) * 80.0 / 3]
    y[-1] = 180.01                                      # the package 1 cm into the bed
    q = np.column_stack([rng.normal(size=k) * 0.3, y]).ravel()
    q[-2] = 0.0
    x = np.r_[q, rng.normal(size=m_c.nq) * 0.01]
    f_c, f_g = np.array(m_c.ode(x, 1.0, p_c)).ravel(), np.array(m_g.ode(x, 1.0, p_g)).ravel()
    assert np.max(np.abs(f_g - f_c)) <= 1e-12 * np.max(np.abs(f_c))
    e = np.zeros(m_c.dynamics.size1_in(2))
    np.testing.assert_allclose(np.array(m_g.static_force(q, 0 * q, e, p_g)), np.array(m_c.static_force(q, 0 * q, e, p_c)),
                               rtol=1e-12, atol=1e-9)
    out = dict(zip(m_g.output_labels, np.array(m_g.outputs(np.r_[q, 0 * q], e, p_g)).ravel()))
    area = 0.02 * 80.0 / 3 / 2 + 2.0                    # d l / 2 of the lower wire's last element, and the footprint
    assert out["seabed_normal[7]"] == pytest.approx(3e6 * area * 0.01, rel=1e-9)
