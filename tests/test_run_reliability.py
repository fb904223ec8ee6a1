"""Runs and their outputs: no crash, no lost work (issue 9), and the run result object (issue 10).

Library-level checks here; the `cablesys` sub-process checks (signals, killed runs, --out) are in
``test_run_reliability_cli.py``.
"""

import dataclasses
import json
import os

import numpy as np
import pytest

from cablesys import units as U
from cablesys.errors import ParameterError
from cablesys.model import build_model
from cablesys.outputs import CsvStream, OutputDir, atomic_write_text
from cablesys.results import AnalysisResult
from cablesys.scene import dale_scene
from cablesys.time_domain import IntegratorSettings, Simulator, initial_state, simulate
from cablesys.time_domain.record import (
    InterruptFlag,
    RunInterrupted,
    RunRecord,
    check_scene_run_size,
)


@pytest.fixture(scope="module")
def dale():
    scene = dale_scene(duration=20.0, output_step=0.05)
    model = build_model(scene)
    p = model.parameters(scene)
    return scene, model, p, initial_state(scene, model, p)


# -- the result object -----------------------------------------------------------------------
def test_run_returns_a_record_with_states_series_and_status(dale):
    scene, model, p, x0 = dale
    r = Simulator(model, scene.output_times).run(p, x0)
    assert isinstance(r, RunRecord) and isinstance(r, AnalysisResult)
    assert r.success and r.status == "success" and not r.interrupted
    n = scene.output_times.size
    assert r.states.shape == (2 * model.nq, n) and r.modes.shape == (1, n) and r.time.size == n
    assert r.state_labels == model.state_labels
    # the labelled series are the states where they are the same quantity
    np.testing.assert_array_equal(r["phi"], r.states[0])
    np.testing.assert_array_equal(r["u_rate"], r.states[3])
    assert "array" in repr(r) and len(repr(r)) < 600        # short repr, no arrays dumped
    s = r.summary()
    assert s["status"] == "success" and s["n_outputs"] == n
    json.dumps(s, default=float)


def test_amplitude_and_drift_of_a_known_signal():
    """A sine of amplitude 2 that doubles in its last three periods: amplitude 4, drift 2 (closed form)."""
    T = 2.0
    t = np.arange(0, 12.0 + 1e-9, T / 400)
    y = np.where(t >= 6.0, 4.0, 2.0) * np.sin(2 * np.pi * t / T + 0.3)
    r = RunRecord(time=t, data={"y_b": y})
    assert r.steady_amplitude("y_b", T, 3) == pytest.approx(4.0, rel=1e-4)
    assert r.amplitude_drift("y_b", T, 3) == pytest.approx(2.0, rel=1e-4)
    assert r.amplitudes(T, 3) == {"y_b": r.steady_amplitude("y_b", T, 3)}
    with pytest.raises(ValueError):
        r.amplitude_drift("y_b", 3.0, 3)          # 6 periods of 3 s do not fit in 12 s


# -- chunked integration and streaming -------------------------------------------------------
def test_chunks_do_not_change_the_answer_and_blocks_stream_the_whole_series(dale):
    """Chunks of 7 and 19 output intervals (and a remainder) agree with the default chunks to integrator
    tolerance, and the streamed blocks concatenate to exactly the returned series."""
    scene, model, p, x0 = dale
    settings = IntegratorSettings(rtol=1e-10, atol=1e-12)
    ref = Simulator(model, scene.output_times, settings).run(p, x0)

    class Small(Simulator):
        CHUNKS = (7, 19)
    blocks = []
    r = Small(model, scene.output_times, settings).run(p, x0, on_block=lambda t, d: blocks.append((t, d)))
    assert r.success and (scene.output_times.size - 1 - 7) % 19 != 0
    np.testing.assert_allclose(r.states[:2], ref.states[:2], rtol=0, atol=1e-7)
    t = np.concatenate([b[0] for b in blocks])
    np.testing.assert_array_equal(t, r.time)
    for lbl in r.labels:
        np.testing.assert_array_equal(np.concatenate([b[1][lbl] for b in blocks]), r[lbl])


# -- interrupts -----------------------------------------------------------------------------
def test_interrupt_between_integrator_calls_keeps_the_partial_record(dale, monkeypatch):
    """A SIGINT delivered while the run is in Python (here: from the progress callback) stops it
    with RunInterrupted carrying the series up to the last output time reached."""
    import signal

    from cablesys.time_domain import track
    scene, model, p, x0 = dale
    monkeypatch.setattr(track.Track, "FLUSH_S", 0.0)          # hand over every chunk

    class Small(Simulator):
        CHUNKS = (16,)

    calls = []

    def progress(t, t_end, wall):
        calls.append(t)
        if len(calls) == 1:
            os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(RunInterrupted) as info:
        Small(model, scene.output_times).run(p, x0, progress=progress)
    r = info.value.result
    assert isinstance(info.value, KeyboardInterrupt)
    assert r.interrupted and r.status == "interrupted" and not r.success
    assert 1 < r.time.size < scene.output_times.size
    assert "interrupted" in r.message and np.all(np.isfinite(r.states))
    np.testing.assert_array_equal(r.time, scene.output_times[: r.time.size])


def test_casadi_failure_during_an_interrupt_is_an_interrupt_not_a_retry(dale):
    """CasADi reports an interrupt inside the integrator as CV_RHSFUNC_FAIL; with our flag set
    the simulator raises KeyboardInterrupt instead of stepping on interval by interval."""
    scene, model, _, _ = dale
    sim = Simulator(model, scene.output_times)

    def failing(**kw):
        raise RuntimeError('CVode returned "CV_RHSFUNC_FAIL". Consult CVODES documentation.')
    failing.stats = dict
    sim._flag = InterruptFlag()
    with pytest.raises(RuntimeError):
        sim._call(failing)                     # a genuine failure stays a failure
    sim._flag.hit = True
    with pytest.raises(KeyboardInterrupt):
        sim._call(failing)


