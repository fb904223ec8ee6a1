"""Sweeps refuse bad input before any case runs, die with their parent, stop cleanly on Ctrl-C, and draw
one summary figure titled by what varies.

The process tests run ``cablesys sweep`` as a child process (its own process group, as a terminal's
foreground job is) with two local workers, and wait on events, never on the clock: a chunk file
on disk before the signal, the end of the child's pipes after it.
"""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import cablesys
from cablesys.cli import main
from cablesys.errors import ParameterError
from cablesys.scene import OMEGA_N_MEASURED, dale_scene, dump_scene
from cablesys.sweeps import analyses, parse_vary
from cablesys.sweeps.api import SweepInterrupted
from cablesys.sweeps.store import records_of

ROOT = Path(__file__).resolve().parents[1]
WAIT_S = 120.0            # the bound on any wait below (a loaded machine); an event ends it
FX, FY = "top_motion.x[0].frequency", "top_motion.y[0].frequency"


@pytest.fixture
def spy(monkeypatch):
    """Counts the cases that reach the ``run`` analysis (a case that ran), returning a fixed summary."""
    calls = []

    def run(scene, options, cache):
        calls.append(scene)
        return {"tension_mid_max_N": 1.0}, True, ""
    monkeypatch.setitem(analyses.ANALYSIS, "run", run)
    return calls


def sweep(vary, **kw):
    return cablesys.sweep(dale_scene(duration=1.0), vary, "run", workers=1, progress=False, **kw)


# ----------------------------------------------------------------------------------- bad input
def test_text_among_numbers_is_refused_before_any_case(spy, tmp_path):
    with pytest.raises(ParameterError) as err:
        sweep(parse_vary(["body.weight=0.2,O.3,0.4"]), out=tmp_path / "o")    # a typo: the letter O
    assert err.value.field == "vary['body.weight']" and err.value.value == "O.3"
    assert "text and numbers" in str(err.value)
    with pytest.raises(ParameterError, match=r"must be a number \(N\)") as err:
        sweep({"body.weight": ["heavy", "light"]})                             # all text, numeric field
    assert err.value.value == "heavy"
    with pytest.raises(ParameterError, match="must be an integer") as err:
        sweep({"numerics.drag_segments": [2, 2.5]})
    assert err.value.value == 2.5
    assert spy == [] and not (tmp_path / "o").exists()
    # the control: the same sweep with numbers reaches every case (the spy sees cases that run)
    sweep({"body.weight": [0.2, 0.3, 0.4]})
    assert len(spy) == 3


