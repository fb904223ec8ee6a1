"""The several-segments study in quick mode (segmented cable): convergence of modes and stochastic
body response with N, and the 2-DOF model's error."""

import json


def test_segments_convergence_quick(run_study):
    out = run_study("segments_convergence", "--quick")
    doc = json.loads((out / "segments_convergence.json").read_text())
    assert doc["n_sections"] == [1, 2, 4, 8]
    for key in ("dale", "heavy_cable"):
        rows = doc[key]["rows"]
        swing = [r["swing_rad_s"][0] for r in rows]
        stretch = [r["stretch_rad_s"][0] for r in rows]
        # lumped node masses: the elements' frequencies rise monotonically towards the continuous cable
        assert all(a < b for a, b in zip(swing[1:], swing[2:]))
        assert all(a < b for a, b in zip(stretch[1:], stretch[2:]))
        errs = [r["rel_err"]["swing_1"] for r in rows[1:-1]]
        assert errs[1] < 0.3 * errs[0]                                   # second order in 1/N (vs the finest N)
        assert len(rows[-1]["swing_rad_s"]) == 3                       # higher string modes appear
    dale, heavy = doc["dale"], doc["heavy_cable"]
    assert dale["cable_to_body_weight"] < 0.2 < 4.0 < heavy["cable_to_body_weight"]
    # light cable: the 2-DOF model is within 0.1 % in frequency; heavy cable: > 1 % and far off in sway
    assert dale["two_dof_rel_err"]["swing_1"] < 1e-3 and dale["two_dof_rel_err"]["stretch_1"] < 1e-3
    assert heavy["two_dof_rel_err"]["swing_1"] > 0.01 and heavy["two_dof_rel_err"]["stretch_1"] > 0.02
    assert heavy["two_dof_rel_err"]["x_b_sig"] > 5.0          # the straight heavy cable carries the sway down
    assert heavy["two_dof_rel_err"]["y_b_sig"] < 0.01         # heave is a spring-mass problem either way
    assert (out / "segments_convergence.png").stat().st_size > 20000
