"""Names that mean one thing and commands that link: the segmented cable's stretch u (the element
elongations) against its chord, the steady tow's shape lines, and the design's active constraints."""

import collections
import dataclasses
import json

import numpy as np
import pytest

from cablesys.model.segmented import build_segmented_model
from cablesys.result_protocol import long_name_of, unit_of
from cablesys.scene import dale_scene
from cablesys.statics import steady_state


def _sagging(n=6):
    """Dale's scene, 6 elements, in a 1.5 m/s current: the cable bows, so its chord is shorter than it."""
    sc = dale_scene(duration=1.0).replace_section(0, cable={"segments": n})
    env = dataclasses.replace(sc.environment, current_depths=(0.0,), current_speeds=(1.5,))
    return sc.replace(environment=env)


def test_segmented_u_is_the_element_stretch_and_the_chord_is_named_apart():
    sc = _sagging()
    model = build_segmented_model(sc)
    p = model.parameters(sc)
    st = steady_state(model, p)
    y = st.outputs
    x = np.asarray([y[f"node_x[{k}]"] for k in range(7)])
    yy = np.asarray([y[f"node_y[{k}]"] for k in range(7)])
    l_0 = sc.cable.length_zero
    # independent route: the polyline through the nodes
    along = float(np.sum(np.hypot(np.diff(x), np.diff(yy)))) - l_0
    chord = float(np.hypot(x[-1] - x[0], yy[-1] - yy[0])) - l_0
    assert y["u"] == pytest.approx(along, rel=1e-9, abs=1e-12)
    assert y["chord_stretch"] == pytest.approx(chord, rel=1e-9, abs=1e-12)
    # the cable bows: the chord is shorter than the stretched cable by more than the solver's tolerance
    assert y["chord_stretch"] < y["u"] - 1e-6
    # the stretch is elastic: the sum over elements of T_k h_r / AE (taut elements, no damping at rest)
    tension = np.asarray([y[f"element_tension[{k}]"] for k in range(6)])
    assert y["u"] == pytest.approx(float(np.sum(tension / sc.cable.ae)) * sc.cable.length / 6, rel=1e-6)
    assert unit_of("chord_stretch") == "m" and "chord" in long_name_of("chord_stretch")
    assert "zero-tension" in long_name_of("u")


# -- design: the active set agrees with the margins; an infeasible design is a failed computation ----

from cablesys.isolation import DesignInfeasible, design  # noqa: E402
from cablesys.isolation.example import dual_scene, example_settings  # noqa: E402
from cablesys.isolation.solve import ACTIVE_TOL, active_set  # noqa: E402


def test_active_set_is_the_constraints_at_their_bound():
    var = collections.namedtuple("var", "name")
    vars_ = (var("ae_1"), var("ae_2"), var("c_1"))
    names = ("slack_1", "static_strain_1", "peak_tension_1")
    # the report's case: slack_1 with margin +0.764 is not active; a margin of 0.5 ACTIVE_TOL is
    g = np.array([-0.764, -0.5 * ACTIVE_TOL, -10 * ACTIVE_TOL])
    got = active_set(vars_, np.array([0.5, 0.1 * ACTIVE_TOL, 1.0]), names, g)
    assert got == ["ae_2 at lower bound", "c_1 at upper bound", "static_strain_1"]


def test_design_active_constraints_have_zero_margin():
    r = design(dual_scene(), example_settings(n_starts=1, outer_iterations=1))
    for name, m in r.margins.items():
        assert (name in r.active) == (abs(m) <= ACTIVE_TOL), (name, m, r.active)
    assert "static_strain_1" in r.active         # the 10 % strain limit binds (tests/test_design_solve.py)


def test_infeasible_design_exits_1_with_the_best_point(tmp_path, capsys):
    from cablesys.cli import main
    from cablesys.scene import dump_scene
    path = tmp_path / "dual.toml"
    # a 0.1 % static strain limit on the first rope: no AE within [3e4, 3e6] N meets it
    path.write_text(dump_scene(dual_scene()) + "\n[design]\nae_bounds = [[3e4, 3e6], [3e4, 3e6]]\n"
                    "damping_bounds = [[5e3, 5e5], [5e3, 5e5]]\nhs = 2.5\ntp = 9.0\nstrain_limit = [0.001, 0.1]\n"
                    "working_load = [1.5e4, 1.5e4]\nn_starts = 1\nouter_iterations = 1\n")
    assert main(["design", str(path), "--out", str(tmp_path / "out")]) == 1
    doc = json.loads((tmp_path / "out" / "design.json").read_text())
    assert doc["status"] == "infeasible" and doc["violated_constraint"] == "static_strain_1"
    assert doc["violation"] > 0.1 and doc["constraint_margins"]["static_strain_1"] == pytest.approx(-doc["violation"])
    lo, hi = 3e4, 3e6
    assert set(doc["best_point"]) == {"ae_1", "ae_2", "internal_damping_1", "internal_damping_2"}
    # IPOPT relaxes the bounds by 1e-8 relative (its bound_relax_factor)
    assert lo * (1 - 1e-7) <= doc["best_point"]["ae_1"] <= hi * (1 + 1e-7)
    out = capsys.readouterr().out
    assert "INFEASIBLE: constraint 'static_strain_1'" in out and "best point found:" in out and "ae_1" in out
    manifest = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert manifest["status"] == "failed"
    assert DesignInfeasible.exit_code == 1


# -- a steady tow prints its shape ---------------------------------------------------------------------

def test_steady_tow_reports_top_tension_depth_and_layback():
    """Towed at 0.3 m/s from the steady state, Wang's straight cable keeps its shape: depth (l_0 + u) cos phi
    and layback (l_0 + u) sin phi (e_t = (-sin phi, cos phi), Wang 1971 eq. 10), the top's pull the steady one."""
    from cablesys.linear import steady_state as linear_steady
    from cablesys.model import build_model
    from cablesys.scene import Initial, TopMotion
    from cablesys.time_domain import simulate
    from cablesys.units import output_unit
    from cablesys.verdict import report, steady_shape_lines
    scene = dale_scene(duration=4.0, output_step=0.5).replace(top_motion=TopMotion()).with_environment(system_speed=0.3)
    model = build_model(scene)
    ss = linear_steady(model, model.parameters(scene))
    phi, u = ss.q[0], ss.q[1]
    r = simulate(scene.replace(initial=Initial(phi=phi, u=u)), model=model)
    assert r.success
    shape = report(scene, r)["steady_shape"]
    length = scene.cable.length_zero + u
    assert shape["body_depth_m"] == pytest.approx(length * np.cos(phi), rel=1e-6)
    assert shape["layback_m"] == pytest.approx(length * np.sin(phi), rel=1e-6)
    assert shape["layback_m"] > 0.0                              # the body trails behind the towing point
    assert shape["top_tension_N"] == pytest.approx(ss.outputs["tension_top"], rel=1e-6)
    (line,) = steady_shape_lines({"steady_shape": shape})
    assert f"layback {shape['layback_m']:.5g} m" in line and f"top tension {shape['top_tension_N']:.5g} N" in line
    (fps,) = steady_shape_lines({"steady_shape": shape}, lambda unit: output_unit(unit, "fps"))
    assert " lbf" in fps and " ft" in fps and " N" not in fps
    # a moving top, or no tow speed: no shape lines
    assert "steady_shape" not in report(dale_scene(duration=2.0), simulate(dale_scene(duration=2.0)))
    assert steady_shape_lines({}) == []
