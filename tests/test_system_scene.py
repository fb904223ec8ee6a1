"""The system form of a scene: [[point]] and [[line]] tables. A system that is a chain is today's scene exactly (the
same Scene, hence the same model and run: checked on the model's functions and a short run); bad systems are named
errors, with the file's line, before any work."""

import dataclasses
import tomllib

import numpy as np
import pytest

from cablesys.errors import ParameterError
from cablesys.model import build_model
from cablesys.scene import Anchor, Body, Cable, Scene, Seabed, Section, TopMotion, dump_scene, load_scene, scene_from_dict
from cablesys.scene.components import Initial, Numerics
from cablesys.scene.harmonics import Sinusoid
from cablesys.scene.system import Line, Point, System

WIRE = dict(length=100.0, ae=2e6, diameter=0.02, mass_per_length=1.5, weight_per_length=12.0, cd_normal=1.2,
            internal_damping=500.0)
PKG = dict(weight=3000.0, mass_x=400.0, mass_y=450.0, drag_area_normal=0.8, drag_area_tangential=0.8)
CLUMP = dict(weight=800.0, mass_x=120.0, mass_y=130.0, drag_area_normal=0.2, drag_area_tangential=0.2)


def cable(n=4, **kw):
    return Cable(**{**WIRE, "segments": n, **kw})


def toml_system(points, lines, extra=""):
    """A scene file of [[point]] and [[line]] tables from dicts (a line's sections under "section")."""
    out = ['name = "scene"', extra]
    for p in points:
        out += ["[[point]]"] + [f"{k} = {v!r}".replace("'", '"') for k, v in p.items()] + [""]
    for ln in lines:
        out += ["[[line]]"] + [f"{k} = {v!r}".replace("'", '"') for k, v in ln.items() if k != "section"] + [""]
        for s in ln["section"]:
            out += ["[[line.section]]"] + [f"{k} = {v!r}" for k, v in s.items()] + [""]
    return "\n".join(out)


MOTION = TopMotion(x=(Sinusoid(amplitude=1.0, frequency=0.6),), y=(Sinusoid(amplitude=0.5, frequency=0.6),), ramp_s=10.0)
NUM = Numerics(duration=8.0, output_step=0.5, model="as-built")


def chain_pair(reverse=False, anchored=False):
    """(the old form, the system form) of the ship -> wire -> clump -> wire -> package (or anchor) chain."""
    top = Point(name="ship", kind="prescribed")
    mid = Point(name="clump", kind="junction", body=Body(**CLUMP))
    low = (Point(name="anchor", kind="fixed", x=60.0, y=150.0) if anchored
           else Point(name="pkg", kind="body", body=Body(**PKG)))
    a = Line(name="upper", start="ship", end="clump", section=(cable(4),))
    b = (Line(name="lower", start=low.name, end="clump", section=(cable(3, length=80.0),)) if reverse
         else Line(name="lower", start="clump", end=low.name, section=(cable(3, length=80.0),)))
    system = System(point=(low, top, mid), line=(b, a) if reverse else (a, b))
    old = Scene(sections=(Section(cable=cable(4), body=Body(**CLUMP)),
                          Section(cable=cable(3, length=80.0), body=Body(weight=0.0, mass_x=1.0, mass_y=1.0)
                                  if anchored else Body(**PKG))),
                anchor=Anchor(x=60.0, y=150.0) if anchored else None, top_motion=MOTION, numerics=NUM)
    return old, Scene(system=system, top_motion=MOTION, numerics=NUM)


