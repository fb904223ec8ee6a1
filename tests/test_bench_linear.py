"""The linear/periodic benchmark in quick mode: its JSON carries each target beside the measured
value and the comparison is at equal accuracy (timings are reported, never asserted)."""

import itertools
import json

import pytest


@pytest.mark.slow
def test_bench_linear_quick(run_study):
    out = run_study("bench_linear", "--quick")
    doc = json.loads((out / "bench_linear.json").read_text())
    for key in ("periodic_speedup_cold", "periodic_speedup_warm"):
        assert doc[key] > 0 and doc[f"{key}_target"] == 20.0
    target = doc["target_rel_err"]
    # both sides reach the orbit to the same accuracy: the periodic solve (H = 20 against H = 40) ...
    assert doc["periodic_rel_err_vs_H40"] < target
    # ... with the error falling as harmonics are added (the drag's |v| v limits the rate to algebraic)
    errs = [doc["periodic_rel_err_vs_H40_by_harmonics"][str(h)] for h in (5, 10, 15, 20)]
    assert all(b < a for a, b in itertools.pairwise(errs))
    # ... and the time domain's baseline run, which needs more than one period from rest
    base = doc["time_domain_to_steady"][doc["time_domain_baseline"]]["oracle"]
    assert base["rel_err"] < target and base["periods"] >= 2
    practical = doc["time_domain_to_steady"][doc["time_domain_baseline_practical"]]["practical"]
    assert practical["periods"] >= base["periods"] - 1
    # continuation: every frequency converged, and a warm step takes fewer Newton iterations than a cold solve
    assert doc["periodic_sweep_converged"] == doc["periodic_sweep_frequencies"]
    assert max(doc["periodic_sweep_newton_iterations"][2:]) < doc["periodic_newton_iterations"]
    assert (out / "bench_linear.png").stat().st_size > 20000
