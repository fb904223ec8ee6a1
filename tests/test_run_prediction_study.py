"""studies/run_prediction.py in quick mode: a cold-cache compiled run's cost predicted before its build against
what it cost. No timing is asserted (the machine is shared); what is checked is that the study measures what it
says (the run compiled on an empty cache, every compile logged its prediction and its actual time) and that the
parts of the prediction that do not depend on the machine hold: the steps of CVODES from the tolerance and the
forcing periods, the operations of the built model, the output memory, each within the study's factor 3."""

import json

import pytest


@pytest.mark.slow
def test_run_prediction_quick(run_study):
    out = run_study("run_prediction", "--quick")
    res = json.loads((out / "run_prediction.json").read_text())
    assert {"machine", "cpus", "load_before", "load_after", "date"} <= set(res) and res["quick"]
    [row] = res["rows"]
    assert row["scene"] == "dale" and row["success"] and row["predicted_model"]["name"] == "wang"
    pred, act = row["prediction"], row["actual"]
    assert pred["compiled"] and pred["compile_s"] > 0
    # a cold cache: the predicted run compiled its libraries, each line carrying its prediction and its actual time
    mine = [c for c in row["compiles"] if c["phase"] == "predicted"]
    assert len(mine) >= 2 and all(c["actual_s"] > 0 and c["predicted_s"] > 0 and c["c_mb"] > 0 for c in mine)
    assert act["compile_s"] == pytest.approx(sum(c["actual_s"] for c in mine))
    for key in ("operations", "memory_bytes"):          # machine-independent: within the factor 3
        assert row["within_3x"][key], (key, pred[key], act[key])
    [run] = [r for r in row["runs"] if r["covered"]]
    assert act["steps"] == run["nsteps"] > 0 and row["ratio"]["steps"] == pytest.approx(act["steps"] / pred["steps"])
    assert (out / "run_prediction.png").stat().st_size > 10_000
