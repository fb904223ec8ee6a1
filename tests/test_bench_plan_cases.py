"""The plan cases of studies/bench_vs_moordyn.py (issue 28: light_lift, harsh_sea) in quick mode without MoorDyn.

No timing is asserted (the machine may be shared): the checks are that the cases' scenes are the packaged examples
edited as stated, and that the JSON holds each run of auto's plan, the Richardson triple N, N / 2, N / 4, inside the
call that was timed, with steps no coarser than the element's axial travel time.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "studies"))


def test_plan_scenes_are_the_packaged_examples_without_current():
    from _bench_slack import HARSH_SEA, plan_scene
    light, harsh = plan_scene("light_lift", 5.0), plan_scene("harsh_sea")
    assert light.sections[0].cable.length == 60.0 and light.numerics.duration == 5.0
    assert harsh.sections[0].cable.length == 500.0 and harsh.numerics.duration == 600.0
    assert (harsh.top_motion.spectrum.hs, harsh.top_motion.spectrum.tp) == (HARSH_SEA["hs"], HARSH_SEA["tp"])
    assert all(u == 0.0 for sc in (light, harsh) for u in sc.environment.current_speeds)


@pytest.mark.filterwarnings("ignore")
def test_quick_plan_case_reports_each_run_of_the_plan(tmp_path):
    import bench_vs_moordyn as B
    B.main(["--out", str(tmp_path), "--quick", "--case", "light_lift", "--no-moordyn", "--plan-duration", "2"])
    row = json.loads((tmp_path / "bench_vs_moordyn.json").read_text())["cases"][0]
    assert row["case"] == "light_lift" and row["duration_s"] == 2.0 and "auto_speedup" not in row
    auto = row["auto_default"]
    assert auto["success"] and auto["model"] == "segmented" and auto["load_1min"] >= 0.0
    runs = auto["plan_runs"]
    n = auto["segments"]
    assert sorted(r["segments"] for r in runs)[:3] == [n // 4, n // 2, n] or n > 16      # the triple (or doubled)
    assert all(r["status"] == "success" and r["steps"] > 0 and r["cpu_s"] > 0 for r in runs)
    assert sum(r["cpu_s"] for r in runs) <= auto["cpu_s"] * 1.01          # the runs are inside the timed call
    c = B.plan_scene("light_lift", 2.0).sections[0].cable
    for r in runs:                                  # RKC at most the axial travel time across one element
        travel = c.length / r["segments"] * math.sqrt(c.mass_per_length / c.ae)
        assert r["steps"] >= 2.0 / travel * (1 - 1e-9) or r["method"] == "rk"
    eq = row["segmented_equal_n"]
    assert eq["segments"] == 40 and eq["success"] and eq["steps"] > 0 and eq["cpu_per_step_us"] > 0
