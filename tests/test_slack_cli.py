"""The `cablesys slack` sub-command, the TOML format and the benchmark script."""

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from cablesys.errors import ParameterError
from cablesys.slack import cli
from cablesys.slack.scene import EXAMPLE_TOML, load_slack_scene

ROOT = Path(__file__).resolve().parents[1]


def run(argv):
    p = argparse.ArgumentParser()
    sub = p.add_subparsers(dest="command")
    cli.register(sub)
    a = p.parse_args(argv)
    return a.func(a)


def test_example_scene_runs_and_writes_outputs(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("MPLBACKEND", "Agg")
    f = tmp_path / "s.toml"
    f.write_text(EXAMPLE_TOML)
    scene = load_slack_scene(f)
    assert len(scene.masses) == 2 and scene.n_modes == 12
    assert run(["slack", str(f), "--out", str(tmp_path / "o")]) == 0
    doc = json.loads((tmp_path / "o" / "slack_result.json").read_text())
    types = [m["mode_type"] for m in doc["modes"]]
    assert types[:9] == list("OAOSOAOSO")
    assert doc["equilibrium"]["horizontal_tension_N"] > 0
    # every number says its unit: omega in rad/s (the key and the units table)
    assert doc["units"]["omega_rad_s"] == "rad/s" and all(set(m) == {"mode_type", "omega_rad_s"} for m in doc["modes"])
    printed = capsys.readouterr().out
    sag = float(printed.split("sag/L = ")[1].split(",")[0])
    assert sag == pytest.approx(doc["equilibrium"]["sag_to_length"], rel=1e-5)
    assert (tmp_path / "o" / "equilibrium.png").exists() and (tmp_path / "o" / "mode_shapes.png").exists()


@pytest.mark.parametrize("edit, field", [
    (("mass = 4.5", "mass = -4.5"), "masses[0].mass"),
    (("position = 15.867", "position = 40.0"), "masses[1].position"),
    (("span = 22.9 ", "span = 30.0 "), "scene.chord"),
    (("length = 23.80", "length = 0"), "cable.length"),
    (("medium = \"air\"", "colour = \"red\""), "scene.colour"),
    (("n_modes = 12 ", "n_modes = 0 "), "scene.n_modes"),
    (("n_modes = 12 ", "n_modes = 400 "), "scene.n_modes"),            # above MAX_MODES
    (("n_elements = 120", "n_elements = 4"), "scene.n_modes"),         # 12 modes > 3 (4 - 1) - 1 degrees of freedom
    (("n_modes = 12 ", "n_modes = \"all\" "), "scene.n_modes"),
])
def test_bad_toml_names_the_field(tmp_path, edit, field):
    f = tmp_path / "bad.toml"
    assert edit[0] in EXAMPLE_TOML
    f.write_text(EXAMPLE_TOML.replace(edit[0], edit[1], 1))
    with pytest.raises(ParameterError) as err:
        load_slack_scene(f)
    assert err.value.field == field


def test_example_flag(capsys):
    assert run(["slack", "--example"]) == 0
    assert "[cable]" in capsys.readouterr().out


def test_bench_script_small(tmp_path):
    env = dict(os.environ, MPLBACKEND="Agg")
    subprocess.run([sys.executable, str(ROOT / "studies" / "bench_slack.py"), "--out", str(tmp_path),
                    "--elements", "300", "--modes", "20", "--repeat", "1"], check=True, env=env)
    doc = json.loads((tmp_path / "bench_slack.json").read_text())
    assert {"static_s", "modes_s", "total_s"} <= set(doc)
    assert doc["static_nlp_vs_shooting_max_dz_m"] < 1e-6
    assert max(abs(x) for x in doc["rel_diff_first10_vs_400_dense"]) < 1e-3
