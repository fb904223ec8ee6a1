"""Output folders under faults: one writer at a time, killed runs, full disks.

Each test injects one fault with a known outcome: a second writer while the first holds the
folder, a ``running`` manifest whose process is gone, ``OSError(ENOSPC)`` in the middle of a
block of rows or of the final manifest, and a real full disk (a small tmpfs, when this process
may mount one).
"""

import contextlib
import errno
import json
import logging
import os
import subprocess
import sys
import uuid
from pathlib import Path

import numpy as np
import pytest

from cablesys.atomic import CsvStream, OutputWriteError, read_streamed_csv
from cablesys.cli import main
from cablesys.errors import CablesysError, ParameterError
from cablesys.outputs import LOCK, MANIFEST, OutputDir, folder_state
from cablesys.scene import dale_scene, dump_scene

ENOSPC = OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


def _scene_file(tmp_path, name="dale.toml", **kw):
    f = tmp_path / name
    f.write_text(dump_scene(dale_scene(**kw)))
    return f


def _dead_pid() -> int:
    """The pid of a process that has exited (and been reaped)."""
    proc = subprocess.Popen([sys.executable, "-c", "pass"])
    proc.wait()
    return proc.pid


def _manifest(path: Path) -> dict:
    return json.loads((path / MANIFEST).read_text())


# -- one writer ----------------------------------------------------------------------------------
def test_a_second_writer_is_refused_at_once_naming_the_first(tmp_path):
    out = tmp_path / "out"
    first = OutputDir(out, "run", {"a": 1}).start(scene="a")
    with pytest.raises(ParameterError) as info:
        OutputDir(out, "run", {"a": 1})                     # the same scene: still one writer
    assert info.value.field == "--out"
    assert "being written by another cablesys run" in str(info.value) and f"pid {os.getpid()}" in str(info.value)
    with pytest.raises(ParameterError, match="being written"):
        OutputDir(out, "run", {"a": 2}, overwrite=True)    # --overwrite does not break a live writer's lock
    assert _manifest(out)["status"] == "running"           # the first writer's set is untouched
    first.write_text("timeseries.csv", "time [s]\n0\n")
    first.finish("success")
    with OutputDir(out, "run", {"a": 1}) as again:          # the lock is released by finish
        again.write_text("timeseries.csv", "time [s]\n1\n")
    assert _manifest(out)["status"] == "success" and (out / "timeseries.csv").read_text() == "time [s]\n1\n"


def test_a_refused_folder_keeps_no_lock(tmp_path):
    """A check that fails (another scene) must not leave the folder locked for the next try."""
    out = tmp_path / "out"
    with OutputDir(out, "run", {"a": 1}):
        pass
    with pytest.raises(ParameterError, match="another scene"):
        OutputDir(out, "run", {"a": 2})
    OutputDir(out, "run", {"a": 2}, overwrite=True).start().finish("success")
    assert _manifest(out)["status"] == "success"


def test_two_cablesys_runs_into_one_folder_the_second_is_refused_before_computing(tmp_path, capsys, monkeypatch):
    """A sub-process holds the folder (as a running `cablesys run` does); the in-process run is refused
    with exit 2 and a named error before any model is built, and the holder's set is untouched."""
    from cablesys.time_domain import run

    def forbidden(*a, **k):
        raise AssertionError("computation started although another run writes --out")
    monkeypatch.setattr(run, "simulate", forbidden)
    monkeypatch.setattr(run.Simulator, "__init__", forbidden)
    scene = _scene_file(tmp_path, duration=2.0)
    out = tmp_path / "out"
    holder = subprocess.Popen(
        [sys.executable, "-c", "import sys; from cablesys.outputs import OutputDir; "
         f"od = OutputDir({str(out)!r}, 'run', 'x').start(); print('ready', flush=True); sys.stdin.read(); "
         "od.finish('success')"],
        stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True,
        env=dict(os.environ, PYTHONPATH=str(Path(__file__).resolve().parents[1])))
    try:
        assert holder.stdout.readline().strip() == "ready"
        assert main(["run", str(scene), "--out", str(out), "--overwrite"]) == 2
        err = capsys.readouterr().err
        assert "being written by another cablesys run" in err and f"pid {holder.pid}" in err
        assert _manifest(out)["status"] == "running" and _manifest(out)["pid"] == holder.pid
    finally:
        holder.communicate("", timeout=60)
    assert holder.returncode == 0 and _manifest(out)["status"] == "success"


