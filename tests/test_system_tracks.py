"""A system of lines joined at points towed by a ship on a track (cablesys.statics.tow, cablesys.statics.turning): its
steady straight tow and steady turn against the chain's (a chain built as a graph, other solvers along other paths),
the steady states held by the time domain (the ground frame's equations against the statics in the tow point's
frame), and the points a track refuses."""

import dataclasses
import math
import warnings

import numpy as np
import pytest

from cablesys.errors import NumericalWarning, ParameterError
from cablesys.ladder.steady_tow import steady_run
from cablesys.model import build_model
from cablesys.model.system import build_system_model
from cablesys.scene import Body, Cable, Scene, TopMotion
from cablesys.scene.components import Numerics
from cablesys.scene.system import Line, Point, System
from cablesys.scene.track import Track
from cablesys.time_domain.initial import initial_state
from cablesys.time_domain.integrators import IntegratorSettings
from cablesys.time_domain.run import Simulator

pytestmark = pytest.mark.filterwarnings("ignore")
SPEED, RADIUS = 2.0, 75.0


def wire(n, length, **kw):
    return Cable(**{**dict(length=length, ae=4e7, diameter=0.02, mass_per_length=1.5, weight_per_length=12.0,
                           cd_normal=1.5, internal_damping=2e4, segments=n), **kw})


def fish(weight, mass):
    """A towed body whose virtual masses are equal across the horizontal (x, z): a point body's virtual masses are
    fixed in the scene's axes (Wang 1971 eq. 16), so unequal ones would change with the heading of a turn and no turn
    would be steady."""
    return Body(weight=weight, mass_x=mass, mass_y=1.2 * mass, mass_z=mass, drag_area_normal=0.5,
                drag_area_tangential=0.2, axis_angle_deg=0.0)


SPLIT = Body(weight=500.0, mass_x=60.0, mass_y=60.0, mass_z=60.0, drag_area_normal=0.05, drag_area_tangential=0.05)


def towed_array(**kw) -> System:
    """ship -> 60 m tow wire -> a split (junction) -> 20 m and 35 m drop lines to two bodies: a graph, not a chain."""
    return System(point=(Point(name="ship", kind="prescribed"), Point(name="split", kind="junction", body=SPLIT),
                         Point(name="a", kind="body", body=fish(3000.0, 500.0)),
                         Point(name="b", kind="body", body=fish(1500.0, 250.0))),
                  line=(Line(name="tow", start="ship", end="split", section=(wire(6, 60.0, **kw),)),
                        Line(name="drop_a", start="split", end="a", section=(wire(3, 20.0, **kw),)),
                        Line(name="drop_b", start="split", end="b", section=(wire(4, 35.0, **kw),))))


def track(kind):
    return Track(kind="circle", speed=SPEED, radius=RADIUS) if kind == "circle" else Track(kind="straight", speed=SPEED)


def scene(system, kind, duration=20.0):
    return Scene(system=system, top_motion=TopMotion(track=track(kind)),
                 numerics=Numerics(duration=duration, output_step=0.5, model="as-built"))


def turning_start(system, duration=40.0):
    """(scene, model, p, x0): ``system`` on the 75 m circle, started on its steady turn, where every node moves and
    accelerates as a point of the turning frame, v = Omega x r (1e-12 m/s) and a = -Omega^2 (x, 0, z) (1e-7 m/s^2;
    Wang 1971 p. 32, towing in a circle)."""
    sc = scene(system, "circle", duration=duration)
    model = build_model(sc)
    p = model.parameters(sc)
    x0 = initial_state(sc, model, p)
    w = sc.top_motion.track.turn_rate
    q, v = x0[:model.nq].reshape(-1, 3), x0[model.nq:].reshape(-1, 3)
    np.testing.assert_allclose(v, np.column_stack([-w * q[:, 2], 0 * q[:, 0], w * q[:, 0]]), atol=1e-12)
    acc = np.array(model.ode(x0, 0.0, p)).ravel()[model.nq:].reshape(-1, 3)
    assert np.max(np.abs(acc - np.column_stack([-w**2 * q[:, 0], 0 * q[:, 0], -w**2 * q[:, 2]]))) < 1e-7
    return sc, model, p, x0


