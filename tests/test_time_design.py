"""Design through the nonlinear time domain (cablesys.control.design, cablesys.control.gradient): exact
gradients against central differences, the KS envelope's bounds, the ROV lift's design against the static
strain limit's closed form and re-run by the plain time domain, bad input, the study and the door."""

import json
import math

import casadi as ca
import numpy as np
import pytest

from cablesys.control.design import (design_functions, ks_max, resimulate_design, time_design_problem,
                                     time_domain_design)
from cablesys.control.gradient import central_differences, rollout_gradient
from cablesys.errors import ParameterError
from cablesys.examples import example_path
from cablesys.scene import load_scene


@pytest.fixture(scope="module")
def rov():
    """The ROV lift with one drag segment (the 2-DOF model's cheapest form)."""
    return load_scene(example_path("rov-lift")).with_numerics(drag_segments=1)


@pytest.mark.parametrize("segments,duration,h", [(1, 30.0, 0.25), (4, 20.0, 0.05)], ids=["2-dof", "segmented"])
def test_rollout_gradient_matches_central_differences(rov, segments, duration, h):
    # issue 26's check: the time-domain design gradient against central differences at 1e-6, both models;
    # at a soft insert AE = 2e5 N inside the [design] bounds (near both design optima)
    scene = rov.replace_section(0, cable={"ae": 2e5, "segments": segments})
    rg = rollout_gradient(scene, duration, h)
    assert rg.kind == ("wang" if segments == 1 else "segmented")
    J, g = rg.gradient(rg.theta0)
    g = np.array(g).ravel()
    assert float(J) == pytest.approx(float(rg.objective(rg.theta0)), rel=1e-12)   # the same roll-out
    fd = central_differences(rg.objective, rg.theta0, (1e-4, 1e-5))
    err = np.min(np.abs(fd - g) / np.abs(g), axis=0)
    assert np.all(err < 1e-6), err


def test_ks_envelope_bounds_the_maximum():
    # Kreisselmeier-Steinhauser: max v <= KS <= max v + ln(n) / rho, and the shift by max v is exact
    v = np.random.default_rng(3).normal(size=(1, 500))
    for rho in (10.0, 200.0):
        ks = float(ks_max(ca.DM(v), rho))
        assert v.max() <= ks <= v.max() + math.log(v.size) / rho
        assert ks == pytest.approx(math.log(np.sum(np.exp(rho * v))) / rho, rel=1e-12)


@pytest.mark.parametrize("model,segments,duration", [("wang", None, 75.0), ("segmented", 4, 70.0)],
                         ids=["2-dof", "segmented"])
def test_design_jacobian_matches_central_differences(rov, model, segments, duration):
    # issue 26's check on the design itself: its objective's and every constraint's gradient (forward sensitivities
    # of the RK4 roll-out, the rest state's by the implicit-function theorem) against Richardson central differences
    # to 1e-6 of the row's largest entry, on Wang's 2-DOF model and on the node model the ladder runs for the ROV
    # lift (N = 4, its RK4 step set by the stiffest design's Voigt-damped axial mode)
    problem = time_design_problem(rov, seeds=(1,), duration=duration, model=model, segments=segments)
    assert problem.heave.model.nx == (6 if model == "wang" else 18)
    fns = design_functions(problem)
    z = np.array([0.1, 0.5])
    J = np.vstack([np.array(v) for v in fns.jac(z)])
    val = lambda zz: np.concatenate([np.array(v).ravel() for v in fns.fg(zz)])
    fd = np.zeros_like(J)
    for i in range(2):
        d = np.zeros(2)
        d[i] = 1e-5
        D = lambda s: (val(z + s * d) - val(z - s * d)) / (2 * s * d[i])
        fd[:, i] = (4 * D(0.5) - D(1.0)) / 3            # Richardson
    err = np.abs(fd - J) / np.max(np.abs(J), axis=1, keepdims=True)
    assert fns.rows == ("peak_tension (seed 1)", "slack (seed 1)", "excursion (seed 1)", "static_strain")
    assert np.max(err) < 1e-6, err


