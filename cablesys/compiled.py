"""Compiled model functions with an on-disk cache of shared libraries.

CasADi generates C for a set of functions (and their Jacobians, named ``jac_<name>`` so that
``casadi.external`` finds them); the C is compiled once with the system C compiler and the
shared library is kept in the cache (:mod:`cablesys.disk_cache`: versioned folder, atomic
writes, per-entry locks, size cap with least-recently-used eviction), keyed by a hash of the
functions (their serialized expression graphs, from which the C is generated
deterministically), the compiler and its flags. The generated code depends on the scene
*structure* only (every scene number is an entry of ``p``), so a second run of the same
structure, with any parameter values, loads the library instead of compiling it again.

A second start need not even build the functions: :class:`DerivedStore` maps (a model
structure key, the name of a derived function) to its library, so a model that knows its
structure (:func:`cablesys.model.build_model` attaches the store to ``model.cache``) loads its
compiled DAE with ``casadi.external`` without building or serializing its expression graph.

Every library is sealed with its SHA-256 when it is built (:func:`cablesys.disk_cache.seal_file`)
and checked before every ``dlopen``: a truncated or garbled file (which ``dlopen`` would turn
into a bus error or a segmentation fault of the whole process) is removed with a one-line
warning and rebuilt, as is one that fails to load (removed by another process's eviction,
without one of the names). The index entries of :class:`DerivedStore`, the compiler memo and
the record of an entry whose C is above ``MAX_C_BYTES`` (``<key>.vm``: later runs go to the
virtual machine without generating that C again) are sealed likewise.

A compile runs in a build folder of the cache (:func:`cablesys.disk_cache.build_folder`, also
the compiler's ``TMPDIR``) under the entry's lock, in a process group of its own: on Ctrl-C,
SIGTERM, SIGHUP or any error the whole group (driver, ``cc1``, assembler, linker) is killed
and the folder removed before the interruption goes on (a signal left at its default action
then ends the process as it would have), so nothing partial is left; a folder left by
``kill -9`` is removed by the next eviction.

Progress of a build, in the log (``cablesys`` prints warnings on stderr, info lines with ``-v``): a start line
with the size of the generated C and the predicted compile time (:func:`predicted_compile_s`), a line every
``PROGRESS_EVERY_S`` while the C is generated and compiled (elapsed against predicted; from a thread that only
logs, so a signal still interrupts the main thread's wait on the compiler at once), and an end line with the
actual time beside the prediction. A build predicted past ``PROGRESS_EVERY_S`` or of more than
``LOUD_BUILD_BYTES`` of C is announced as warnings (seen without ``-v``), others at info level.

Settings (environment), checked whenever read (a bad value is a
:class:`~cablesys.errors.ParameterError` naming it): ``CABLESYS_CC`` the compiler command
(default ``cc``), ``CABLESYS_CFLAGS`` its optimization flags (default ``-O2``, less for very
large functions: ``SIZE_FLAGS``), ``CABLESYS_COMPILE`` (``0``/``false``/``no``/``off`` to use
CasADi's virtual machine, ``1``/``true``/``yes``/``on`` or unset to compile); the cache folder
and its cap: see :mod:`cablesys.disk_cache`. Without a working compiler the functions run in
the virtual machine and one warning per process says so.
"""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import json
import logging
import os
import shlex
import shutil
import signal
import threading
import time
from pathlib import Path

import casadi as ca

from .disk_cache import (
    CACHE_FORMAT,
    build_folder,
    cache_dir,
    digest,
    evict,
    file_lock,
    read_sealed,
    seal_file,
    sealed_problem,
    touch,
    write_sealed,
)
from .derivatives import state_jacobian
from .errors import ParameterError

log = logging.getLogger(__name__)

__all__ = ["CACHE_FORMAT", "Compiled", "DerivedStore", "cache_dir", "compilation_enabled", "compile_functions",
           "compiler_command", "generate", "predicted_compile_s"]


