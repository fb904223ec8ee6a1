"""Interrupts at any moment of a run: before the first block, while a block is stored,
at the last block, twice; the compiled explicit driver's bounded calls; no import cycle.

The sub-process tests send SIGINT at seeded random moments after the run has written its
``running`` manifest (so the signal may land in the model choice, a compile, the first block, a
flush or the integration) and check what any moment must give: exit 130, status ``interrupted``,
whole CSV rows that agree with the message, and a manifest that lists only files that exist.
No assertion depends on when the signal lands.
"""

import ast
import json
import os
import random
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from cablesys.atomic import CsvStream
from cablesys.model import build_model
from cablesys.scene import dale_scene, dump_scene
from cablesys.time_domain import Simulator, track
from cablesys.time_domain.integrators import IntegratorSettings
from cablesys.time_domain.record import RunInterrupted

HANG_GUARD_S = 600          # only against a hang; never reached by a working run
KEPT = re.compile(r"results up to t = ([0-9.eE+-]+) s are kept")


# -- in-process: the moments of one run ----------------------------------------------------------
@pytest.fixture(scope="module")
def dale20(dale):
    """(scene, model, p, x0): the Dale scene of conftest over 20 s, outputs every 0.05 s."""
    from cablesys.time_domain.run import initial_state
    scene, model, _ = dale
    scene = scene.with_numerics(duration=20.0, output_step=0.05)
    p = model.parameters(scene)
    return scene, model, p, initial_state(scene, model, p)


class _Small(Simulator):
    CHUNKS = (16,)


def _streamed_run(dale20, tmp_path, monkeypatch, on_nth_block=None, flush_s=0.0, sim_cls=_Small):
    """Run with every block streamed to a CsvStream; SIGINT to this process inside block ``on_nth_block``
    (before its rows are written). Returns (RunInterrupted or record, stream, blocks seen)."""
    scene, model, p, x0 = dale20
    monkeypatch.setattr(track.Track, "FLUSH_S", flush_s)
    stream = CsvStream(tmp_path / "timeseries.csv")
    seen = []

    def on_block(t, data):
        seen.append(t.size)
        if len(seen) == on_nth_block:
            os.kill(os.getpid(), signal.SIGINT)     # lands while this block is being stored
        stream.append(t, data)
    try:
        return sim_cls(model, scene.output_times).run(p, x0, on_block=on_block), stream, seen
    except RunInterrupted as err:
        return err, stream, seen


def _kept_time(message: str) -> float:
    match = KEPT.search(message)
    assert match, message
    return float(match.group(1))


def test_an_interrupt_while_a_block_is_stored_keeps_that_block_and_says_so(dale20, tmp_path, monkeypatch):
    err, stream, seen = _streamed_run(dale20, tmp_path, monkeypatch, on_nth_block=2)
    assert isinstance(err, RunInterrupted)
    r = err.result
    assert r.interrupted and r.status == "interrupted" and len(seen) >= 2
    assert stream.rows == r.time.size == sum(seen)        # every block stored whole, none dropped
    assert stream.t_last == r.time[-1]
    assert _kept_time(r.message) == pytest.approx(r.time[-1], rel=1e-6)
    assert "SIGINT" in r.message and r.stats["interrupt_s"] >= 0 and r.stats["stop_after_s"] >= 0
    np.testing.assert_allclose(np.loadtxt(stream.partial, delimiter=",", skiprows=1)[:, 0], r.time, rtol=1e-10)  # %.10g


def test_an_interrupt_before_the_first_block_keeps_the_start_not_an_index_error(dale20, monkeypatch):
    """The signal lands in the first integrator call, before any block was stored."""
    scene, model, p, x0 = dale20
    sim = _Small(model, scene.output_times)
    real = sim._call
    calls = []

    def first_call_interrupted(f, **kw):
        calls.append(1)
        if len(calls) == 1:
            os.kill(os.getpid(), signal.SIGINT)
        return real(f, **kw)
    monkeypatch.setattr(sim, "_call", first_call_interrupted)
    with pytest.raises(RunInterrupted) as info:
        sim.run(p, x0)
    r = info.value.result
    assert 1 <= r.time.size < scene.output_times.size and r.time[0] == 0.0
    assert _kept_time(r.message) == pytest.approx(r.time[-1], abs=1e-9)
    assert np.all(np.isfinite(r.states))


