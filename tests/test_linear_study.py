"""The linear-response study in quick mode, run as a script."""

import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_linear_response_quick(tmp_path):
    env = dict(os.environ, MPLBACKEND="Agg")
    subprocess.run([sys.executable, str(ROOT / "studies" / "linear_response.py"), "--out", str(tmp_path), "--quick"],
                   check=True, env=env, cwd=ROOT)
    doc = json.loads((tmp_path / "linear_response.json").read_text())
    for key in ("dale", "full_scale"):
        d = doc[key]
        assert 1.0 < d["natural_frequencies_rad_s"][0] / d["omega_n_measured_rad_s"] < 1.25
        assert 0.0 < d["damping_ratios"][0] < 1.0
        assert d["small_amplitude_rel_err"] < 0.01
        assert d["dale_equivalent_linearization_rel_err"] < 0.05
        assert d["nonlinear_rao_rel_err"] < 1e-4
        assert d["rao_peaks"]["describing_circular_x_b"]["amplitude_per_m"] > 1.0
    assert (tmp_path / "dale_rao_x_b.png").stat().st_size > 10000