# -- killed runs ---------------------------------------------------------------------------------
def _killed_set(out: Path, scene_hash: str, command: str = "run") -> int:
    """A folder as a SIGKILL leaves it: a running manifest of a dead pid and a partial stream."""
    out.mkdir()
    pid = _dead_pid()
    (out / MANIFEST).write_text(json.dumps({"command": command, "status": "running", "scene_hash": scene_hash,
                                            "started": "2026-01-01T00:00:00+00:00", "pid": pid, "scene": "old",
                                            "files": [], "streaming": "timeseries.partial.csv"}))
    (out / "timeseries.partial.csv").write_text("time [s],x_b [m]\n0,1\n")
    return pid


def test_a_killed_run_is_reported_as_killed_and_incomplete(tmp_path, caplog):
    from cablesys.outputs import scene_hash
    out = tmp_path / "out"
    pid = _killed_set(out, scene_hash({"a": 1}))
    state = folder_state(out)
    assert state["status"] == "killed" and state["killed"] and state["recorded_status"] == "running"
    with pytest.raises(ParameterError) as info:             # another scene: --overwrite, and why
        OutputDir(out, "run", {"a": 2})
    msg = str(info.value)
    assert "killed run" in msg and "incomplete" in msg and f"pid {pid} no longer runs" in msg and "--overwrite" in msg
    with caplog.at_level(logging.WARNING, logger="cablesys.outputs"):   # the same scene: replaced, and said so
        od = OutputDir(out, "run", {"a": 1}).start(scene="a")
    assert any("killed run" in r.getMessage() for r in caplog.records)
    assert not (out / "timeseries.partial.csv").exists()          # the killed set's files go
    assert _manifest(out)["replaces_killed_run"]["pid"] == pid
    assert folder_state(out)["status"] == "running"              # now a live writer holds it
    od.finish("success")
    assert folder_state(out)["status"] == "success"


