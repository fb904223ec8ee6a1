"""A rigid body, a winch and several prescribed points in a system of lines joined at points (cablesys.model.system).

A chain written as a graph with a rigid body at its end, or paid out by a winch, is the chain's node model to
round-off (the independent route: the graph's own builder against the chain's); a rigid body held by three lines
finds at rest the attitude of its closed-form moment balance (plane and space) and conserves its energy without drag
and damping; the graph runs from the Python API and from ``cablesys run`` on a TOML, saying which model ran and why. A
winch lowering a package held by guys comes to rest at the statics of the longer line. Two prescribed points of one
vessel are translation invariant and lift a package at the elastic bars' closed form. Bad input is refused by name."""

import json
import math
import sys
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from energy_checks import energy_history  # noqa: E402
from test_system_model import as_graph, same_dynamics  # noqa: E402

import cablesys  # noqa: E402
from cablesys.cli import main  # noqa: E402
from cablesys.model import build_model  # noqa: E402
from cablesys.model.rigid_assembly import RIGID_OUTPUTS, RIGID_OUTPUTS_3D  # noqa: E402
from cablesys.model.rigid_body import rotation  # noqa: E402
from cablesys.model.system import build_system_model  # noqa: E402
from cablesys.ladder.auto import decide  # noqa: E402
from cablesys.scene import Body, Cable, Scene, TopMotion, dump_scene, load_scene  # noqa: E402
from cablesys.errors import ParameterError  # noqa: E402
from cablesys.model.segmented_winch import WINCH_OUTPUTS  # noqa: E402
from cablesys.scene.components import Numerics  # noqa: E402
from cablesys.scene.ends import Seabed, Winch  # noqa: E402
from cablesys.scene.harmonics import Sinusoid  # noqa: E402
from cablesys.scene.system import Line, Point, System  # noqa: E402
from cablesys.statics.system import system_initial_state, system_steady  # noqa: E402

pytestmark = pytest.mark.filterwarnings("ignore")

W_B, BUOY = 3000.0, 500.0                 # the body's weight in water and buoyancy (N)
ATTACH, CB = (0.3, -0.8, 0.2), (-0.1, -0.2, 0.0)   # attachment point and centre of buoyancy from the CG (m, body axes)


def wire(n, **kw):
    return Cable(**{**dict(length=30.0, ae=2e6, diameter=0.02, mass_per_length=1.5, weight_per_length=12.0,
                           cd_normal=1.2, internal_damping=400.0, segments=n), **kw})


def rigid(space: bool, **kw) -> Body:
    """A rigid package: attached 0.8 m above and 0.3 m ahead of its CG (0.2 m to the side in space), its buoyancy
    centre 0.2 m above and 0.1 m behind the CG; a cylinder's drag at 10 deg and per-axis drag."""
    return Body(**{**dict(weight=W_B, mass_x=400.0, mass_y=450.0, drag_area_normal=0.8, drag_area_tangential=0.5,
                          axis_angle_deg=10.0, drag_area_x=0.3, pitch_inertia=900.0, pitch_added_inertia=100.0,
                          attachment_x=ATTACH[0], attachment_y=ATTACH[1], buoyancy=BUOY, buoyancy_x=CB[0],
                          buoyancy_y=CB[1], pitch_damping=200.0),
                   **(dict(mass_z=420.0, inertia_xx=700.0, inertia_yy=800.0, inertia_xy=30.0,
                           attachment_z=ATTACH[2]) if space else {}), **kw})


