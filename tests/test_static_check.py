"""The a priori check of the mean shape (cablesys.ladder.static_check): a rung's static equilibrium in the
scene's current against the node model's converged one, before any run."""

import dataclasses

import pytest

import cablesys
from cablesys.examples import example_path
from cablesys.ladder import static_check as sc
from cablesys.ladder.choice import choose, tolerances
from cablesys.ladder.rungs import RungCache
from cablesys.scene import dale_scene


@pytest.fixture(scope="module")
def rov():
    return cablesys.load_scene(example_path("rov-lift"))


def test_the_reference_statics_are_converged(rov):
    cache = RungCache()
    ref = sc.static_values(rov, "segmented", sc.REFERENCE_SEGMENTS, cache)
    finer = sc.static_values(rov, "segmented", 2 * sc.REFERENCE_SEGMENTS, cache)
    # the polygon's error falls as N^-2: N = 64 is within a tenth of the 1 % tolerance of N = 128
    assert max(sc.static_errors(ref, finer).values()) < 1e-3


def test_a_coarse_polygon_in_the_current_is_replaced_before_it_runs(rov):
    cache = RungCache()
    tol = tolerances(rov)
    ref = sc.static_values(rov, "segmented", sc.REFERENCE_SEGMENTS, cache)
    coarse = sc.static_errors(sc.static_values(rov, "segmented", 4, cache), ref)
    assert coarse["static_x_b"] > tol[0]            # N = 4: 18.31 m against 17.87 m, 2.5 %
    first = choose(rov, cache=cache)
    checked = sc.check(rov, dataclasses.replace(first, name="segmented", segments=4), tol, cache)
    n = checked.segments
    assert n > 4 and checked.numbers["static_errors"]["segments"] == n
    again = sc.static_errors(sc.static_values(rov, "segmented", n, cache), ref)
    assert max(v for k, v in again.items() if "tension" not in k) <= tol[0]
    assert max(v for k, v in again.items() if "tension" in k) <= tol[1]
    assert f"within the tolerance from N = {n}" in checked.reason


def test_in_still_water_nothing_is_checked():
    scene = dale_scene()
    choice = choose(scene)
    assert not sc.applies(scene, choice) and sc.check(scene, choice, tolerances(scene), RungCache()) is choice


def test_the_run_reports_the_static_shape_error(rov):
    run = cablesys.simulate(rov.with_numerics(duration=20.0, output_step=0.5))
    block = run.stats["model"]["static_shape_error"]
    assert block["segments"] == run.stats["model"]["segments"] and block["reference_segments"] >= 64
    assert block["static_x_b"] <= 0.01 and "static shape in the current" in run.stats["model"]["reason"]


def test_a_cost_chosen_quasi_static_plan_grown_past_its_cost_cap_runs_the_node_model(rov):
    # the rk23-stepped quasi-static segmented cable is chosen for its cost only up to EXPLICIT_COST_MAX_ELEMENTS
    # (choice.element_plan); the current's static shape raises rov_lift's N = 4 to 14, where the node model runs
    from ladder_pricing import priced

    from cablesys.ladder.choice import EXPLICIT_COST_MAX_ELEMENTS
    cache = RungCache()
    tol = tolerances(rov)
    with priced(True):               # the choice as compiled code prices it (users'); no C is built here
        first = choose(rov, cache=cache)
    assert first.numbers["plan"]["explicit_only"]
    assert first.name == "quasi-static" and first.segments <= EXPLICIT_COST_MAX_ELEMENTS
    checked = sc.check(rov, first, tol, cache)
    assert checked.segments > EXPLICIT_COST_MAX_ELEMENTS
    assert checked.name == "segmented" and checked.numbers["plan"]["name"] == "segmented"
    assert not checked.numbers["plan"]["explicit_only"]
    assert f"only up to N = {EXPLICIT_COST_MAX_ELEMENTS}" in checked.reason