def test_an_interrupt_during_the_last_block_keeps_the_whole_run(dale20, tmp_path, monkeypatch):
    """One block only (stored at the end): the signal inside it is acted on after it is stored."""
    err, stream, seen = _streamed_run(dale20, tmp_path, monkeypatch, on_nth_block=1, flush_s=1e9)
    assert isinstance(err, RunInterrupted) and seen == [dale20[0].output_times.size]
    r = err.result
    assert r.time.size == dale20[0].output_times.size == stream.rows
    assert _kept_time(r.message) == pytest.approx(20.0)


def test_two_interrupts_in_one_store_are_one_stop(dale20, tmp_path, monkeypatch):
    scene, model, p, x0 = dale20
    monkeypatch.setattr(track.Track, "FLUSH_S", 0.0)
    stream = CsvStream(tmp_path / "timeseries.csv")
    n = []

    def on_block(t, data):
        n.append(1)
        if len(n) == 2:
            os.kill(os.getpid(), signal.SIGINT)
            os.kill(os.getpid(), signal.SIGINT)
        stream.append(t, data)
    with pytest.raises(RunInterrupted) as info:
        _Small(model, scene.output_times).run(p, x0, on_block=on_block)
    assert info.value.result.time.size == stream.rows and stream.t_last == info.value.result.time[-1]


# -- the compiled explicit driver: calls of bounded cost -----------------------------------------
@pytest.fixture(scope="module")
def rk23(dale20, compiling):
    scene, _, p, x0 = dale20
    model = build_model(scene)           # its own model: the compiled library, not the VM's
    settings = IntegratorSettings(method="rk23", rtol=1e-6, atol=1e-8)
    from cablesys.time_domain.explicit_rk import make_explicit_rk
    F = make_explicit_rk(model, settings, np.arange(201) * 0.05)
    if F is None:
        pytest.skip("no compiled explicit driver here (no C compiler or CABLESYS_COMPILE=0)")
    return F, settings, model


def test_the_explicit_driver_stops_a_call_at_its_step_budget_and_resumes_exactly(dale20, rk23):
    scene, _, p, x0 = dale20
    F, _, model = rk23
    pt = np.concatenate([p, [0.0, 1.0]])
    F.call_budget = 0
    full = F(x0=x0, p=pt)["xf"]
    tried_full = F.stats()["nsteps"] + F.stats()["n_rejected"]
    assert not F.paused and np.all(np.isfinite(full))
    F.call_budget = 3000
    part = F(x0=x0, p=pt)["xf"]
    st = F.stats()
    assert F.paused and st["status"] == 4 and st["nsteps"] + st["n_rejected"] == 3000 < tried_full
    n_ok = int(np.argmin(np.all(np.isfinite(part), axis=0)))
    assert 0 < n_ok < part.shape[1] and np.all(np.isnan(part[:, n_ok:]))
    np.testing.assert_array_equal(part[:, :n_ok], full[:, :n_ok])    # the same steps up to the pause
    F.call_budget = 0


def test_a_run_of_paused_calls_gives_the_run_of_whole_calls(dale20, rk23):
    """A small step budget (4000 steps a call, ~11 of a chunk's 64 output intervals) pauses every call;
    the run resumes from the last output each time and ends where an unbounded run ends, within the
    tolerance."""
    scene, _, p, x0 = dale20
    _, settings, model = rk23

    class Tiny(Simulator):
        FIRST_STEP_BUDGET = 4000

        def _next_chunk(self, size, m, wall, f):
            return 64

    class Unbounded(Simulator):
        FIRST_STEP_BUDGET = 0          # 0: no budget (explicit_rk.c)
        CHUNK_MAX_S = 1e9

        def _next_chunk(self, size, m, wall, f):
            self._budget = 0
            return max(self._sizes())
    pauses = []
    tiny = Tiny(model, scene.output_times, settings)
    real = tiny._call

    def counting(f, **kw):
        out = real(f, **kw)
        pauses.append(bool(getattr(f, "paused", False)))
        return out
    tiny._call = counting
    a = tiny.run(p, x0)
    b = Unbounded(model, scene.output_times, settings).run(p, x0)
    assert a.success and b.success and a.time.size == b.time.size == scene.output_times.size
    assert sum(pauses) >= 3
    for lbl in ("x_b", "y_b"):
        scale = np.ptp(b[lbl])
        assert np.max(np.abs(a[lbl] - b[lbl])) < 1e-4 * scale