@pytest.mark.parametrize("space", [False, True])
def test_a_chain_with_a_rigid_body_built_as_a_graph_is_the_chains_node_model(space):
    """ship -> wire (4 elements) -> rigid package, heaving and surging (swaying in space): the graph builder's ode, energy
    and outputs (the body's pitch, CG, in space roll, yaw, body rates and quaternion, named point.pkg.*) equal the
    chain builder's at random states to 1e-12 (measured: exactly equal), its orientation coordinates after the
    nodes as the chain's."""
    motion = TopMotion(x=(Sinusoid(amplitude=1.0, frequency=0.6),), y=(Sinusoid(amplitude=0.5, frequency=0.6),),
                       z=(Sinusoid(amplitude=0.7, frequency=0.4),) if space else (), ramp_s=10.0)
    system = System(point=(Point(name="ship", kind="prescribed"), Point(name="pkg", kind="body", body=rigid(space))),
                    line=(Line(name="wire", start="ship", end="pkg", section=(wire(4),)),))
    chain = Scene(system=system, top_motion=motion)
    assert chain.system is None and chain.sections[0].body.is_rigid
    graph = as_graph(system, top_motion=motion)
    m_c, m_g = build_model(chain), build_system_model(graph)
    names = ("theta_b",) if not space else tuple(f"quat_{c}_b" for c in "wxyz")
    assert m_g.q_labels == m_c.q_labels[:-len(names)] + tuple(f"point.pkg.{n}" for n in names)
    assert m_g.n_rotations == m_c.n_rotations == len(names) and m_g.rotation_rest == m_c.rotation_rest
    rng = np.random.default_rng(5)
    dim, nq = m_c.dim, m_c.nq
    x = rng.normal(size=2 * nq)
    x[:nq - len(names)] += np.tile(np.r_[0.0, 25.0, 0.0][:dim], 4) * np.repeat(np.arange(1, 5), dim)
    p_c, p_g = m_c.parameters(chain), m_g.parameters(graph)
    for _, y_c, y_g in same_dynamics(m_c, m_g, p_c, p_g, x, (0.7, 13.1)):
        for k in RIGID_OUTPUTS + (RIGID_OUTPUTS_3D if space else ()):
            assert y_g[f"point.pkg.{k}"] == pytest.approx(y_c[k], rel=1e-12, abs=1e-12), k
        assert y_g["line.wire.tension_to"] == pytest.approx(y_c["tension_bottom"], rel=1e-12)


def star(space: bool, n: int = 6, **body):
    """A rigid package held by three lines (not a chain): 30 m from the ship and from a post 40 m away at the ship's
    depth, and a soft 20 m downhaul to a sinker 45 m below the mid-point."""
    return System(point=(Point(name="ship", kind="prescribed"), Point(name="post", kind="fixed", x=40.0, y=0.0),
                         Point(name="pkg", kind="body", body=rigid(space, **body)),
                         Point(name="sinker", kind="fixed", x=20.0, y=45.0)),
                  line=(Line(name="a", start="ship", end="pkg", section=(wire(n),)),
                        Line(name="b", start="post", end="pkg", section=(wire(n),)),
                        Line(name="c", start="pkg", end="sinker", section=(wire(n, length=20.0, ae=2e4),))))


@pytest.mark.parametrize("space", [False, True])
def test_a_rigid_body_held_by_three_lines_rests_at_its_closed_form_attitude(space):
    """The lines act at the attachment point, so at rest the body's moment about it vanishes: its weight W_b + B at the
    CG and its buoyancy B at the centre of buoyancy give R (W_b c + B b) vertical, up (c the attachment point, b the
    centre of buoyancy from the CG in body axes; rigid_body.py's potential). In the plane theta_b = atan(v_x / v_y),
    v = W_b c + B b, to 1e-12; in space R v / |v| = (0, -1, 0) to 1e-9 (the yaw about the vertical through the
    attachment neutral, pinned by the statics). The attachment node sits on the symmetry line x = 20 m."""
    sc = Scene(system=star(space))
    assert sc.system is not None and sc.three_d == space
    m = build_model(sc)
    st = system_steady(m, m.parameters(sc))
    y = st.outputs
    assert y["point.pkg.x"] == pytest.approx(20.0, abs=1e-9)
    v = W_B * np.array(ATTACH[:3 if space else 2]) + BUOY * np.array(CB[:3 if space else 2])
    if not space:
        v = np.r_[v[0], v[1]]
        assert y["point.pkg.theta_b"] == pytest.approx(math.atan(v[0] / v[1]), abs=1e-12)
        assert y["point.pkg.theta_b"] < -0.3                        # a real tilt, not the level guess
    else:
        R = np.array(rotation(ca.DM(st.q[-4:])))
        np.testing.assert_allclose(R @ v / np.linalg.norm(v), [0.0, -1.0, 0.0], atol=1e-9)
        assert abs(y["point.pkg.roll_b"]) > 0.2 and np.linalg.norm(st.q[-4:]) == pytest.approx(1.0, abs=1e-12)
    # the CG hangs straight below the attachment point's vertical through the combined centre (no drag at rest)
    assert y["point.pkg.y_cg"] > y["point.pkg.y"]