def test_cli_mixed_list_is_a_named_error_and_no_output(tmp_path, capsys, spy):
    scene = tmp_path / "dale.toml"
    scene.write_text(dump_scene(dale_scene(duration=1.0)))
    out = tmp_path / "sw"
    assert main(["sweep", str(scene), "--vary", "cable.ae=10,2O,40", "--workers", "1", "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("cablesys sweep: error: vary['cable.ae'] = '2O'") and "\n" not in err
    assert spy == [] and not out.exists()


def test_a_repeated_label_is_refused(spy):
    with pytest.raises(ParameterError, match="repeats the label 'body.weight'") as err:
        parse_vary(["body.weight=0.2,0.3", "cable.ae=10", "body.weight=0.5"])
    assert err.value.value == "body.weight=0.5" and "body.weight=0.2,0.3" in str(err.value)
    # two spellings of one value (one section: cable.ae is sections[0].cable.ae)
    with pytest.raises(ParameterError, match="names the same value as 'cable.ae'"):
        sweep({"cable.ae": [10.0], "sections[0].cable.ae": [20.0]})
    assert spy == []


@pytest.mark.parametrize("where", ["under_a_file", "a_file", "proc"])
def test_an_out_that_cannot_hold_results_is_refused_before_any_case(tmp_path, spy, where):
    """Root writes through chmod, so the places used here fail for root too: below a regular file,
    a regular file itself, and a folder in /proc (no directories can be made there)."""
    (tmp_path / "plain").write_text("not a folder")
    out = {"under_a_file": tmp_path / "plain" / "sweep", "a_file": tmp_path / "plain",
           "proc": Path("/proc/cablesys-sweep-test")}[where]
    if where == "proc" and not Path("/proc/self").exists():
        pytest.skip("no /proc on this platform")
    with pytest.raises(ParameterError) as err:
        sweep({"body.weight": [0.2, 0.3]}, out=out)
    assert err.value.field == "--out" and err.value.value == str(out)
    assert spy == []


# ----------------------------------------------------------------------------- units and names
def test_parameter_columns_carry_units_and_long_names(tmp_path, capsys, spy):
    scene = tmp_path / "dale.toml"
    scene.write_text(dump_scene(dale_scene(duration=1.0)))
    out = tmp_path / "sw"
    assert main(["sweep", str(scene), "--vary", "cable.ae=10,20", "--vary", f"{FX}=1,2", "--workers", "1",
                 "--out", str(out), "--no-plots"]) == 0
    ds = xr.open_dataset(out / "sweep.nc", engine="scipy")
    assert ds["cable.ae"].attrs["units"] == "N" and ds[FX].attrs["units"] == "rad/s"
    assert ds["cable.ae"].attrs["long_name"].endswith("(cable.ae)") and len(ds["cable.ae"].attrs["long_name"]) > 12
    head = (out / "sweep.csv").read_text().splitlines()[0].split(",")
    assert head[:3] == ["cable.ae [N]", f"{FX} [rad/s]", "status"] and "tension_mid_max_N [N]" in head


# --------------------------------------------------------------------------------- processes
def _children(pid: int) -> list:
    """Live (not zombie) processes whose parent is ``pid``."""
    out = []
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                state, ppid = (d / "stat").read_text().rsplit(")", 1)[1].split()[:2]
            except (OSError, IndexError, ValueError):
                continue
            if int(ppid) == pid and state != "Z":
                out.append(int(d.name))
    return out


def _alive(pid: int) -> bool:
    try:
        return (Path("/proc") / str(pid) / "stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except (OSError, IndexError):
        return False


def _start_sweep(tmp_path) -> tuple:
    """``cablesys sweep`` of 40 Dale cases on two workers, in its own process group, SIGINT at its default
    (a background job inherits it ignored); returns (process, out folder)."""
    scene = tmp_path / "dale.toml"
    scene.write_text(dump_scene(dale_scene(duration=60.0)))
    out = tmp_path / "sw"
    code = ("import signal, sys; signal.signal(signal.SIGINT, signal.default_int_handler); "
            "from cablesys.cli import main; sys.exit(main(sys.argv[1:]))")
    env = dict(os.environ, CABLESYS_COMPILE="0", PYTHONPATH=str(ROOT))
    proc = subprocess.Popen([sys.executable, "-c", code, "sweep", str(scene), "--vary", "cable.ae=10:1000:log:40",
                             "--metric", "tension_mid_max_N", "--workers", "2", "--out", str(out), "--no-plots"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                            start_new_session=True)
    return proc, out


def _wait_for(what, proc):
    t0 = time.monotonic()
    while not what():
        if proc.poll() is not None:
            raise AssertionError(f"the sweep ended early ({proc.returncode}): {proc.stderr.read()}")
        if time.monotonic() - t0 > WAIT_S:
            raise AssertionError("the sweep did not get there")
        time.sleep(0.05)


def _stored(out: Path) -> int:
    n = 0
    for f in (out / "cases").glob("chunk-*.nc"):
        with xr.open_dataset(f, engine="scipy") as ds:
            n += len(records_of(ds.load()))
    return n


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_killing_the_sweep_leaves_no_worker_and_frees_its_pipes(tmp_path):
    proc, out = _start_sweep(tmp_path)
    try:
        _wait_for(lambda: len(_children(proc.pid)) >= 2 and any((out / "cases").glob("chunk-*.nc")), proc)
        workers = _children(proc.pid)
        os.kill(proc.pid, signal.SIGKILL)
        # returns once no process holds the child's stdout and stderr (orphans would: they wait forever
        # on a task queue whose write end they hold themselves)
        proc.communicate(timeout=30.0)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
    assert proc.returncode == -signal.SIGKILL
    t0 = time.monotonic()
    while any(_alive(w) for w in workers) and time.monotonic() - t0 < 10.0:
        time.sleep(0.05)
    assert not [w for w in workers if _alive(w)]


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_ctrl_c_stops_the_sweep_keeps_the_finished_cases_and_exits_130(tmp_path):
    proc, out = _start_sweep(tmp_path)
    try:
        _wait_for(lambda: any((out / "cases").glob("chunk-*.nc")), proc)
        workers = _children(proc.pid)
        os.killpg(proc.pid, signal.SIGINT)     # what Ctrl-C does: the whole foreground group
        stdout, stderr = proc.communicate(timeout=WAIT_S)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
    assert proc.returncode == 130, stderr
    assert "Traceback" not in stderr and len(stderr.strip().splitlines()) == 1, stderr
    kept = _stored(out)
    assert stderr.startswith(f"cablesys sweep: interrupted: {kept} of 40 cases finished, kept in {out}/cases/")
    assert 1 <= kept < 40 and stdout == ""
    assert not [w for w in workers if _alive(w)]
    assert not (out / "sweep.nc").exists()       # no result file that looks complete


def test_an_interrupt_keeps_what_finished_and_the_same_sweep_resumes(tmp_path, monkeypatch, spy):
    """The Ctrl-C path in-process: the third case raises KeyboardInterrupt; two cases are kept (on disk
    and in the exception's Dataset), and the same sweep again runs only the others."""
    real = analyses.ANALYSIS["run"]

    def stop_at_third(scene, options, cache):
        if len(spy) == 2:
            raise KeyboardInterrupt
        return real(scene, options, cache)
    monkeypatch.setitem(analyses.ANALYSIS, "run", stop_at_third)
    vary = {"body.weight": [0.2, 0.3, 0.4, 0.5]}
    with pytest.raises(SweepInterrupted) as err:
        sweep(vary, out=tmp_path / "o", chunk_size=1)
    assert err.value.n_finished == 2 and err.value.n_cases == 4
    assert list(err.value.dataset["status"].values) == ["ok", "ok", "missing", "missing"]
    assert _stored(tmp_path / "o") == 2
    monkeypatch.setitem(analyses.ANALYSIS, "run", real)
    ds = sweep(vary, out=tmp_path / "o", chunk_size=1)
    assert ds.attrs["n_computed"] == 2 and len(spy) == 4 and (ds["status"] == "ok").all()


# ------------------------------------------------------------------------------------ figures
def test_summary_figure_names_what_varies_and_draws_categories_with_a_legend(tmp_path):
    """A ladder sweep (forcing frequency x AE, one AE refused): the model's element count N and status are
    categorical (one legend entry per value present), the title names the varied labels, not the base
    scene's own values; one PNG per sweep."""
    from cablesys.sweeps.plots import figure_sweep, plot_sweep
    w = [0.3 * OMEGA_N_MEASURED, 3.0 * OMEGA_N_MEASURED]
    ds = cablesys.sweep(dale_scene(), {FX: w, FY: w, "cable.ae": [-1.0, 20.0, 2e3]}, "ladder", zip=[(FX, FY)],
                        workers=1, progress=False)
    fig = figure_sweep(ds)
    title = fig.get_suptitle()
    assert f"varying {FX}" in title and "cable.ae" in title and f"{FY} in step" in title
    assert "omega/omega_n = 1" not in title and ds.attrs["scene"] not in title
    panels = {ax.get_title(): ax for ax in fig.axes if ax.get_title()}
    legend = {t.get_text() for t in panels["model_segments"].get_legend().get_texts()}
    n_values = {f"N = {v:g}" for v in np.unique(ds["model_segments"].values[np.isfinite(ds["model_segments"].values)])}
    assert legend == n_values and len(n_values) >= 2
    assert {t.get_text() for t in panels["status"].get_legend().get_texts()} == {"ok", "error"}
    # no colour bar for a categorical panel: the figure's axes are the panels plus one bar per continuous map
    continuous = [n for n, ax in panels.items() if ax.get_legend() is None]
    assert len([ax for ax in fig.axes if ax.get_visible()]) == len(panels) + len(continuous)
    files = plot_sweep(ds, tmp_path / "plots")
    assert [f.name for f in files] == ["sweep.png"] and files[0].stat().st_size > 10_000
