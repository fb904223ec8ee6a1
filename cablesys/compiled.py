"""Compiled model functions with an on-disk cache of shared libraries.

CasADi generates C for a set of functions (and their Jacobians, named ``jac_<name>`` so that
``casadi.external`` finds them); the C is compiled once with the system C compiler and the
shared library is kept in a cache keyed by a hash of the functions (their serialized
expression graphs, from which the C is generated deterministically), the compiler and its flags. The generated code depends on the scene *structure* only (every scene number is an
entry of ``p``), so a second run of the same structure, with any parameter values, loads the
library in a millisecond instead of compiling it again.

Cache: ``$CABLESYS_CACHE_DIR`` or ``~/.cache/cablesys``, in a sub-folder per cablesys and
CasADi version and cache-format version. Safe under concurrent runs (sweeps): a per-key file
lock serializes builders, and each library is compiled under a temporary name and renamed into
place atomically, so a reader never sees a half-written file.

Settings (environment): ``CABLESYS_CC`` the compiler command (default ``cc``),
``CABLESYS_CFLAGS`` its optimization flags (default ``-O2``, less for very large functions:
``SIZE_FLAGS``), ``CABLESYS_COMPILE=0`` to use
CasADi's virtual machine. Without a working compiler the functions run in the virtual machine
and one warning says so.
"""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import hashlib
import logging
import os
import shlex
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

import casadi as ca

from . import __version__

log = logging.getLogger(__name__)

CACHE_FORMAT = 1          # bump when the layout of the cache or of the generated library changes


@dataclasses.dataclass(frozen=True)
class Compiled:
    """Functions loaded from a compiled library (or the originals when not compiled).

    ``functions`` maps each name to a ``casadi.Function``; ``compiled`` says whether they are
    external (compiled) functions; ``cached`` whether the library came from the cache;
    ``build_s`` code generation + compilation time, ``load_s`` loading time [s];
    ``library`` the path of the shared library (None in the virtual machine).
    """

    functions: dict
    compiled: bool
    cached: bool
    build_s: float
    load_s: float
    library: Path | None = None
    note: str = ""


def cache_dir() -> Path:
    """The versioned cache folder (created on demand)."""
    base = os.environ.get("CABLESYS_CACHE_DIR") or os.path.join(os.path.expanduser("~"), ".cache", "cablesys")
    return Path(base) / f"cablesys-{__version__}_casadi-{ca.__version__}_v{CACHE_FORMAT}"


# default optimization by size of the functions (serialized characters): gcc's time grows
# faster than linearly with the length of straight-line code (a 305-sample top-motion series:
# 1.6 MB of C, 39 s at -O2, 7 s at -O0), while small models gain 2x at run time from -O2
SIZE_FLAGS = ((400_000, "-O2"), (1_500_000, "-O1"), (float("inf"), "-O0"))


def compiler_command(size: int = 0) -> list[str]:
    """The compiler command and flags: ``CABLESYS_CC`` (default ``cc``) and ``CABLESYS_CFLAGS``
    (default by ``size``, the functions' serialized length: see ``SIZE_FLAGS``)."""
    cc = shlex.split(os.environ.get("CABLESYS_CC", "cc")) or ["cc"]
    default = next(flag for limit, flag in SIZE_FLAGS if size < limit)
    flags = shlex.split(os.environ.get("CABLESYS_CFLAGS", default))
    return cc + flags + ["-fPIC", "-shared"]


def _compiler_identity(cmd: list[str]) -> str | None:
    """First line of ``<cc> --version`` (part of the cache key); None when there is no compiler."""
    return _identity(tuple(cmd[:1]))


@functools.lru_cache(maxsize=8)
def _identity(cc: tuple) -> str | None:
    """Memoized per compiler command: asking the compiler costs a process start."""
    exe = shutil.which(cc[0])
    if exe is None:
        return None
    try:
        out = subprocess.run([exe, "--version"], capture_output=True, text=True, timeout=30, check=False)
    except (OSError, subprocess.SubprocessError):
        return None
    return f"{exe}|{(out.stdout or out.stderr).splitlines()[0] if (out.stdout or out.stderr) else ''}"


