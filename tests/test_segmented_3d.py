"""The node model (segmented cable) in three dimensions: the plane as the special case, rotation about the
vertical, the hanging chain's out-of-plane modes, energy, and the ladder's segmented rung on a 3-D scene."""

import math
import sys
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies"))
import _three_d_nodes as nodes  # noqa: E402
import three_d_checks as checks  # noqa: E402

from cablesys.errors import ParameterError  # noqa: E402
from cablesys.model import build_model  # noqa: E402
from cablesys.scene import Anchor  # noqa: E402


def test_a_planar_scene_keeps_the_planar_node_equations():
    sc = nodes.divided(checks.planar_scenes()[0], 4)
    m2, m3 = build_model(sc), build_model(sc.with_numerics(dimensions=3))
    assert m2.dim == 2 and m2.q_labels[:2] == ("x[1]", "y[1]") and m2.top.size1_out(0) == 7
    assert m2.kernel_ode is not None                       # the planar mapped kernel is kept
    assert m3.dim == 3 and m3.q_labels[:3] == ("x[1]", "y[1]", "z[1]") and m3.top.size1_out(0) == 10
    assert {"phi_z", "z_b", "node_z[4]"} <= set(m3.output_labels)


def test_planar_scenes_run_by_the_3d_node_equations_equal_the_planar_node_model():
    r = nodes.planar_equivalence([checks.planar_scenes()[0]], quick=True, n_el=3)
    case = r["cases"]["one"]
    assert case["equations_max_rel"] < 1e-13 and case["equations_out_of_plane_max_abs"] == 0.0
    assert case["equilibrium_max_abs_m"] < 1e-10           # the 3-D statics find the planar equilibrium
    assert r["run_max_abs"] < 1e-10 and r["max_rel"] < 1e-10     # same RK4 steps: the difference is rounding
    assert case["run_out_of_plane_max_abs"] == 0.0


def test_a_scene_turned_about_the_vertical_gives_the_turned_answer():
    r = nodes.rotation_invariance(checks.rotation_scene(), checks.rotated_scene, checks.rotate, quick=True,
                                  alpha=math.radians(50.0), n_el=3)
    assert r["node_excursion_m"] > 0.3                      # the nodes do move (sway, surge, heave, current)
    assert r["equations_max_abs"] < 1e-10 and r["equations_max_rel"] < 1e-10
    assert r["run_position_max_abs_m"] < 1e-10 and r["run_tension_max_rel"] < 1e-9


def test_hanging_chain_out_of_plane_modes_are_the_in_plane_ones_and_converge_to_bessel():
    r = nodes.chain_modes(quick=True)
    assert r["out_of_plane_vs_in_plane_max_rel"] < 1e-8
    err8, err16 = (np.array(row["rel_err_vs_bessel"]) for row in r["by_elements"])
    assert np.all(err16 < err8)
    assert 1.8 < r["observed_order"][0][0] < 2.2            # the lumped chain: second order in 1 / N (mode 1)


def test_3d_node_model_takes_an_anchor_and_a_seabed_in_space():
    """An [anchor] (held at (x, y, 0) unless anchor.z is set: tests/test_spans.py checks that an anchored span hangs
    in space as in the plane) and a [seabed] in space build the 3-D node model (tests/test_seabed_3d.py checks them)."""
    from cablesys.scene import Seabed
    sc = nodes.divided(checks.rotation_scene(), 3)
    for bed in (None, Seabed(depth=200.0)):
        anchored = type(sc)(sections=sc.sections, environment=sc.environment, top_motion=sc.top_motion,
                            numerics=sc.numerics, anchor=Anchor(x=5.0, y=55.0), seabed=bed)
        model = build_model(anchored)
        assert model.anchored and model.dim == 3
        assert ("seabed_friction_lateral[1]" in model.output_labels) == (bed is not None)


def test_cablesys_run_of_a_3d_scene_says_which_element_model_ran(tmp_path):
    import json

    from cablesys.cli import main
    from cablesys.scene import dump_scene
    sc = checks.rotation_scene().with_numerics(model="auto", duration=12.0)
    f = tmp_path / "turned.toml"
    f.write_text(dump_scene(sc))
    assert main(["run", str(f), "--out", str(tmp_path / "out")]) == 0
    model = json.loads((tmp_path / "out" / "summary.json").read_text())["model"]
    # the straight cable misses the 1 % tolerance on this current turning with depth: N elements in 3-D, with the
    # estimated error as for the plane; the stiff wire (omega / omega_ax < 1/30) makes it the quasi-static segmented
    # cable, its element stretches following the tension; checked a posteriori, N grows to where the node model's
    # functions are the smaller ones, and the reason says so
    assert "quasi-static segmented with N" in model["reason"] and "<= 1/30" in model["reason"]
    assert model["checked"].startswith("a posteriori") and model["segments"] >= 4
    assert model["name"] == "quasi-static" or "x the node model's: the node model with N" in model["reason"]
    assert 0 < model["estimated_error"]["body"] < 0.01


