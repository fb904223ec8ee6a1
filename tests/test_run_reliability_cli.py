"""`cablesys` runs from outside: signals, killed runs, --out checks, manifests, limits (issue 9).

The signal tests start `cablesys run` in a sub-process and send the signal once the run has
started streaming (a `running` manifest and a partial time series on disk), not after a sleep.
"""

import json
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from cablesys import units as U
from cablesys.atomic import read_streamed_csv
from cablesys.cli import main
from cablesys.scene import dale_scene, dump_scene

HANG_GUARD_S = 600          # only against a hang; never reached by a working run


def _scene_file(tmp_path, name="dale.toml", **kw):
    f = tmp_path / name
    f.write_text(dump_scene(dale_scene(**kw)))
    return f


def _start_and_wait_for_streaming(tmp_path):
    """A long run in a sub-process, returned once its manifest says running and rows are on disk."""
    scene = _scene_file(tmp_path, duration=5000.0, output_step=0.1)
    out = tmp_path / "out"
    env = dict(os.environ, MPLBACKEND="Agg")
    proc = subprocess.Popen([sys.executable, "-m", "cablesys.cli", "run", str(scene), "--out", str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    partial = out / "timeseries.partial.csv"
    t0 = time.monotonic()
    while True:
        if proc.poll() is not None:
            pytest.fail(f"the run ended before streaming (exit {proc.returncode}): {proc.stderr.read()[-2000:]}")
        if time.monotonic() - t0 > HANG_GUARD_S:
            proc.kill()
            pytest.fail("no streamed rows")
        try:
            manifest = json.loads((out / "summary.json").read_text())
            rows = partial.read_text().count("\n")
        except (OSError, ValueError):
            manifest, rows = {}, 0
        if manifest.get("status") == "running" and rows >= 3:
            return proc, out
        time.sleep(0.02)


def _read_series(path):
    head = path.read_text().splitlines()[0]
    assert head.startswith("time [s],phi [rad]")
    return np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)


@pytest.mark.slow
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_signal_stops_the_run_writes_what_was_computed_and_exits_130(tmp_path, sig):
    proc, out = _start_and_wait_for_streaming(tmp_path)
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=HANG_GUARD_S)
    assert proc.returncode == 130, err[-2000:]
    assert "interrupted" in err
    doc = json.loads((out / "summary.json").read_text())
    assert doc["status"] == "interrupted" and doc["success"] is False
    assert "interrupted" in doc["message"]
    data = _read_series(out / "timeseries.csv")
    t = data[:, 0]
    # a readable prefix of the run: from 0 on the output grid, up to where it stopped, well before the end
    assert t[0] == 0.0 and np.allclose(np.diff(t), 0.1) and t[-1] == pytest.approx(doc["t_end_s"])
    assert 0.0 < t[-1] < 5000.0
    assert np.all(np.isfinite(data))
    assert not (out / "timeseries.partial.csv").exists()
    assert "timeseries.nc" in doc["files"] and (out / "timeseries.nc").exists()


@pytest.mark.slow
def test_killed_run_leaves_a_running_manifest_and_a_readable_prefix(tmp_path):
    """SIGKILL cannot be caught: the manifest still says running, the streamed rows are readable."""
    proc, out = _start_and_wait_for_streaming(tmp_path)
    proc.kill()
    proc.communicate(timeout=HANG_GUARD_S)
    doc = json.loads((out / "summary.json").read_text())
    assert doc["status"] == "running" and doc["streaming"] == "timeseries.partial.csv"
    # every line that ends is a whole row; SIGKILL may have cut the last one mid-write (the kernel
    # stops a write at a page boundary), which the reader drops and reports
    header, data, _ = read_streamed_csv(out / doc["streaming"])
    assert header[:2] == ["time [s]", "phi [rad]"] and data.shape[1] == len(header)
    assert data.shape[0] >= 2 and data[0, 0] == 0.0 and np.allclose(np.diff(data[:, 0]), 0.1)
    assert np.all(np.isfinite(data))
    assert not (out / "timeseries.csv").exists()          # the complete name only for a finished set


def test_out_is_checked_before_any_computation(tmp_path, capsys, monkeypatch):
    from cablesys.time_domain import run

    def forbidden(*a, **k):
        raise AssertionError("computation started before --out was checked")
    monkeypatch.setattr(run, "simulate", forbidden)
    monkeypatch.setattr(run.Simulator, "__init__", forbidden)
    scene = _scene_file(tmp_path, duration=2.0)
    a_file = tmp_path / "a_file"
    a_file.write_text("keep me")
    for out in (a_file, a_file / "sub"):
        assert main(["run", str(scene), "--out", str(out)]) == 2
        assert "--out" in capsys.readouterr().err
        assert main(["run", "--out", str(out)]) == 2               # the Dale table too
        assert "--out" in capsys.readouterr().err
    assert a_file.read_text() == "keep me"


