"""The isolation design NLP: the example optimum, infeasibility messages, settings validation, CLI."""

import argparse
import json
import math

import numpy as np
import pytest

from cablesys.errors import ParameterError
from cablesys.isolation import (
    DesignInfeasible,
    DesignSettings,
    design,
    settings_from_dict,
)
from cablesys.isolation import cli as design_cli
from cablesys.isolation.example import baseline_scene, dual_scene, example_settings
from cablesys.isolation.solve import equivalent_jacobian_shift
from cablesys.model import build_model
from cablesys.scene import dump_scene


@pytest.fixture(scope="module")
def example():
    return design(dual_scene(), example_settings())


def test_example_design_converges_to_a_constrained_optimum(example):
    r = example
    assert r.converged and r.status == "Solve_Succeeded"
    # every solve well inside IPOPT's budget; the whole multistart + outer loop in a few hundred
    assert max(run["iterations"] for run in r.runs) < 60
    assert r.nlp_iterations < 200
    # the softest first rope the 10 % static strain allows, the second at its softest bound
    assert "static_strain_1" in r.active and "ae_2 at lower bound" in r.active
    assert r.margins["static_strain_1"] == pytest.approx(0.0, abs=1e-6)
    assert all(m > -1e-6 for m in r.margins.values())
    ae_1 = r.value("ae_1")
    t_1 = r.mean_tension[0]
    assert ae_1 == pytest.approx(t_1 / 0.10 + dual_scene().sections[0].cable.tension_ref, rel=1e-5)
    # interior damping: neither bound binds
    for name in ("internal_damping_1", "internal_damping_2"):
        lo, hi = r.lower[r.variable_names.index(name)], r.upper[r.variable_names.index(name)]
        assert 1.5 * lo < r.value(name) < hi / 1.5
    # the outer drag fixed point: the held dJ reproduces the stochastic linearization at the optimum
    assert r.objective == pytest.approx(r.stochastic_sig_y_b, rel=5e-3)
    # a large reduction against the single rope (the study checks it in the time domain)
    base = baseline_scene()
    m = build_model(base)
    _, st = equivalent_jacobian_shift(m, m.parameters(base), example_settings(), n_log2=7)
    reduction_db = 20 * np.log10(r.objective / st.significant_amplitude("y_b"))
    assert -10.0 < reduction_db < -6.0


def test_optimum_is_a_local_minimum(example):
    """Moving either damping by +-10 % (other variables fixed) does not lower the objective."""
    scene = dual_scene(ae=(example.value("ae_1"), example.value("ae_2")),
                       c_i=(example.value("internal_damping_1"), example.value("internal_damping_2")))
    s1 = example_settings(n_starts=1, outer_iterations=1)
    from cablesys.isolation.objective import nlp_functions
    from cablesys.isolation.problem import variables
    from cablesys.linear.steady import steady_state
    model = build_model(scene)
    p = model.parameters(scene)
    vars_ = variables(scene, s1)
    _, _, _, _, report = nlp_functions(model, s1, vars_, p)
    par = np.r_[example.jacobian_shift.ravel(order="F"), steady_state(model, p).q]
    x_opt = np.array([v.normalized(val) for v, val in zip(vars_, example.values)])
    f0 = float(report(x_opt, par)[0])
    for k in (1, 3):
        for fac in (0.9, 1.1):
            x = x_opt.copy()
            x[k] = vars_[k].normalized(example.values[k] * fac)
            assert float(report(x, par)[0]) > f0


@pytest.mark.parametrize("change, name, words", [
    (dict(strain_limit=(0.001, 0.1)), "static_strain_1", "static stretch u_0 / l_0 of section 1"),
    (dict(working_load=(4000.0, 1.5e4)), "peak_tension_1", "working load of section 1"),
])
def test_infeasible_limits_name_the_constraint(change, name, words):
    s = example_settings(n_starts=1, outer_iterations=1, **change)
    with pytest.raises(DesignInfeasible) as err:
        design(dual_scene(), s)
    assert err.value.constraint == name
    msg = str(err.value)
    assert f"'{name}'" in msg and words in msg and "cannot be met" in msg
    assert err.value.violation > 0.1