@dataclasses.dataclass(frozen=True)
class Compiled:
    """Functions loaded from a compiled library (or the originals when not compiled).

    ``functions`` maps each name to a ``casadi.Function``; ``compiled`` says whether they are
    external (compiled) functions; ``cached`` whether the library came from the cache (no
    compiler run); ``build_s`` code generation + compilation time, ``load_s`` loading time [s];
    ``library`` the path of the shared library (None in the virtual machine).
    """

    functions: dict
    compiled: bool
    cached: bool
    build_s: float
    load_s: float
    library: Path | None = None
    note: str = ""


_ON, _OFF = ("1", "true", "yes", "on"), ("0", "false", "no", "off")


def compilation_enabled(enabled: bool = True) -> bool:
    """False when ``enabled`` is False or ``CABLESYS_COMPILE`` is 0/false/no/off (any case);
    a :class:`~cablesys.errors.ParameterError` when it is set to anything else than those or
    1/true/yes/on (empty: unset)."""
    text = os.environ.get("CABLESYS_COMPILE", "").strip()
    if text and text.lower() not in _ON + _OFF:
        raise ParameterError("CABLESYS_COMPILE", text, f"must be one of {', '.join(_ON)} (compile) or "
                             f"{', '.join(_OFF)} (CasADi's virtual machine)")
    return enabled and text.lower() not in _OFF


def compiles(enabled: bool = True) -> bool:
    """Whether functions will run compiled: :func:`compilation_enabled` and a C compiler found
    (``CABLESYS_CC``, default ``cc``); without one every function runs in CasADi's VM (with a one-line notice),
    so whatever prices runs by how they will run asks this, not the setting alone."""
    return compilation_enabled(enabled) and _compiler_identity(compiler_command()) is not None


_NOTICES: set = set()
_NOTICES_LOCK = threading.Lock()


def _notice(note: str) -> None:
    """Log ``note`` as a warning the first time this process meets it, later only at debug level
    (a run derives many functions: each falls back for the same reason)."""
    with _NOTICES_LOCK:
        first = note not in _NOTICES
        _NOTICES.add(note)
    log.log(logging.WARNING if first else logging.DEBUG, "%s", note)


# default optimization by size of the functions (serialized characters): gcc's time grows
# faster than linearly with the length of straight-line code (a 305-sample top-motion series:
# 1.6 MB of C, 39 s at -O2, 7 s at -O0), while small models gain 2x at run time from -O2
SIZE_FLAGS = ((400_000, "-O2"), (1_500_000, "-O1"), (float("inf"), "-O0"))
# generated C above this runs in the VM: the compiler's memory grows with the code (at -O0: 19 MB of C, the
# quasi-static segmented DAE at N = 20, took 3.5 GB; the 120 MB of a dense N = 20 Jacobian ran cc1 past 8 GB
# under a cap and past 22 GB without one, killed by the kernel)
MAX_C_BYTES = 40_000_000
# a compile of more C than this is announced as a warning (seen without -v), smaller ones at info level
LOUD_BUILD_BYTES = 1_000_000
# while C is generated and compiled, a line every PROGRESS_EVERY_S (s) with the time elapsed and the prediction
PROGRESS_EVERY_S = 10.0
# predicted compile time: COMPILE_START_S + MB of C x COMPILE_S_PER_MB[optimization flag] (s), least-squares fits to
# the compiler's CPU time (its wall time on an idle machine) over 50 cold-cache compiles of 0.03-18.5 MB of C
# (studies/results/run_prediction.json, "compile_rates": -O0 1.8, -O1 4.5, -O2 11.3 s/MB; gcc, x86_64); a loaded
# machine stretches the wall time (2-3x at a load of 6.6 on 2 cores), gcc's time grows faster than linearly with
# the size (small -O2 libraries take about 4 s/MB, 0.5 MB ones 12 s/MB); -O3 is not measured (-O2's rate x 1.25)
COMPILE_START_S = 0.3
COMPILE_S_PER_MB = {"-O0": 1.9, "-O1": 4.5, "-O2": 11.5, "-O3": 14.0}


