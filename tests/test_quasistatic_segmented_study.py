"""The quasi-static segmented study (issue 12) in --quick mode: JSON, chart, and what it must show."""

import json


def test_quick_study(run_study):
    out = run_study("quasistatic_segmented", "--quick")
    doc = json.loads((out / "quasistatic_segmented.json").read_text())
    assert (out / "quasistatic_segmented_dale.png").stat().st_size > 10_000
    (case,) = doc["cases"]
    assert case["reference"]["success"]
    for e in case["by_n"]:
        # Dale: the stretch does not matter (Wang 1971 p. 29), so both models meet the tolerance at the
        # same N, and without the axial element modes the quasi-static one needs far fewer steps (step
        # counts, not the wall-time choice of "best", which depends on the machine's load)
        ok = {kind: [r for r in e[kind]["runs"] if _within(r)] for kind in ("quasi-static", "segmented")}
        assert ok["quasi-static"] and ok["segmented"]
        assert all(r["least_tension_margin_N"] > 0 for r in ok["quasi-static"])
        steps = {kind: min(r["nsteps"] for r in rows) for kind, rows in ok.items()}
        assert 5 * steps["quasi-static"] < steps["segmented"]
        assert e["quasi-static"]["best"] is not None


def _within(r):
    """Within 1 % / 2 % of the reference and within half that of the model's own tight run."""
    return (r.get("success") and r["error"]["body"] <= 0.01 and r["error"]["tension"] <= 0.02
            and r["error_vs_own_tight"]["body"] <= 0.005 and r["error_vs_own_tight"]["tension"] <= 0.01)
