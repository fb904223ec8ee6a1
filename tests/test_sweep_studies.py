"""The operability and sweep-benchmark studies, run as scripts in quick mode."""

import json

import numpy as np
import pytest


@pytest.mark.slow
def test_operability_quick(run_study, monkeypatch):
    monkeypatch.setenv("CABLESYS_COMPILE", "0")    # 12 short runs of one structure: no C compile on a cold cache
    out = run_study("operability", "--quick")
    doc = json.loads((out / "operability.json").read_text())
    assert (out / "operability.png").exists() and (out / "operability.csv").exists() and (out / "sweep.nc").exists()
    assert doc["n_cases"] == 12 and doc["n_not_ok"] == 0
    assert {"peak_tension", "slack", "daf", "excursion"} <= set(doc["criteria"])
    rows = doc["cases"]
    hs = sorted({r["hs_m"] for r in rows})
    tp = sorted({r["tp_s"] for r in rows})
    margin = np.array([[next(r["min_margin"] for r in rows if r["hs_m"] == h and r["tp_s"] == t) for t in tp] for h in hs])
    # a higher sea at the same period never leaves more margin (same seed: the same sea scaled by Hs)
    assert np.all(np.diff(margin, axis=0) < 1e-9)
    assert 0 < doc["n_allowed"] < doc["n_cases"]          # the chart has a boundary
    assert all(r["allowed"] == (r["min_margin"] >= 0) for r in rows)


@pytest.mark.slow
def test_bench_sweep_quick(run_study):
    out = run_study("bench_sweep", "--quick")
    doc = json.loads((out / "bench_sweep.json").read_text())
    assert (out / "bench_sweep.png").exists()
    for name, n in (("time_domain", 8), ("rao", 100)):
        r = doc[name]
        assert r["cases"] == n and r["parallel_equals_serial"]
        assert {"loop", "sweep_serial", "sweep_parallel", "dask"} <= set(r["throughput_cases_per_s"])
        assert all(v > 0 for v in r["throughput_cases_per_s"].values())
        assert 0 < r["parallel_efficiency"] and "overhead_fraction" in r