def _split_setting(name: str, default: str) -> list[str]:
    """``shlex.split`` of the environment variable ``name`` (``default`` when unset or blank);
    a :class:`~cablesys.errors.ParameterError` when it does not parse (an unclosed quote)."""
    text = os.environ.get(name, "")
    try:
        return shlex.split(text if text.strip() else default)
    except ValueError as err:
        raise ParameterError(name, text, f"must be a shell-quoted command line ({err})") from None


def compiler_command(size: int = 0, optimization: str | None = None) -> list[str]:
    """The compiler command and flags: ``CABLESYS_CC`` (default ``cc``) and ``CABLESYS_CFLAGS``
    (default ``optimization`` when given, else by ``size``, the functions' serialized length: see ``SIZE_FLAGS``)."""
    cc = _split_setting("CABLESYS_CC", "cc")
    default = optimization or next(flag for limit, flag in SIZE_FLAGS if size < limit)
    flags = _split_setting("CABLESYS_CFLAGS", default)
    return cc + flags + ["-fPIC", "-shared"]


def _compiler_identity(cmd: list[str]) -> str | None:
    """The compiler's path and first line of ``--version`` (part of the cache key); None when
    there is no compiler. Remembered per process and, on disk, per executable (path, size,
    modification time): asking the compiler costs a process start."""
    return _identity(cmd[0], os.environ.get("PATH", ""))


@functools.lru_cache(maxsize=8)
def _identity(cc: str, path: str) -> str | None:
    exe = shutil.which(cc, path=path or None)
    if exe is None:
        return None
    real = os.path.realpath(exe)
    try:
        st = os.stat(real)
    except OSError:
        return None
    stamp = f"{real}|{st.st_size}|{st.st_mtime_ns}"
    memo = cache_dir() / "compilers.json"
    try:
        known = json.loads(read_sealed(memo))
    except (OSError, ValueError):             # absent, or truncated or garbled: asked again and rewritten
        known = {}
    if stamp in known:
        touch(memo)
        return known[stamp]
    import subprocess  # only on a first start with this compiler: a warm start imports less
    try:
        out = subprocess.run([exe, "--version"], capture_output=True, text=True, timeout=30, check=False)
    except (OSError, subprocess.SubprocessError):
        return None
    text = out.stdout or out.stderr
    ident = f"{exe}|{text.splitlines()[0] if text else ''}"
    with contextlib.suppress(OSError):
        write_sealed(memo, json.dumps({**known, stamp: ident}).encode())
    return ident


def generate(functions, *, jacobians=True) -> str:
    """C source of ``functions`` and, when ``jacobians``, their Jacobians ``jac_<name>``
    (``True``: the full Jacobian; a tuple of input names: only those blocks, see
    :func:`cablesys.derivatives.state_jacobian`)."""
    cg = ca.CodeGenerator("cablesys_model.c", {"with_header": False, "verbose": False})
    for f in functions:
        cg.add(f)
        if jacobians is True:
            cg.add(f.jacobian())
        elif jacobians:
            cg.add(state_jacobian(f, tuple(jacobians)))
    return cg.dump()


def cache_key(serialized, jacobians, ident: str, cmd: list[str]) -> str:
    """Hash of what the library is made of: the functions' serialized form (CasADi's exact,
    deterministic description of the expression graphs, from which the C code is generated;
    hashing it is much cheaper than generating the C), whether Jacobians are
    included, the compiler identity, its flags and the cache format."""
    return digest(*serialized, jacobians, ident, " ".join(cmd[1:]), CACHE_FORMAT)[:24]


class _Terminated(BaseException):
    """SIGTERM or SIGHUP arrived during a compile (with the default action, which would end the
    process at once and leave the compiler, in a session of its own, running and its folder
    behind); ``args[0]`` is the signal."""


# signals whose default action ends the process and that a Python program does not handle by default
_ENDING = tuple(getattr(signal, name) for name in ("SIGTERM", "SIGHUP") if hasattr(signal, name))