@contextlib.contextmanager
def _file_lock(path: Path):
    """An exclusive advisory lock on ``path`` (POSIX ``flock``; no-op where unavailable)."""
    try:
        import fcntl
    except ImportError:          # pragma: no cover (Windows): atomic rename still protects readers
        yield
        return
    with open(path, "a+") as fh:
        fcntl.flock(fh, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(fh, fcntl.LOCK_UN)


def state_jacobian(f: ca.Function, wrt) -> ca.Function:
    """``f.jacobian()``'s signature with only the blocks with respect to the inputs ``wrt``;
    every other block is declared structurally zero.

    What an integrator or a Newton solver asks of its residual is the state blocks (d/dx,
    d/dz); the full Jacobian also carries d/dp, whose size grows with the number of scene
    parameters (a 305-sample series: 610 columns, most of 1.6 MB of C, and every Jacobian
    evaluation paying for them). A library built this way must not be used for parameter
    sensitivities: those blocks read as zero.
    """
    J = f.jacobian()
    ins = [ca.SX.sym(name, J.sparsity_in(i)) for i, name in enumerate(J.name_in())]
    vals = f.call(ins[: f.n_in()])
    outs = []
    for k, name in enumerate(J.name_out()):          # jac_<output>_<input>
        o = next(o for o in f.name_out() if name.startswith(f"jac_{o}_"))
        i = name[len(f"jac_{o}_"):]
        if i in wrt:
            outs.append(ca.jacobian(vals[f.name_out().index(o)], ins[f.name_in().index(i)]))
        else:
            outs.append(ca.SX(J.sparsity_out(k).size1(), J.sparsity_out(k).size2()))
    return ca.Function(J.name(), ins, outs, J.name_in(), J.name_out())


def generate(functions, *, jacobians=True) -> str:
    """C source of ``functions`` and, when ``jacobians``, their Jacobians ``jac_<name>``
    (``True``: the full Jacobian; a tuple of input names: only those blocks, see
    :func:`state_jacobian`)."""
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
    hashing it costs ~1 ms where generating the C costs ~100 ms), whether Jacobians are
    included, the compiler identity, its flags and the cache format."""
    h = hashlib.sha256()
    for part in list(serialized) + [str(jacobians), ident, " ".join(cmd[1:]), str(CACHE_FORMAT)]:
        h.update(part.encode())
        h.update(b"\0")
    return h.hexdigest()[:24]


def _build(code: str, cmd: list[str], target: Path) -> None:
    """Compile ``code`` to ``target``: temporary files in the cache folder, then an atomic rename."""
    target.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(dir=target.parent, prefix=".build-") as tmp:
        src = Path(tmp) / "model.c"
        src.write_text(code)
        tmp_so = Path(tmp) / "model.so"
        proc = subprocess.run(cmd + [str(src), "-o", str(tmp_so), "-lm"], capture_output=True, text=True,
                              check=False)
        if proc.returncode != 0:
            raise RuntimeError(f"{' '.join(cmd)} failed: {(proc.stderr or proc.stdout).strip()[-500:]}")
        os.replace(tmp_so, target)


def compile_functions(functions, *, jacobians=True, enabled: bool = True) -> Compiled:
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

    Returns
    -------
    Compiled
        The functions (external when compiled), and the build and load times [s]. Without a C
        compiler, or when compilation fails, the original functions with one logged warning.
    """
    functions = list(functions)
    originals = {f.name(): f for f in functions}
    if not enabled or os.environ.get("CABLESYS_COMPILE", "1").strip() in ("0", "false", "no"):
        return Compiled(originals, False, False, 0.0, 0.0, note="compilation disabled")
    t0 = time.perf_counter()
    serialized = [f.serialize() for f in functions]
    cmd = compiler_command(sum(len(x) for x in serialized))
    ident = _compiler_identity(cmd)
    if ident is None:
        note = (f"no C compiler '{cmd[0]}' found: running the CasADi virtual machine (slower); "
                "install cc or set CABLESYS_CC")
        log.warning(note)
        return Compiled(originals, False, False, time.perf_counter() - t0, 0.0, note=note)
    key = cache_key(serialized, jacobians, ident, cmd)
    folder = cache_dir()
    target = folder / f"{key}.so"
    cached = target.exists()
    if not cached:
        try:
            folder.mkdir(parents=True, exist_ok=True)
            with _file_lock(folder / f"{key}.lock"):
                cached = target.exists()          # another process may have built it meanwhile
                if not cached:
                    _build(generate(functions, jacobians=jacobians), cmd, target)
        except (OSError, RuntimeError) as err:
            note = f"compilation failed ({err}): running the CasADi virtual machine (slower)"
            log.warning(note)
            return Compiled(originals, False, False, time.perf_counter() - t0, 0.0, note=note)
    t1 = time.perf_counter()
    loaded = {name: ca.external(name, str(target)) for name in originals}
    t2 = time.perf_counter()
    return Compiled(loaded, True, cached, t1 - t0, t2 - t1, library=target)