def test_the_ladder_chooses_for_a_3d_scene_whose_stretch_is_not_stiff():
    from cablesys.ladder.auto import decide
    sc = checks.rotation_scene().replace_section(0, cable={"ae": 2e5}).with_numerics(duration=12.0)
    choice, _, _ = decide(sc, "auto", None, None)
    assert choice.name in ("wang", "segmented")


def test_3d_kernel_ode_equals_the_element_by_element_ode():
    """Two sections with a joint body in a 3-D scene (current and wave with headings, sway): the mapped element
    kernel (3 x 3 node blocks) is the same function as the element-by-element ode, to rounding."""
    from three_d_checks import Section
    sc = checks.rotation_scene()
    low = Section(cable=checks.wire(length=30.0, segments=5), body=sc.body)
    two = nodes.divided(type(sc)(sections=(sc.sections[0], low), environment=sc.environment, top_motion=sc.top_motion,
                                 numerics=sc.numerics), 6)
    m = build_model(two)
    assert m.dim == 3 and m.kernel_ode is not None and m.loop_ode is m.kernel_ode
    p = m.parameters(two)
    for x in nodes._random_states(m, p, np.random.default_rng(2), 3, 3):
        for t in (0.0, 4.2):
            a, b = (np.array(f(x, t, p)).ravel() for f in (m.ode, m.kernel_ode))
            assert np.max(np.abs(b - a)) <= 1e-12 * np.max(np.abs(a))
    # its Jacobian by the chain rule over the elements (3 x 3 blocks) is AD of the element-by-element ode
    xs, ts, ps = ca.SX.sym("x", m.ode.size1_in(0)), ca.SX.sym("t"), ca.SX.sym("p", m.ode.size1_in(2))
    ad = ca.Function("ode_jac", [xs, ts, ps], [ca.jacobian(m.ode(xs, ts, ps), xs)])
    for x in nodes._random_states(m, p, np.random.default_rng(3), 3, 1):
        a, b = np.array(ad(x, 4.2, p)), np.array(m.kernel_jacobian(x, 4.2, p))
        assert np.max(np.abs(b - a)) <= 1e-11 * np.max(np.abs(a))


def test_the_element_coordinates_take_a_3d_scene_and_refuse_an_anchored_line():
    """(phi_k, phi_z_k, u_k) in 3-D (tests/test_quasistatic_3d.py checks their physics); an anchored line's fixed last
    node is no element coordinate: refused by name."""
    from cablesys.model.element_coordinates import build_element_model
    sc = nodes.divided(checks.rotation_scene(), 3)
    assert build_element_model(sc).q_labels[:3] == ("phi[0]", "phi_z[0]", "u[0]")
    anchored = type(sc)(sections=sc.sections, environment=sc.environment, top_motion=sc.top_motion,
                        numerics=sc.numerics, anchor=Anchor(x=5.0, y=55.0))
    with pytest.raises(ParameterError, match="anchor.*element coordinates"):
        build_element_model(anchored)


def test_to_xarray_stacks_positions_on_an_axis_dimension():
    """A 3-D run's dataset has ``axis`` (x, y, z): the body's ``r_b`` is (x_b, y_b, z_b), and its node positions'
    last node is the body (the node model's body sits on its last node); the top node moves with the top."""
    import cablesys
    sc = nodes.divided(checks.rotation_scene(), 3).with_numerics(duration=2.0, output_step=0.5, model="as-built")
    r = cablesys.simulate(sc)
    ds = r.to_xarray()
    assert list(ds["axis"].values) == ["x", "y", "z"] and ds["r_b"].dims == ("time", "axis")
    np.testing.assert_array_equal(ds["r_b"].values, np.column_stack([r["x_b"], r["y_b"], r["z_b"]]))
    np.testing.assert_allclose(ds["node_position"].values[:, -1, :], ds["r_b"].values, rtol=0, atol=1e-12)
    assert ds["node_position"].attrs["units"] == "m" and ds["v_b"].dims == ("time", "axis")
    assert float(np.ptp(ds["node_position"].values[:, 0, 2])) > 0.0          # the top sways