def test_rov_design_sits_on_the_strain_limit_and_holds_when_rerun(rov):
    problem = time_design_problem(rov, seeds=(1,), duration=90.0, model="wang")
    res = time_domain_design(problem)
    assert res.success, res.message
    assert res.stats["iterations"] < 100 and res.stats["starts"] == 2
    s = res.summary()
    assert s["heave_reduction_db"] < -2.0                          # the soft insert isolates
    for row, (v, b) in res.constraints.items():
        assert v <= b + 1e-6, row
    # the static strain limit decides AE: at rest the mid tension is T_r, so u_0 / l_0 = eps gives
    # T_r / AE = eps / (1 + eps) (Wang 1971 eq. 1); the current shifts the rest tension slightly
    eps, t_r = 0.15, rov.sections[0].cable.tension_ref
    assert res.theta[0] == pytest.approx(t_r * (1 + eps) / eps, rel=5e-3)
    assert res.constraints["static_strain"][0] == pytest.approx(eps, rel=1e-6)
    ds = res.to_xarray()
    assert ds["tension_top"].attrs["units"] == "N" and ds.sizes["seed"] == 1
    # re-run by the plain time domain (CVODES): every limit holds to 1 %, and the heave variance of the
    # RK4 roll-out agrees with it (independent integrators)
    rerun = resimulate_design(problem, res.theta)
    assert rerun["max_relative_violation"] <= 0.01
    assert rerun["heave_variance_m2"] == pytest.approx(res.objective, rel=0.02)
    # the KS envelopes are conservative: never below the re-run's sampled extremes by more than the RK4 error
    for name, (v, b) in rerun["per_seed"][1]["constraints"].items():
        assert res.constraints[f"{name} (seed 1)"][0] >= v - 0.01, name


def test_node_model_design_sits_on_the_strain_limit_and_holds_when_rerun(rov):
    """The design on the segmented node model (N = 2, one seed, 90 s, from one start): IPOPT converges to the static
    strain limit, as on Wang's model, by the same closed form (hanging at rest the element tensions fall linearly
    from the top, so the mean element strain is the mid-length tension T_r over AE, Wang 1971 eq. 1 and 12); its
    slack row bounds the least element tension; the node model re-run by the plain time domain keeps every limit
    to 1 % and its heave variance agrees with the roll-out's to 2 %."""
    problem = time_design_problem(rov, seeds=(1,), duration=90.0, model="segmented", segments=2)
    assert problem.floor_output == "tension_least" and problem.scene.sections[0].cable.segments == 2
    res = time_domain_design(problem, starts=[(3e5, 1e5)])
    assert res.success, res.message
    assert "N = 2" in res.model and res.floor_output == "tension_least"
    eps, t_r = 0.15, rov.sections[0].cable.tension_ref
    assert res.theta[0] == pytest.approx(t_r * (1 + eps) / eps, rel=5e-3)
    assert res.constraints["static_strain"][0] == pytest.approx(eps, rel=1e-6)
    rerun = resimulate_design(problem, res.theta)
    assert rerun["segments"] == 2 and rerun["max_relative_violation"] <= 0.01
    assert rerun["heave_variance_m2"] == pytest.approx(res.objective, rel=0.02)


def test_design_steps_are_stable_for_the_stiffest_design(rov):
    """The RK4 steps per interval come from the stiffest corner of the [design] box, not from the scene's own line:
    at N = 4 the Voigt damping's fast real eigenvalue (C_I at its upper bound: element damping C_I N / l_r on node
    masses m' l_r / N) dominates the axial modes; (dt / n) max |lambda| is within RK4's stability interval for every
    design."""
    from cablesys.control.payout import RK4_STEP_LAMBDA, fastest_mode, model_rest_state
    problem = time_design_problem(rov, seeds=(1,), duration=70.0, model="segmented", segments=4)
    hp = problem.heave
    lay = hp.model.layout
    ae_var, ci_var = problem.variables                  # one section: (AE, C_I)
    lam = {}
    for ae in (ae_var.lower, ae_var.upper):
        for ci in (ci_var.lower, ci_var.upper):
            p = np.array(hp.p, float)
            p[lay.index("cable.ae")], p[lay.index("cable.internal_damping")] = ae, ci
            lam[ae, ci] = fastest_mode(hp.model, model_rest_state(hp.model, p, hp.c), p, hp.c)
    stiffest = max(lam, key=lam.get)
    assert lam[stiffest] == pytest.approx(problem.fastest_mode, rel=1e-12)
    assert stiffest[1] == ci_var.upper
    assert lam[stiffest] > 2 * fastest_mode(hp.model, hp.x_rest, hp.p, hp.c)          # well above the scene's line
    assert hp.substeps == math.ceil(problem.dt * lam[stiffest] / RK4_STEP_LAMBDA)


