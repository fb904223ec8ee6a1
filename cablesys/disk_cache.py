"""The on-disk cache folder: location, versioning, atomic writes, locks and a size cap.

What is cached: compiled model libraries (:mod:`cablesys.compiled`), the index that maps a
model structure and a derived function to its library, the compiler identities, the records
of code too large to compile, and the serialized CasADi functions of a model structure
(:mod:`cablesys.model.store`). Everything in it can be deleted at any
time; it is rebuilt on demand.

Settings (environment):

- ``CABLESYS_CACHE`` the folder (``CABLESYS_CACHE_DIR`` is read too, the former name);
  default ``~/.cache/cablesys``;
- ``CABLESYS_CACHE_MB`` its size cap in megabytes (default :data:`DEFAULT_CAP_MB`): after each
  new entry, the least recently used files (by modification time, refreshed at every use) are
  removed until the whole folder, all versions together, fits. Everything in the folder counts,
  builds in progress included. Both settings are checked at every use of the cache
  (:func:`cache_dir`), warm or cold: a bad value is a :class:`~cablesys.errors.ParameterError`.

Verified: every entry is *sealed* (:func:`seal`): a trailer holding the SHA-256 of its content,
written with it and checked before it is used (:func:`unseal`, :func:`sealed_problem`), so a
truncated or garbled file (a full disk, a killed copy, a fuzzer) is detected and rebuilt instead
of being handed to ``dlopen`` or the unpickler. The trailer follows the content, so a sealed
shared library is still a valid one (loaders ignore bytes past the end of the image).

Self-cleaning: a compiler run works in a ``.build-<key>-<pid>-*`` folder (:func:`build_folder`)
while holding the entry's lock; a folder whose lock is free and whose process is gone (a
``kill -9`` during a compile) is an orphan, removed by the next :func:`evict`, as are temporary
files and older build folders untouched for :data:`ORPHAN_AGE_S`.

Versioned: one sub-folder per cablesys version, CasADi version and cache format
(:data:`CACHE_FORMAT`), so an upgrade never reads an old entry. Safe under concurrent runs
(sweeps): every entry is written under a temporary name in its own folder and renamed into
place (``os.replace`` is atomic), so a reader sees the whole file or none; builders of one
entry are serialized by a per-entry file lock.
"""

from __future__ import annotations

import contextlib
import functools
import hashlib
import os
import re
import shutil
import tempfile
import time
from pathlib import Path

from . import __version__
from .atomic import atomic_path
from .errors import ParameterError

CACHE_FORMAT = 3          # bump when the layout of the cache or of an entry changes (3: sealed entries)
DEFAULT_CAP_MB = 500.0
# a temporary file or a build folder without a readable owner, untouched this long [s], is an orphan
ORPHAN_AGE_S = 3600.0
SEAL_MAGIC = b"CABLESYS-SHA256\0"          # the trailer: this, then the 32-byte SHA-256 of the content
SEAL_BYTES = len(SEAL_MAGIC) + 32


def cache_root() -> Path:
    """The cache folder holding every version: ``$CABLESYS_CACHE``, ``$CABLESYS_CACHE_DIR`` or
    ``~/.cache/cablesys``; a :class:`~cablesys.errors.ParameterError` when the setting names an
    existing file that is not a folder."""
    for name in ("CABLESYS_CACHE", "CABLESYS_CACHE_DIR"):
        base = os.environ.get(name)
        if base:
            path = Path(base).expanduser()
            if path.exists() and not path.is_dir():
                raise ParameterError(name, base, "must be a folder (or a path where one can be made), not a file")
            return path
    return Path(os.path.expanduser("~")) / ".cache" / "cablesys"


def cache_dir() -> Path:
    """The versioned folder of this cablesys, CasADi and cache format (not created here).

    Every use of the cache goes through here, so the settings are checked here, warm cache or
    cold: ``CABLESYS_CACHE`` (:func:`cache_root`) and ``CABLESYS_CACHE_MB`` (:func:`cap_bytes`).
    """
    import casadi as ca
    cap_bytes()
    return cache_root() / f"cablesys-{__version__}_casadi-{ca.__version__}_v{CACHE_FORMAT}"


def cap_bytes() -> int:
    """The size cap [bytes] from ``CABLESYS_CACHE_MB`` (default :data:`DEFAULT_CAP_MB`)."""
    text = os.environ.get("CABLESYS_CACHE_MB", "").strip()
    try:
        mb = float(text) if text else DEFAULT_CAP_MB
    except ValueError:
        mb = -1.0
    if not mb >= 0.0:
        raise ParameterError("CABLESYS_CACHE_MB", text, "must be a size in megabytes >= 0 (inf: no cap)")
    return int(min(mb * 1e6, 2.0 ** 62))