@contextlib.contextmanager
def _signals_stop_build():
    """While a compile runs in the main thread, SIGTERM and SIGHUP left at their default action
    raise :class:`_Terminated` so that the build is cleaned up; the caller then ends the process
    by the same signal. A Python handler already installed (the ``cablesys`` command turns
    SIGTERM into KeyboardInterrupt) and other threads are left alone."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    ours = [sig for sig in _ENDING if signal.getsignal(sig) is signal.SIG_DFL]

    def handler(signum, frame):
        raise _Terminated(signum)
    for sig in ours:
        signal.signal(sig, handler)
    try:
        yield
    finally:
        for sig in ours:
            signal.signal(sig, signal.SIG_DFL)


def _run_compiler(argv: list[str], workdir: Path):
    """Run the compiler ``argv`` in a session of its own (its temporary files in ``workdir``);
    on any exception while it runs (Ctrl-C, SIGTERM) its whole process group is killed and
    waited for before the exception goes on. Returns the finished ``Popen``'s (returncode, output)."""
    import subprocess
    proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            start_new_session=True, env=dict(os.environ, TMPDIR=str(workdir)))
    try:
        out, _ = proc.communicate()
    except BaseException:
        with contextlib.suppress(OSError):
            if hasattr(os, "killpg"):
                os.killpg(proc.pid, signal.SIGKILL)
            else:                                    # pragma: no cover (Windows: no process groups)
                proc.kill()
        proc.wait()
        raise
    finally:
        if proc.stdout is not None:
            proc.stdout.close()
    return proc.returncode, out or ""


def _too_large(c_bytes: int, what: str) -> str:
    return (f"{what}: {c_bytes / 1e6:.1f} MB of generated C, above the {MAX_C_BYTES / 1e6:.1f} MB a compiler run "
            "is given (its memory grows with the code)")


def _known_too_large(marker: Path) -> int | None:
    """The C size [bytes] recorded in ``marker`` (``<key>.vm``, written when that entry's C was found above
    ``MAX_C_BYTES``) when it is still above it, else None: that entry goes to the VM without generating its C
    again."""
    try:
        c_bytes = int(json.loads(read_sealed(marker))["c_bytes"])
    except (OSError, ValueError, KeyError, TypeError):
        return None
    touch(marker)
    return c_bytes if c_bytes > MAX_C_BYTES else None


def predicted_compile_s(c_bytes: int, cmd: list[str]) -> float:
    """Predicted wall time (s) of compiling ``c_bytes`` of generated C with ``cmd`` (its last ``-O`` flag chooses the
    rate; ``COMPILE_START_S`` + MB x ``COMPILE_S_PER_MB``, the fit of ``studies/run_prediction.py``)."""
    flags = [a for a in cmd if a.startswith("-O")]
    rate = COMPILE_S_PER_MB.get(flags[-1] if flags else "-O0", COMPILE_S_PER_MB["-O2"])
    return COMPILE_START_S + rate * c_bytes / 1e6


class _Ticker:
    """A line in the log every ``every`` s (a thread of its own) while C is generated and compiled: what is done and
    how long it has taken against the prediction (``phase(text, predicted_s)`` names the current step). The lines are
    warnings (a step this long is worth seeing without ``-v``); the thread only logs, so a signal still reaches the
    main thread, which stops it on the way out (a daemon thread: it never holds the process)."""

    def __init__(self, what: str, every: float):
        self.what, self.every = what, float(every)
        self.text, self.predicted, self.t0 = "generating the C of", None, time.perf_counter()
        self.ticks = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._loop, name="cablesys-compile-progress", daemon=True)

    def phase(self, text: str, predicted_s: float | None = None) -> None:
        self.text, self.predicted = text, predicted_s

    def line(self) -> str:
        elapsed = time.perf_counter() - self.t0
        pred = "" if self.predicted is None else (
            f" of about {self.predicted:.2g} s predicted" if elapsed <= self.predicted
            else f", past the {self.predicted:.2g} s predicted")
        return f"{self.text} {self.what}: {elapsed:.0f} s elapsed{pred}"

    def _loop(self) -> None:
        while not self._stop.wait(self.every):
            self.ticks += 1
            log.warning("%s", self.line())

    def __enter__(self):
        self._thread.start()
        return self

    def __exit__(self, *exc):
        self._stop.set()
        self._thread.join(timeout=1.0)
        return False


