"""The compiled-code cache under real faults: damaged entries, killed compiles, bad settings, signals.

Each test injects the fault a user met (a truncated or garbled library, which ``dlopen`` turns
into a bus error or a failed loader assertion; a ``kill -9`` during a compile; a bad
``CABLESYS_CACHE_MB``; a missing compiler; SIGTERM or Ctrl-C during a compile) in a temporary
``CABLESYS_CACHE`` folder, and checks the outcome: a fresh process runs and gets the right
numbers, the entry is rebuilt, nothing partial is left, the error names the setting.
"""

import contextlib
import json
import logging
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from cablesys.compiled import cache_dir, compile_functions
from cablesys.disk_cache import (
    ORPHAN_AGE_S,
    build_folder,
    evict,
    file_lock,
    sealed_problem,
)
from cablesys.errors import ParameterError

HANG_GUARD_S = 120          # only against a hang; never reached by a working run


@pytest.fixture
def cache(tmp_path, monkeypatch):
    """Compilation on, into an empty cache of this test; the settings of the machine cleared."""
    monkeypatch.setenv("CABLESYS_CACHE", str(tmp_path / "cache"))
    monkeypatch.setenv("CABLESYS_COMPILE", "1")
    monkeypatch.setenv("CABLESYS_CFLAGS", "-O0")
    for name in ("CABLESYS_CACHE_DIR", "CABLESYS_CC", "CABLESYS_CACHE_MB"):
        monkeypatch.delenv(name, raising=False)
    return tmp_path / "cache"


def _python(code: str, **env):
    """Run ``code`` in a fresh interpreter with this environment (plus ``env``)."""
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True,
                          env=dict(os.environ, **env), timeout=HANG_GUARD_S)


_RUN = """
    import json
    from cablesys.scene import dale_scene
    from cablesys.time_domain import Simulator, simulate
    from cablesys.time_domain.integrators import IntegratorSettings
    from cablesys.model import build_model
    scene = dale_scene().with_numerics(duration=2.0, drag_segments=2)
    model = build_model(scene)
    sim = Simulator(model, scene.output_times, IntegratorSettings(method="cvodes", rtol=1e-9, atol=1e-11))
    res = simulate(scene, model=model, simulator=sim)
    print(json.dumps({"compiled": res.stats["compiled"], "stored": model.build_info["stored"],
                      "x_b": res["x_b"].tolist(), "tension_mid": res["tension_mid"].tolist()}))
"""


def _loads_directly(library: Path, name: str):
    """A fresh process that hands ``library`` straight to ``casadi.external`` (no cache checks)."""
    return _python(f"""
        import casadi as ca
        f = ca.external({name!r}, {str(library)!r})
        print(f.n_in())
    """)