def seal(data: bytes) -> bytes:
    """``data`` followed by its trailer (:data:`SEAL_MAGIC` and the SHA-256 of ``data``)."""
    return data + SEAL_MAGIC + hashlib.sha256(data).digest()


def _seal_problem(blob: bytes) -> str | None:
    if len(blob) < SEAL_BYTES or blob[-SEAL_BYTES:-32] != SEAL_MAGIC:
        return f"no checksum trailer ({len(blob)} bytes: truncated or not written by this cache)"
    if hashlib.sha256(memoryview(blob)[:-SEAL_BYTES]).digest() != blob[-32:]:
        return "SHA-256 mismatch (garbled)"
    return None


def unseal(blob: bytes) -> bytes:
    """The content of a sealed ``blob`` (:func:`seal`); ValueError saying what is wrong when its
    trailer is missing or its SHA-256 does not match."""
    problem = _seal_problem(blob)
    if problem:
        raise ValueError(problem)
    return blob[:-SEAL_BYTES]


def sealed_problem(path: Path) -> str | None:
    """None when the file ``path`` is sealed and intact, else what is wrong with it (a missing
    file raises FileNotFoundError). Reads the whole file: the check before every ``dlopen``."""
    return _seal_problem(Path(path).read_bytes())


def seal_file(path: Path) -> None:
    """Append the trailer of :func:`seal` to the file ``path`` (written but not yet renamed into place)."""
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    with open(path, "ab") as fh:
        fh.write(SEAL_MAGIC + h.digest())


def write_sealed(target: Path, data: bytes) -> None:
    """:func:`atomic_write` of ``data`` sealed (:func:`seal`); read it back with :func:`read_sealed`."""
    atomic_write(target, seal(data))


def read_sealed(target: Path) -> bytes:
    """The content of the sealed file ``target`` (OSError when it cannot be read; ValueError,
    saying why, when it is truncated or garbled)."""
    return unseal(Path(target).read_bytes())


def digest(*parts) -> str:
    """A 32-hex-digit SHA-256 of ``parts`` (each turned to text, separated by NUL)."""
    h = hashlib.sha256()
    for part in parts:
        h.update(part if isinstance(part, bytes) else str(part).encode())
        h.update(b"\0")
    return h.hexdigest()[:32]


@functools.lru_cache(maxsize=1)
def code_fingerprint() -> str:
    """Fingerprint of the source files the cached functions are built from (paths, sizes and
    modification times of ``cablesys/model``, ``cablesys/time_domain``, ``cablesys/scene`` and the
    cache modules): an edit of any of them starts fresh cache entries, so a development tree
    never loads a function built by older code. Costs a few ``stat`` calls."""
    pkg = Path(__file__).resolve().parent
    files = [pkg / "compiled.py", pkg / "disk_cache.py"]
    for sub in ("model", "time_domain", "scene"):
        files += sorted((pkg / sub).glob("*.py"))
    parts = []
    for f in files:
        try:
            st = f.stat()
        except OSError:
            continue
        parts.append(f"{f.relative_to(pkg)}:{st.st_size}:{st.st_mtime_ns}")
    return digest(__version__, *parts)


@contextlib.contextmanager
def file_lock(path: Path, *, blocking: bool = True):
    """An exclusive advisory lock on ``path`` (POSIX ``flock``); yields False when
    ``blocking=False`` and another process holds it. A no-op where ``fcntl`` is missing (the
    atomic renames still protect readers)."""
    try:
        import fcntl
    except ImportError:          # pragma: no cover (Windows)
        yield True
        return
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "a+") as fh:
        try:
            fcntl.flock(fh, fcntl.LOCK_EX | (0 if blocking else fcntl.LOCK_NB))
        except BlockingIOError:
            yield False
            return
        try:
            yield True
        finally:
            fcntl.flock(fh, fcntl.LOCK_UN)


def atomic_write(target: Path, data: bytes) -> None:
    """Write ``data`` to ``target`` through a temporary file in the same folder and an atomic
    rename (:func:`cablesys.atomic.atomic_path`): concurrent readers see the old file, the new
    one, or none; never a part."""
    target.parent.mkdir(parents=True, exist_ok=True)
    with atomic_path(target) as tmp:
        tmp.write_bytes(data)


def touch(path: Path) -> None:
    """Mark ``path`` as just used (its modification time orders the eviction)."""
    with contextlib.suppress(OSError):
        os.utime(path)


_BUILD = re.compile(r"\.build-(?P<key>[0-9a-f]+)-(?P<pid>\d+)-")