@pytest.mark.parametrize("kind", ["straight", "circle"])
def test_a_chain_built_as_a_graph_tows_as_the_chain(kind):
    """ship -> 60 m wire -> split -> 20 m wire -> body, on a straight track and towed in a circle: the graph's steady
    state (the system's statics in the streaming water; the turn continued from the straight tow in node positions)
    is the chain's (the chain's statics; the turn continued from the hanging cable in element angles and lengths) to
    the statics' tolerance."""
    points = (Point(name="ship", kind="prescribed"), Point(name="split", kind="junction", body=SPLIT),
              Point(name="a", kind="body", body=fish(3000.0, 500.0)))
    lines = (Line(name="tow", start="ship", end="split", section=(wire(6, 60.0),)),
             Line(name="drop_a", start="split", end="a", section=(wire(3, 20.0),)))
    chain = scene(System(point=points, line=lines), kind)
    assert chain.system is None and len(chain.sections) == 2            # the Scene makes it the chain of sections
    graph = scene(towed_array(), kind)
    object.__setattr__(graph, "system", System(point=points, line=lines))   # the same chain, held as a graph
    m_c, m_g = build_model(chain), build_system_model(graph)
    assert m_g.q_labels == m_c.q_labels
    x_c = initial_state(chain, m_c, m_c.parameters(chain))
    x_g = initial_state(graph, m_g, m_g.parameters(graph))
    r = x_c[:m_c.nq].reshape(-1, 3)
    assert np.ptp(r[:, 0]) > 30.0                                        # towed well back from the vertical
    if kind == "circle":
        assert np.ptp(r[:, 2]) > 10.0                                    # and swung out of the tow's vertical plane
    np.testing.assert_allclose(x_g, x_c, rtol=0, atol=1e-6 * 80.0)


def test_the_straight_tow_of_a_graph_is_held_by_the_time_domain():
    """The towed array on a straight track at 2 m/s: at its steady tow no node accelerates, and a run of 20 s in the
    ground frame (every node moving at 2 m/s through still water, the cable's added mass in ground velocities: its
    Munk couples are in the statics' polish, cablesys.statics.tow) keeps every point's place relative to the tow point
    within 1e-6 m of the start, the lines' tensions within 1e-6 of themselves."""
    sc = scene(towed_array(), "straight")
    model = build_model(sc)
    p = model.parameters(sc)
    x0 = initial_state(sc, model, p)
    acc = np.array(model.ode(x0, 0.0, p)).ravel()[model.nq:]
    assert np.max(np.abs(acc)) < 1e-7
    assert np.allclose(x0[model.nq:].reshape(-1, 3), [SPEED, 0.0, 0.0], atol=0.0)
    r = Simulator(model, sc.output_times, IntegratorSettings(method="cvodes", rtol=1e-10, atol=1e-12)).run(p, x0)
    assert r.success
    for name in ("split", "a", "b"):
        rel = np.asarray(r[f"point.{name}.x"]) - np.asarray(r["x_s"])
        assert rel[0] < -30.0 and np.max(np.abs(rel - rel[0])) < 1e-6
        assert np.max(np.abs(np.asarray(r[f"point.{name}.y"]) - r[f"point.{name}.y"][0])) < 1e-6
    for line in ("tow", "drop_a", "drop_b"):
        T = np.asarray(r[f"line.{line}.tension_from"])
        assert np.max(np.abs(T - T[0])) < 1e-6 * T[0]