def _build(code: str, cmd: list[str], target: Path, what: str = "", ticker: _Ticker | None = None) -> float:
    """Compile ``code`` to ``target``: in a build folder of the cache, sealed with its SHA-256,
    then an atomic rename; nothing is left behind on failure or interruption. Hold the entry's
    lock around it. ``what`` names the functions in the progress messages: a start line with the size of the C and
    the predicted compile time (:func:`predicted_compile_s`), ``ticker``'s periodic lines, an end line with the
    actual time; returns that time (s). Code above ``MAX_C_BYTES`` is not compiled (RuntimeError) and its size
    recorded beside the entry (``<key>.vm``), so that later runs skip generating it."""
    if len(code) > MAX_C_BYTES:
        with contextlib.suppress(OSError):
            write_sealed(target.with_suffix(".vm"), json.dumps({"c_bytes": len(code)}).encode())
        raise RuntimeError(_too_large(len(code), what or target.stem))
    key = target.stem
    predicted = predicted_compile_s(len(code), cmd)
    loud = len(code) > LOUD_BUILD_BYTES or predicted > PROGRESS_EVERY_S
    log.log(logging.WARNING if loud else logging.INFO,
            "compiling %s (%.2f MB of C, %s) into the cache %s, predicted about %.2g s: once, later runs load it",
            what or key, len(code) / 1e6, " ".join(cmd[:-2]), target.parent, predicted)
    if ticker is not None:
        ticker.phase("compiling", predicted)
    t0 = time.perf_counter()
    try:
        with _signals_stop_build(), build_folder(target.parent, key) as tmp:
            src = tmp / "model.c"
            src.write_text(code)
            tmp_so = tmp / "model.so"
            code_rc, out = _run_compiler(cmd + [str(src), "-o", str(tmp_so), "-lm"], tmp)
            if code_rc != 0:
                raise RuntimeError(f"{' '.join(cmd)} failed (exit {code_rc}): {out.strip()[-500:]}")
            seal_file(tmp_so)
            os.replace(tmp_so, target)
    except _Terminated as stop:     # cleaned up: now end as the signal's default action would have
        signal.signal(stop.args[0], signal.SIG_DFL)
        os.kill(os.getpid(), stop.args[0])
        raise KeyboardInterrupt(f"signal {stop.args[0]}") from None   # pragma: no cover (the signal ends it)
    took = time.perf_counter() - t0
    loud = loud or (ticker is not None and ticker.ticks > 0)      # the end of what was shown is shown
    log.log(logging.WARNING if loud else logging.INFO, "compiled %s in %.2g s (predicted about %.2g s, %.2f MB of C): %s",
            what or key, took, predicted, len(code) / 1e6, target.name)
    return took


def _load(target: Path, names) -> dict:
    """``casadi.external`` of every name in the library ``target`` (RuntimeError when it does
    not load: removed, or without one of the names). Check it first (:func:`_damage`)."""
    loaded = {name: ca.external(name, str(target)) for name in names}
    touch(target)
    return loaded


def _damage(target: Path) -> str | None:
    """What is wrong with the library file ``target``: ``"missing"``, a truncated or garbled
    content (:func:`cablesys.disk_cache.sealed_problem`), or None when it is intact and may be
    handed to ``dlopen``."""
    try:
        return sealed_problem(target)
    except FileNotFoundError:
        return "missing"
    except OSError as err:
        return f"unreadable ({err})"


