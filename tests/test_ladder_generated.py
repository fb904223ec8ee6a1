"""Issue 22 on generated scenes: the stated error must be the actual error.

``studies/ladder_generated.py --quick --vm`` draws two small scenes (seed 22: a 26 m wire surged in a sheared
current, a 21 m two-section chain heaved) within the issue's ranges, runs auto in CasADi's VM and the segmented
node model at N = 64 per section as the reference, and reports every quantity auto reports. Asserted on every
quantity: the actual error is within the tolerance (1 % body, 2 % tension), and the stated error is at least half
the actual one wherever that is resolved (above 5 % of the tolerance). The compiled runs of the issue are the study's
full mode (``--compiled``), too slow for CI here.
"""

import json

import pytest


@pytest.fixture(scope="module")
def doc(tmp_path_factory):
    import os
    import subprocess
    import sys
    from pathlib import Path
    root = Path(__file__).resolve().parents[1]
    out = tmp_path_factory.mktemp("ladder_generated")
    proc = subprocess.run([sys.executable, str(root / "studies" / "ladder_generated.py"), "--out", str(out), "--quick",
                           "--vm", "--count", "2", "--seed", "22"], capture_output=True, text=True, cwd=root,
                          env=dict(os.environ, MPLBACKEND="Agg", CABLESYS_COMPILE="0"))
    assert proc.returncode == 0, proc.stderr[-4000:]
    assert (out / "ladder_generated.png").stat().st_size > 10_000
    return json.loads((out / "ladder_generated.json").read_text())


def test_generated_scenes_are_within_the_ranges_and_settled(doc):
    kinds = {c["params"]["kind"] for c in doc["cases"]}
    assert kinds == {"wire", "chain"}
    for c in doc["cases"]:
        p = c["params"]
        assert 0.1 <= p["mass_ratio_scene"] <= 10 and 0 <= p["surface_current_m_s"] <= 1.5
        assert 0.2 <= p["string_ratio"] <= 1.5 and c["settling_note"] == ""
        assert c["reference"] == {"model": "segmented", "segments": 64, "compiled": False, "method": "cvodes-bdf2",
                                  "rtol": 1e-6, "atol": 1e-7}
        assert c["reference_window_change"] < 0.01, c["case"]      # the window holds the settled response
        assert {"x_b_amplitude", "x_b_mean", "y_b_amplitude"} & {r["quantity"] for r in c["rows"]} or \
            {"x_b_2_amplitude", "x_b_1_mean"} <= {r["quantity"] for r in c["rows"]}


def test_every_quantity_is_within_the_tolerance(doc):
    bad = [(c["case"], r["quantity"], r["actual"], r["tolerance"]) for c in doc["cases"] for r in c["rows"]
           if not r["actual"] <= r["tolerance"]]
    assert not bad, bad


def test_every_run_of_elements_is_checked_a_posteriori(doc):
    """No run of N >= 4 elements goes unchecked: an N across the drag rule's switch (chain-22-1's quasi-static
    segmented N = 11 per section) is checked against N / 2 with one drag point per element (choice.check_scene), and
    for its integration error against the candidate run at ten times the rtol of the run kept."""
    for c in doc["cases"]:
        if c["model"]["segments"] >= 4:
            assert c["model"]["checked"].startswith("a posteriori"), (c["case"], c["model"]["checked"])
            # the run kept is the one at a tenth of the candidate's rtol, its integration error stated (ladder.checks)
            ic = c["integration_check"]
            assert ic["rtol"] == pytest.approx(ic["rtol_compared"] / 10) and set(ic["per_quantity"]) == \
                {r["quantity"] for r in c["rows"]}, (c["case"], ic)


def test_every_quantity_has_a_stated_error_at_least_half_the_actual(doc):
    """Every reported quantity has a stated error (``model.estimated_error_per_quantity``), at least half its actual
    error against the N = 64 reference wherever that error is resolved: above RESOLVED (5 %) x the tolerance, the
    study's ``stated_honest``; below it no estimate need resolve it (wire-22-0's top tension maximum: 0.04 %
    actual, 0.01 % stated, the estimates' floor est.RESOLUTION)."""
    bad = [(c["case"], r["quantity"], r["actual"], r["stated"]) for c in doc["cases"] for r in c["rows"]
           if r["stated"] is None or not r["stated_honest"]]
    assert not bad, bad