def test_cablesys_run_says_a_killed_set_of_another_scene_is_a_killed_run(tmp_path, capsys):
    out = tmp_path / "out"
    pid = _killed_set(out, "0123456789abcdef")
    scene = _scene_file(tmp_path, duration=2.0, output_step=0.1)
    assert main(["run", str(scene), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "killed run" in err and f"pid {pid}" in err and "--overwrite" in err
    assert main(["run", str(scene), "--out", str(out), "--overwrite"]) == 0
    doc = _manifest(out)
    assert doc["status"] == "success" and doc["replaces_killed_run"]["pid"] == pid
    assert all((out / f).exists() for f in doc["files"]) and "timeseries.csv" in doc["files"]


# -- full disk, injected -------------------------------------------------------------------------
class _DiskFullAfter:
    """A file object that takes ``room`` more bytes, then fails as a full disk does (part written)."""

    def __init__(self, fh, room: int):
        self.fh, self.room = fh, room

    def write(self, data) -> int:
        if self.room <= 0:
            raise ENOSPC
        n = self.fh.write(bytes(data[: self.room]))
        self.room -= n
        return n

    def __getattr__(self, name):
        return getattr(self.fh, name)


def test_a_full_disk_mid_block_leaves_whole_rows_and_a_named_error(tmp_path):
    s = CsvStream(tmp_path / "timeseries.csv")
    s.append(np.array([0.0, 0.1]), {"x_b": np.array([1.0, 2.0])})
    whole = s.partial.read_bytes()
    s._fh = _DiskFullAfter(s._fh, room=7)                    # the next block gets 7 bytes, then ENOSPC
    with pytest.raises(OutputWriteError) as info:
        s.append(np.array([0.2, 0.3, 0.4]), {"x_b": np.array([3.0, 4.0, 5.0])})
    err = info.value
    assert isinstance(err, CablesysError) and isinstance(err, OSError) and err.errno == errno.ENOSPC
    assert "timeseries.partial.csv" in str(err) and "ENOSPC" in str(err) and "2 whole rows" in str(err)
    assert "\n" not in str(err)                              # one line
    assert s.partial.read_bytes() == whole                   # the torn block is cut off again
    assert s.rows == 2 and s.t_last == pytest.approx(0.1)
    s._fh = s._fh.fh                                         # space again: the stream goes on
    s.append(np.array([0.2]), {"x_b": np.array([3.0])})
    np.testing.assert_array_equal(np.loadtxt(s.close(), delimiter=",", skiprows=1)[:, 1], [1, 2, 3])


def test_a_stream_cut_anywhere_reads_as_its_whole_rows(tmp_path):
    """kill -9 can stop a write at any byte: whatever is left reads as the rows before the cut."""
    s = CsvStream(tmp_path / "timeseries.csv")
    t = np.arange(6) * 0.25
    s.append(t[:2], {"x_b": -t[:2], "tension_top": 1e5 + t[:2]})
    s.append(t[2:], {"x_b": -t[2:], "tension_top": 1e5 + t[2:]})
    full = s.partial.read_bytes()
    lines = full.decode().splitlines(keepends=True)
    header_end = len(lines[0])
    ends = np.cumsum([len(ln) for ln in lines])             # byte offset after each whole line
    cut = tmp_path / "cut.partial.csv"
    for size in range(header_end, len(full) + 1):
        cut.write_bytes(full[:size])
        header, rows, dropped = read_streamed_csv(cut)
        n_whole = int(np.searchsorted(ends, size, side="right")) - 1      # data rows that ended
        assert header == ["time [s]", "x_b [m]", "tension_top [N]"]
        assert rows.shape == (n_whole, 3) and dropped == (size not in ends)
        np.testing.assert_array_equal(rows[:, 0], t[:n_whole])
        np.testing.assert_array_equal(rows[:, 1], -t[:n_whole])


def test_a_stream_says_whether_it_holds_a_record_whole(tmp_path):
    s = CsvStream(tmp_path / "timeseries.csv")
    s.append(np.array([0.0, 0.1]), {"x_b": np.array([1.0, 2.0])})
    s.append(np.array([0.2]), {"x_b": np.array([3.0])})
    assert s.holds([0.0, 0.1, 0.2])
    assert not s.holds([0.0, 0.1, 0.2, 0.3]) and not s.holds([0.0, 0.1]) and not s.holds([])


def test_the_final_manifest_is_written_in_place_when_the_disk_is_full(tmp_path, monkeypatch):
    from cablesys import outputs
    out = tmp_path / "out"
    od = OutputDir(out, "run", {"a": 1}).start(scene="a")
    od.write_text("timeseries.csv", "time [s]\n0\n")
    real = outputs.atomic_write_text

    def full(path, text):
        if Path(path).name == MANIFEST:
            raise OutputWriteError(path, ENOSPC)
        return real(path, text)
    monkeypatch.setattr(outputs, "atomic_write_text", full)
    od.finish("success", stats={"big": list(range(5000))})    # a summary far larger than the reserve
    doc = _manifest(out)
    assert doc["status"] == "success" and doc["files"] == ["timeseries.csv"]
    assert "ENOSPC" in doc["summary_incomplete"]
    assert folder_state(out)["status"] == "success"


def test_a_manifest_that_cannot_be_finished_says_so_and_reads_as_killed(tmp_path, monkeypatch):
    from cablesys import outputs
    out = tmp_path / "out"
    od = OutputDir(out, "run", {"a": 1}).start()

    def full(*a, **k):
        raise OutputWriteError(out / MANIFEST, ENOSPC)
    monkeypatch.setattr(outputs, "atomic_write_text", full)
    monkeypatch.setattr(OutputDir, "_write_manifest_in_place",
                        lambda self, why: (_ for _ in ()).throw(OSError(errno.EIO, "I/O error")))
    with pytest.raises(OutputWriteError, match="still says running"):
        od.finish("failed", message="x")
    assert _manifest(out)["status"] == "running"
    assert folder_state(out)["status"] == "killed"            # the lock is gone with the writer's finish


def test_the_manifest_lists_only_files_that_exist(tmp_path):
    out = tmp_path / "out"
    with pytest.raises(OutputWriteError), OutputDir(out, "run", {}) as od:
        od.write_text("a.txt", "a")
        od.file("planned.nc")                                 # named, never written
        with od.writing("b.nc") as tmp:
            tmp.write_text("half")
            raise ENOSPC                                      # the writer fails: b.nc never exists
    doc = _manifest(out)
    assert doc["status"] == "failed" and "b.nc" in doc["message"] and "ENOSPC" in doc["message"]
    assert doc["files"] == ["a.txt"] and all((out / f).exists() for f in doc["files"])
    assert sorted(set(os.listdir(out)) - {LOCK}) == ["a.txt", MANIFEST]     # no temporary left


# -- full disk, real -----------------------------------------------------------------------------
@contextlib.contextmanager
def _small_tmpfs(tmp_path, size: str):
    where = tmp_path / f"tmpfs-{uuid.uuid4().hex[:8]}"
    where.mkdir()
    done = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", str(where)],
                          capture_output=True, text=True, check=False)
    if done.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here ({done.stderr.strip()}); the injected-ENOSPC tests cover the writer")
    try:
        yield where
    finally:
        subprocess.run(["umount", "-l", str(where)], check=False)


@pytest.mark.parametrize("size", ["3m", "700k"], ids=["full-at-netcdf", "full-at-first-block"])
def test_cablesys_run_on_a_full_disk_fails_by_name_and_keeps_whole_rows(tmp_path, size):
    scene = _scene_file(tmp_path, duration=400.0, output_step=0.05)     # ~2 MB of CSV, more than 700k
    with _small_tmpfs(tmp_path, size) as disk:
        out = disk / "out"
        done = subprocess.run([sys.executable, "-m", "cablesys.cli", "run", str(scene), "--out", str(out)],
                              capture_output=True, text=True, timeout=600, check=False,
                              env=dict(os.environ, MPLBACKEND="Agg"))
        assert done.returncode == 1, done.stderr[-2000:]
        err = done.stderr.strip().splitlines()
        assert "Traceback" not in done.stderr
        assert any("error: cannot write" in line and "ENOSPC" in line for line in err)
        doc = _manifest(out)
        assert doc["status"] == "failed" and "ENOSPC" in doc["message"]
        assert all((out / f).exists() for f in doc["files"])
        series = [out / f for f in ("timeseries.csv", "timeseries.partial.csv") if (out / f).exists()]
        assert len(series) == 1
        text = series[0].read_text()
        assert text == "" or text.endswith("\n")                 # whole rows only
        lines = text.splitlines()
        if len(lines) > 1:
            width = lines[0].count(",")
            assert all(line.count(",") == width for line in lines)
            t = np.loadtxt(series[0], delimiter=",", skiprows=1, ndmin=2)[:, 0]
            np.testing.assert_allclose(np.diff(t), 0.05, rtol=1e-6)
            assert f"{len(lines) - 1} whole rows" in doc["message"] or doc["files"] == ["timeseries.csv"]