@contextlib.contextmanager
def build_folder(parent: Path, key: str):
    """A fresh folder ``parent/.build-<key>-<pid>-*`` for the files of one build, removed when the
    block ends however it ends (an exception, Ctrl-C). Hold the lock ``parent/<key>.lock``
    (:func:`file_lock`) around it: a folder whose lock is free and whose process is gone is an
    orphan that :func:`evict` removes (:func:`orphaned`)."""
    parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".build-{key}-{os.getpid()}-", dir=parent))
    try:
        yield tmp
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def _pid_running(pid: int) -> bool:
    """Whether a process ``pid`` exists on this machine (POSIX signal 0 checks without sending;
    elsewhere ``os.kill`` would end the process, so it counts as running and age decides)."""
    if os.name != "posix":
        return True
    try:
        os.kill(pid, 0)
    except (ProcessLookupError, OverflowError):
        return False
    except PermissionError:          # another user's process
        return True
    return True


def orphaned(path: Path, now: float | None = None) -> bool:
    """Whether ``path``, a build folder or a temporary file in the cache, was left by a process
    that will not finish it.

    A build folder ``.build-<key>-<pid>-*`` (:func:`build_folder`) is an orphan when no process
    holds its entry's lock ``<key>.lock`` and either its process ``pid`` is gone or it is older
    than :data:`ORPHAN_AGE_S` (the lock alone could be a file that an eviction unlinked under a
    working builder). Anything else (a temporary ``.*.tmp*`` file of :func:`atomic_write`, a build
    folder of an older layout) is an orphan once untouched for :data:`ORPHAN_AGE_S`.
    """
    path = Path(path)
    now = time.time() if now is None else now
    try:
        old = now - path.stat().st_mtime > ORPHAN_AGE_S
    except OSError:
        return False
    m = _BUILD.match(path.name)
    if m is None or not path.is_dir():
        return old
    lock = path.parent / f"{m['key']}.lock"
    if lock.exists():
        with file_lock(lock, blocking=False) as free:
            if not free:
                return False
    return old or not _pid_running(int(m["pid"]))


def _tree_size(path: Path) -> int:
    total = 0
    for dirpath, _, filenames in os.walk(path):
        for name in filenames:
            with contextlib.suppress(OSError):
                total += os.lstat(os.path.join(dirpath, name)).st_size
    return total


def _temporary(name: str) -> bool:
    """A name :func:`atomic_write` or :func:`build_folder` writes under before the final rename."""
    return name.startswith(".build-") or (name.startswith(".") and ".tmp" in name)


def evict(cap: int | None = None, keep=()) -> list[Path]:
    """Remove orphans, then the least recently used cache files until the cache folder fits in
    ``cap`` bytes.

    Parameters
    ----------
    cap : int, optional
        Size cap [bytes]; default :func:`cap_bytes`.
    keep : iterable of Path
        Files never removed by this call (the entry just written).

    Returns
    -------
    list of Path
        What was removed: orphaned build folders and temporary files (:func:`orphaned`), whatever
        the cap, then entries by age of last use. Every byte under the cache root counts against
        the cap: entries of every version, lock files, and the build folders and temporary files
        being written (those are never removed while their writer may still finish them). When
        another process is evicting, nothing is done.
    """
    cap = cap_bytes() if cap is None else cap
    root = cache_root()
    if not root.is_dir():
        return []
    keep = {Path(k).resolve() for k in keep}
    removed = []
    with file_lock(root / ".evict.lock", blocking=False) as got:
        if not got:
            return []
        entries, total, now = [], 0, time.time()
        for dirpath, dirnames, filenames in os.walk(root):
            for name in [d for d in dirnames if d.startswith(".build-")]:
                dirnames.remove(name)
                path = Path(dirpath) / name
                size = _tree_size(path)
                if orphaned(path, now):
                    shutil.rmtree(path, ignore_errors=True)
                    if not path.exists():
                        removed.append(path)
                        continue
                total += size
            for name in filenames:
                path = Path(dirpath) / name
                try:
                    st = path.stat()
                except OSError:
                    continue
                if _temporary(name) and orphaned(path, now):
                    with contextlib.suppress(OSError):
                        path.unlink()
                        removed.append(path)
                        continue
                total += st.st_size
                if not (name.startswith(".") or name.endswith(".lock") or path.resolve() in keep):
                    entries.append((st.st_mtime, st.st_size, path))
        for _, size, path in sorted(entries, key=lambda e: e[0]):
            if total <= cap:
                break
            with contextlib.suppress(OSError):
                path.unlink()
                total -= size
                removed.append(path)
            with contextlib.suppress(OSError):   # its build lock (a racing builder at worst builds twice: atomic)
                path.with_suffix(".lock").unlink()
    return removed
