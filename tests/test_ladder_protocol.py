"""The ladder's protocol from outside, in CasADi's virtual machine: typed options, a rung registered from outside
the package, the linear analyses' model, and help texts written from the registries."""

import json

import numpy as np
import pytest

import cablesys
from cablesys.cli import main
from cablesys.scene import dale_scene, dump_scene


def test_an_unknown_option_is_an_error_not_ignored():
    with pytest.raises(TypeError, match="rtoll"):
        cablesys.simulate(dale_scene(duration=1.0), rtoll=1e-12)
    with pytest.raises(cablesys.ParameterError, match="numerics.model"):
        cablesys.simulate(dale_scene(duration=1.0), model="lumped")


class HalfWang:
    """A toy rung from outside the package: Wang's model under another name, claiming half Wang's estimated error
    at a tenth of its cost (a made-up model: what the ladder must do with it is the point)."""

    name = "half-wang"

    def build(self, scene):
        return cablesys.build_model(scene)

    def estimate(self, scene, assessment):
        e = assessment.estimates["wang"]
        return {"body": 0.5 * e["body"], "tension": 0.5 * e["tension"], "note": "toy: half Wang's estimate"}

    def cost(self, scene, assessment):
        return 0.1


def test_a_rung_from_outside_is_considered_chosen_and_run():
    from cablesys import ladder
    scene = dale_scene(omega_ratio=0.5, duration=30.0)
    before = ladder.choose(scene)
    wang = ladder.choose(scene).numbers["estimates"]["wang"]
    ladder.register_rung(HalfWang())
    try:
        assert isinstance(HalfWang(), ladder.Rung)
        chosen = ladder.choose(scene)
        # on this scene Wang's estimate misses the 1 % tolerance and half of it is within: the toy is chosen
        assert wang["body"] > 0.01 and 0.5 * wang["body"] <= 0.01 and 0.5 * wang["tension"] <= 0.02
        assert before.name != "wang" and chosen.name == "half-wang" and "registered rung" in chosen.reason
        assert chosen.estimated_error["body"] == pytest.approx(0.5 * wang["body"])
        run = cablesys.simulate(scene)
        assert run.stats["model"]["name"] == "half-wang" and run.success
        with pytest.warns(cablesys.NumericalWarning, match="OUTSIDE its validity"):
            ref = cablesys.simulate(scene, model="wang")        # the same equations under its own name
        np.testing.assert_allclose(run["x_b"], ref["x_b"], rtol=1e-9, atol=1e-12)
        assert cablesys.simulate(scene, model="half-wang").stats["model"]["name"] == "half-wang"
        with pytest.raises(cablesys.ParameterError, match="rung.name"):
            ladder.register_rung(type("Bad", (HalfWang,), {"name": "wang"})())
    finally:
        ladder.unregister_rung("half-wang")
    assert (ladder.choose(scene).name, ladder.choose(scene).segments) == (before.name, before.segments)


def test_the_linear_analyses_linearize_the_ladders_model_and_say_so(tmp_path):
    from cablesys import ladder
    heavy = cablesys.heavy_wire_scene()
    choice = ladder.choose(heavy)
    assert choice.segments > 1                            # the straight cable misses the tolerance on this wire
    sc, model, which = ladder.linear_model(heavy)
    assert (which["name"], which["segments"]) == ("segmented", choice.segments)
    assert max(s.cable.segments for s in sc.sections) == choice.segments
    assert model.kind == "segmented" and which["estimated_error"]["body"] <= 0.01
    # a scene the ladder runs straight is linearized straight, and the rao command writes which and why
    dale = dale_scene(omega_ratio=0.5)
    path = tmp_path / "dale.toml"
    path.write_text(dump_scene(dale))
    assert main(["rao", str(path), "--out", str(tmp_path / "rao"), "--n", "50"]) == 0
    doc = json.loads((tmp_path / "rao" / "rao_summary.json").read_text())
    expect = ladder.linear_model(dale)[2]
    assert doc["model"] == json.loads(json.dumps(expect)) and doc["model"]["name"] in ("wang", "segmented")


def test_run_help_is_written_from_the_registries(capsys):
    import dataclasses

    from cablesys.integration import METHODS
    from cablesys.ladder import MODEL_CHOICES
    from cablesys.time_domain import IntegratorSettings
    with pytest.raises(SystemExit):
        main(["run", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert all(m in text for m in METHODS) and all(m in text for m in MODEL_CHOICES)
    steps = next(f.default for f in dataclasses.fields(IntegratorSettings) if f.name == "max_num_steps")
    assert f"default {steps})" in text
