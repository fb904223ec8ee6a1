"""Wang (1971) p. 28 direct checks, through the study script (quick mode)."""

import json
import math


def test_direct_checks_meet_the_report_and_tighter(run_study):
    out = run_study("wang_direct_checks", "--quick")
    r = json.loads((out / "wang_direct_checks.json").read_text())
    # 1 ft of top heave at resonance grows by a (1 + omega t / 2): 50 pi + 1 ft after 50 cycles ("150 feet")
    assert r["resonance_rel_err"] < 1e-4
    assert r["resonance_final_amplitude_ft"] > 150.0
    assert r["resonance_final_amplitude_ft"] == pytest_approx(50 * math.pi, 0.02)
    assert r["spring_mass_rel_err"] < 1e-6                # 2 pi sqrt((M + M_c/3)/k)
    assert r["pendulum_small_rel_err"] < 1e-5             # simple and compound pendulum (Tong)
    assert r["pendulum_large_rel_err"] < 1e-5             # elliptic-integral period at 60 degrees
    assert r["energy_drift"] < 1e-6                       # drag and damping off
    assert (out / "wang_direct_checks.png").stat().st_size > 20000


def pytest_approx(x, rel):
    import pytest
    return pytest.approx(x, rel=rel)
