"""The segmented-convergence study in quick mode: convergence with N on the Dale scene and the
2-DOF model's error where the cable bows under drag (omega = 2 omega_n)."""

import json

import pytest


def test_segmented_convergence_quick(run_study):
    out = run_study("segmented_convergence", "--quick")
    doc = json.loads((out / "segmented_convergence.json").read_text())
    dale = doc["results"][0]
    rows = dale["rows"]
    assert [r["n"] for r in rows] == [2, 4, 8] and all(r["success"] for r in rows)
    e2, e4 = rows[0]["rel_err"], rows[1]["rel_err"]
    assert e4["x_amp"] < e2["x_amp"] / 3 and e4["top_max"] < e2["top_max"] / 3     # faster than first order
    assert rows[0]["observed_order"]["x_amp"] > 1.5
    # the straight cable cannot bow: its sway amplitude is off by several per cent (MoorDyn: 9.2 %)
    assert 0.05 < dale["two_dof"]["rel_err"]["x_amp"] < 0.2
    assert e4["x_amp"] < 0.01
    assert (out / "segmented_convergence.png").stat().st_size > 20000


def test_reference_free_observed_order_recovers_a_known_rate():
    """The slack study's order needs no reference: log2(|f(N) - f(2N)| / |f(2N) - f(4N)|) is p exactly
    for f(N) = f* + C N^-p (here p = 1 and p = 2 on two metrics)."""
    import sys
    from pathlib import Path
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies"))
    from segmented_convergence import _orders
    rows = [{"n": n, "a": 1.5 + 0.3 / n, "b": 6e4 - 2e5 / n**2} for n in (10, 20, 40, 80)]
    _orders(rows, ("a", "b"))
    assert rows[0]["observed_order"]["a"] == pytest.approx(1.0, rel=1e-9)
    assert rows[1]["observed_order"]["b"] == pytest.approx(2.0, rel=1e-9)
    assert "observed_order" not in rows[2]
    assert rows[2]["change_to_2n"]["a"] == pytest.approx((0.3 / 40 - 0.3 / 80) / (1.5 + 0.3 / 80), rel=1e-12)