def test_the_steady_turn_of_a_graph_turns_rigidly_and_the_time_domain_keeps_it():
    """The towed array on a 75 m circle at 2 m/s: at its steady turn every node moves and accelerates as a point of
    the turning frame, v = Omega x r, a = -Omega^2 (x, 0, z) (Wang 1971 p. 32, towing in a circle), and a run through
    a sixth of a revolution keeps each point's radius and depth within 1e-6 m (2e-8 m measured); the model ladder's
    steady rung (its state carried round the circle) is that run to 1e-6 m and its eigenvalues decay."""
    sc, model, p, x0 = turning_start(towed_array())
    w = sc.top_motion.track.turn_rate
    assert abs(w) * 40.0 > math.pi / 3 * 0.99
    r = Simulator(model, sc.output_times, IntegratorSettings(method="cvodes", rtol=1e-9, atol=1e-11)).run(p, x0)
    assert r.success
    for name in ("split", "a", "b"):
        rad = np.hypot(r[f"point.{name}.x"], r[f"point.{name}.z"])
        assert RADIUS - 40.0 < rad[0] < RADIUS and np.max(np.abs(rad - rad[0])) < 1e-6
        assert np.max(np.abs(np.asarray(r[f"point.{name}.y"]) - r[f"point.{name}.y"][0])) < 1e-6
    # the ladder's steady rung on the same model and start: the steady turn carried round (not stepped) is the run,
    # point by point and line end by line end, and its rotating-frame eigenvalues all decay
    s = steady_run(sc, sc, model, x0, 0)
    assert s.stats["steady"]["stable"] and s.stats["steady"]["kind"] == "turn"
    for k in [f"point.{n}.{c}" for n in ("split", "a", "b") for c in "xyz"]:
        np.testing.assert_allclose(s[k], r[k], rtol=0, atol=1e-6)
    for line in ("tow", "drop_a", "drop_b"):
        np.testing.assert_allclose(s[f"line.{line}.tension_to"], r[f"line.{line}.tension_to"], rtol=1e-7)


def test_a_track_refuses_a_held_system_by_name():
    """A system held at a fixed point cannot be towed along with its tow point: refused before any work, naming the
    point."""
    base = towed_array()
    held = System(point=base.point + (Point(name="post", kind="fixed", x=50.0, y=80.0),),
                  line=base.line + (Line(name="guy", start="b", end="post", section=(wire(2, 60.0),)),))
    with pytest.raises(ParameterError, match=r"point\[4\]\.kind = 'fixed'.*'post'"):
        scene(held, "straight")


def two_booms() -> System:
    """A sled towed from two booms of one ship 20 m apart across the course (two prescribed points), a 50 m wire from
    each."""
    sled = Body(weight=3000.0, mass_x=500.0, mass_y=600.0, mass_z=500.0, drag_area_normal=0.5,
                drag_area_tangential=0.3, axis_angle_deg=0.0)
    return System(point=(Point(name="port", kind="prescribed"), Point(name="stbd", kind="prescribed", x=0.0, y=0.0,
                                                                      z=20.0),
                         Point(name="sled", kind="body", body=sled, x=-20.0, y=40.0, z=10.0)),
                  line=(Line(name="p", start="port", end="sled", section=(wire(4, 50.0),)),
                        Line(name="s", start="stbd", end="sled", section=(wire(4, 50.0),))))


def test_a_sled_towed_from_two_booms_on_a_straight_course():
    """Two prescribed points of one ship on a straight course keep their places about each other (the heading holds):
    the steady tow has no node accelerating (1e-7 m/s^2), the sled midway across (z = 10 m) with equal wire tensions
    by symmetry (1e-9), towed well back; a 20 s run (CVODES, rtol 1e-10) keeps every point's place behind the booms
    within 1e-6 m, and the ladder's steady rung on the same model and start is that run (1e-6 m). On a circle the two
    points would swing round with the ship's heading: refused by name before any work."""
    sc = scene(two_booms(), "straight")
    model = build_model(sc)
    p = model.parameters(sc)
    x0 = initial_state(sc, model, p)
    assert np.max(np.abs(np.array(model.ode(x0, 0.0, p)).ravel()[model.nq:])) < 1e-7
    r = Simulator(model, sc.output_times, IntegratorSettings(method="cvodes", rtol=1e-10, atol=1e-12)).run(p, x0)
    assert r.success
    np.testing.assert_allclose(r["point.stbd.x"], r["point.port.x"], atol=1e-12)      # both moved by the track
    assert r["point.sled.z"][0] == pytest.approx(10.0, abs=1e-9)
    assert r["line.p.tension_from"][0] == pytest.approx(r["line.s.tension_from"][0], rel=1e-9)
    rel = np.asarray(r["point.sled.x"]) - np.asarray(r["point.port.x"])
    assert rel[0] < -20.0 and np.max(np.abs(rel - rel[0])) < 1e-6
    assert np.max(np.abs(np.asarray(r["point.sled.y"]) - r["point.sled.y"][0])) < 1e-6
    s = steady_run(sc, sc, model, x0, 0)
    assert s.stats["steady"]["stable"] and s.stats["steady"]["kind"] == "tow"
    for k in [f"point.sled.{c}" for c in "xyz"]:
        np.testing.assert_allclose(s[k], r[k], rtol=0, atol=1e-6)
    zig = Track(kind="zig-zag", speed=SPEED, radius=RADIUS, heading_change_deg=20.0, leg_length=200.0)
    with pytest.raises(ParameterError, match=r"top_motion\.track.*straight course or a circle with 2 prescribed"):
        Scene(system=two_booms(), top_motion=TopMotion(track=zig), numerics=Numerics(duration=20.0, model="as-built"))