@pytest.mark.parametrize("reverse, anchored", [(False, False), (True, False), (False, True)])
def test_a_chain_written_as_a_system_is_todays_scene(reverse, anchored):
    """Lines in any order and direction: the chain from the prescribed point is today's sections (the anchored one with
    today's [anchor]); the Scene is equal, so the parameter vector and the model are today's."""
    old, new = chain_pair(reverse, anchored)
    assert new == old and new.system is None and (new.anchor is not None) == anchored
    m_old, m_new = build_model(old), build_model(new)
    assert m_new.q_labels == m_old.q_labels and m_new.output_labels == m_old.output_labels
    rng = np.random.default_rng(1)
    x = rng.normal(size=2 * m_old.nq) + np.r_[np.tile([0.0, 40.0], m_old.nq // 2), np.zeros(m_old.nq)]
    p_old, p_new = m_old.parameters(old), m_new.parameters(new)
    np.testing.assert_array_equal(p_new, p_old)
    np.testing.assert_array_equal(np.array(m_new.ode(x, 1.3, p_new)), np.array(m_old.ode(x, 1.3, p_old)))


def test_a_chain_in_a_file_runs_as_the_old_form(tmp_path):
    """The system file of the free chain and today's [[sections]] file: the same run (as built) to round-off."""
    import cablesys
    old, new = chain_pair()
    (tmp_path / "old.toml").write_text(dump_scene(old))
    text = toml_system(
        [dict(name="ship", kind="prescribed"), dict(name="clump", kind="junction", **CLUMP),
         dict(name="pkg", kind="body", **PKG)],
        [dict(name="upper", **{"from": "ship", "to": "clump"}, section=[{**WIRE, "segments": 4}]),
         dict(name="lower", **{"from": "clump", "to": "pkg"}, section=[{**WIRE, "length": 80.0, "segments": 3}])])
    text += "\n[environment]" + dump_scene(old).split("[environment]", 1)[1]
    (tmp_path / "new.toml").write_text(text)
    a, b = load_scene(tmp_path / "old.toml"), load_scene(tmp_path / "new.toml")
    assert b == a
    ra, rb = cablesys.simulate(a), cablesys.simulate(b)
    assert ra.success and rb.success
    for k in ("x_b_2", "y_b_2", "tension_top_1"):
        np.testing.assert_allclose(rb[k], ra[k], rtol=0, atol=1e-12 * max(1.0, np.abs(ra[k]).max()))


def non_chain():
    """A package held by a bridle of two legs from a junction (not a chain: the junction ends three lines)."""
    return System(point=(Point(name="ship", kind="prescribed"), Point(name="ring", kind="junction", body=Body(**CLUMP)),
                         Point(name="pkg", kind="body", body=Body(**PKG)),
                         Point(name="post", kind="fixed", x=80.0, y=60.0)),
                  line=(Line(name="main", start="ship", end="ring", section=(cable(4), cable(2, length=20.0))),
                        Line(name="drop", start="ring", end="pkg", section=(cable(3, length=50.0),)),
                        Line(name="guy", start="ring", end="post", section=(cable(3, length=60.0),))))


def test_a_system_that_is_not_a_chain_keeps_its_points_and_lines_and_round_trips():
    s = Scene(system=non_chain())
    assert s.system is not None and s.sections == () and not s.three_d
    for units in ("SI", "fps"):
        back = scene_from_dict(tomllib.loads(dump_scene(s, units=units, annotate=True)))
        assert back.system.point[1].body.mass_x == pytest.approx(CLUMP["mass_x"], rel=1e-12)
        assert back.system.line[0].section[1].length == pytest.approx(20.0, rel=1e-12)
        assert [ln.start for ln in back.system.line] == ["ship", "ring", "ring"]
        if units == "SI":
            assert back == s
    off = System(point=non_chain().point[:3] + (Point(name="post", kind="fixed", x=80.0, y=60.0, z=5.0),),
                 line=non_chain().line)
    assert Scene(system=off).three_d and "point[3].z" in Scene(system=off).three_d_fields()


BASE_POINTS = [dict(name="ship", kind="prescribed"), dict(name="ring", kind="junction", **CLUMP),
               dict(name="pkg", kind="body", **PKG), dict(name="post", kind="fixed", x=80.0, y=60.0)]
BASE_LINES = [dict(name="main", section=[dict(WIRE)], **{"from": "ship", "to": "ring"}),
              dict(name="drop", section=[dict(WIRE, length=50.0)], **{"from": "ring", "to": "pkg"}),
              dict(name="guy", section=[dict(WIRE, length=60.0)], **{"from": "ring", "to": "post"})]


def edited(points=None, lines=None, extra=""):
    return toml_system(BASE_POINTS if points is None else points, BASE_LINES if lines is None else lines, extra)


@pytest.mark.parametrize("text, field, words", [
    # a point connected to nothing
    (edited(points=BASE_POINTS + [dict(name="spare", kind="junction", **CLUMP)]), "point[4].name", "connected to nothing"),
    # a line naming an unknown point
    (edited(lines=BASE_LINES[:2] + [dict(BASE_LINES[2], to="pots")]), "line[2].to", "names no point"),
    # a line shorter than the distance between its held ends: 30 m from the ship to a post 100 m away
    (edited(points=BASE_POINTS + [dict(name="far", kind="fixed", x=60.0, y=80.0)],
            lines=BASE_LINES + [dict(name="tie", section=[dict(WIRE, length=30.0)], **{"from": "ship", "to": "far"})]),
     "line[3].section[0].length", "shorter than the 100 m"),
    # ... and a path through a junction: main (100 m) + guy (30 m) from the ship to the post 100 m away is fine,
    # but the post at 140 m is not
    (edited(points=BASE_POINTS[:3] + [dict(name="post", kind="fixed", x=140.0, y=0.0)],
            lines=BASE_LINES[:2] + [dict(BASE_LINES[2], section=[dict(WIRE, length=30.0)])]),
     "line[2].section[0].length", "main + guy"),
    # a fixed point below the seabed (bed 50 m below the top, the post at 60 m)
    (edited(extra="[seabed]\ndepth = 50.0\n"), "point[3].y", "below the seabed"),
    # a negative friction coefficient
    (edited(extra="[seabed]\ndepth = 100.0\nfriction_axial = -0.2\n"), "seabed.friction_axial", ">= 0"),
    # nothing holds the system
    (edited(points=[dict(name="ship", kind="body", **PKG)] + BASE_POINTS[1:3] + [dict(name="post", kind="junction",
                                                                                        **CLUMP)]),
     "point", "nothing holds the system"),
    # a second prescribed point without its mean position, a first one off the origin
    (edited(points=BASE_POINTS[:3] + [dict(name="post", kind="prescribed")]), "point[3].x", "second prescribed point"),
    (edited(points=[dict(BASE_POINTS[0], x=5.0, y=1.0)] + BASE_POINTS[1:]), "point[0].x", "first prescribed point"),
    # a body's field on a fixed point, an unknown key, a rigid junction, a bad kind, a self-loop, a duplicate name
    (edited(points=BASE_POINTS[:3] + [dict(BASE_POINTS[3], weight=10.0)]), "point[3].weight", "fixed point"),
    (edited(points=BASE_POINTS[:3] + [dict(BASE_POINTS[3], colour="red")]), "point[3].colour", "unknown key"),
    (edited(points=[BASE_POINTS[0], dict(BASE_POINTS[1], pitch_inertia=5.0)] + BASE_POINTS[2:]),
     "point[1].pitch_inertia", "junction"),
    (edited(points=BASE_POINTS[:3] + [dict(BASE_POINTS[3], kind="anchor")]), "point[3].kind", "must be one of"),
    (edited(points=BASE_POINTS[:3] + [dict(name="post", kind="fixed", y=60.0)]), "point[3].x", "required"),
    (edited(lines=BASE_LINES[:2] + [dict(BASE_LINES[2], to="ring")]), "line[2].to", "must differ"),
    (edited(points=BASE_POINTS + [dict(BASE_POINTS[2])]), "point[4].name", "unique"),
    (edited(lines=BASE_LINES[:2] + [dict(BASE_LINES[2], section=[dict(WIRE, ae=-1.0)])]), "line[2].section[0].ae", "> 0"),
    (edited(extra="[cable]\nlength = 1.0\n"), "cable", "either"),
])
def test_bad_systems_are_named_errors_with_their_line(tmp_path, text, field, words):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(ParameterError) as err:
        load_scene(path)
    assert err.value.field == field, str(err.value)
    assert words in str(err.value)
    assert err.value.file == str(path) and (err.value.line is not None or field == "point")


def test_the_system_form_refuses_what_its_model_does_not_take_yet():
    sys_ = non_chain()
    with pytest.raises(ParameterError, match="initial.u"):
        Scene(system=sys_, initial=Initial(u=0.1))
    off = System(point=sys_.point[:3] + (Point(name="post", kind="fixed", x=80.0, y=60.0, z=5.0),), line=sys_.line)
    assert Scene(system=off, seabed=Seabed(depth=500.0)).three_d         # a seabed in space (as the chain's)
    bed = Seabed(depth=60.5, slope_deg=10.0, heading_deg=-90.0)          # 0.88 m shallower at the post's z = 5 m
    with pytest.raises(ParameterError) as err:
        Scene(system=off, seabed=bed)
    assert err.value.field == "point[3].y" and "z = 5 m" in str(err.value)
    from cablesys.scene.components import TopMotion as TM
    still = System(point=(Point(name="a", kind="fixed", x=0.0, y=0.0), Point(name="b", kind="fixed", x=50.0, y=0.0),
                          Point(name="m", kind="junction", body=Body(**CLUMP))),
                   line=(Line(name="l", start="a", end="m", section=(cable(),)), Line(name="r", start="m", end="b",
                                                                                     section=(cable(),))))
    with pytest.raises(ParameterError) as err:              # top motion without a prescribed point to move
        Scene(system=still, top_motion=TM(y=(Sinusoid(amplitude=1.0, frequency=1.0),)))
    assert err.value.field == "top_motion.y"
    with pytest.raises(ParameterError) as err:
        Scene(sections=(Section(cable=cable(), body=Body(**PKG)),), system=sys_)
    assert err.value.field == "sections"


def test_a_chain_to_a_fixed_point_off_the_plane_is_todays_chain_with_a_3d_anchor():
    """The anchored chain with its fixed point 30 m out of the x-y plane is today's sections with [anchor] at
    (x, y, z) in a 3-D scene: the same Scene, parameters and ode; a fixed point at z = 0 stays in the plane."""
    off = lambda z: System(point=(Point(name="ship", kind="prescribed"),
                                  Point(name="clump", kind="junction", body=Body(**CLUMP)),
                                  Point(name="anchor", kind="fixed", x=60.0, y=150.0, z=z)),
                           line=(Line(name="upper", start="ship", end="clump", section=(cable(4),)),
                                 Line(name="lower", start="clump", end="anchor", section=(cable(3, length=80.0),))))
    old, _ = chain_pair(anchored=True)
    old3 = dataclasses.replace(old, anchor=Anchor(x=60.0, y=150.0, z=30.0))
    got = Scene(system=off(30.0), top_motion=MOTION, numerics=NUM)
    assert got == old3 and got.system is None and got.three_d and got.anchor.position == (60.0, 150.0, 30.0)
    flat = Scene(system=off(0.0), top_motion=MOTION, numerics=NUM)
    assert flat == old and not flat.three_d
    m_old, m_new = build_model(old3), build_model(got)
    assert m_new.q_labels == m_old.q_labels and m_new.dim == 3
    p_old, p_new = m_old.parameters(old3), m_new.parameters(got)
    np.testing.assert_array_equal(p_new, p_old)
    x = np.random.default_rng(2).normal(size=2 * m_old.nq) + np.r_[np.tile([0.0, 40.0, 5.0], m_old.nq // 3),
                                                                    np.zeros(m_old.nq)]
    np.testing.assert_array_equal(np.array(m_new.ode(x, 1.3, p_new)), np.array(m_old.ode(x, 1.3, p_old)))