# -- limits and the step budget -------------------------------------------------------------
@pytest.mark.parametrize("changes, words", [
    ({"output_step": 1e-7}, "output times"),              # 2e8 outputs: hung before
    ({"duration": 1e12}, "output times"),                 # 2e13 outputs, 146 TiB: asked for before
    ({"duration": 3e5, "output_step": 0.05}, "GiB"),      # 6e6 outputs: within the count, not the memory
])
def test_run_size_limits_are_named_errors_before_building(changes, words):
    scene = dale_scene().with_numerics(**changes)
    with pytest.raises(ParameterError) as info:
        check_scene_run_size(scene)
    assert info.value.field == "numerics.output_step" and words in str(info.value)
    with pytest.raises(ParameterError):
        simulate(scene)                                     # checked before the grid is built


def test_step_budget_exhausted_is_a_named_failure():
    """AE = 1e10 N on the Dale cable (stretch period ~ 3e-5 s) took 11.5 million steps for 5 s;
    now the run stops at the first output interval that exceeds the budget and says so."""
    scene = dale_scene(duration=5.0, ae_lb=1e10 / U.LBF)
    r = simulate(scene, max_num_steps=2000)
    assert not r.success and r.status == "failed"
    assert "step budget exhausted" in r.message and "max_num_steps = 2000" in r.message
    assert "--max-steps" in r.message and r.stats["max_num_steps"] == 2000
    assert r.time[0] == 0.0 and r.time.size < 3


# -- output folders --------------------------------------------------------------------------
def test_output_dir_refuses_files_and_other_scenes(tmp_path):
    f = tmp_path / "a_file"
    f.write_text("x")
    for bad in (f, f / "sub"):
        with pytest.raises(ParameterError) as info:
            OutputDir(bad, "run", {"a": 1})
        assert info.value.field == "--out"
    out = tmp_path / "out"
    with OutputDir(out, "run", {"a": 1}) as od:
        od.write_text("timeseries.csv", "time [s]\n0\n")
    doc = json.loads((out / "summary.json").read_text())
    assert doc["status"] == "success" and doc["files"] == ["timeseries.csv"]
    OutputDir(out, "run", {"a": 1})                               # the same scene: fine
    with pytest.raises(ParameterError, match="another scene"):
        OutputDir(out, "run", {"a": 2})
    with pytest.raises(ParameterError, match="cablesys run"):
        OutputDir(out, "rao", {"a": 1})
    OutputDir(out, "run", {"a": 2}, overwrite=True)
    bare = tmp_path / "bare"
    bare.mkdir()
    (bare / "timeseries.csv").write_text("old results")
    with pytest.raises(ParameterError, match="without a summary.json"):
        OutputDir(bare, "run", {"a": 1}, owned=("timeseries.csv",))
    (bare / "scene.toml").write_text("")                            # a folder with inputs only is fine
    OutputDir(bare, "run", {"a": 1}, owned=("timeseries.nc",))


@pytest.mark.skipif(os.geteuid() == 0, reason="root may write anywhere")
def test_output_dir_refuses_an_unwritable_place(tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o500)
    try:
        with pytest.raises(ParameterError, match="not writable"):
            OutputDir(ro / "out", "run", {})
    finally:
        ro.chmod(0o700)


def test_manifest_says_failed_or_interrupted_and_files_are_all_or_nothing(tmp_path):
    out = tmp_path / "o"
    with pytest.raises(ZeroDivisionError), OutputDir(out, "run", {}) as od:
        assert json.loads((out / "summary.json").read_text())["status"] == "running"
        with od.writing("big.csv") as tmp:
            tmp.write_text("half")
            raise ZeroDivisionError
    assert json.loads((out / "summary.json").read_text())["status"] == "failed"
    assert sorted(set(os.listdir(out)) - {".cablesys.lock"}) == ["summary.json"]   # no partial big.csv, no temporary
    with pytest.raises(KeyboardInterrupt), OutputDir(out, "run", {}):
        raise KeyboardInterrupt
    assert json.loads((out / "summary.json").read_text())["status"] == "interrupted"
    atomic_write_text(out / "x.txt", "y")
    assert (out / "x.txt").read_text() == "y" and (out / "x.txt").stat().st_mode & 0o044


def test_csv_stream_is_a_readable_prefix_at_any_time(tmp_path):
    s = CsvStream(tmp_path / "timeseries.csv")
    s.append(np.array([0.0, 0.1]), {"x_b": np.array([1.0, 2.0])})
    prefix = np.loadtxt(s.partial, delimiter=",", skiprows=1)     # readable while the run goes on
    assert prefix.shape == (2, 2)
    s.append(np.array([0.2]), {"x_b": np.array([3.0])})
    path = s.close()
    assert not s.partial.exists()
    assert path.read_text().splitlines()[0] == "time [s],x_b [m]"
    np.testing.assert_array_equal(np.loadtxt(path, delimiter=",", skiprows=1)[:, 1], [1, 2, 3])


def test_scene_hash_is_stable_and_sees_every_number():
    from cablesys.outputs import scene_hash
    a, b = dale_scene(), dale_scene()
    assert scene_hash(a) == scene_hash(b)
    assert scene_hash(a) != scene_hash(dataclasses.replace(a, name=a.name + " "))
    assert scene_hash(a) != scene_hash(a.with_numerics(duration=a.numerics.duration * (1 + 1e-12)))