def test_a_rigid_body_held_by_three_lines_conserves_energy_without_drag_and_damping():
    """The star released 0.2 rad off its static pitch in still water, no drag, Voigt or pitch damping: K + V (the
    model's own energy, the body's rotation and its buoyancy included) drifts by less than 1e-6 of the swing energy
    over 20 s (several pitch periods)."""
    still = dict(cd_normal=0.0, ct_tangential=0.0, internal_damping=0.0)
    pts = star(False, n=3, drag_area_normal=0.0, drag_area_tangential=0.0, drag_area_x=0.0, pitch_damping=0.0)
    system = System(point=pts.point, line=tuple(Line(name=ln.name, start=ln.start, end=ln.end, section=tuple(
        Cable(**{**{f: getattr(c, f) for f in ("length", "ae", "diameter", "mass_per_length", "weight_per_length",
                                                 "segments")}, **still}) for c in ln.section)) for ln in pts.line))
    sc = Scene(system=system, numerics=Numerics(duration=20.0, output_step=0.1))
    m = build_model(sc)
    p = m.parameters(sc)
    x_static = system_steady(m, p).x
    x0 = x_static.copy()
    x0[m.q_labels.index("point.pkg.theta_b")] += 0.2
    r, E, swing = energy_history(sc, m, p, x0, x_static)
    crossings = np.sum(np.diff(np.sign(r["point.pkg.theta_b"] - r["point.pkg.theta_b"].mean())) != 0)
    assert crossings >= 6 and swing > 10.0
    assert np.max(np.abs(E - E[0])) < 1e-6 * swing


def test_a_rigid_body_of_a_system_starts_at_its_initial_attitude():
    """``initial_pitch_deg`` (in space also roll and yaw) turns the body about its attachment point at the start of a
    run (as the chain's, statics.catenary.released): the nodes keep their static places, the orientation is the
    named angles (1e-12)."""
    for space, angles in ((False, dict(initial_pitch_deg=10.0)), (True, dict(initial_roll_deg=5.0,
                                                                               initial_yaw_deg=-20.0))):
        still, turned = Scene(system=star(space, n=3)), Scene(system=star(space, n=3, **angles))
        m = build_model(turned)
        x_still = system_initial_state(still, m, m.parameters(still))
        x0 = system_initial_state(turned, m, m.parameters(turned))
        n_node = m.nq - m.n_rotations
        np.testing.assert_allclose(x0[:n_node], x_still[:n_node], rtol=0, atol=1e-12)
        y = dict(zip(m.output_labels, np.array(m.outputs(x0, np.zeros(m.top.size1_out(0)), m.parameters(turned))).ravel()))
        for name, value in angles.items():
            key = {"initial_pitch_deg": "theta_b", "initial_roll_deg": "roll_b", "initial_yaw_deg": "yaw_b"}[name]
            assert y[f"point.pkg.{key}"] == pytest.approx(math.radians(value), abs=1e-12), key


def test_a_system_with_a_rigid_body_runs_from_the_api_and_the_cli(tmp_path):
    """The star under a heaving ship: cablesys.simulate and ``cablesys run`` on its TOML run the node model and say so
    (a system of lines, a rigid body's orientation among its coordinates); the run starts at the static pitch and the
    CSV names the body's pitch per point, in rad."""
    sc = Scene(system=star(False, n=3), top_motion=TopMotion(y=(Sinusoid(amplitude=0.5, frequency=0.8),)),
               numerics=Numerics(duration=4.0, output_step=0.1))
    r = cablesys.simulate(sc, model="as-built")
    assert r.success and r.stats["model"]["name"] == "segmented"
    v = W_B * np.array(ATTACH[:2]) + BUOY * np.array(CB[:2])
    assert r["point.pkg.theta_b"][0] == pytest.approx(math.atan(v[0] / v[1]), abs=1e-9)
    f = tmp_path / "star.toml"
    f.write_text(dump_scene(sc))
    out = tmp_path / "out"
    assert main(["run", str(f), "--out", str(out)]) == 0
    reason = json.loads((out / "summary.json").read_text())["model"]["reason"]
    assert "system of lines joined at points" in reason and "rigid body's orientation" in reason
    header = (out / "timeseries.csv").read_text().splitlines()[0].split(",")
    assert "point.pkg.theta_b [rad]" in header and "point.pkg.y_cg [m]" in header


