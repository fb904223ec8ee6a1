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

A library that fails to load (truncated, corrupt, removed by another process's eviction) is
removed and rebuilt. Settings (environment): ``CABLESYS_CC`` the compiler command (default
``cc``), ``CABLESYS_CFLAGS`` its optimization flags (default ``-O2``, less for very large
functions: ``SIZE_FLAGS``), ``CABLESYS_COMPILE=0`` to use CasADi's virtual machine; the cache
folder and its cap: see :mod:`cablesys.disk_cache`. Without a working compiler the functions
run in the virtual machine and one warning says so.
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
import tempfile
import time
from pathlib import Path

import casadi as ca

from .disk_cache import (
    CACHE_FORMAT,
    atomic_write,
    cache_dir,
    digest,
    evict,
    file_lock,
    touch,
)

log = logging.getLogger(__name__)

__all__ = ["CACHE_FORMAT", "Compiled", "DerivedStore", "cache_dir", "compilation_enabled", "compile_functions",
           "compiler_command", "generate", "state_jacobian"]


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


def compilation_enabled(enabled: bool = True) -> bool:
    """False when ``enabled`` is False or ``CABLESYS_COMPILE`` is 0/false/no."""
    return enabled and os.environ.get("CABLESYS_COMPILE", "1").strip().lower() not in ("0", "false", "no")


# default optimization by size of the functions (serialized characters): gcc's time grows
# faster than linearly with the length of straight-line code (a 305-sample top-motion series:
# 1.6 MB of C, 39 s at -O2, 7 s at -O0), while small models gain 2x at run time from -O2
SIZE_FLAGS = ((400_000, "-O2"), (1_500_000, "-O1"), (float("inf"), "-O0"))
# generated C above this runs in the VM: the compiler's memory grows with the code (at -O0: 19 MB of C, the
# quasi-static segmented DAE at N = 20, took 3.5 GB; the 120 MB of a dense N = 20 Jacobian ran cc1 past 8 GB
# under a cap and past 22 GB without one, killed by the kernel)
MAX_C_BYTES = 40_000_000


def compiler_command(size: int = 0) -> list[str]:
    """The compiler command and flags: ``CABLESYS_CC`` (default ``cc``) and ``CABLESYS_CFLAGS``
    (default by ``size``, the functions' serialized length: see ``SIZE_FLAGS``)."""
    cc = shlex.split(os.environ.get("CABLESYS_CC", "cc")) or ["cc"]
    default = next(flag for limit, flag in SIZE_FLAGS if size < limit)
    flags = shlex.split(os.environ.get("CABLESYS_CFLAGS", default))
    return cc + flags + ["-fPIC", "-shared"]


def _compiler_identity(cmd: list[str]) -> str | None:
    """The compiler's path and first line of ``--version`` (part of the cache key); None when
    there is no compiler. Remembered per process and, on disk, per executable (path, size,
    modification time): asking the compiler costs a process start (~5 ms)."""
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
        known = json.loads(memo.read_text())
    except (OSError, ValueError):
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
        atomic_write(memo, json.dumps({**known, stamp: ident}).encode())
    return ident


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
    return digest(*serialized, jacobians, ident, " ".join(cmd[1:]), CACHE_FORMAT)[:24]


def _build(code: str, cmd: list[str], target: Path) -> None:
    """Compile ``code`` to ``target``: temporary files in the cache folder, then an atomic rename."""
    import subprocess
    target.parent.mkdir(parents=True, exist_ok=True)
    if len(code) > MAX_C_BYTES:
        raise RuntimeError(f"{len(code) / 1e6:.0f} MB of generated C, above the {MAX_C_BYTES / 1e6:.0f} MB a compiler "
                           "run is given (its memory grows with the code)")
    with tempfile.TemporaryDirectory(dir=target.parent, prefix=".build-") as tmp:
        src = Path(tmp) / "model.c"
        src.write_text(code)
        tmp_so = Path(tmp) / "model.so"
        proc = subprocess.run(cmd + [str(src), "-o", str(tmp_so), "-lm"], capture_output=True, text=True,
                              check=False)
        if proc.returncode != 0:
            raise RuntimeError(f"{' '.join(cmd)} failed: {(proc.stderr or proc.stdout).strip()[-500:]}")
        os.replace(tmp_so, target)


def _load(target: Path, names) -> dict:
    """``casadi.external`` of every name in the library ``target`` (RuntimeError when it does
    not load: truncated, corrupt, removed, or without one of the names)."""
    loaded = {name: ca.external(name, str(target)) for name in names}
    touch(target)
    return loaded


def compile_functions(functions, *, jacobians=True, enabled: bool = True, extra_c: str = "",
                      extra_names=(), size: int | None = None) -> Compiled:
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

    Returns
    -------
    Compiled
        The functions (external when compiled), and the build and load times [s]. Without a C
        compiler, or when compilation fails, the original functions with one logged warning.
        A cached library that does not load is removed and built again.
    """
    functions = list(functions)
    originals = {f.name(): f for f in functions}
    if not compilation_enabled(enabled):
        return Compiled(originals, False, False, 0.0, 0.0, note="compilation disabled")
    t0 = time.perf_counter()
    serialized = [f.serialize() for f in functions]
    cmd = compiler_command(sum(len(x) for x in serialized) if size is None else int(size))
    ident = _compiler_identity(cmd)
    if ident is None:
        note = (f"no C compiler '{cmd[0]}' found: running the CasADi virtual machine (slower); "
                "install cc or set CABLESYS_CC")
        log.warning(note)
        return Compiled(originals, False, False, time.perf_counter() - t0, 0.0, note=note)
    key = cache_key(serialized + ([extra_c] if extra_c else []), jacobians, ident, cmd)
    folder = cache_dir()
    target = folder / f"{key}.so"
    for attempt in (0, 1):
        cached = target.exists()
        if not cached:
            try:
                with file_lock(folder / f"{key}.lock"):
                    cached = target.exists()          # another process may have built it meanwhile
                    if not cached:
                        _build(generate(functions, jacobians=jacobians) + extra_c, cmd, target)
            except (OSError, RuntimeError) as err:
                note = f"compilation failed ({err}): running the CasADi virtual machine (slower)"
                log.warning(note)
                return Compiled(originals, False, False, time.perf_counter() - t0, 0.0, note=note)
            with contextlib.suppress(OSError):
                evict(keep=[target])
        t1 = time.perf_counter()
        try:
            loaded = _load(target, [*originals, *extra_names])
        except RuntimeError as err:
            if attempt:
                note = f"the compiled library {target} does not load ({err}): running the CasADi virtual machine"
                log.warning(note)
                return Compiled(originals, False, False, time.perf_counter() - t0, 0.0, note=note)
            log.warning("cached library %s does not load (%s): building it again", target.name,
                        str(err).strip().splitlines()[-1][:200] if str(err).strip() else "")
            with file_lock(folder / f"{key}.lock"), contextlib.suppress(OSError):
                target.unlink()
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
        settings = (os.environ.get("CABLESYS_CC", "cc"), os.environ.get("CABLESYS_CFLAGS", ""))
        return cache_dir() / "derived" / f"{digest(self.structure, key, *settings)}.json"

    def load(self, key: str) -> Compiled | None:
        """The compiled item stored under ``key``, or None (see the class docstring)."""
        if not compilation_enabled():
            return None
        path = self._path(key)
        try:
            entry = json.loads(path.read_text())
        except (OSError, ValueError):
            return None
        t0 = time.perf_counter()
        target = cache_dir() / entry.get("library", "")
        ident = _compiler_identity(compiler_command())
        if entry.get("key") != key or entry.get("compiler") != ident or not target.is_file():
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
            atomic_write(self._path(key), json.dumps(entry).encode())
