"""A towing ship's track beyond the circle (cablesys/scene/track.py, cablesys/model/track_path.py, cablesys/statics/
tow.py): the path's geometry against hand-drawn closed forms, Galilean invariance against the ship's frame, the Munk
couple that separates the two frames with the cable's added mass, a turn settling on the steady turn, a zig-zag turned
about the vertical, the ladder's choice, the plan view, and field-named errors."""

import math
import sys
from pathlib import Path

import casadi as ca
import numpy as np
import pytest
import tomllib

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies"))
import _tracks  # noqa: E402

from cablesys.errors import ParameterError  # noqa: E402
from cablesys.ladder.auto import decide  # noqa: E402
from cablesys.ladder.rung.base import TURNING  # noqa: E402
from cablesys.ladder.rungs import BUILTIN  # noqa: E402
from cablesys.model import build_model  # noqa: E402
from cablesys.model.track_path import path_position  # noqa: E402
from cablesys.scene import scene_from_dict  # noqa: E402
from cablesys.scene.toml_io import dump_scene  # noqa: E402
from cablesys.scene.track import Track  # noqa: E402
from cablesys.time_domain.initial import initial_state  # noqa: E402

PATH = """[top_motion.track]
kind = "path"
speed = 2.0
[[top_motion.track.leg]]
kind = "straight"
length = 100.0
[[top_motion.track.leg]]
kind = "arc"
radius = 50.0
angle_deg = 90.0
direction = "port"
[[top_motion.track.leg]]
kind = "straight"
length = 80.0
[[top_motion.track.leg]]
kind = "arc"
radius = 30.0
angle_deg = 180.0
direction = "starboard"
"""


def _top(sc):
    model = build_model(sc)
    p = model.parameters(sc)
    return lambda t: np.array(model.top(t, p)).ravel()           # (t, x, y, z, x', y', z', x'', y'', z'')


def test_a_path_of_legs_goes_where_the_legs_drawn_by_hand_go():
    """Straight 100 m along +x, a port arc of 50 m through 90 deg (centre (100, 50), to (150, 50) heading +z), straight
    80 m (to (150, 130)), a starboard arc of 30 m through 180 deg (centre (180, 130): through (180, 160) to (210, 130),
    heading -z), then straight on; at 2 m/s, speed U everywhere, acceleration U^2 / R towards the centre on the arcs,
    none on the straights, and before t = 0 the straight tow along +x."""
    U = 2.0
    top = _top(_tracks.scene(PATH))
    s1, s2, s3, s4 = 100.0, 100.0 + 25.0 * math.pi, 180.0 + 25.0 * math.pi, 180.0 + 55.0 * math.pi
    expect = {0.0: (0.0, 0.0), s1: (100.0, 0.0), 0.5 * (s1 + s2): (100.0 + 50.0 * math.sin(math.pi / 4),
                                                                      50.0 - 50.0 * math.cos(math.pi / 4)),
              s2: (150.0, 50.0), s3: (150.0, 130.0), 0.5 * (s3 + s4): (180.0, 160.0), s4: (210.0, 130.0),
              s4 + 40.0: (210.0, 90.0), -30.0: (-30.0, 0.0)}
    for s, (x, z) in expect.items():
        e = top(s / U)
        assert e[1] == pytest.approx(x, abs=1e-9) and e[3] == pytest.approx(z, abs=1e-9) and e[2] == 0.0, s
    for s, centre, R in ((0.5 * (s1 + s2), (100.0, 50.0), 50.0), (0.5 * (s3 + s4), (180.0, 130.0), 30.0)):
        e = top(s / U)
        a = e[[7, 9]]
        assert np.linalg.norm(a) == pytest.approx(U**2 / R, rel=1e-12)
        assert a @ (np.array(centre) - e[[1, 3]]) == pytest.approx(U**2, rel=1e-12)        # towards the centre
    for s in np.linspace(-20.0, s4 + 50.0, 97):
        e = top(s / U)
        assert np.hypot(e[4], e[6]) == pytest.approx(U, rel=1e-12)
    assert np.allclose(top(0.5 * (s2 + s3) / U)[7:], 0.0) and np.allclose(top((s4 + 10.0) / U)[[4, 6]], (0.0, -U))