def test_settings_are_validated_with_field_names():
    with pytest.raises(ParameterError, match=r"design\.ae_bounds\[1\]"):
        example_settings(ae_bounds=((3e4, 3e6), (3e6, 3e4)))
    with pytest.raises(ParameterError, match=r"design\.damping_bounds.*one \[lower, upper\] pair per section"):
        example_settings(damping_bounds=((5e3, 5e5),))
    with pytest.raises(ParameterError, match=r"design\.damping_bounds\[0\] lower"):
        example_settings(damping_bounds=((0.0, 5e5), (5e3, 5e5)))
    with pytest.raises(ParameterError, match=r"design\.objective"):
        example_settings(objective="peak")
    with pytest.raises(ParameterError, match=r"design\.band"):
        example_settings(band=(0.1, 1.0))
    with pytest.raises(ParameterError, match=r"design\.max_iters"):
        settings_from_dict({"ae_bounds": [[1, 2]], "damping_bounds": [[1, 2]], "max_iters": 3})
    with pytest.raises(ParameterError, match=r"design\.ae_bounds\[0\] lower.*reference tension"):
        design(dual_scene(), example_settings(ae_bounds=((5e3, 3e6), (3e4, 3e6))))
    with pytest.raises(ParameterError, match=r"the scene has 1 sections"):
        design(baseline_scene(), example_settings())
    with pytest.raises(ParameterError, match=r"intermediate body"):
        design(baseline_scene(), DesignSettings(ae_bounds=((1e5, 1e7),), damping_bounds=((1e3, 1e6),),
                                                strain_limit=(0.1,), working_load=(2e4,),
                                                intermediate_mass_bounds=(100.0, 200.0)))


DESIGN_TABLE = """
[design]
ae_bounds = [[3e4, 3e6], [3e4, 3e6]]
damping_bounds = [[5e3, 5e5], [5e3, 5e5]]
hs = 2.5
tp = 9.0
strain_limit = [0.1, 0.1]
working_load = [1.5e4, 1.5e4]
n_starts = 2
"""


def _cli(argv):
    ap = argparse.ArgumentParser()
    design_cli.register(ap.add_subparsers())
    args = ap.parse_args(argv)
    return args.func(args)


def test_cli_design_writes_json(tmp_path, capsys):
    path = tmp_path / "dual.toml"
    path.write_text(dump_scene(dual_scene()) + DESIGN_TABLE)   # hand-written table, as a user would
    assert _cli(["design", str(path), "--out", str(tmp_path / "out")]) == 0
    doc = json.loads((tmp_path / "out" / "design.json").read_text())
    assert doc["converged"] and "static_strain_1" in doc["active"]
    # the active 10 % strain limit fixes AE_1 in closed form: u_0 = T_1 l_r / AE (eq. 54 at rest),
    # l_0 = l_r (1 - T_r / AE) (Wang 1971 eq. 1), so u_0 / l_0 = T_1 / (AE - T_r) = 0.10
    t_1, t_r = doc["mean_tension_N"][0], dual_scene().sections[0].cable.tension_ref
    assert doc["variables"]["ae_1"]["value"] == pytest.approx(t_1 / 0.10 + t_r, rel=1e-5)
    # the prediction states its linearization error: two criteria a few % apart, never zero
    e = doc["prediction_error"]
    assert e["baseline_m"] == pytest.approx(doc["baseline"]["significant_heave_m"], rel=1e-9)
    assert all(0 < e[k] < 0.1 for k in ("baseline_error_rel", "designed_error_rel", "ratio_error_rel"))
    out = capsys.readouterr().out
    assert "active: " in out and "linearization error" in out
    # which model the design linearizes, and the ladder's estimate of its error, as every result says
    assert doc["model"]["name"] == "wang" and "as built" in doc["model"]["reason"]
    assert doc["model"]["estimated_error"]["body"] > 0 and "model: wang" in out


def test_settings_toml_round_trip():
    import tomllib

    from cablesys.isolation import settings_to_toml
    s = example_settings(intermediate_mass_bounds=(900.0, 3600.0), objective="rao_band", band=(0.6, 1.2))
    assert settings_from_dict(tomllib.loads(settings_to_toml(s))["design"]) == s