@pytest.mark.parametrize("space, bed", [(False, False), (False, True), (True, False), (True, True)])
def test_a_chain_paid_out_by_a_winch_built_as_a_graph_is_the_chains_node_model(space, bed):
    """ship -> wire (5 elements) -> package, the wire paid out at 0.5 m/s (ramped), surging (swaying in space), with
    and without a seabed its lower nodes lie on (the material sliding past them): the graph builder's ode, energy and
    outputs (the winch's length, speed, acceleration and power, the line's end tensions at the sheave's material
    acceleration) equal the chain builder's at random states during the ramp and the payout to 1e-12 (measured:
    exactly equal)."""
    motion = TopMotion(x=(Sinusoid(amplitude=1.0, frequency=0.6),),
                       z=(Sinusoid(amplitude=0.7, frequency=0.4),) if space else (), ramp_s=10.0)
    pkg = Body(weight=3000.0, mass_x=400.0, mass_y=450.0, drag_area_normal=0.8, drag_area_tangential=0.8, bed_area=1.0)
    system = System(point=(Point(name="ship", kind="prescribed"), Point(name="pkg", kind="body", body=pkg)),
                    line=(Line(name="wire", start="ship", end="pkg", section=(wire(5, length=100.0),)),))
    kw = dict(top_motion=motion, winch=Winch(speed=0.5, duration=20.0, ramp=2.0, max_length=150.0),
              seabed=Seabed(depth=80.0) if bed else None)
    chain, graph = Scene(system=system, **kw), as_graph(system, **kw)
    assert chain.system is None
    m_c, m_g = build_model(chain), build_system_model(graph)
    p_c, p_g = m_c.parameters(chain), m_g.parameters(graph)
    rng = np.random.default_rng(7)
    x = rng.normal(size=2 * m_c.nq)
    x[:m_c.nq] += np.tile(np.r_[0.0, 25.0, 0.0][:m_c.dim], 5) * np.repeat(np.arange(1, 6), m_c.dim)
    for t, y_c, y_g in same_dynamics(m_c, m_g, p_c, p_g, x, (0.7, 5.1, 13.1)):
        pairs = {k: k for k in WINCH_OUTPUTS}
        pairs.update({"tension_top": "line.wire.tension_from", "tension_bottom": "line.wire.tension_to"})
        pairs.update({f"element_tension_rate[{k}]": f"element_tension_rate[{k}]" for k in range(5)})
        if bed:
            pairs.update({f"seabed_friction[{j}]": f"seabed_friction[{j}]" for j in range(6)})
        for a, b in pairs.items():
            assert y_g[b] == pytest.approx(y_c[a], rel=1e-12, abs=1e-12), (a, b)
        if t > 2.0:                                       # past the ramp: paying out at full speed
            assert y_c["winch_speed"] == pytest.approx(0.5, rel=1e-12)


def lowering(lift: float) -> System:
    """A package lowered on a 4-element lift line from the ship and steadied by two soft, light 42 m guys to posts at
    (+-40 m, 50 m): not a chain (the package ends three lines)."""
    guy = wire(3, length=42.0, ae=2e5, weight_per_length=4.0, internal_damping=2e4)
    pkg = Body(weight=3000.0, mass_x=400.0, mass_y=400.0, drag_area_normal=8.0, drag_area_tangential=8.0)
    return System(point=(Point(name="ship", kind="prescribed"), Point(name="pkg", kind="body", body=pkg),
                         Point(name="east", kind="fixed", x=40.0, y=50.0),
                         Point(name="west", kind="fixed", x=-40.0, y=50.0)),
                  line=(Line(name="lift", start="ship", end="pkg",
                             section=(wire(4, length=lift, ae=5e6, internal_damping=2e4),)),
                        Line(name="east_guy", start="pkg", end="east", section=(guy,)),
                        Line(name="west_guy", start="pkg", end="west", section=(guy,))))


