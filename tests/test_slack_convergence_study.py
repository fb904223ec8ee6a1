"""studies/slack_convergence.py --quick end to end (a few seconds, CasADi's VM).

Quick mode runs auto on 6 s of the packaged light-cage lift with its extrapolation at N = 2, 4, 8, and the study's
own runs at those N with half auto's time step and sampling. Two numbers that mean something: auto's stated error of
its N run's time series, per quantity (|f(N) - f(N / 2)| relative, the first-order estimate), is what the study's
independent runs at N / 2 and N show, within a few per cent; and auto's extrapolated statistics equal the limit of
the study's finer-stepped runs at the same N to the resolution floor (the time step and sampling add nothing the
statement would have to hold).
"""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from cablesys.ladder import estimate as est

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    out = tmp_path_factory.mktemp("slack_convergence")
    env = dict(os.environ, MPLBACKEND="Agg")
    subprocess.run([sys.executable, str(ROOT / "studies" / "slack_convergence.py"), "--quick", "--out", str(out)],
                   check=True, env=env, cwd=ROOT)
    return out, json.loads((out / "slack_convergence.json").read_text())


def test_structure_and_figure(study):
    out, doc = study
    assert doc["quick"] and doc["reference_segments"] == [2, 4, 8] and (out / "slack_convergence.png").stat().st_size > 10_000
    (c,) = doc["cases"]
    a = c["auto"]
    assert a["model"] == "segmented" and a["extrapolated_segments"] == [2, 4, 8]
    assert [p["segments"] for p in a["plan"]] == [8, 4, 2] and all(p["status"] == "success" for p in a["plan"])
    quantities = {"x_b_amplitude", "y_b_amplitude", "x_b_mean", "y_b_mean", "tension_top_max", "tension_top_min",
                  "tension_bottom_max", "tension_bottom_min"}
    assert {r["quantity"] for r in c["rows"]} == quantities == set(a["stated_per_quantity"])
    assert all(r["stated_source"] == "per quantity" for r in c["rows"])
    assert c["reference"]["kind"] == "richardson" and len(c["reference"]["runs"]) == 3
    assert doc["totals"]["quantities"] == len(quantities)


def test_stated_time_series_error_is_what_independent_runs_show(study):
    (c,) = study[1]["cases"]
    pair = c["own_pair"]
    assert pair["segments"] == [4, 8]
    for k, d in pair["difference"].items():
        if d > 1e-5:           # resolved: above the time-step and sampling differences of the two routes
            assert pair["stated_time_series"][k] == pytest.approx(d, rel=0.05), k
    assert all(pair["covered"].values())


def test_extrapolated_statistics_are_converged_in_time_step_and_sampling(study):
    (c,) = study[1]["cases"]
    assert c["reference"]["time_step_check"]["largest"] < est.RESOLUTION
    for r in c["rows"]:
        assert r["actual"] < est.RESOLUTION, r["quantity"]
        assert r["stated"] >= est.RESOLUTION and r["stated_at_least_half"], r["quantity"]
