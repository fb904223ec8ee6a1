"""The figure and benchmark studies run and write sensible JSON (no timing asserts)."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def run(name, out, *args):
    env = dict(os.environ, MPLBACKEND="Agg")
    proc = subprocess.run([sys.executable, str(ROOT / "studies" / f"{name}.py"), "--out", str(out), *args],
                          capture_output=True, text=True, env=env)
    assert proc.returncode == 0, proc.stderr[-3000:]


def test_towed_figures_quick(tmp_path):
    run("towed_figures", tmp_path, "--quick")
    res = json.loads((tmp_path / "towed_figures.json").read_text())
    assert res["t0_s"]["report_eq25_delta1_eq_p"] == pytest.approx(146.0, abs=1.0)
    assert res["max_abs_exact_minus_shooting"] < 1e-8
    assert res["max_abs_exact_minus_mpmath"] < 1e-10
    wp = res["water_pulley"]
    assert wp["c_star_at_omega_1e-3"] == pytest.approx(wp["1_plus_1_over_p"], rel=1e-5)
    bands = res["real_order_map"]["worst_real_order_error_by_eq8b_ratio"]
    assert bands["0-0.01"]["max_abs_dH"] < bands["0.3-10"]["max_abs_dH"] < 0.05
    for name in ("towed_shapes.png", "towed_space_frequency.png", "towed_real_order_map.png",
                 "towed_interaction.png"):
        assert (tmp_path / name).stat().st_size > 10_000


def test_bench_writes_grid_time_and_accuracy(tmp_path):
    run("bench_towed", tmp_path)
    res = json.loads((tmp_path / "bench_towed.json").read_text())
    assert res["grid_200x200_s"] > 0 and res["speedup_vs_mpmath"] > 0
    assert res["max_abs_diff_vs_mpmath"] < 1e-9
    assert res["max_abs_diff_vs_bvp"] < 1e-8
