"""The stated error holds for every reported quantity (each body coordinate's amplitude and mean, each tension
extreme), checked against a converged segmented cable on a scene the a priori estimates get wrong: a wire in a
sheared current, surged and heaved, where the small surge amplitude converges slowly in N."""

import warnings

import numpy as np
import pytest

import cablesys
from cablesys.ladder import choose, metrics
from cablesys.scene import Body, Cable, Environment, Numerics, Scene, Section, TopMotion
from cablesys.scene.harmonics import Sinusoid

N_REF = 64


@pytest.fixture(scope="module")
def sheared():
    """150 m of 25 mm wire, a 4 kN sphere, current 1.2 / 0.6 / 0.1 m/s at 0 / 40 / 150 m, 1.5 m surge and 1 m heave
    at T = 9 s: the mean offset is ~7 m, the surge amplitude a few centimetres."""
    w = 0.698
    cable = Cable(length=150.0, tension_ref=5500.0, ae=4.0e7, diameter=0.025, mass_per_length=2.5,
                  weight_per_length=19.6, cd_normal=1.2, ct_tangential=0.01, internal_damping=1.2e5,
                  tension_floor=0.0)
    body = Body(weight=4000.0, mass_x=1500.0, mass_y=1500.0, drag_area_normal=1.0, drag_area_tangential=1.0,
                axis_angle_deg=999.0)
    env = Environment(density=1025.0, current_depths=(0.0, 40.0, 150.0), current_speeds=(1.2, 0.6, 0.1))
    top = TopMotion(x=(Sinusoid(amplitude=1.5, frequency=w, phase=np.pi / 2),), y=(Sinusoid(amplitude=1.0, frequency=w),))
    scene = Scene(name="sheared current", sections=(Section(cable=cable, body=body),), environment=env,
                  top_motion=top, numerics=Numerics(duration=90.0, output_step=0.1), angles="per_section")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        auto = cablesys.simulate(scene)
        ref = cablesys.simulate(scene, model="segmented", segments=N_REF)
    period = metrics.forcing_period(scene)
    return scene, auto, metrics.statistics(auto, period), metrics.statistics(ref, period)


def test_every_quantity_is_within_the_tolerance_and_the_stated_error_is_honest(sheared):
    scene, auto, got, ref = sheared
    model = auto.stats["model"]
    assert model["checked"].startswith("a posteriori") and model["segments"] < N_REF
    stated = model["estimated_error_per_quantity"]
    actual = metrics.quantity_errors(got, ref)
    tol = {"body": 0.01, "tension": 0.02}
    assert set(stated) == set(actual) and {"x_b_amplitude", "x_b_mean", "tension_top_min"} <= set(actual)
    for k, e in actual.items():
        assert e <= tol[metrics.group(k)], (k, e, model["reason"])
        if e > 0.05 * tol[metrics.group(k)]:   # resolved: the stated error is not below the actual by more than 2x
            assert stated[k] >= 0.5 * e, (k, stated[k], e)


def test_the_a_priori_choice_alone_would_have_missed_the_surge(sheared):
    """The linear estimates put the body error of N = 4 far within the tolerance; the checks grow N."""
    scene, auto, got, ref = sheared
    first = choose(scene)
    assert first.estimated_error["body"] < 0.005 and first.segments < auto.stats["model"]["segments"]


def test_quantities_of_interest_narrow_the_check(sheared):
    scene, auto, got, ref = sheared
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        heave = cablesys.simulate(scene, quantities=("y_b_amplitude", "tension_top_max", "tension_top_min"))
    assert heave.stats["model"]["segments"] < auto.stats["model"]["segments"]
    period = metrics.forcing_period(scene)
    actual = metrics.quantity_errors(metrics.statistics(heave, period), ref)
    assert actual["y_b_amplitude"] <= 0.01 and actual["tension_top_max"] <= 0.02


def test_the_ladder_quantities_study_runs_quick(run_study):
    import json
    out = run_study("ladder_quantities", "--quick")
    doc = json.loads((out / "ladder_quantities.json").read_text())
    (c,) = doc["cases"]
    assert c["all_held_within_tolerance"] and c["all_stated_honest"]
    assert {r["quantity"] for r in c["rows"]} >= {"x_b_amplitude", "x_b_mean", "tension_top_max"}
    assert (out / "ladder_quantities.png").stat().st_size > 10_000