def test_the_zigzag_swings_symmetrically_about_its_base_course_and_repeats():
    """Waypoints L apart at +-delta about the base course, fillets of radius R: the arcs' mid-points (the track's
    extremes) lie at +-((L/2) sin delta - R (sec delta - 1)) from the base course (a fillet of deflection 2 delta
    passes R (sec delta - 1) inside its waypoint, on the bisector, which is normal to the base course), the track
    nowhere beyond, and after its first half leg it repeats every two legs, moved 2 L cos delta along the base
    course (the waypoints' polyline; the fillets cut its corners alike)."""
    L, d, R, U, lead = 200.0, math.radians(20.0), 40.0, 2.0, 20.0
    track = Track(kind="zig-zag", speed=U, radius=R, heading_change_deg=20.0, leg_length=L, lead_in=lead)
    legs, cycle = track.pieces()
    t = ca.SX.sym("t")
    f = ca.Function("f", [t], [ca.vertcat(*path_position(t, U, 0.0, legs, cycle))])
    T = np.linspace(0.0, 3000.0, 30001)
    xz = np.array(f.map(T.size)(T))
    apex = L / 2 * math.sin(d) - R * (1 / math.cos(d) - 1)
    period = sum(length for length, _ in cycle) / U
    start = sum(length for length, _ in legs) / U
    assert float(np.array(f(start + R * d / U))[1, 0]) == pytest.approx(apex, rel=1e-12)             # the -2 delta arc
    assert float(np.array(f(start + period / 2 + R * d / U))[1, 0]) == pytest.approx(-apex, rel=1e-12)
    assert np.max(np.abs(xz[1])) <= apex * (1 + 1e-12)
    for t0 in (start + 1.0, start + 77.7, start + 301.0):
        a, b = np.array(f(t0)).ravel(), np.array(f(t0 + period)).ravel()
        assert b - a == pytest.approx([2 * L * math.cos(d), 0.0], abs=1e-9)


def test_a_straight_track_is_the_ship_frame_tow_seen_from_the_ground():
    """Galilean invariance: a straight track at 2 m/s in still water and the same scene towed in the ship's frame
    (environment.system_speed = 2 m/s), both released from the shape of the steady tow at 1 m/s (the body swings
    back ~18 m): with a cable without added mass the body's motion relative to the tow point and the tensions agree to
    rounding on the same fixed RK4 steps, and to CVODES' accuracy on its own steps; the two steady tows (the runs'
    own initial states) are the same shape."""
    rk = _tracks.galilean(0.0)
    assert rk["body_swing_m"] > 10.0 and rk["start_max_abs_m"] < 1e-12
    assert rk["max_rel"] < 1e-9
    cv = _tracks.galilean(0.0, method="cvodes", rtol=1e-10)
    assert cv["position_max_rel"] < 1e-8 and cv["tension_max_rel"] < 1e-6


def test_with_added_mass_the_two_frames_differ_by_the_elements_munk_couples():
    """The node model's added mass is written in the nodes' velocities over the ground (Wang 1971 eq. 23-24), so a
    cable moving obliquely through still water feels each element's Munk couple (Newman 1977 sec. 4.13) and the
    ship's frame does not: at the same shape the forces differ by exactly the closed form, and the runs by 1e-4 of
    the motion. The track's own start is its steady tow: no node accelerates (its residual polished from the ship
    frame's)."""
    m = _tracks.munk()
    assert m["rel_err"] < 1e-12 and m["largest_term_N"] > 0.1
    g = _tracks.galilean(1.0)
    assert 1e-5 < g["max_rel"] < 1e-3 and 1e-3 < g["start_max_abs_m"] < 0.05
    sc = _tracks.scene('[top_motion.track]\nkind = "straight"\nspeed = 2.0\n')
    model = build_model(sc)
    p = model.parameters(sc)
    x0 = initial_state(sc, model, p)
    acc = np.array(model.ode(x0, 0.0, p)).ravel()[model.nq:]
    assert np.max(np.abs(acc)) < 1e-8
    assert np.allclose(x0[model.nq:].reshape(-1, 2), [2.0, 0.0], atol=0.0)


def test_a_turn_through_450_degrees_settles_on_the_steady_turn():
    """From the steady straight tow into a 40 m turn to port at 2 m/s: after 450 degrees the body's place relative to
    the tow point (in the frame of its heading) is the steady turn's of the circle of the same radius and speed
    (cablesys.statics.turning) within 1e-4 of the line's length, from ~22 m off at the start; the top tension within
    1e-5."""
    r = _tracks.turn_settles(450.0)
    assert r["start_distance_m"] > 10.0
    assert r["rel_err"] < 1e-4 and r["tension_top_rel_err"] < 1e-5


def test_a_zigzag_turned_by_its_base_course_gives_the_turned_answer():
    """The zig-zag on base course 0 and 35 deg (3-D both), the same fixed RK4 steps over 30 s (~60 m of track): the
    node positions of one turned about the vertical are the other's, the tensions equal, to rounding."""
    r = _tracks.rotation(35.0, duration=30.0)
    assert r["excursion_m"] > 50.0
    assert r["position_max_abs_m"] < 1e-10 and r["tension_max_rel"] < 1e-10