def test_signal_blind_loops_get_chunks_sized_to_their_measured_cost(dale20):
    scene, model, _, _ = dale20
    sim = Simulator(model, scene.output_times, IntegratorSettings(method="rk"))
    assert sim._blind and sim._chunk == Simulator.SMALL_CHUNKS[0]     # unknown cost: the smallest first
    assert sim._next_chunk(16, 16, 16 * 1e-5, None) == 4096            # 10 us an interval: 4096 in 41 ms
    assert sim._next_chunk(4096, 4096, 40.96, None) == 16              # 10 ms an interval: 16 in 0.16 s
    assert sim._next_chunk(256, 256, 256 * 3e-3, None) == 64           # 3 ms an interval: 64 in 0.19 s
    cv = Simulator(model, scene.output_times, IntegratorSettings(method="cvodes"))
    assert not cv._blind and cv._chunk == Simulator.CHUNKS[0]          # CVODES sees signals inside a call
    # its chunks grow on a fixed schedule: a slow (loaded) call must not move the restarts, and with them the result
    assert [cv._next_chunk(c, c, wall, None) for c, wall in ((256, 10.0), (1024, 1e-3), (4096, 60.0))] == \
        [1024, 4096, 4096]


def test_a_signal_blind_loop_on_an_uneven_grid_runs_in_chunks_with_the_same_answer(dale20):
    """rk on uneven output times: chunks from any output time (not one call over the whole horizon,
    which no signal could cut short), and the same RK4 steps as that one call."""
    scene, model, p, x0 = dale20
    times = np.cumsum(np.r_[0.0, np.tile([0.03, 0.07], 150)])           # 300 uneven intervals, 15 s
    settings = IntegratorSettings(method="rk")

    class Whole(Simulator):
        SMALL_CHUNKS = CHUNKS = (10**6,)
    calls = []
    chunked = Simulator(model, times, settings)
    real = chunked._call
    chunked._call = lambda f, **kw: calls.append(1) or real(f, **kw)
    a = chunked.run(p, x0)
    b = Whole(model, times, settings).run(p, x0)
    assert a.success and b.success and len(calls) > 1
    np.testing.assert_allclose(a.states, b.states, rtol=1e-12, atol=1e-12 * np.max(np.abs(b.states)))