def test_a_sled_towed_from_two_booms_on_a_circle_swings_round_with_the_ship():
    """On the 75 m circle the starboard boom swings round with the ship's heading (model.ship_points.turned): it keeps its
    20 m from the port boom and its radius about the centre (1e-9 m), both booms turning at the track's rate; the steady
    turn from the statics moves every node as a point of the turning frame (v = Omega x r, a = -Omega^2 (x, 0, z):
    1e-7), a run through a sixth of a revolution (CVODES, rtol 1e-9) keeps the sled's radius and depth within 1e-6 m,
    and the ladder's steady rung on the same model and start is that run."""
    sc, model, p, x0 = turning_start(two_booms())
    w = sc.top_motion.track.turn_rate
    r = Simulator(model, sc.output_times, IntegratorSettings(method="cvodes", rtol=1e-9, atol=1e-11)).run(p, x0)
    assert r.success
    port = np.column_stack([r["point.port.x"], r["point.port.z"]])
    stbd = np.column_stack([r["point.stbd.x"], r["point.stbd.z"]])
    np.testing.assert_allclose(np.hypot(*(stbd - port).T), 20.0, atol=1e-9)
    for name, xz in (("port", port), ("stbd", stbd)):
        rad, ang = np.hypot(*xz.T), np.unwrap(np.arctan2(xz[:, 1], xz[:, 0]))
        np.testing.assert_allclose(rad, rad[0], atol=1e-9)
        np.testing.assert_allclose(ang - ang[0], w * (np.asarray(r.time) - r.time[0]), atol=1e-9)
    assert abs(np.hypot(*stbd[0]) - RADIUS) > 1.0          # the booms on two circles, not one
    rad = np.hypot(r["point.sled.x"], r["point.sled.z"])
    assert np.max(np.abs(rad - rad[0])) < 1e-6
    assert np.max(np.abs(np.asarray(r["point.sled.y"]) - r["point.sled.y"][0])) < 1e-6
    st = steady_run(sc, sc, model, x0, 0)
    assert st.stats["steady"]["stable"] and st.stats["steady"]["kind"] == "turn"
    for k in [f"point.{n}.{c}" for n in ("stbd", "sled") for c in "xyz"]:
        np.testing.assert_allclose(st[k], r[k], rtol=0, atol=1e-6)


def test_a_body_whose_masses_change_with_the_heading_is_warned_of_and_rings_about_the_turn():
    """A point body's virtual masses are fixed in the scene's axes (Wang 1971 eq. 16): with mass_z = 1.1 mass_x the
    steady turn is an equilibrium at the start's heading only. Its statics warn, naming the field, and the run moves
    about it by millimetres where the isotropic body holds 1e-6 m (the test above); equal masses do not warn."""
    odd = System(point=towed_array().point[:2] + (Point(name="a", kind="body", body=dataclasses.replace(
        fish(3000.0, 500.0), mass_z=550.0)),), line=towed_array().line[:2])
    graph = scene(towed_array(), "circle", duration=20.0)
    object.__setattr__(graph, "system", odd)                 # a chain, held as a graph
    model = build_system_model(graph)
    p = model.parameters(graph)
    with pytest.warns(NumericalWarning, match=r"point\[2\]\.body\.mass_z = 550 kg \(mass_x = 500 kg\)"):
        x0 = initial_state(graph, model, p)
    r = Simulator(model, graph.output_times, IntegratorSettings(method="cvodes", rtol=1e-8, atol=1e-10)).run(p, x0)
    rad = np.hypot(r["point.a.x"], r["point.a.z"])
    assert np.max(np.abs(rad - rad[0])) > 1e-3
    with warnings.catch_warnings():
        warnings.simplefilter("error", NumericalWarning)
        sc = scene(towed_array(), "circle")
        m = build_model(sc)
        initial_state(sc, m, m.parameters(sc))