def test_a_straight_track_along_x_runs_the_planar_equations():
    plain = _tracks.scene('[top_motion.track]\nkind = "straight"\nspeed = 2.0\n')
    turned = _tracks.scene('[top_motion.track]\nkind = "straight"\nspeed = 2.0\nheading_deg = 30.0\n')
    assert not plain.three_d and build_model(plain).dim == 2
    assert turned.three_d_fields() == ("top_motion.track",) and build_model(turned).dim == 3
    assert _top(turned)(10.0)[[1, 3]] == pytest.approx([20.0 * math.cos(math.pi / 6), 20.0 * math.sin(math.pi / 6)])


@pytest.mark.parametrize("track", ['[top_motion.track]\nkind = "straight"\nspeed = 2.0\n', PATH])
def test_the_ladder_runs_a_track_on_the_node_model_and_says_why(track):
    """The node model runs a track; a straight course is its steady tow for all time, which the steady rung answers
    without stepping (tests/test_ladder_steady.py), a path with arcs is not and steps."""
    sc = _tracks.scene(track)
    straight = "arc" not in track
    assert {r.name: r.valid(sc) == "" for r in BUILTIN} == {"frequency": False, "quasi-static": False, "wang": False,
                                                            "steady": straight, "segmented": True}
    assert next(r for r in BUILTIN if r.name == "wang").valid(sc) == TURNING
    choice, _, checked = decide(sc, "auto", None, None)
    assert choice.name == ("steady" if straight else "segmented") and "track" in choice.reason and checked
    assert decide(sc, "segmented", None, None)[0].name == "segmented"         # the stepped run may still be named
    with pytest.raises(ParameterError, match="numerics.model.*track"):
        decide(sc, "wang", None, None)
    from cablesys.ladder import linear_model                # the linear doors work about the statics at rest
    with pytest.raises(ParameterError) as err:
        linear_model(sc)
    assert err.value.field == "top_motion.track" and "system_speed" in str(err.value)


def test_a_track_run_writes_its_plan_view(tmp_path):
    """A zig-zag run written by the run command's writer: the plan view (x against z) beside the time series."""
    from cablesys.commands.run import write_run
    sc = _tracks.scene(_tracks.ZIGZAG.format(heading=0.0), n=3, duration=60.0, output_step=1.0)
    model = build_model(sc)
    result = _tracks._run(sc, model, rtol=1e-6)
    write_run(sc, result, tmp_path, plot=True)
    assert (tmp_path / "plan_view.png").stat().st_size > 20000 and (tmp_path / "timeseries.png").stat().st_size > 20000


def test_track_tables_round_trip():
    sc = _tracks.scene(PATH)
    again = scene_from_dict(tomllib.loads(dump_scene(sc)))
    assert again.top_motion.track == sc.top_motion.track and len(again.top_motion.track.leg) == 4
    zz = _tracks.scene(_tracks.ZIGZAG.format(heading=10.0))
    back = scene_from_dict(tomllib.loads(dump_scene(zz, units="fps"))).top_motion.track
    for a, b in zip(back.pieces(), zz.top_motion.track.pieces()):
        np.testing.assert_allclose(np.array(a), np.array(b), rtol=1e-12)


@pytest.mark.parametrize("text, field", [
    ('kind = "turn"\nspeed = 2.0\nradius = -5.0\nturn_angle_deg = 90.0', "top_motion.track.radius"),
    ('kind = "straight"\nspeed = 0.0', "top_motion.track.speed"),
    ('kind = "spiral"\nspeed = 1.0', "top_motion.track.kind"),
    ('kind = "turn"\nspeed = 2.0\nradius = 50.0', "top_motion.track.turn_angle_deg"),
    ('kind = "straight"\nspeed = 2.0\nradius = 50.0', "top_motion.track.radius"),
    ('kind = "zig-zag"\nspeed = 2.0\nradius = 40.0\nheading_change_deg = 20.0\nleg_length = 30.0',
     "top_motion.track.leg_length"),
    ('kind = "zig-zag"\nspeed = 2.0\nradius = 40.0\nheading_change_deg = 95.0\nleg_length = 300.0',
     "top_motion.track.heading_change_deg"),
    ('kind = "path"\nspeed = 2.0\n[[top_motion.track.leg]]\nkind = "arc"\nradius = 10.0\nangle_deg = 90.0',
     "top_motion.track.leg[0].direction"),
    ('kind = "path"\nspeed = 2.0\n[[top_motion.track.leg]]\nkind = "straight"\nlength = 10.0\n'
     '[[top_motion.track.leg]]\nkind = "straight"\nradius = 5.0', "top_motion.track.leg[1].length"),
    ('kind = "path"\nspeed = 2.0\n[[top_motion.track.leg]]\nkind = "straight"\nlength = -1.0',
     "top_motion.track.leg[0].length"),
    ('kind = "path"\nspeed = 2.0', "top_motion.track.leg"),
])
def test_bad_track_input_is_named(text, field):
    """Negative radius, zero speed, an unknown kind, a field a kind needs or does not take, a zig-zag whose legs cannot
    hold its turns, a leg table with a missing field: the field named, at reading the scene."""
    with pytest.raises(ParameterError) as err:
        _tracks.scene("[top_motion.track]\n" + text + "\n")
    assert err.value.field == field