def _discard(target: Path, why: str) -> None:
    """Remove the damaged library ``target`` with a one-line warning (the caller rebuilds it).
    Unlinking is safe for a process that has it mapped: its pages stay until it unmaps them."""
    _notice(f"cached library {target.name} does not load ({why}): removed, building it again")
    with contextlib.suppress(FileNotFoundError):
        target.unlink()


def compile_functions(functions, *, jacobians=True, enabled: bool = True, extra_c: str = "",
                      extra_names=(), size: int | None = None, optimization: str | None = None) -> Compiled:
    """Compiled versions of ``functions`` from the cache, building the library if needed.

    Parameters
    ----------
    functions : sequence of casadi.Function
        Functions with distinct names (SX or MX, code-generatable).
    jacobians : bool or tuple of str
        Also compile each function's Jacobian ``jac_<name>``, so that solvers (CVODES, IDAS,
        Newton) use it: ``True`` the full one, a tuple of input names only those blocks
        (:func:`state_jacobian`).
    enabled : bool
        False (or ``CABLESYS_COMPILE=0``) returns the functions unchanged.
    extra_c : str, optional
        Hand-written C appended to the generated code (it may call the generated functions by
        name, e.g. an integrator driver around a right-hand side); part of the cache key.
    extra_names : sequence of str, optional
        Functions defined in ``extra_c`` with CasADi's external-function API, loaded with
        ``casadi.external`` too (absent from ``functions`` when not compiled).
    size : int, optional
        The code size that chooses the default flags (``SIZE_FLAGS``) instead of the functions'
        serialized length, for code whose serialized form overstates its C (an MX loop over
        mapped kernels: the segmented RK4 loop at N = 80 serializes to 0.57 MB for ~25 kB of C).
    optimization : str, optional
        The default optimization flag (e.g. ``"-O1"``) instead of the one ``SIZE_FLAGS`` picks, for
        code whose run time matters more than its size suggests (``CABLESYS_CFLAGS`` still wins).

    Returns
    -------
    Compiled
        The functions (external when compiled), and the build and load times [s]. Without a C
        compiler, or when compilation fails, the original functions with one logged warning per
        process and reason (``note``). A cached library is checked before it is loaded: one that
        is truncated, garbled or does not load is removed and built again.

    Raises
    ------
    ParameterError
        A bad ``CABLESYS_*`` setting (compiler command, flags, cache folder or cap).
    KeyboardInterrupt
        Ctrl-C (or SIGTERM under the ``cablesys`` command) during a compile, after the compiler
        is killed and its build folder removed.
    """
    functions = list(functions)
    originals = {f.name(): f for f in functions}
    if not compilation_enabled(enabled):
        return Compiled(originals, False, False, 0.0, 0.0, note="compilation disabled")
    t0 = time.perf_counter()
    serialized = [f.serialize() for f in functions]
    cmd = compiler_command(sum(len(x) for x in serialized) if size is None else int(size), optimization)
    folder = cache_dir()                      # checks the cache settings, warm or cold
    ident = _compiler_identity(cmd)
    if ident is None:
        note = (f"no C compiler '{cmd[0]}' found: running the CasADi virtual machine (slower); "
                "install cc or set CABLESYS_CC")
        _notice(note)
        return Compiled(originals, False, False, time.perf_counter() - t0, 0.0, note=note)
    key = cache_key(serialized + ([extra_c] if extra_c else []), jacobians, ident, cmd)
    target = folder / f"{key}.so"
    lock = folder / f"{key}.lock"
    what = ", ".join(originals) or key
    c_bytes = _known_too_large(target.with_suffix(".vm"))
    if c_bytes is not None:
        note = f"compilation skipped ({_too_large(c_bytes, what)}): running the CasADi virtual machine (slower)"
        _notice(note)
        return Compiled(originals, False, False, time.perf_counter() - t0, 0.0, note=note)
    for attempt in (0, 1):
        damage = _damage(target)
        cached = damage is None
        if not cached:
            try:
                with file_lock(lock):
                    damage = _damage(target)          # another process may have built or removed it meanwhile
                    cached = damage is None
                    if damage not in (None, "missing"):
                        _discard(target, damage)
                    if not cached:
                        with _Ticker(what, PROGRESS_EVERY_S) as ticker:
                            _build(generate(functions, jacobians=jacobians) + extra_c, cmd, target, what, ticker)
            except (OSError, RuntimeError) as err:
                note = f"compilation failed ({err}): running the CasADi virtual machine (slower)"
                _notice(note)
                return Compiled(originals, False, False, time.perf_counter() - t0, 0.0, note=note)
            with contextlib.suppress(OSError):
                evict(keep=[target])
        t1 = time.perf_counter()
        try:
            loaded = _load(target, [*originals, *extra_names])
        except RuntimeError as err:
            if attempt:
                note = f"the compiled library {target} does not load ({err}): running the CasADi virtual machine"
                _notice(note)
                return Compiled(originals, False, False, time.perf_counter() - t0, 0.0, note=note)
            with file_lock(lock):
                _discard(target, str(err).strip().splitlines()[-1][:200] if str(err).strip() else "dlopen failed")
            continue
        t2 = time.perf_counter()
        return Compiled(loaded, True, cached, t1 - t0, t2 - t1, library=target)
    raise AssertionError("unreachable")     # pragma: no cover


