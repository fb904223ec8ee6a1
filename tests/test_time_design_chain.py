"""The time-domain design of a chain of sections (a soft insert below an intermediate body, Wang 1971 p. 33's dual
isolation; the packaged ``dual-isolation`` example): the node model's winch on a chain at rest against the hanging
weights' closed form, the design's exact Jacobian over every section's AE and C_I and the intermediate body's mass
against central differences, the design through ``cablesys control --design`` against the frequency-domain design
judged by the same roll-out and re-run by the plain time domain, and bad input."""

import json

import numpy as np
import pytest

from cablesys.control.design import design_functions, time_design_problem
from cablesys.control.payout import control_model
from cablesys.errors import ParameterError
from cablesys.examples import example_path
from cablesys.model.segmented_winch_control import rest_state
from cablesys.scene import load_scene


@pytest.fixture(scope="module")
def dual():
    """The dual-isolation example with one drag segment per element (the cheapest form)."""
    return load_scene(example_path("dual-isolation")).with_numerics(drag_segments=1)


def _weights(scene, mass_scale=1.0):
    """(W below section 1's mid-length, W below section 2's mid-length, W below section 2's top) (N): the hanging
    weights in water of the bodies and ropes (l_r per rope), the plate's scaled with its mass."""
    (c1, b1), (c2, b2) = ((s.cable, s.body) for s in scene.sections)
    w1, w2 = c1.weight_per_length, c2.weight_per_length
    below_2 = b2.weight + w2 * c2.length
    return (below_2 + mass_scale * b1.weight + w1 * c1.length / 2, b2.weight + w2 * c2.length / 2, below_2)


def test_packaged_example_is_the_isolation_examples_chain(dual):
    # the TOML says it is cablesys.isolation.example.dual_scene with a sea: every rope's and body's number agrees
    # with that scene's derivation (the plate's added mass rho D^3 / 3, the ropes' mean hanging tensions)
    import dataclasses

    from cablesys.isolation.example import dual_scene
    ref = dual_scene()
    for mine, theirs in zip(dual.sections, ref.sections):
        for part in ("cable", "body"):
            a, b = dataclasses.asdict(getattr(mine, part)), dataclasses.asdict(getattr(theirs, part))
            for k, v in b.items():
                if isinstance(v, float):
                    assert a[k] == pytest.approx(v, rel=1e-12), (part, k)


@pytest.mark.parametrize("n", [1, 3])
def test_chain_winch_hangs_at_rest_as_the_weights_say(dual, n):
    # at rest the pull on the sheave is the whole weight in water, section 2's top carries what hangs below it, and
    # each rope's strain u_0 / l_0 is its mid-length tension T over AE - T_r (its tensions fall linearly with depth,
    # and its spring is AE / l_r with l_0 = l_r (1 - T_r / AE): Wang 1971 eq. 1, 12)
    sc, model = control_model(dual, "segmented", n)
    assert model.sections == 2 and model.segments == n and model.nq == 4 * n
    p = model.parameters(sc)
    x = rest_state(model, p)
    y = dict(zip(model.output_labels, np.array(model.outputs(x, [0, 0], 0.0, p, np.zeros(4))).ravel()))
    mid_1, mid_2, top_2 = _weights(sc)
    total = top_2 + sc.sections[0].body.weight + sc.sections[0].cable.weight_per_length * sc.sections[0].cable.length
    l0 = [s.cable.length * (1 - s.cable.tension_ref / s.cable.ae) for s in sc.sections]
    # the rope weights act on the unstretched lengths l_0 (within (T_r / AE) of l_r: 4e-3 here, on 2 % of the load)
    assert y["tension_top"] == pytest.approx(total, rel=1e-4)
    assert y["tension_top_2"] == pytest.approx(top_2, rel=1e-4)
    c1, c2 = (s.cable for s in sc.sections)
    assert y["stretch"] / l0[0] == pytest.approx(mid_1 / (c1.ae - c1.tension_ref), rel=1e-4)
    assert y["stretch_2"] / l0[1] == pytest.approx(mid_2 / (c2.ae - c2.tension_ref), rel=1e-4)
    assert y["heave"] == pytest.approx(l0[0] + y["stretch"] + l0[1] + y["stretch_2"], rel=1e-9)   # the package


def test_chain_design_strains_follow_every_variable(dual):
    # the design's static strains (the rest state of each candidate, by Newton's method) against the closed form at a
    # design far from the scene's: a heavier plate loads the upper rope, each rope's AE divides its own strain
    problem = time_design_problem(dual, seeds=(1,), duration=75.0)
    assert problem.names == ("ae_1", "internal_damping_1", "ae_2", "internal_damping_2", "intermediate_mass")
    fns = design_functions(problem)
    theta = np.array([2e5, 3e4, 8e4, 2e5, 4000.0])
    _, strain = fns.series(theta, fns.tables[0])
    scale = theta[4] / dual.sections[0].body.mass_y
    mid_1, mid_2, _ = _weights(dual, scale)
    t_r = [s.cable.tension_ref for s in dual.sections]
    assert np.array(strain).ravel() == pytest.approx([mid_1 / (theta[0] - t_r[0]), mid_2 / (theta[2] - t_r[1])],
                                                     rel=2e-3)


