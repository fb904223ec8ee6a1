"""The rao sweep analysis on a 3-D scene reports the sway: every top input (x_s, y_s, z_s) against every body axis
(x_b, y_b, z_b). Checked by a symmetry no code path shares: a current at 45 deg makes the plane x = z a mirror of the
scene, which swaps x and z, so the surge-to-surge RAO equals the sway-to-sway one and the cross terms are equal."""

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies"))
import _bench_3d as B  # noqa: E402

from cablesys.sweeps.analyses import ModelCache, rao  # noqa: E402


def test_the_rao_sweep_reports_sway_and_a_45_degree_current_mirrors_surge_into_sway():
    sc = B.current_scene(60.0).replace_section(0, cable={"segments": 1})
    s, ok, msg = rao(sc, {"n_omega": 200}, ModelCache())
    assert ok, msg
    for o in ("x_b", "z_b"):
        for inp in ("x_s", "z_s"):
            assert f"rao_peak_{o}_{inp}" in s and f"rao_{o}_{inp}" in s
    assert s["rao_peak_z_b_z_s"] == pytest.approx(s["rao_peak_x_b_x_s"], rel=1e-6)
    assert s["rao_peak_omega_z_b_z_s_rad_s"] == pytest.approx(s["rao_peak_omega_x_b_x_s_rad_s"], rel=1e-9)
    assert s["rao_z_b_x_s"] == pytest.approx(s["rao_x_b_z_s"], rel=1e-6)
    assert s["rao_x_b_x_s"] == pytest.approx(s["rao_z_b_z_s"], rel=1e-6) and s["rao_z_b_x_s"] > 1e-3 * s["rao_x_b_x_s"]