def test_cli_design_needs_a_design_table(tmp_path):
    path = tmp_path / "plain.toml"
    path.write_text(dump_scene(dual_scene()))
    with pytest.raises(ParameterError, match=r"\[design\] table"):
        _cli(["design", str(path)])


def test_intermediate_mass_as_a_variable_can_only_improve(example):
    """The example's plate mass (1800 kg) lies inside the bounds: freeing it cannot make the optimum worse."""
    r = design(dual_scene(), example_settings(intermediate_mass_bounds=(900.0, 3600.0), n_starts=2))
    assert r.converged and r.variable_names[-1] == "intermediate_mass"
    assert r.objective < example.objective * 1.002
    assert all(m > -1e-6 for m in r.margins.values())


@pytest.mark.slow
def test_cli_design_writes_the_designed_scene_and_checks_it_in_the_time_domain(tmp_path, capsys):
    """``--write-scene`` writes the scene with the optimum's values (read back by the scene loader as a user's
    `cablesys run` would), and ``--check`` runs the baseline and the designed scene in the time domain in the
    design sea: the heave reduction the equivalent linearization predicted is what the nonlinear time domain gives,
    within the stated error (the spread of two linearization criteria, the realised sea's offset and two sampling
    errors of the 300 s record, cablesys.isolation.check), for each scene and for the ratio."""
    from cablesys.scene import load_scene
    path = tmp_path / "dual.toml"
    path.write_text(dump_scene(dual_scene(duration=600.0)) + DESIGN_TABLE)
    written = tmp_path / "designed.toml"
    assert _cli(["design", str(path), "--out", str(tmp_path / "out"), "--write-scene", str(written), "--check"]) == 0
    doc = json.loads((tmp_path / "out" / "design.json").read_text())
    new = load_scene(written)
    for i in (1, 2):
        assert new.sections[i - 1].cable.ae == pytest.approx(doc["variables"][f"ae_{i}"]["value"], rel=1e-9)
        assert new.sections[i - 1].cable.internal_damping == pytest.approx(doc["variables"][f"internal_damping_{i}"]["value"], rel=1e-9)
    check = doc["time_domain_check"]
    # the check's predictions are the design's own numbers (the same linearization, recomputed)
    assert check["baseline"]["predicted_m"] == pytest.approx(doc["baseline"]["significant_heave_m"], rel=1e-3)
    assert check["designed"]["predicted_m"] == pytest.approx(doc["significant_y_b_stochastic_m"], rel=1e-3)
    ratio = check["ratio"]
    assert ratio["predicted"] < 0.5 and ratio["time_domain"] < 0.5       # a large improvement, seen in both
    for key in ("baseline", "designed", "ratio"):
        e = check[key]
        # the stated error is a real one: neither zero nor so wide it accepts anything (< 30 %)
        assert 0 < e["linearization_error_rel"] < 0.1 and 0 < e["sampling_error_rel"] < 0.15 and e["allowed_rel"] < 0.3
        assert e["realisation_offset_rel"] < 0.02          # 100 sinusoids carry the spectrum's heave variance
        assert abs(e["difference_rel"]) <= e["allowed_rel"] and e["agree"], (key, e)
    # one sea drives both: the ratio's sampling error is smaller than either scene's
    assert ratio["sampling_error_rel"] < min(check["baseline"]["sampling_error_rel"], check["designed"]["sampling_error_rel"])
    out = capsys.readouterr().out
    assert "DISAGREE" not in out and out.count(": agree") == 3
    assert "baseline (the scene's values)" in out and "time domain" in out
    # `cablesys run` of the written scene is the check's designed run: the same 2 sigma of the body heave (another
    # door: the run command, its summary window), so the written scene reproduces the predicted improvement
    from cablesys.cli import main
    assert main(["run", str(written), "--out", str(tmp_path / "run")]) == 0
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["model"]["name"] == check["designed"]["model"]
    sigma = summary["statistics"]["length_m"]["y_b_2"]["std"]
    d = check["designed"]
    assert 2 * sigma == pytest.approx(d["time_domain_m"], rel=1e-6)
    assert abs(math.log(2 * sigma / d["predicted_m"])) <= d["allowed_rel"]
