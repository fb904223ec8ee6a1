"""The on-disk cache folder: location, versioning, atomic writes, locks and a size cap.

What is cached: compiled model libraries (:mod:`cablesys.compiled`), the index that maps a
model structure and a derived function to its library, and the serialized CasADi functions
of a model structure (:mod:`cablesys.model.store`). Everything in it can be deleted at any
time; it is rebuilt on demand.

Settings (environment):

- ``CABLESYS_CACHE`` the folder (``CABLESYS_CACHE_DIR`` is read too, the former name);
  default ``~/.cache/cablesys``;
- ``CABLESYS_CACHE_MB`` its size cap in megabytes (default :data:`DEFAULT_CAP_MB`): after each
  new entry, the least recently used files (by modification time, refreshed at every use) are
  removed until the whole folder, all versions together, fits.

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
from pathlib import Path

from . import __version__
from .atomic import atomic_path
from .errors import ParameterError

CACHE_FORMAT = 2          # bump when the layout of the cache or of an entry changes
DEFAULT_CAP_MB = 500.0


def cache_root() -> Path:
    """The cache folder holding every version: ``$CABLESYS_CACHE``, ``$CABLESYS_CACHE_DIR`` or
    ``~/.cache/cablesys``."""
    base = os.environ.get("CABLESYS_CACHE") or os.environ.get("CABLESYS_CACHE_DIR")
    return Path(base) if base else Path(os.path.expanduser("~")) / ".cache" / "cablesys"


def cache_dir() -> Path:
    """The versioned folder of this cablesys, CasADi and cache format (not created here)."""
    import casadi as ca
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
    never loads a function built by older code. Costs a few ``stat`` calls (< 1 ms)."""
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


def evict(cap: int | None = None, keep=()) -> list[Path]:
    """Remove the least recently used cache files until the cache folder fits in ``cap`` bytes.

    Parameters
    ----------
    cap : int, optional
        Size cap [bytes]; default :func:`cap_bytes`.
    keep : iterable of Path
        Files never removed by this call (the entry just written).

    Returns
    -------
    list of Path
        The files removed. Files being written (temporary names, ``.build-`` folders) and lock
        files are never removed; when another process is evicting, nothing is done.
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
        entries, total = [], 0
        for dirpath, dirnames, filenames in os.walk(root):
            dirnames[:] = [d for d in dirnames if not d.startswith(".build-")]
            for name in filenames:
                path = Path(dirpath) / name
                try:
                    st = path.stat()
                except OSError:
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