def test_truncated_and_garbled_entries_are_rebuilt_by_the_next_run(cache):
    """The fault of the report: every later run crashed. Truncate the largest library, garble
    another, truncate the stored model and garble a derived-function index entry; a fresh run
    exits 0 with the numbers of the undamaged run (the same machine code), warns once per damaged
    entry and leaves every entry rebuilt and intact."""
    first = _python(_RUN)
    assert first.returncode == 0, first.stderr[-2000:]
    ref = json.loads(first.stdout)
    assert ref["compiled"] is True and ref["stored"] is False
    libraries = sorted(cache_dir().glob("*.so"), key=lambda f: f.stat().st_size)
    assert len(libraries) >= 2 and all(sealed_problem(f) is None for f in libraries)
    truncated, garbled = libraries[-1], libraries[-2]
    blob = truncated.read_bytes()
    truncated.write_bytes(blob[: len(blob) // 2])
    data = bytearray(garbled.read_bytes())
    for i in range(len(data) // 4, len(data) - 64, 61):       # the image garbled, its checksum trailer intact
        data[i] ^= 0xFF
    garbled.write_bytes(bytes(data))
    stored_model = next(cache_dir().glob("models/*.model"))
    stored_model.write_bytes(stored_model.read_bytes()[:-1000])
    index = sorted(cache_dir().glob("derived/*.json"))
    assert index
    entry = bytearray(index[0].read_bytes())
    at = entry.index(b'"structure": "') + len(b'"structure": "')
    entry[at] ^= 0x01                         # one hex digit of a value: still valid JSON, not what was written
    index[0].write_bytes(bytes(entry))
    # the faults are real: these files handed to dlopen directly end the process abnormally (a
    # signal or the loader's own abort), not with a Python exception
    for damaged in (truncated, garbled):
        direct = _loads_directly(damaged, "no_such_function")
        assert direct.returncode not in (0, 1), (damaged, direct.returncode, direct.stderr[-300:])

    again = _python(_RUN)
    assert again.returncode == 0, again.stderr[-2000:]
    out = json.loads(again.stdout)
    assert out["compiled"] is True and out["stored"] is False          # the model was rebuilt, not trusted
    assert np.array_equal(out["x_b"], ref["x_b"]) and np.array_equal(out["tension_mid"], ref["tension_mid"])
    warnings = [line for line in again.stderr.splitlines() if "removed, building it again" in line]
    assert sum(truncated.name in w and "truncated" in w for w in warnings) == 1, again.stderr[-2000:]
    assert sum(garbled.name in w and "SHA-256 mismatch" in w for w in warnings) == 1, again.stderr[-2000:]
    assert f"stored model {stored_model.name} is unreadable (no checksum trailer" in again.stderr
    assert f"stored index entry {index[0].name} is unreadable (SHA-256 mismatch" in again.stderr
    assert sorted(cache_dir().glob("*.so"), key=lambda f: f.stat().st_size)[-1].name == truncated.name
    assert sealed_problem(truncated) is None and sealed_problem(garbled) is None
    assert not list(cache_dir().glob(".build-*"))
    # and the numbers are right, not merely repeated: the VM run of the same scene (another route)
    vm = json.loads(_python(_RUN, CABLESYS_COMPILE="0").stdout)
    assert vm["compiled"] is False
    for label in ("x_b", "tension_mid"):
        a, b = np.asarray(out[label]), np.asarray(vm[label])
        assert np.max(np.abs(a - b)) < 1e-6 * (1e-3 + np.max(np.abs(b)))
    third = _python(_RUN)                               # and now everything comes from the cache, silently
    assert third.returncode == 0 and json.loads(third.stdout)["stored"] is True
    assert "building it again" not in third.stderr


def _dead_pid() -> int:
    proc = subprocess.Popen([sys.executable, "-c", "pass"])
    proc.wait()
    return proc.pid


def _fill(folder: Path, size: int) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "model.c").write_bytes(b"x" * size)
    return folder


def test_orphaned_build_folders_are_removed_and_live_ones_counted(cache):
    """A build folder left by a dead process (its lock free) is removed by the next eviction
    whatever the cap; one being written (its lock held) stays but counts against the cap, so an
    entry goes to make room for it; a temporary file and a folder of the old layout go once old."""
    folder = cache_dir()
    folder.mkdir(parents=True)
    entries = []
    for k in range(2):
        f = folder / f"{k:024x}.so"
        f.write_bytes(b"e" * 1000)
        os.utime(f, (1000 + k, 1000 + k))           # entry 0 the least recently used
        entries.append(f)
    orphan = _fill(folder / f".build-{'a' * 24}-{_dead_pid()}-q1", 5000)
    old_layout = _fill(folder / ".build-k2j3h4", 700)
    stale_tmp = folder / ".abc.x1y2.tmp.model"
    stale_tmp.write_bytes(b"t" * 300)
    fresh_tmp = folder / ".abc.z9.tmp.model"
    fresh_tmp.write_bytes(b"t" * 200)
    long_ago = time.time() - 2 * ORPHAN_AGE_S
    os.utime(old_layout, (long_ago, long_ago))
    os.utime(stale_tmp, (long_ago, long_ago))
    key = "b" * 24
    with file_lock(folder / f"{key}.lock"), build_folder(folder, key) as live:
        _fill(live, 2800)
        # 2000 (entries) + 2800 (live build) + 200 (fresh temporary) = 5000 bytes against a cap of 4200
        removed = evict(cap=4200)
        assert set(removed) == {orphan, old_layout, stale_tmp, entries[0]}
        assert live.exists() and fresh_tmp.exists() and entries[1].exists()
        # the owner process alive, its lock free, the folder young: not (yet) an orphan
        assert evict(cap=10 ** 9) == []
    assert not live.exists()                         # its builder removed it on the way out
    with file_lock(folder / f"{key}.lock"):
        mine = _fill(folder / f".build-{key}-{_dead_pid()}-q2", 100)
        assert evict(cap=10 ** 9) == []              # a dead pid, but the lock held: someone builds
    assert evict(cap=10 ** 9) == [mine]


def test_a_compile_killed_by_sigkill_leaves_an_orphan_that_the_next_build_removes(cache, tmp_path):
    """``kill -9`` during a compile (the fuzzing run's ten 24 MB folders): the next compile's
    eviction removes the folder, and its own build leaves none."""
    pidfile = tmp_path / "cc.pid"
    cc = _slow_compiler(tmp_path, pidfile)
    proc = subprocess.Popen([sys.executable, "-c", _COMPILE], env=dict(os.environ, CABLESYS_CC=str(cc)),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        _wait_for(pidfile, proc)
        [build] = cache_dir().glob(".build-*")
        proc.kill()
        proc.wait(timeout=HANG_GUARD_S)
    finally:
        _end_fake_compiler(pidfile)
    assert build.exists() and not list(cache_dir().glob("*.so"))
    x = ca.SX.sym("x", 2)
    out = compile_functions([ca.Function("after_kill", [x], [ca.sin(x)])], jacobians=False)
    assert out.compiled and not build.exists() and not list(cache_dir().glob(".build-*"))
    assert np.allclose(np.array(out.functions["after_kill"]([0.5, 1.0])).ravel(), np.sin([0.5, 1.0]), rtol=1e-15)


_COMPILE = """
import signal
signal.signal(signal.SIGINT, signal.default_int_handler)   # a background job starts with SIGINT ignored
import casadi as ca
from cablesys.compiled import compile_functions
x = ca.SX.sym("x", 3)
out = compile_functions([ca.Function("slow_f", [x], [ca.cos(x) * x])], jacobians=False)
print(out.compiled, out.note)
"""


def _slow_compiler(tmp_path: Path, pidfile: Path) -> Path:
    """A compiler that answers ``--version`` and otherwise starts a long child (like ``cc1`` under
    the ``cc`` driver), writes that child's pid to ``pidfile`` and waits for it."""
    cc = tmp_path / "slowcc"
    cc.write_text(textwrap.dedent(f"""\
        #!/bin/sh
        if [ "$1" = "--version" ]; then echo "slowcc 1.0"; exit 0; fi
        sleep 300 &
        echo $! > {str(pidfile)!r}.tmp && mv {str(pidfile)!r}.tmp {str(pidfile)!r}
        wait
        exit 1
        """))
    cc.chmod(0o755)
    return cc


def _wait_for(pidfile: Path, proc) -> int:
    """The pid in ``pidfile`` once the fake compiler has written it (``proc`` still running)."""
    deadline = time.monotonic() + HANG_GUARD_S
    while not pidfile.exists():
        assert proc.poll() is None, proc.communicate()
        assert time.monotonic() < deadline, "the compiler never started"
        time.sleep(0.05)
    return int(pidfile.read_text())


def _running(pid: int) -> bool:
    """Whether ``pid`` is a live process (a zombie waiting for its parent's reaping is not)."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return False
    return stat.rsplit(")", 1)[1].split()[0] not in ("Z", "X")


def _end_fake_compiler(pidfile: Path) -> None:
    """End the fake compiler's child that this test started, when it is still running."""
    if pidfile.exists() and _running(pid := int(pidfile.read_text())):
        with contextlib.suppress(ProcessLookupError):
            os.kill(pid, signal.SIGKILL)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc to see the compiler's child end")
@pytest.mark.parametrize("how, sig, expected", [("library", signal.SIGTERM, -signal.SIGTERM),
                                                 ("library", signal.SIGINT, -signal.SIGINT),
                                                 ("library", signal.SIGHUP, -signal.SIGHUP),
                                                 ("cli", signal.SIGTERM, 130)])
def test_a_signal_during_a_compile_kills_the_compiler_and_leaves_nothing(cache, tmp_path, how, sig, expected):
    """SIGTERM, Ctrl-C or a hang-up while the compiler runs: the process ends as that signal asks
    (a plain script dies by it; the ``cablesys`` command exits 130 on SIGTERM), the compiler's
    whole process group (driver and child) is killed, and neither a build folder nor a library is
    left."""
    pidfile = tmp_path / "cc.pid"
    env = dict(os.environ, CABLESYS_CC=str(_slow_compiler(tmp_path, pidfile)), MPLBACKEND="Agg")
    if how == "cli":
        from cablesys.scene import dale_scene, dump_scene
        scene = tmp_path / "dale.toml"
        scene.write_text(dump_scene(dale_scene(duration=1.0, output_step=0.1)))
        argv = [sys.executable, "-m", "cablesys.cli", "run", str(scene), "--out", str(tmp_path / "out")]
    else:
        argv = [sys.executable, "-c", _COMPILE]
    proc = subprocess.Popen(argv, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        child = _wait_for(pidfile, proc)
        assert _running(child) and list(cache_dir().glob(".build-*"))
        proc.send_signal(sig)
        _, err = proc.communicate(timeout=HANG_GUARD_S)
        assert proc.returncode == expected, err[-2000:]
        assert not _running(child)                   # cc1's stand-in went with its driver
    finally:
        _end_fake_compiler(pidfile)
    assert not list(cache_dir().glob(".build-*")) and not list(cache_dir().glob("*.so"))


@pytest.mark.parametrize("name, value, says, model_reads_it", [
    ("CABLESYS_CACHE_MB", "abc", "megabytes", True),
    ("CABLESYS_CACHE_MB", "-5", "megabytes", True),
    ("CABLESYS_COMPILE", "maybe", "0, false, no, off", True),
    ("CABLESYS_CC", "'cc -O2", "shell-quoted", False),
    ("CABLESYS_CFLAGS", '-O2 "-g', "shell-quoted", False),
])
def test_a_bad_setting_is_a_named_error_with_a_warm_cache_and_a_cold_one(cache, monkeypatch, name, value, says,
                                                                          model_reads_it):
    """The setting, its value and what is allowed, before anything is built (cold) and although
    nothing needs building (warm: the entries are on disk). Building a model reads the cache
    settings (its stored functions), not the compiler's."""
    from cablesys.model import build_model
    from cablesys.scene import dale_scene
    x = ca.SX.sym("x", 2)
    f = ca.Function("setting_check", [x], [x ** 2])
    scene = dale_scene().with_numerics(drag_segments=2)
    monkeypatch.setenv(name, value)
    for attempt in ("cold", "warm"):
        with pytest.raises(ParameterError) as err:
            compile_functions([f])
        assert err.value.field == name and err.value.value == value and says in str(err.value)
        assert str(err.value).startswith(f"{name} = {value!r}: ")
        if model_reads_it:
            with pytest.raises(ParameterError, match=name):
                build_model(scene)
        if attempt == "cold":
            assert not [f for f in cache.rglob("*") if f.is_file()]          # nothing built, nothing stored
            monkeypatch.delenv(name)
            assert compile_functions([f]).compiled and build_model(scene).build_info["stored"] is False
            monkeypatch.setenv(name, value)


def test_a_cache_folder_that_is_a_file_is_a_named_error(cache, tmp_path, monkeypatch):
    blocker = tmp_path / "not-a-folder"
    blocker.write_text("x")
    monkeypatch.setenv("CABLESYS_CACHE", str(blocker))
    with pytest.raises(ParameterError, match="CABLESYS_CACHE = .*not-a-folder.*: must be a folder"):
        x = ca.SX.sym("x")
        compile_functions([ca.Function("f", [x], [x + 1])])


def test_no_compiler_notice_is_printed_once_per_process(cache, tmp_path):
    """The report counted six copies in one ``cablesys run``; one per process is the promise
    (the run still succeeds, in the virtual machine)."""
    from cablesys.scene import dale_scene, dump_scene
    scene = tmp_path / "dale.toml"
    scene.write_text(dump_scene(dale_scene(duration=1.0, output_step=0.1)))
    proc = subprocess.run([sys.executable, "-m", "cablesys.cli", "run", str(scene), "--out", str(tmp_path / "out")],
                          capture_output=True, text=True, timeout=HANG_GUARD_S,
                          env=dict(os.environ, CABLESYS_CC="/nonexistent/bin/cc-missing", MPLBACKEND="Agg"))
    assert proc.returncode == 0, proc.stderr[-2000:]
    notices = [line for line in proc.stderr.splitlines() if line.startswith("WARNING cablesys.compiled")]
    assert len(notices) == 1 and "no C compiler '/nonexistent/bin/cc-missing'" in notices[0], proc.stderr
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["stats"]["compiled"] is False


def test_repeated_fallbacks_log_one_warning(cache, monkeypatch, caplog):
    """In one process: many functions falling back for the same reason give one warning, later
    ones at debug level; each still carries the reason in its ``note``."""
    monkeypatch.setenv("CABLESYS_CC", "/nonexistent/bin/cc-once-only")
    x = ca.SX.sym("x")
    with caplog.at_level(logging.DEBUG, logger="cablesys.compiled"):
        outs = [compile_functions([ca.Function(f"f{k}", [x], [x * k])]) for k in range(4)]
    assert all(not o.compiled and "cc-once-only" in o.note for o in outs)
    levels = [r.levelno for r in caplog.records if "cc-once-only" in r.getMessage()]
    assert levels == [logging.WARNING] + [logging.DEBUG] * 3


def test_a_compile_says_what_it_compiles_and_a_large_one_says_it_aloud(cache, monkeypatch, caplog):
    """Progress of a build: the functions, the size of their C and the command, at info level;
    above LOUD_BUILD_BYTES of C as a warning (seen without ``-v``); a cached load says nothing."""
    import cablesys.compiled as C
    x = ca.SX.sym("x", 2)
    with caplog.at_level(logging.INFO, logger="cablesys.compiled"):
        compile_functions([ca.Function("quiet_f", [x], [x * 2])], jacobians=False)
        monkeypatch.setattr(C, "LOUD_BUILD_BYTES", 100)
        compile_functions([ca.Function("loud_f", [x], [x * 3])], jacobians=False)
        compile_functions([ca.Function("loud_f", [x], [x * 3])], jacobians=False)        # cached
    starts = [(r.levelno, r.getMessage()) for r in caplog.records if r.getMessage().startswith("compiling ")]
    assert [level for level, _ in starts] == [logging.INFO, logging.WARNING]
    assert "quiet_f" in starts[0][1] and "MB of C, cc -O0" in starts[0][1] and "loud_f" in starts[1][1]
    assert sum(r.getMessage().startswith("compiled loud_f in ") for r in caplog.records) == 1


def test_code_known_too_large_goes_to_the_vm_without_generating_it_again(cache, monkeypatch, caplog):
    """C above MAX_C_BYTES is refused once and its size recorded in the cache, so a later call (in
    any process: the record is on disk) goes to the VM without generating the C again; with the
    limit above the recorded size the entry is compiled."""
    import cablesys.compiled as C
    limit, generate = C.MAX_C_BYTES, C.generate
    monkeypatch.setattr(C, "MAX_C_BYTES", 1000)
    x = ca.SX.sym("x", 3)
    f = ca.Function("too_big_f", [x], [ca.sin(x) * ca.cos(x) + x ** 3])
    first = compile_functions([f])
    assert not first.compiled and "MB of generated C" in first.note
    [marker] = cache_dir().glob("*.vm")
    assert sealed_problem(marker) is None

    def no_generation(*a, **k):
        raise AssertionError("the C was generated again")
    monkeypatch.setattr(C, "generate", no_generation)
    again = compile_functions([f])
    assert not again.compiled and "compilation skipped" in again.note and again.functions["too_big_f"] is f
    monkeypatch.setattr(C, "MAX_C_BYTES", limit)
    monkeypatch.setattr(C, "generate", generate)
    done = compile_functions([f])                   # the real limit: far above this C
    assert done.compiled and done.library.with_suffix(".vm") == marker
    assert np.allclose(np.array(done.functions["too_big_f"]([0.1, 0.2, 0.3])).ravel(),
                       np.sin([0.1, 0.2, 0.3]) * np.cos([0.1, 0.2, 0.3]) + np.array([0.1, 0.2, 0.3]) ** 3, rtol=1e-14)


def test_a_compile_announces_its_prediction_ticks_and_ends_with_the_actual_time(cache, monkeypatch, caplog):
    """The start line carries the size of the C and the predicted compile time (the rate of the flags times the
    size); lines while it runs say elapsed against predicted; the end line carries the actual time, the one the
    build reports (``Compiled.build_s`` bounds it: code generation and the load come on top)."""
    import re

    import cablesys.compiled as C
    monkeypatch.setattr(C, "PROGRESS_EVERY_S", 0.01)     # a tick well inside the compile's own time
    real = C._run_compiler

    def slower(argv, workdir):
        time.sleep(0.2)           # a compile long enough for ticks, whatever the machine
        return real(argv, workdir)
    monkeypatch.setattr(C, "_run_compiler", slower)
    x = ca.SX.sym("x", 4)
    with caplog.at_level(logging.INFO, logger="cablesys.compiled"):
        out = compile_functions([ca.Function("told_f", [x], [ca.sin(x) * x])], jacobians=True)
    msgs = [r.getMessage() for r in caplog.records]
    [start] = [m for m in msgs if m.startswith("compiling told_f (")]
    mb, pred = re.search(r"\(([0-9.]+) MB of C, cc -O0\).*predicted about ([0-9.e+-]+) s", start).groups()
    c = C.generate([ca.Function("told_f", [x], [ca.sin(x) * x])], jacobians=True)
    assert float(mb) == pytest.approx(len(c) / 1e6, abs=0.006)
    assert float(pred) == pytest.approx(C.COMPILE_START_S + C.COMPILE_S_PER_MB["-O0"] * len(c) / 1e6, rel=0.05)
    ticks = [m for m in msgs if m.startswith("compiling told_f: ")]
    assert ticks and all(re.search(r"\d+ s elapsed(, past the| of about) ", m) for m in ticks)
    [end] = [m for m in msgs if m.startswith("compiled told_f in ")]
    took, pred_end = map(float, re.search(r"in ([0-9.e+-]+) s \(predicted about ([0-9.e+-]+) s", end).groups())
    assert pred_end == float(pred) and took > 0 and out.compiled and not out.cached
    assert not [t for t in threading.enumerate() if t.name == "cablesys-compile-progress"]   # the ticker ended
