"""One scene, one answer for the control (cablesys.control.model_choice): the Python API's default model
(``model="auto"``) is the one ``cablesys control`` runs, with the same N and reason, and every problem and result
says which model ran and why."""

import json

import numpy as np
import pytest

from cablesys.control import WinchLimits, heave_problem, optimal_payout, resolve_model
from cablesys.control.design import time_design_problem
from cablesys.control.model_choice import ModelChoice, ladder_note, winch_form
from cablesys.errors import NumericalWarning, ParameterError
from cablesys.examples import example_path
from cablesys.scene import load_scene

LIMITS = WinchLimits(speed=1.0, acceleration=1.0)


@pytest.fixture(scope="module")
def rov():
    return load_scene(example_path("rov-lift"))


@pytest.fixture(scope="module")
def default_problem(rov):
    """The API's default: heave_problem(scene) with no model (built, not solved)."""
    return heave_problem(rov, LIMITS, dt=0.5)


def test_api_default_is_the_cli_default_on_the_rov_lift(rov, default_problem, tmp_path):
    """On the packaged ROV lift the ladder runs N = 4 elements (the quasi-static cable where the compiled rk23 pair
    makes it the cheaper rung, else the node model itself); the control runs the node model's winch at N = 4 for it.
    ``cablesys control`` (its control.json and the result's summary in it), ``heave_problem``'s default and
    ``time_design_problem``'s default (the model of ``cablesys control --design``) name one model, one N and one
    reason. The CLI runs only the uncompensated plant for 4 s: no optimal control problem is solved."""
    from cablesys.cli import main
    out = tmp_path / "out"
    assert main(["control", str(example_path("rov-lift")), "--strategies", "none", "--duration", "4",
                 "--out", str(out)]) == 0
    doc = json.loads((out / "control.json").read_text())
    cli = doc["models"]["plant_choice"]
    api = default_problem.model_choice
    design = time_design_problem(rov, seeds=(1,)).model_choice         # the scene's own record (numerics.duration)
    assert (api.model, api.segments) == ("segmented", 4)
    assert cli == {"model": api.model, "segments": api.segments, "reason": api.reason}
    assert (design.model, design.segments, design.reason) == (api.model, api.segments, api.reason)
    assert doc["stats"]["plant_model_reason"] == api.reason          # Comparison.summary() reports it
    rung = api.reason.split(":")[0]
    assert rung in ("the ladder's a priori choice is quasi-static, N = 4",
                    "the ladder's a priori choice is segmented, N = 4")
    assert "the control does not" in api.reason           # the checked N of cablesys run is not claimed
    assert ("stands for it" in api.reason) == ("quasi-static" in rung)   # a stand-in is said
    assert api.ladder["name"] == rung.split(" is ")[1].split(",")[0] and api.ladder["segments"] == 4
    assert default_problem.model.segments == 4 and default_problem.model_reason == api.reason
    assert "for the uncompensated scene" in doc["models"]["ladder"]
    assert "NOT the control's model" not in doc["models"]["ladder"] and doc["models"]["ladder_agrees"]
    asked = ModelChoice(model="segmented", segments=2, reason="as asked")
    assert not ladder_note(rov, asked)["ladder_agrees"]               # another N: the console says so apart


def test_the_reason_is_in_the_results_summary(default_problem):
    """The open-loop optimum on the default problem (2 s, 4 intervals) says in its summary which model ran (the node
    model at N = 4) and why (the problem's reason); an explicit model says "as asked"."""
    res = optimal_payout(default_problem, 2.0, max_iter=50)
    s = res.summary()
    json.dumps(s)
    assert s["model"] == default_problem.describe() and "N = 4" in s["model"]
    assert s["model_reason"] == default_problem.model_reason and s["model_reason"].startswith("the ladder's a priori choice is")
    assert resolve_model(default_problem.scene, "wang").reason == "as asked (model = 'wang')"


def test_winch_forms_of_the_ladders_rungs():
    """Wang's rung and the frequency rung (Wang's model's orbit) run Wang's 2-DOF winch; the segmented rung the node
    model at its N; the quasi-static rung a stand-in, said: the node model at N > 1, Wang's straight cable at N = 1."""
    assert winch_form("wang", 1) == ("wang", None, "")
    assert winch_form("frequency", 1) == ("wang", None, "")
    assert winch_form("segmented", 8) == ("segmented", 8, "")
    kind, n, note = winch_form("quasi-static", 6)
    assert (kind, n) == ("segmented", 6) and "node model at N = 6 stands for it" in note
    kind, n, note = winch_form("quasi-static", 1)
    assert (kind, n) == ("wang", None) and "Wang's 2-DOF model stands for it" in note


def test_auto_follows_the_scenes_numerics_model(rov):
    """``auto`` is the scene's [numerics] model, as ``cablesys run`` runs it: a scene asking for Wang's model runs
    Wang's winch (and N elements for it are refused by name, not dropped); ``as-built`` runs the scene's own N with
    no ladder. Bad names and counts are refused before any work."""
    with pytest.warns(NumericalWarning, match="OUTSIDE its validity"):        # the straight cable bows here
        wang = resolve_model(rov.with_numerics(model="wang"))
    assert (wang.model, wang.segments) == ("wang", None)
    assert wang.reason.startswith("the scene's numerics.model, wang:") and "OUTSIDE its validity" in wang.reason
    with pytest.raises(ParameterError, match="segments"), pytest.warns(NumericalWarning):
        resolve_model(rov.with_numerics(model="wang"), "auto", 4)
    built = resolve_model(rov.with_numerics(model="as-built").replace_section(cable={"segments": 3}))
    assert (built.model, built.segments, built.ladder) == ("segmented", 3, None) and "as-built" in built.reason
    with pytest.raises(ParameterError, match="model"):
        resolve_model(rov, "chain")
    with pytest.raises(ParameterError, match="plant_elements"):
        resolve_model(rov, "segmented", 0, names=("plant_model", "plant_elements"))
    asked = ModelChoice(model="segmented", segments=2, reason="as asked (model = 'segmented', segments = 2)")
    assert resolve_model(rov, asked) is asked
    with pytest.raises(ParameterError, match="segments"):
        resolve_model(rov, asked, 8)                           # not dropped: the choice's N is not 8
    assert "another N (2 against the ladder's 4)" in ladder_note(rov, asked)["ladder"]