def test_a_winch_lowers_a_package_held_by_guys_to_the_statics_of_the_longer_line(tmp_path):
    """The lift line paid out 10 m (0.5 m/s, 2 s ramps) and held: 38 s after the winch stops the run rests where the
    statics of the same system with a 60 m lift line put it (the independent route: KINSOL on a fixed-length scene):
    the package's depth to 1e-4 m (measured 6e-6), the sheave's tension averaged over the last 10 s to 3e-5 of it
    (measured 9e-6; the guys' transverse modes still ring at +-0.5 N); the lift hangs vertical (symmetry), so its
    tension at the sheave minus at the package is the paid-out line's weight in water, 12 N/m x 60 m (1e-5, measured
    6e-7; Wang 1971 eq. 12 with l_0 -> L: the paid-out mass), and the winch outputs say L = 60 m at rest; the
    payout's power (braking) is positive."""
    sc = Scene(system=lowering(50.0), winch=Winch(speed=0.5, duration=22.0, ramp=2.0, max_length=80.0),
               numerics=Numerics(duration=60.0, output_step=0.5))
    assert sc.system is not None
    r = cablesys.simulate(sc, model="as-built")
    assert r.success
    ref = Scene(system=lowering(60.0))
    m = build_model(ref)
    st = system_steady(m, m.parameters(ref)).outputs
    late = r.time > r.time[-1] - 10.0
    assert r["point.pkg.y"][-1] == pytest.approx(st["point.pkg.y"], abs=1e-4)
    assert abs(r["point.pkg.x"][-1]) < 1e-9
    assert np.mean(r["line.lift.tension_from"][late]) == pytest.approx(st["line.lift.tension_from"], rel=3e-5)
    weight = r["line.lift.tension_from"][-1] - r["line.lift.tension_to"][-1]
    assert weight == pytest.approx(12.0 * 60.0, rel=1e-5)
    assert r["winch_length"][-1] == pytest.approx(60.0, rel=1e-12) and r["winch_speed"][-1] == 0.0
    assert r["winch_power"].max() > 0.4 * 3000.0          # braking the payout of ~3.4 kN at 0.5 m/s
    f = tmp_path / "lowering.toml"                         # the TOML door: the ladder says why the node model runs
    f.write_text(dump_scene(sc))
    choice, _, _ = decide(load_scene(f), "auto", None, None)
    assert choice.name == "segmented" and "system of lines" in choice.reason and "[winch]" in choice.reason


def test_a_winch_on_a_system_needs_the_prescribed_points_one_line():
    """Refused by name before any work: a winch when no line starts at the prescribed point (the line written towards
    it), when two do, and when the system has no prescribed point; a rigid body with a seabed (as the chain's)."""
    w = Winch(speed=0.5, duration=10.0, max_length=80.0)
    base = lowering(50.0)
    towards = System(point=base.point, line=(Line(name="lift", start="pkg", end="ship", section=base.line[0].section),)
                     + base.line[1:])
    with pytest.raises(ParameterError) as err:
        Scene(system=towards, winch=w)
    assert err.value.field == "winch" and "0 lines from the prescribed point 'ship'" in str(err.value)
    two = System(point=base.point, line=base.line + (Line(name="tag", start="ship", end="east",
                                                          section=(wire(2, length=70.0),)),))
    with pytest.raises(ParameterError) as err:
        Scene(system=two, winch=w)
    assert err.value.field == "winch" and "(lift, tag)" in str(err.value) and "exactly one" in str(err.value)
    held = System(point=(Point(name="ship", kind="fixed", x=0.0, y=0.0),) + base.point[1:], line=base.line)
    with pytest.raises(ParameterError) as err:
        Scene(system=held, winch=w)
    assert err.value.field == "winch" and "has none" in str(err.value)
    with pytest.raises(ParameterError) as err:              # the drum too small for the line in the water
        Scene(system=base, winch=Winch(speed=0.5, duration=10.0, max_length=40.0))
    assert err.value.field == "winch.max_length" and "line[0].section[0].length" in str(err.value)
    with pytest.raises(ParameterError) as err:
        Scene(system=star(False), seabed=Seabed(depth=200.0))
    assert err.value.field == "point[2].pitch_inertia" and "seabed" in str(err.value)


