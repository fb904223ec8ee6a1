"""The ladder's cost weights against their measurement (studies/bench_rung_costs.py): the quick benchmark measures
every weight it names, and the committed measurement (studies/results/rung_costs.json) is of the constants the
ladder prices by now, with the machine it ran on. Timings are reported, never asserted."""

import json
import math
from pathlib import Path

import pytest

from cablesys.ladder.rung import quasistatic, segmented
from cablesys.ladder.rungs import get_rung

ROOT = Path(__file__).resolve().parents[1]
CONSTANTS = {"quasi-static straight_cost": get_rung("quasi-static").straight_cost,
             "frequency straight_cost": get_rung("frequency").straight_cost,
             "STIFF_QS_COST": quasistatic.STIFF_QS_COST, "EXPLICIT_COST": quasistatic.EXPLICIT_COST,
             "CHECK_COST": segmented.CHECK_COST}


def _check(doc: dict) -> None:
    assert set(doc["ratios"]) == set(CONSTANTS)
    for name, entries in doc["ratios"].items():
        assert entries and all(e["constant"] == CONSTANTS[name] for e in entries), name
        assert all(math.isfinite(e["measured"]) and e["measured"] > 0 for e in entries), name
    # the rows compared ran the model asked, at the one rtol
    for r in doc["rows"]:
        assert r["success"] and r["ran"] == r["rung"] and r["rtol"] == doc["rows"][0]["rtol"]
        assert r["asked_segments"] in (None, r["segments"])
    assert doc["machine"]["cpu_count"] >= 1 and doc["machine"]["casadi"]


@pytest.mark.slow
def test_the_quick_benchmark_measures_every_weight(run_study):
    out = run_study("bench_rung_costs", "--quick")
    _check(json.loads((out / "rung_costs.json").read_text()))
    assert (out / "rung_costs.png").stat().st_size > 20000


def test_the_committed_measurement_is_of_the_current_constants():
    """A constant changed without measuring it again fails here; the measurement is compiled, on its machine."""
    doc = json.loads((ROOT / "studies" / "results" / "rung_costs.json").read_text())
    _check(doc)
    assert not doc["quick"] and doc["machine"]["compiled"]
    # past the cap the explicit quasi-static cable is measured as well: the cap's evidence
    caps = [e for e in doc["ratios"]["EXPLICIT_COST"] if e["segments"] > quasistatic.EXPLICIT_COST_MAX_ELEMENTS]
    assert caps