class DerivedStore:
    """The disk index of a model structure's compiled derived functions.

    ``load(key)`` returns the :class:`Compiled` stored under (structure, ``key``) by an earlier
    process, loaded with ``casadi.external`` without building anything, or None (not stored,
    library gone or not loading: the caller builds it); ``save(key, item)`` records a compiled
    item. Keys are those of :class:`~cablesys.model.FunctionCache` (what is derived and its
    structural options), so the entry is exactly as specific as the in-memory cache; the
    structure key (:func:`cablesys.model.store.structure_key`) includes the versions and the
    source fingerprint, and the entry's name includes the compiler settings.

    Parameters
    ----------
    structure : str
        The model's structure key.
    """

    def __init__(self, structure: str):
        self.structure = structure

    def __repr__(self) -> str:
        return f"DerivedStore({self.structure})"

    def _path(self, key: str) -> Path:
        return cache_dir() / "derived" / f"{digest(self.structure, key, *compiler_command())}.json"

    def load(self, key: str) -> Compiled | None:
        """The compiled item stored under ``key``, or None (see the class docstring). An index
        entry or a library that is truncated or garbled is removed with a warning."""
        if not compilation_enabled():
            return None
        path = self._path(key)
        try:
            entry = json.loads(read_sealed(path))
        except OSError:
            return None
        except ValueError as err:
            _notice(f"stored index entry {path.name} is unreadable ({err}): removed, building it again")
            with contextlib.suppress(OSError):
                path.unlink()
            return None
        t0 = time.perf_counter()
        target = cache_dir() / str(entry.get("library", ""))
        ident = _compiler_identity(compiler_command())
        if entry.get("key") != key or entry.get("compiler") != ident or target.suffix != ".so":
            return None
        damage = _damage(target)
        if damage is not None:
            if damage != "missing":
                with file_lock(target.with_suffix(".lock")):
                    if _damage(target) not in (None, "missing"):
                        _discard(target, damage)
            return None
        try:
            loaded = _load(target, entry["names"])
        except (RuntimeError, KeyError, TypeError):
            log.info("stored library %s of %s does not load: building it again", target.name, key)
            return None
        touch(path)
        return Compiled(loaded, True, True, 0.0, time.perf_counter() - t0, library=target)

    def save(self, key: str, item) -> None:
        """Record ``item`` under ``key`` when it is a compiled :class:`Compiled` (else nothing)."""
        if not (isinstance(item, Compiled) and item.compiled and item.library is not None):
            return
        entry = {"key": key, "structure": self.structure, "library": item.library.name,
                 "names": list(item.functions), "compiler": _compiler_identity(compiler_command())}
        with contextlib.suppress(OSError):
            write_sealed(self._path(key), json.dumps(entry).encode())