# -- `cablesys run` in a sub-process -------------------------------------------------------------
def _start(tmp_path, duration=20000.0):
    scene = tmp_path / "long.toml"
    scene.write_text(dump_scene(dale_scene(duration=duration, output_step=0.05)))
    out = tmp_path / "out"
    proc = subprocess.Popen([sys.executable, "-m", "cablesys.cli", "run", str(scene), "--out", str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env=dict(os.environ, MPLBACKEND="Agg", CABLESYS_COMPILE="1"))   # the compiled default path
    return proc, out


def _wait_for(proc, out, rows: int = 0):
    """Poll until the manifest says running (and, with ``rows``, that many rows are streamed)."""
    t0 = time.monotonic()
    while time.monotonic() - t0 < HANG_GUARD_S:
        if proc.poll() is not None:
            pytest.fail(f"the run ended early (exit {proc.returncode}): {proc.stderr.read()[-2000:]}")
        try:
            running = json.loads((out / "summary.json").read_text()).get("status") == "running"
            have = (out / "timeseries.partial.csv").read_text().count("\n") - 1 if rows else 0
        except (OSError, ValueError):
            running, have = False, 0
        if running and have >= rows:
            return
        time.sleep(0.01)
    proc.kill()
    pytest.fail("the run never started streaming")


def _check_interrupted_set(proc, out):
    _, err = proc.communicate(timeout=HANG_GUARD_S)
    assert proc.returncode == 130, err[-3000:]
    assert "Traceback" not in err, err[-3000:]
    doc = json.loads((out / "summary.json").read_text())
    assert doc["status"] == "interrupted" and "interrupted" in doc["message"]
    assert all((out / f).exists() for f in doc["files"]), doc["files"]
    if "streaming" in doc:
        assert (out / doc["streaming"]).exists()
    else:
        assert not (out / "timeseries.partial.csv").exists()
    csv = out / "timeseries.csv"
    if "timeseries.csv" not in doc["files"]:
        assert not csv.exists() and "up to t" not in doc["message"]
        return doc
    text = csv.read_text()
    assert text.endswith("\n")
    lines = text.splitlines()
    width = lines[0].count(",")
    assert all(line.count(",") == width for line in lines)             # whole rows
    t = np.loadtxt(csv, delimiter=",", skiprows=1, ndmin=2)[:, 0]
    assert t[0] == 0.0 and np.allclose(np.diff(t), 0.05)
    assert t[-1] == pytest.approx(doc["t_end_s"])
    assert _kept_time(doc["message"]) == pytest.approx(t[-1], rel=1e-6)   # the message tells what is kept
    return doc


@pytest.mark.slow
@pytest.mark.parametrize("trial", range(3))
def test_sigint_at_a_random_moment_of_cablesys_run(tmp_path, trial):
    delay = random.Random(2300 + trial).uniform(0.0, 1.5)      # after the running manifest: any phase
    proc, out = _start(tmp_path)
    _wait_for(proc, out)
    time.sleep(delay)
    proc.send_signal(signal.SIGINT)
    _check_interrupted_set(proc, out)


@pytest.mark.slow
def test_a_double_sigint_leaves_a_consistent_interrupted_set(tmp_path):
    proc, out = _start(tmp_path)
    _wait_for(proc, out, rows=3)
    proc.send_signal(signal.SIGINT)
    proc.send_signal(signal.SIGINT)
    time.sleep(0.2)                                             # a third one, most likely while saving
    if proc.poll() is None:
        proc.send_signal(signal.SIGINT)
    doc = _check_interrupted_set(proc, out)
    assert "timeseries.csv" in doc["files"] and "timeseries.nc" in doc["files"]


# -- no import cycle in the time domain ----------------------------------------------------------
def _imports(path: Path, mod: str, modules: set) -> set:
    pkg = mod if path.name == "__init__.py" else mod.rsplit(".", 1)[0]
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):        # function-local imports included
        if isinstance(node, ast.ImportFrom):
            base = pkg.split(".")[: len(pkg.split(".")) - node.level + 1] if node.level else []
            target = ".".join(base + ([node.module] if node.module else []))
            for alias in node.names:
                sub = f"{target}.{alias.name}"
                out.add(sub if sub in modules else target)
        elif isinstance(node, ast.Import):
            out.update(a.name for a in node.names)
    return out & modules


def test_no_import_cycle_through_the_time_domain():
    root = Path(__file__).resolve().parents[1] / "cablesys"
    files = {}
    for path in root.rglob("*.py"):
        parts = path.relative_to(root.parent).with_suffix("").parts
        files[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    graph = {m: _imports(p, m, set(files)) - {m} for m, p in files.items()}
    bad = []
    for start in (m for m in graph if m.startswith("cablesys.time_domain.") and m != "cablesys.time_domain"):
        stack, seen = [(start, (start,))], set()
        while stack:
            node, trail = stack.pop()
            for nxt in graph[node]:
                if nxt == start:
                    bad.append(" -> ".join((*trail, start)))
                elif nxt not in seen and nxt != "cablesys.time_domain":
                    seen.add(nxt)
                    stack.append((nxt, (*trail, nxt)))
    assert not bad, "import cycles:\n" + "\n".join(sorted(set(bad)))