@pytest.mark.parametrize("argv, words", [
    (["--duration", "1e12"], "output times"),
    (["--duration", "0"], "--duration"),
    (["--max-steps", "5"], "--max-steps"),
])
def test_limits_and_options_are_named_errors(tmp_path, capsys, argv, words):
    scene = _scene_file(tmp_path, duration=2.0)
    assert main(["run", str(scene), "--out", str(tmp_path / "o"), *argv]) == 2
    assert words in capsys.readouterr().err
    assert not (tmp_path / "o").exists()


def test_a_failed_run_replaces_the_old_summary_and_another_scene_needs_overwrite(tmp_path, capsys):
    out = tmp_path / "out"
    ok = _scene_file(tmp_path, "ok.toml", duration=2.0, output_step=0.1)
    assert main(["run", str(ok), "--out", str(out)]) == 0
    assert json.loads((out / "summary.json").read_text())["status"] == "success"
    stiff = _scene_file(tmp_path, "stiff.toml", duration=2.0, output_step=0.1, ae_lb=1e10 / U.LBF)
    assert main(["run", str(stiff), "--out", str(out)]) == 2             # another scene's results
    assert "--overwrite" in capsys.readouterr().err
    assert json.loads((out / "summary.json").read_text())["status"] == "success"    # untouched
    # Wang's model forced: auto would run the quasi-static segmented cable, which has no stiff stretch mode
    assert main(["run", str(stiff), "--out", str(out), "--overwrite", "--max-steps", "1000", "--model", "wang"]) == 1
    doc = json.loads((out / "summary.json").read_text())
    assert doc["status"] == "failed" and doc["success"] is False
    assert "step budget exhausted" in doc["message"] and doc["stats"]["max_num_steps"] == 1000
    assert _read_series(out / "timeseries.csv")[:, 0].max() == pytest.approx(doc["t_end_s"])


def test_other_commands_check_out_first(tmp_path, capsys):
    a_file = tmp_path / "a_file"
    a_file.write_text("")
    scene = _scene_file(tmp_path, duration=2.0)
    assert main(["rao", str(scene), "--out", str(a_file)]) == 2
    assert "--out" in capsys.readouterr().err
    from cablesys.slack.scene import EXAMPLE_TOML
    slack = tmp_path / "slack.toml"
    slack.write_text(EXAMPLE_TOML)
    assert main(["slack", str(slack), "--out", str(a_file)]) == 2
    assert "--out" in capsys.readouterr().err


def test_progress_line_only_for_long_runs(capsys):
    from cablesys.commands.run import _Progress
    p = _Progress()
    p(1.0, 10.0, 0.5)
    p(10.0, 10.0, 1.0)                    # a short run: finished before the first line is due
    assert capsys.readouterr().err == ""
    p = _Progress()
    p(3.0, 10.0, 3.5)
    p(10.0, 10.0, 4.0)
    err = capsys.readouterr().err
    assert "t = 3 of 10 s (30 %)" in err and "about 8 s left" in err and "t = 10 of 10 s (100 %)" in err


def test_an_interrupted_analysis_is_marked_and_exits_130(tmp_path, capsys, monkeypatch):
    """Any sub-command: an interrupt during the analysis leaves status interrupted, exit 130."""
    import importlib
    lin = importlib.import_module("cablesys.linear.linearization")     # the module (the package exports the function)

    def interrupted(*a, **k):
        raise KeyboardInterrupt
    monkeypatch.setattr(lin, "linearize", interrupted)
    scene = _scene_file(tmp_path, duration=2.0)
    assert main(["rao", str(scene), "--out", str(tmp_path / "rao")]) == 130
    assert "interrupted" in capsys.readouterr().err
    assert json.loads((tmp_path / "rao" / "summary.json").read_text())["status"] == "interrupted"


def test_interrupted_dale_table_keeps_the_rows_and_the_main_run(tmp_path, capsys, monkeypatch):
    """`cablesys run` (the Dale table) interrupted in its third frequency: the two rows computed and
    the omega = omega_n run's files are written, the manifest says interrupted, exit 130."""
    from cablesys.time_domain import run as run_module
    calls = []
    real = run_module.simulate

    def third_interrupted(scene, **kw):
        calls.append(scene.name)
        if len(calls) == 3:
            raise KeyboardInterrupt
        return real(scene, **kw)
    monkeypatch.setattr(run_module, "simulate", third_interrupted)
    out = tmp_path / "dale"
    assert main(["run", "--out", str(out), "--duration", "10"]) == 2       # too short for 3 periods
    assert "--duration" in capsys.readouterr().err and not out.exists()
    assert main(["run", "--out", str(out), "--duration", "40"]) == 130
    rows = json.loads((out / "dale_amplitudes.json").read_text())
    assert [r["omega_over_omega_n"] for r in rows] == [0.5, 1.0]
    doc = json.loads((out / "summary.json").read_text())
    assert doc["status"] == "interrupted" and doc["t_end_s"] == 40.0        # the omega_n run is complete
    assert _read_series(out / "timeseries.csv").shape[0] == 801
