"""The time-domain studies (issue 2, sections 6-7 and the benchmark) run in --quick mode.

Each study is run once as a subprocess, as a person would, and the numbers it writes are
checked for meaning. No timing is asserted (the machine may be shared).
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
TOP_AMPLITUDE_FT = 2.5 / 12.0


def run_study(script: str, out: Path) -> None:
    env = dict(os.environ, MPLBACKEND="Agg")
    proc = subprocess.run([sys.executable, str(ROOT / "studies" / script), "--out", str(out), "--quick"],
                          cwd=ROOT, env=env, capture_output=True, text=True)
    assert proc.returncode == 0, f"{script} failed:\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}"


@pytest.fixture(scope="module")
def dale(tmp_path_factory):
    out = tmp_path_factory.mktemp("dale")
    run_study("wang_dale_table2.py", out)
    assert (out / "wang_dale_table2.png").stat().st_size > 10_000
    return json.loads((out / "wang_dale_table2.json").read_text())


@pytest.fixture(scope="module")
def wp(tmp_path_factory):
    out = tmp_path_factory.mktemp("wp")
    run_study("work_precision.py", out)
    for name in ("work_precision.png", "rk_stability.png"):
        assert (out / name).stat().st_size > 10_000
    return (json.loads((out / "work_precision.json").read_text()),
            json.loads((out / "rk_stability.json").read_text()))


@pytest.fixture(scope="module")
def bench(tmp_path_factory):
    out = tmp_path_factory.mktemp("bench")
    run_study("bench_time_domain.py", out)
    assert (out / "bench_time_domain.png").stat().st_size > 10_000
    return json.loads((out / "bench_time_domain.json").read_text())


# -- Dale et al. (Wang 1971 Table 2) ---------------------------------------------------------
def test_dale_keys_and_frequencies(dale):
    assert dale["omega_over_omega_n"] == [0.5, 1.0, 1.5, 2.0]
    assert len(dale["xbA_ft"]) == len(dale["ybA_ft"]) == 4


def test_dale_vertical_amplitude_follows_top(dale):
    # a stiff cable (AE 1000 lb) carries the 2.5 in vertical top motion to the body
    for y in dale["ybA_ft"]:
        assert y == pytest.approx(TOP_AMPLITUDE_FT, rel=0.03)


def test_dale_horizontal_amplitude_falls_above_resonance(dale):
    x = dale["xbA_ft"]
    assert all(v > 0 for v in x)
    assert x[1] > x[2] > x[3]
    assert x[3] < 0.7 * TOP_AMPLITUDE_FT


def test_dale_steady_state_reached(dale):
    # last K periods against the K before
    assert max(dale["steady_change_ft"]) < 1e-3


def test_dale_ae_changes_amplitudes_by_less_than_a_hundredth_of_a_foot(dale):
    assert "5" in dale["ae_sensitivity"]
    assert 0.0 < dale["ae_sensitivity_max_change_ft"] < 0.01


def test_dale_drag_sensitivity(dale):
    rows = {(r["sphere_cd"], r["cable_cd"]): r for r in dale["drag_sensitivity"]}
    nominal = rows[(0.5, 1.4)]
    # a stiff cable (AE 1000 lb) is a rigid link in the vertical: every drag variant carries
    # the 2.5 in vertical top motion to the body (drag changes the swing, not the heave)
    for row in rows.values():
        assert row["ybA_ft"] == pytest.approx([TOP_AMPLITUDE_FT] * 4, rel=0.03)
    # more drag, less swing at resonance
    assert rows[(0.7, 1.4)]["xbA_ft"][1] < nominal["xbA_ft"][1]
    assert rows[(0.5, 1.8)]["xbA_ft"][1] < nominal["xbA_ft"][1]


def test_dale_model_pendulum_frequency_near_measured(dale):
    assert 0.8 < dale["model_frequencies"]["pendulum_over_measured_omega_n"] < 1.3


# -- work-precision --------------------------------------------------------------------------
@pytest.mark.parametrize("scene", ["dale", "stiff"])
@pytest.mark.parametrize("method", ["cvodes", "cvodes-adams", "idas"])
def test_adaptive_error_falls_as_tolerance_tightens(wp, scene, method):
    rows = [r for r in wp[0]["scenes"][scene]["methods"][method] if r["success"]]
    assert len(rows) >= 3
    errs = [r["error_m"] for r in sorted(rows, key=lambda r: -r["rtol"])]
    assert errs[-1] < errs[0] / 100.0
    assert errs[-1] < 1e-9


@pytest.mark.parametrize("scene", ["dale", "stiff"])
def test_fixed_step_methods_converge_or_fail_where_expected(wp, scene):
    methods = wp[0]["scenes"][scene]["methods"]
    rk = methods["rk"]
    for r in rk:
        # RK4 is unstable beyond h omega_max = 2 sqrt(2) (the stretch mode is an undamped oscillation)
        if r["h_omega_max"] > 3.0:
            assert not r["success"]
        if r["h_omega_max"] < 2.6:
            assert r["success"]
    ok = [r["error_m"] for r in methods["collocation"] if r["success"]]
    assert ok and min(ok) < 1e-8


def test_rk_stability_limit_matches_rk4_theory(wp):
    stab = wp[1]
    assert len(stab["rows"]) >= 3
    for r in stab["rows"]:
        assert r["h_omega_max"] == pytest.approx(2.785, rel=0.2)
        assert r["omega_linearized_rad_s"] == pytest.approx(r["omega_max_rad_s"], rel=1e-6)
    aes = [r["ae_lb"] for r in stab["rows"]]
    hs = [r["h_max_s"] for r in stab["rows"]]
    assert hs == sorted(hs, reverse=True) and aes == sorted(aes)


# -- benchmark and the independent NumPy right-hand side -----------------------------------
def test_numpy_rhs_matches_casadi_model(bench):
    assert bench["rhs_cross_check"]["max_rel_diff"] < 1e-10
    assert bench["rhs_cross_check"]["variant"]["n_states"] > 0


def test_bench_trajectories_agree(bench):
    # both runs at rtol 1e-6 land within a micrometre of the tight CasADi reference
    assert bench["scipy_errors"]["body_position_m"] < 1e-6
    assert bench["cablesys_errors"]["body_position_m"] < 1e-6
    for k, v in bench["compiled"].items():
        # BDF capped at order 2 is second order: its error at a given rtol is far larger (8e-7 m in 5 s)
        assert v["errors"]["body_position_m"] < (1e-5 if k == "cvodes-bdf2" else 1e-6), k


def test_bench_work_precision_converges(bench):
    """Every cablesys method of the sweep gets more accurate as its tolerance or step shrinks,
    and each equal-accuracy pick is at least as accurate as the SciPy run it is compared with."""
    wp = bench["work_precision"]
    for method, key in (("cvodes", "rtol"), ("cvodes-bdf2", "rtol"), ("dopri5", "rtol"), ("rk4", "steps_per_output")):
        rows = sorted((r for r in wp if r["method"] == method), key=lambda r: r[key], reverse=key == "rtol")
        err = [r["errors"]["body_position_m"] for r in rows]
        assert len(rows) >= 2 and err[-1] < err[0], method
    for e in bench["equal_accuracy"]:
        for pick in (e["fastest"], e["fastest_adaptive"]):
            if pick:
                assert pick["error_m"] <= e["scipy_error_m"] and pick["speedup"] > 0


def test_bench_ramp_removes_the_stretch_ringing_steps(bench):
    # the abrupt start rings the undamped stretch mode; the A-stable BDF2 then has to follow it
    assert bench["abrupt_bdf2"]["steps"] > 5 * bench["compiled"]["cvodes-bdf2"]["steps"]
    assert bench["abrupt"]["steps"] > bench["cablesys_steps"]


def test_bench_reports_its_numbers(bench):
    for key in ("cablesys_ms", "scipy_ms", "speedup_vs_scipy", "build_s"):
        assert math.isfinite(bench[key]) and bench[key] > 0
    assert bench["cablesys_steps"] > 0 and bench["scipy_rhs_evals"] > 0
