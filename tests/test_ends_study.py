"""studies/ends_checks.py --quick writes the issue's keys: computed ones within their checks, the parts
not built as null and named."""

import json


def test_ends_checks_quick(run_study):
    out = run_study("ends_checks", "--quick")
    res = json.loads((out / "ends_checks.json").read_text())
    assert (out / "mooring_static_shape.png").stat().st_size > 20_000
    assert res["catenary_seabed_max_rel_err"] < 5e-6          # Richardson of N = 40, 80 (the full run: 80, 160)
    assert abs(res["catenary_seabed_order"] - 2.0) < 0.05
    assert res["sloped_seabed_max_rel_err"] < 1e-9
    assert res["resting_chain_drift_m"] < 1e-6
    assert res["contact_energy_drift_rel"] < 1e-4 and res["bounce_contacts"] >= 6
    for key in ("lowering_tension_rel_err", "payout_mass_rel_err", "span_decay_vs_modes_max_rel_err",
                "slack_table1_max_rel_err", "slack_table3_modes_inside_band"):
        assert res[key] is None and key in res["not_built"]