def vessel_points(first, second, space, pkg_name="pkg"):
    """Two prescribed points of one vessel (a crane tip and a davit) lifting a package on two wires: ``first`` the
    origin's name, ``second`` (name, mean position)."""
    pkg = Body(weight=3000.0, mass_x=400.0, mass_y=450.0, mass_z=420.0 if space else None, drag_area_normal=0.8,
               drag_area_tangential=0.8)
    name, (x, y, z) = second
    return (Point(name=first, kind="prescribed"), Point(name=name, kind="prescribed", x=x, y=y, z=z),
            Point(name=pkg_name, kind="body", body=pkg))


@pytest.mark.parametrize("space", [False, True])
def test_two_prescribed_points_of_one_vessel_are_translation_invariant(space):
    """A crane tip (the origin) and a davit 10 m aft, 2 m lower (3 m to the side in space), both moved by the one top
    motion, lift a package on two wires. In still, uniform water the physics does not depend on where the origin is:
    the same system with the davit as the origin and the crane tip at (-10, -2, -3) gives the same accelerations at
    the same states shifted by the davit's offset, at random states and times (1e-12 of the largest; measured ~1e-16),
    and every prescribed point's outputs are its mean position plus the top motion."""
    motion = TopMotion(x=(Sinusoid(amplitude=1.0, frequency=0.6),), y=(Sinusoid(amplitude=0.5, frequency=0.6),),
                       z=(Sinusoid(amplitude=0.7, frequency=0.4),) if space else (), ramp_s=10.0)
    off = np.array([10.0, 2.0, 3.0 if space else 0.0])
    lines = (Line(name="a", start="crane", end="pkg", section=(wire(4),)),
             Line(name="b", start="davit", end="pkg", section=(wire(3, length=25.0),)))
    here = Scene(system=System(point=vessel_points("crane", ("davit", (*off[:2], off[2] or None)), space),
                               line=lines), top_motion=motion)
    there = Scene(system=System(point=vessel_points("davit", ("crane", (*-off[:2], -off[2] or None)), space),
                                line=lines), top_motion=motion)
    assert here.system.n_prescribed == 2 and here.three_d == space
    m_a, m_b = build_model(here), build_model(there)
    assert m_a.q_labels == m_b.q_labels and "system.point[1].x" in m_a.layout.labels
    p_a, p_b = m_a.parameters(here), m_b.parameters(there)
    dim, nq = m_a.dim, m_a.nq
    rng = np.random.default_rng(11)
    x = rng.normal(size=2 * nq)
    x[:nq] += np.tile(np.r_[3.0, 25.0, 0.0][:dim], nq // dim)
    x_b = x.copy()
    x_b[:nq] -= np.tile(off[:dim], nq // dim)
    for t in (0.7, 13.1):
        f_a, f_b = np.array(m_a.ode(x, t, p_a)).ravel(), np.array(m_b.ode(x_b, t, p_b)).ravel()
        assert np.max(np.abs(f_a - f_b)) <= 1e-12 * np.max(np.abs(f_a))
        e = np.array(m_a.top(t, p_a)).ravel()
        y = dict(zip(m_a.output_labels, np.array(m_a.outputs(x, e, p_a)).ravel()))
        for c, axis in enumerate("xyz"[:dim]):
            assert y[f"point.davit.{axis}"] == pytest.approx(off[c] + e[1 + c], abs=1e-12)
            assert y[f"point.crane.{axis}"] == pytest.approx(e[1 + c], abs=1e-12)
            assert y[f"point.davit.{axis}_rate"] == pytest.approx(e[1 + dim + c], abs=1e-12)


def test_two_prescribed_points_lift_a_package_at_the_elastic_bars_closed_form(tmp_path):
    """Two weightless 30 m wires (AE = 2 MN) from the crane tip and from a davit 10 m away lift a 3 kN package: by
    symmetry it hangs at x = 5 m, and its depth y solves 2 AE (l / 30 - 1) y / l = W with l = sqrt(25 + y^2) (two
    elastic bars); the statics' depth and both wires' tensions agree to 1e-9 (measured 1e-13). The scene round-trips
    through TOML (the davit's mean position), and a run under heave and surge moves the davit with the top motion
    about its mean position."""
    light = wire(4, length=30.0, weight_per_length=0.0)
    sc = Scene(system=System(point=vessel_points("crane", ("davit", (10.0, 0.0, None)), False),
                             line=(Line(name="a", start="crane", end="pkg", section=(light,)),
                                   Line(name="b", start="davit", end="pkg", section=(light,)))),
               top_motion=TopMotion(x=(Sinusoid(amplitude=0.5, frequency=0.7),),
                                    y=(Sinusoid(amplitude=0.8, frequency=0.7),), ramp_s=3.0),
               numerics=Numerics(duration=4.0, output_step=0.1))
    f = tmp_path / "two.toml"
    f.write_text(dump_scene(sc))
    assert load_scene(f) == sc
    m = build_model(sc)
    y = system_steady(m, m.parameters(sc)).outputs
    bars = lambda d: 2 * 2e6 * (math.hypot(5.0, d) / 30.0 - 1.0) * d / math.hypot(5.0, d) - 3000.0
    from scipy.optimize import brentq
    depth = brentq(bars, 29.0, 31.0, xtol=1e-14)
    tension = 2e6 * (math.hypot(5.0, depth) / 30.0 - 1.0)
    assert y["point.pkg.x"] == pytest.approx(5.0, abs=1e-9)
    assert y["point.pkg.y"] == pytest.approx(depth, rel=1e-9)
    assert y["line.a.tension_to"] == pytest.approx(tension, rel=1e-9)
    assert y["line.b.tension_from"] == pytest.approx(tension, rel=1e-9)
    r = cablesys.simulate(sc, model="as-built")
    assert r.success
    np.testing.assert_allclose(r["point.davit.x"], 10.0 + r["x_s"], atol=1e-12)
    np.testing.assert_allclose(r["point.davit.y"], r["y_s"], atol=1e-12)
    assert np.ptp(r["y_s"]) > 0.5


def test_two_prescribed_points_take_a_vessels_6dof_rao():
    """A vessel's 6-DOF RAO with two prescribed points moves each by its own lever arm (tests/test_system_vessel.py):
    the model takes the vessel's rotation as input (rot_z_s in the plane, with heave and pitch), the planar
    translation RAO ([top_motion.rao]) none."""
    from cablesys.scene.sea import MotionRAO, SeaSpectrum
    from cablesys.scene.vessel import HeadingRAO, VesselRAO
    omega = (0.3, 0.5, 0.8, 1.2)
    heave = dict(heave_amplitude=(1.0, 0.9, 0.5, 0.1), heave_phase_deg=(0.0, -5.0, -40.0, -120.0))
    pitch = dict(pitch_amplitude=(0.5, 1.0, 0.8, 0.2), pitch_phase_deg=(0.0, 10.0, 30.0, 60.0))
    sea = SeaSpectrum(hs=3.0, tp=9.0, n_components=5, seed=4)
    system = System(point=vessel_points("crane", ("davit", (10.0, 0.0, None)), False),
                    line=(Line(name="a", start="crane", end="pkg", section=(wire(3),)),
                          Line(name="b", start="davit", end="pkg", section=(wire(3),))))
    sc = Scene(system=system, top_motion=TopMotion(spectrum=sea, vessel=VesselRAO(
        omega=omega, headings=(HeadingRAO(heading_deg=0.0, **heave, **pitch),))))
    assert not sc.three_d and sc.vessel_rotation_axes == ("z",)
    assert build_model(sc).vessel_inputs == ("rot_z_s",)
    assert Scene(system=system, top_motion=TopMotion(spectrum=sea, rao=MotionRAO(omega=omega, **heave))
                 ).vessel_rotation_axes == ()