"""The run's cost predicted before its build (cablesys.ladder.plan_cost): the fixed-step count is exact
(duration / step), a prediction past the time budget refuses the run before any model is built, and the
``run`` command prints the prediction line."""

import pytest

import cablesys
from cablesys.ladder import plan_cost
from cablesys.ladder.choice import Choice
from cablesys.ladder.extrapolation import PlanRefused
from cablesys.ladder.rungs import RungCache
from cablesys.scene import default_scene
from cablesys.time_domain import IntegratorSettings


def test_fixed_step_prediction_is_duration_over_step():
    scene = default_scene().with_numerics(duration=12.0, output_step=0.05)
    choice = Choice("segmented", 8, "", {"body": 0.01, "tension": 0.02}, {})
    p = plan_cost.predict(scene, choice, IntegratorSettings(method="rk", steps_per_output=7, compiled=False))
    assert p.steps == round(12.0 / (0.05 / 7))          # 1680 steps of 0.05 / 7 s over 12 s
    assert p.steps_from == "duration / step" and p.compile_s == 0.0 and p.elements == 8


def test_past_the_budget_refused_before_any_build(monkeypatch):
    built = []
    import cablesys.ladder.rungs as R
    real = R.build_rung
    monkeypatch.setattr(R, "build_rung", lambda *a, **k: built.append(a) or real(*a, **k))
    cache = RungCache()
    scene = default_scene().with_numerics(time_budget_s=1e-6, model="segmented")
    with pytest.raises(PlanRefused, match=r"time budget 1e-06 s: segmented N = \d+ is predicted to take about") as err:
        cablesys.simulate(scene, cache=cache, segments=8)
    assert "nothing was built" in str(err.value) and err.value.exit_code == 1
    # the choice itself linearizes Wang's model; the run's model (segmented N = 8) is never built
    assert [a[1:] for a in built if a[1] == "segmented"] == []


def test_run_command_prints_the_prediction(tmp_path, capsys):
    from cablesys.cli import main
    scene = tmp_path / "s.toml"
    from cablesys.scene import dump_scene
    scene.write_text(dump_scene(default_scene().with_numerics(duration=12.0)))
    rc = main(["run", str(scene), "--out", str(tmp_path / "o"), "--model", "wang"])
    err = capsys.readouterr().err
    assert rc == 0 and "cablesys run: building wang: about" in err and "steps (cvodes" in err
    import json
    pred = json.loads((tmp_path / "o" / "summary.json").read_text())["model"]["prediction"]
    assert pred["what"] == "wang" and pred["steps"] > 0


@pytest.mark.parametrize("anchored", [False, True])
def test_past_the_element_rule_the_prediction_compiles_as_the_run_does(anchored, monkeypatch):
    # before the build, the prediction's "compiled" (plan_cost.kernel_compiled) must be what the built model's run
    # does (integrators.compiled_by_default): past COMPILE_MAX_ELEMENTS the node model's element kernel compiles the
    # DAE of an adaptive ODE-form method (the run is then ~10x cheaper per step than in the VM), an anchored line's
    # kernel too (its last node the anchor's parameters)
    from cablesys.model import build_model
    from cablesys.scene.ends import Anchor
    from cablesys.time_domain.integrators import COMPILE_MAX_ELEMENTS, compiled_by_default
    monkeypatch.setenv("CABLESYS_COMPILE", "1")          # as a user's run (the suite runs in the VM); nothing compiles
    n = COMPILE_MAX_ELEMENTS + 4
    scene = default_scene().replace_section(cable={"segments": n})
    if anchored:
        scene = scene.replace(anchor=Anchor(x=0.0, y=scene.sections[0].cable.length * 0.99))
    for method in ("cvodes-bdf2", "rk23"):
        assert plan_cost.kernel_compiled(scene, "segmented", method) == compiled_by_default(build_model(scene), method), \
            method
    assert not plan_cost.kernel_compiled(scene, "quasi-static", "cvodes-bdf2")