def test_bad_input(rov):
    with pytest.raises(ParameterError, match="design"):
        time_design_problem(rov.replace(design=None), duration=80.0)
    with pytest.raises(ParameterError, match="seeds"):
        time_design_problem(rov, seeds=(1, 1), duration=80.0)
    with pytest.raises(ParameterError, match="duration"):
        time_design_problem(rov, seeds=(1,), duration=62.0)          # window [60 s, 62 s]: too short
    with pytest.raises(ParameterError, match="working_load"):
        time_design_problem(rov.replace(design={**rov.design, "working_load": [1000.0]}), duration=80.0, model="wang")
    with pytest.raises(ParameterError, match="ae_bounds"):
        time_design_problem(rov.replace(design={**rov.design, "ae_bounds": [[1e4, 9e7]]}), duration=80.0)
    # a chain needs one pair per section (top first)
    with pytest.raises(ParameterError, match=r"ae_bounds.*pair per section \(2\)"):
        time_design_problem(rov.replace(sections=(rov.sections[0], rov.sections[0])), duration=80.0)


def test_time_domain_design_study_quick(run_study):
    out = run_study("time_domain_design", "--quick")
    doc = json.loads((out / "time_domain_design.json").read_text())
    assert doc["time_domain"]["success"] and doc["resimulated_constraint_violation_rel"] <= 0.01
    assert doc["resimulated"]["frequency_design"]["max_relative_violation"] <= 0.01
    assert doc["design_gradient_fd_rel_err"] < 1e-6
    assert "static_strain" in doc["time_domain_active"] and doc["frequency_domain"]["active"] == ["static_strain_1"]
    assert doc["ae_ratio_time_over_frequency"] == pytest.approx(1.0, rel=1e-3)     # both on the strain limit
    # the quick run designs on Wang's model and says so; the full run on the ladder's (the node model, N = 4)
    assert doc["model"].startswith("wang 2-DOF") and doc["model_why"].startswith("quick: Wang's")
    assert "the ladder's a priori choice is" in doc["model_why"]
    assert (out / "time_domain_design.png").stat().st_size > 20000
    # the chain (dual isolation): five variables, the gradient exact, the re-run within 1 %, its own figure
    dual = doc["dual"]
    assert dual["time_domain"]["success"] and len(dual["variables"]) == 5
    assert dual["resimulated_constraint_violation_rel"] <= 0.01 and dual["design_gradient"]["rel_err"] < 1e-6
    assert dual["frequency_over_time_heave_variance"] >= 1 - 1e-6     # the time design is the better in its own roll-out
    assert (out / "time_domain_design_dual.png").stat().st_size > 20000


def test_control_help_documents_the_design_door(capsys):
    from cablesys.cli import main
    with pytest.raises(SystemExit):
        main(["control", "--help"])
    text = capsys.readouterr().out
    assert "--design" in text and "--seeds" in text and "time_design.json" in text


def test_control_design_door_writes_json_and_png(tmp_path, capsys):
    from cablesys.cli import main
    text = example_path("rov-lift").read_text().replace("drag_segments = 10", "drag_segments = 1")
    scene = tmp_path / "rov.toml"
    scene.write_text(text)
    out = tmp_path / "out"
    rc = main(["control", str(scene), "--design", "--record", "75", "--seeds", "1", "--no-resimulate", "--out", str(out),
               "--model", "wang"])
    assert rc == 0
    doc = json.loads((out / "time_design.json").read_text())
    td, fd = doc["time_domain"], doc["frequency_domain"]
    assert td["success"] and td["seeds"] == [1]
    # both designs sit on the static strain limit; the frequency optimum is also judged by the roll-out
    assert td["ae_n"] == pytest.approx(fd["design"]["ae_1"], rel=1e-3)
    assert fd["in_the_time_domain"]["objective_heave_variance_m2"] >= td["objective_heave_variance_m2"] * (1 - 1e-6)
    assert (out / "time_design.png").stat().st_size > 20000
    printed = capsys.readouterr().out
    assert "frequency-domain design" in printed
    # which model ran, and the ladder's own choice for the scene: the straight cable bows in the current
    assert doc["models"]["design"].startswith("wang 2-DOF") and "as asked (model = 'wang')" in doc["models"]["design"]
    assert doc["models"]["design_choice"] == {"model": "wang", "segments": None, "reason": "as asked (model = 'wang')"}
    assert td["model_reason"] == "as asked (model = 'wang')"                # the result's summary says why too
    assert doc["models"]["ladder_choice"]["name"] != "wang" and "NOT the control's model" in printed