def test_chain_design_jacobian_matches_central_differences(dual):
    # issue 26's gradient check on a chain: the objective's and every constraint's derivative in all five variables
    # (forward sensitivities of the RK4 roll-out, the rest state's by the implicit-function theorem) against
    # Richardson central differences, to 1e-6 of each row's largest entry
    problem = time_design_problem(dual, seeds=(1,), duration=75.0)
    fns = design_functions(problem)
    assert fns.rows == ("peak_tension (seed 1)", "peak_tension_2 (seed 1)", "slack (seed 1)", "excursion (seed 1)",
                        "static_strain", "static_strain_2")
    z = np.array([0.3, 0.5, 0.6, 0.4, 0.7])
    J = np.vstack([np.array(v) for v in fns.jac(z)])
    val = lambda zz: np.concatenate([np.array(v).ravel() for v in fns.fg(zz)])
    fd = np.zeros_like(J)
    for i in range(z.size):
        d = np.zeros(z.size)
        d[i] = 1e-5
        D = lambda s: (val(z + s * d) - val(z - s * d)) / (2 * s * d[i])
        fd[:, i] = (4 * D(0.5) - D(1.0)) / 3            # Richardson
    err = np.abs(fd - J) / np.max(np.abs(J), axis=1, keepdims=True)
    assert np.max(err) < 1e-6, err


def test_dual_isolation_design_door_against_the_frequency_design(tmp_path, capsys):
    # cablesys control --design on a chain: the time-domain optimum over both ropes' AE and C_I and the plate's mass
    # meets every limit, at most the frequency-domain optimum's heave variance in the same roll-out (that design is
    # one candidate of the same problem), and holds when re-run by the plain time domain (CVODES) to 1 %
    from cablesys.cli import main
    text = example_path("dual-isolation").read_text().replace("drag_segments = 6", "drag_segments = 1")
    scene = tmp_path / "dual.toml"
    scene.write_text(text)
    out = tmp_path / "out"
    # 80 s: a 20 s statistics window after the scene's 60 s start-up (studies/time_domain_design.py --quick designs
    # the same chain over the same record)
    rc = main(["control", str(scene), "--design", "--record", "80", "--seeds", "1", "--out", str(out)])
    assert rc == 0
    doc = json.loads((out / "time_design.json").read_text())
    td, fd = doc["time_domain"], doc["frequency_domain"]
    assert td["success"], td["message"]
    assert set(td["design"]) == {"ae_1_n", "internal_damping_1_n_s", "ae_2_n", "internal_damping_2_n_s",
                                 "intermediate_mass_kg"}
    assert "ae_n" not in td                     # a chain's AE is per section, never under the one-line name
    for row, c in td["constraints"].items():
        assert c["value"] <= c["bound"] + 1e-6, row
    assert td["objective_heave_variance_m2"] < td["baseline_heave_variance_m2"]
    assert td["objective_heave_variance_m2"] <= fd["in_the_time_domain"]["objective_heave_variance_m2"] * (1 + 1e-6)
    rerun = doc["resimulated"]["design"]
    assert rerun["sections"] == 2 and rerun["max_relative_violation"] <= 0.01
    assert rerun["heave_variance_m2"] == pytest.approx(td["objective_heave_variance_m2"], rel=0.03)
    assert "N = 1 per section, 2 sections" in doc["models"]["design"]
    printed = capsys.readouterr().out
    assert "m_1" in printed and "peak_tension_2" in printed
    assert (out / "time_design.png").stat().st_size > 20000


def test_chain_bad_input(dual):
    rov = load_scene(example_path("rov-lift"))
    with pytest.raises(ParameterError, match="intermediate_mass_bounds"):
        time_design_problem(rov.replace(design={**rov.design, "intermediate_mass_bounds": [100.0, 1000.0]}),
                            duration=80.0, model="wang")
    with pytest.raises(ParameterError, match="model = 'wang'.*one section"):
        time_design_problem(dual, duration=80.0, model="wang")
    with pytest.raises(ParameterError, match="working_load"):
        time_design_problem(dual.replace(design={**dual.design, "working_load": [1.5e4, 1.5e4, 1.5e4]}), duration=80.0)
    from cablesys.control import WinchLimits
    from cablesys.control.mpc import compare_compensation
    with pytest.raises(ParameterError, match="sections = 2: must be 1"):      # the winch strategies: one section
        compare_compensation(dual, WinchLimits(), duration=60.0)
    with pytest.raises(ParameterError, match="damping_bounds"):
        time_design_problem(dual.replace(design={**dual.design, "damping_bounds": [[5e3, 5e5]]}), duration=80.0)