def test_a_track_leaves_no_rigid_body_in_a_circle_and_no_flow():
    with pytest.raises(ParameterError) as err:
        _tracks.scene('[top_motion.track]\nkind = "straight"\nspeed = 1.0\n[environment]\nsystem_speed = 1.0\n')
    assert err.value.field == "environment.system_speed"
    text = _tracks.BASE.format(gamma=1.0, n=3, what="") + "pitch_inertia = 50.0\n"
    with pytest.raises(ParameterError) as err:
        scene_from_dict(tomllib.loads(text + "[top_motion.track]\nradius = 50.0\nspeed = 1.0\n"))
    assert err.value.field == "body.pitch_inertia"
    rigid = scene_from_dict(tomllib.loads(text + '[top_motion.track]\nkind = "straight"\nspeed = 1.0\n'))
    model = build_model(rigid)
    p = model.parameters(rigid)
    x0 = initial_state(rigid, model, p)                    # a rigid body in the steady straight tow: at rest in it
    assert np.max(np.abs(np.array(model.ode(x0, 0.0, p)).ravel()[model.nq:])) < 1e-8


def test_a_sweep_varies_a_track():
    """A sweep sets a track's number on the scene: the circle's sinusoids are realised again (not appended to the
    old circle's), a zig-zag's pieces follow its leg length (the model's structure unchanged)."""
    from cablesys.model.params import structure_of
    from cablesys.sweeps.values import apply_values
    circle = _tracks.scene("[top_motion.track]\nradius = 40.0\nspeed = 2.0\n")
    wider, _ = apply_values(circle, {"top_motion.track.radius": 50.0}, "run")
    assert [s.amplitude for s in wider.top_motion.x + wider.top_motion.z] == [50.0, 50.0]
    zz = _tracks.scene(_tracks.ZIGZAG.format(heading=0.0))
    longer, _ = apply_values(zz, {"top_motion.track.leg_length": 300.0}, "run")
    assert longer.top_motion.track.pieces()[1][1][0] == pytest.approx(300.0 - 80.0 * math.tan(math.radians(20.0)))
    assert structure_of(longer) == structure_of(zz)


@pytest.mark.parametrize("direction", ["counter-clockwise", "clockwise"])
def test_a_circle_started_on_another_heading_is_the_turned_steady_turn(direction):
    """heading_deg = 30 on a circle: the tow point starts at (x, z) = +-R (sin 30, -cos 30) heading 30 deg, and the
    steady turn the run starts on is the heading-0 one turned by 30 degrees about the circle's centre."""
    alpha = math.radians(30.0)
    base = f'[top_motion.track]\nradius = 40.0\nspeed = 2.0\ndirection = "{direction}"\n'
    states = []
    for extra in ("", "heading_deg = 30.0\n"):
        sc = _tracks.scene(base + extra)
        model = build_model(sc)
        p = model.parameters(sc)
        states.append((initial_state(sc, model, p), _top(sc)(0.0), model.nq))
    (x0, e0, nq), (x1, e1, _) = states
    side = 1.0 if direction == "counter-clockwise" else -1.0
    assert e1[[1, 3]] == pytest.approx([side * 40.0 * math.sin(alpha), -side * 40.0 * math.cos(alpha)], abs=1e-12)
    assert e1[[4, 6]] == pytest.approx([2.0 * math.cos(alpha), 2.0 * math.sin(alpha)], abs=1e-12)
    turned = np.array([_tracks.rotate(alpha, r) for r in x0[:nq].reshape(-1, 3)])
    assert np.max(np.abs(turned - x1[:nq].reshape(-1, 3))) < 1e-8 * _tracks.LENGTH_M
