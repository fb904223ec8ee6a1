"""Output folders of the ``cablesys`` sub-commands: checked first, written safely, with a manifest.

Every sub-command that writes files goes through :class:`OutputDir`:

- the location is checked *before* any computation (a file, or a place that cannot be
  created or written, is a :class:`~cablesys.errors.ParameterError` naming ``--out``);
- one writer at a time: the folder is locked (``fcntl.flock`` on :data:`LOCK`) from the check to
  :meth:`OutputDir.finish`; a second writer gets a ParameterError at once, naming the first;
- a folder that holds another scene's results (another scene hash in its manifest, or
  result files without a manifest) is refused unless ``overwrite=True`` (``--overwrite``);
- the manifest ``summary.json`` is written first with ``status: "running"`` and last with
  ``"success"``, ``"failed"`` or ``"interrupted"``; a ``running`` manifest whose writer holds no
  lock is a killed run's incomplete set (:func:`folder_state` says ``"killed"``), which a run of
  the same scene replaces (with a logged warning) and another scene only with ``--overwrite``;
- every file is written under a temporary name and renamed into place (``os.replace``), and the
  manifest lists only files that exist;
- long time series are streamed (:class:`CsvStream`) so that a killed run leaves a readable prefix;
- a write that fails (full disk...) raises :class:`~cablesys.atomic.OutputWriteError`; the final
  manifest is still written (in place of the running one, which reserves room for it, when the
  disk is full) or the error says why it could not be.
"""

from __future__ import annotations

import contextlib
import dataclasses
import datetime as _dt
import hashlib
import json
import logging
import os
from pathlib import Path
from typing import Self

from .atomic import (
    INTERRUPTS,
    CsvStream,
    OutputWriteError,
    atomic_path,
    atomic_write_text,
    interrupts_deferred,
    json_dumps,
)
from .errors import ParameterError

__all__ = ["LOCK", "MANIFEST", "STATUSES", "CsvStream", "OutputDir", "OutputWriteError", "atomic_path",
           "atomic_write_text", "folder_state", "scene_hash"]

log = logging.getLogger(__name__)

MANIFEST = "summary.json"
LOCK = ".cablesys.lock"
STATUSES = ("running", "success", "failed", "interrupted")
RESERVE_BYTES = 4096          # the running manifest is padded to this size: room for a final one on a full disk


def scene_hash(obj) -> str:
    """A short stable hash of a scene (any frozen dataclass, dict, or text) for the manifest.

    Parameters
    ----------
    obj : dataclass, dict, str or bytes
        The input that determines the results.

    Returns
    -------
    str
        16 hex digits of the SHA-256 of its canonical JSON form.
    """
    if isinstance(obj, bytes):
        data = obj
    else:
        if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
            obj = dataclasses.asdict(obj)
        data = json_dumps(obj, sort_keys=True).encode()
    return hashlib.sha256(data).hexdigest()[:16]


def _now() -> str:
    return _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds")


def _pid_alive(pid) -> bool:
    """Whether process ``pid`` exists on this machine."""
    try:
        os.kill(int(pid), 0)
    except (ProcessLookupError, ValueError, TypeError, OverflowError):
        return False
    except PermissionError:            # exists, owned by another user
        return True
    return True


def _read_json(path: Path) -> dict | None:
    try:
        doc = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return doc if isinstance(doc, dict) else {}


def _try_lock(folder: Path):
    """An open file holding the exclusive lock of ``folder`` (:data:`LOCK`), or None when another
    process holds it. Raises OutputWriteError when the lock file cannot be created."""
    import fcntl
    try:
        fd = os.open(folder / LOCK, os.O_RDWR | os.O_CREAT, 0o666)
    except OSError as err:
        raise OutputWriteError(folder / LOCK, err) from None
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        os.close(fd)
        return None
    return fd


def folder_state(path) -> dict | None:
    """The manifest of an output folder with its status as it stands now, or None without one.

    A ``running`` manifest whose writer holds no lock on the folder (killed: SIGKILL, power loss,
    or a final manifest the disk could not take) is returned with ``status: "killed"``,
    ``killed: True`` and ``recorded_status: "running"``.

    Parameters
    ----------
    path : str or Path
        The folder.

    Returns
    -------
    dict or None
    """
    folder = Path(path)
    doc = _read_json(folder / MANIFEST)
    if doc is None or doc.get("status") != "running":
        return doc
    fd = _try_lock(folder) if folder.is_dir() else None
    if fd is None:                      # a live writer holds the lock
        return doc
    os.close(fd)
    return {**doc, "status": "killed", "killed": True, "recorded_status": "running"}


def _killed_note(doc: dict) -> str:
    pid = doc.get("pid")
    gone = "no longer runs" if not _pid_alive(pid) else "holds no lock on the folder"
    return (f"an incomplete set of a killed run (its {MANIFEST} says running; pid {pid} {gone}; "
            f"started {doc.get('started', '?')})")


class OutputDir:
    """One sub-command's output folder: locked, checked before work, manifest first and last, atomic files.

    Parameters
    ----------
    path : str or Path
        The folder (``--out``).
    command : str
        Sub-command name, stored in the manifest.
    scene : object
        What determines the results (a scene dataclass, dict or text); its :func:`scene_hash`
        goes into the manifest and guards against overwriting another scene's results.
    overwrite : bool
        Allow replacing results of another scene.
    owned : iterable of str
        File names this command writes (a folder holding any of them without a manifest
        is refused unless ``overwrite``).

    Notes
    -----
    Use as a context manager around the computation: on leaving, the manifest is finished
    as ``interrupted`` (KeyboardInterrupt), ``failed`` (any other exception) or by what the
    body passed to :meth:`finish` (default ``success``). The folder's lock is held from the check
    (or :meth:`start`, for a folder made then) to :meth:`finish`.
    """

    def __init__(self, path, command: str, scene, *, overwrite: bool = False, owned=()):
        self.path = Path(path)
        self.command = command
        self.hash = scene_hash(scene)
        self.overwrite = bool(overwrite)
        self.owned = tuple(owned)
        self.files: list[str] = []
        self.manifest: dict = {}
        self.status = None
        self.replaced_killed: dict | None = None     # the killed run's manifest this run replaces
        self._lock = None
        self._streams: list[CsvStream] = []
        try:
            self.check()
        except BaseException:
            self._release_lock()
            raise

    def __del__(self):
        self._release_lock()

    # -- before any work ------------------------------------------------------------------
    def check(self) -> None:
        """Refuse a location that cannot hold the results (raises ParameterError naming ``--out``).

        Takes the folder's lock when the folder exists (a folder being written by another
        process is refused here, before any computation).

        Returns
        -------
        None
        """
        p = self.path
        if p.exists() and not p.is_dir():
            raise ParameterError("--out", str(p), "is an existing file; give a folder")
        probe = p
        while not probe.exists():
            if probe.parent == probe:
                break
            probe = probe.parent
        if not probe.is_dir():
            raise ParameterError("--out", str(p), f"cannot be created: {probe} is a file")
        if not os.access(probe, os.W_OK | os.X_OK):
            raise ParameterError("--out", str(p), f"is not writable ({probe} does not allow writing)")
        if p.is_dir():
            self._take_lock()
        old = self._read_manifest() if p.is_dir() else None
        killed = old is not None and old.get("status") == "running"     # we hold the lock: its writer is gone
        if killed:
            self.replaced_killed = old
        if p.is_dir() and not self.overwrite:
            what = f"{_killed_note(old)}, of" if killed else "results of"
            if old is not None and old.get("command") != self.command:
                raise ParameterError("--out", str(p), f"holds {what} `cablesys {old.get('command', '?')}` "
                                     f"(see its {MANIFEST})", "choose another folder or pass --overwrite")
            if old is not None and old.get("scene_hash") != self.hash:
                raise ParameterError("--out", str(p), f"holds {what} another scene ({old.get('scene', '?')!s}, "
                                     f"scene hash {old.get('scene_hash')}; this scene {self.hash})",
                                     "choose another folder or pass --overwrite")
            if old is None:
                clash = [f for f in self.owned if (p / f).exists()]
                if clash:
                    raise ParameterError("--out", str(p), f"holds result files without a {MANIFEST} "
                                         f"({', '.join(clash)})", "choose another folder or pass --overwrite")

    def _take_lock(self) -> None:
        """Hold the folder's lock, or raise ParameterError naming the writer that holds it."""
        if self._lock is not None:
            return
        fd = _try_lock(self.path)
        if fd is None:
            who = _read_json(self.path / LOCK) or {}
            raise ParameterError("--out", str(self.path),
                                 f"is being written by another cablesys run (pid {who.get('pid', '?')}, "
                                 f"`cablesys {who.get('command', '?')}` started {who.get('started', '?')})",
                                 "wait for it to finish or choose another folder")
        self._lock = fd
        with contextlib.suppress(OSError):        # who holds it, for the message above (best effort)
            text = json_dumps({"pid": os.getpid(), "command": self.command, "started": _now()}).encode()
            os.ftruncate(fd, 0)
            os.pwrite(fd, text, 0)

    def _release_lock(self) -> None:
        if self._lock is not None:
            with contextlib.suppress(OSError):
                os.close(self._lock)           # closing drops the flock
            self._lock = None

    def _read_manifest(self) -> dict | None:
        return _read_json(self.path / MANIFEST)

    # -- the manifest -----------------------------------------------------------------------
    def start(self, **info) -> Self:
        """Create and lock the folder and write the manifest with ``status: "running"``.

        Parameters
        ----------
        **info
            JSON-able entries (scene name, options) for the manifest.

        Returns
        -------
        OutputDir
            ``self``.
        """
        try:
            self.path.mkdir(parents=True, exist_ok=True)
        except OSError as err:
            raise ParameterError("--out", str(self.path), f"cannot be created ({err.strerror})") from None
        self._take_lock()
        if self.replaced_killed is not None:
            log.warning("%s held %s; it is replaced", self.path, _killed_note(self.replaced_killed))
        old = self._read_manifest() or {}
        stale = [*old.get("files", []), old.get("streaming"), *self.owned] if isinstance(old, dict) else list(self.owned)
        for name in {n for n in stale if isinstance(n, str) and n and "/" not in n and n not in (MANIFEST, LOCK)}:
            with contextlib.suppress(OSError):     # the previous set goes: no mix of old and new files
                (self.path / name).unlink()
        self.manifest = {"command": self.command, "status": "running", "scene_hash": self.hash,
                         "started": _now(), "pid": os.getpid(), **info, "files": []}
        if self.replaced_killed is not None:
            self.manifest["replaces_killed_run"] = {k: self.replaced_killed.get(k) for k in ("pid", "started", "scene")}
        self._write_manifest()
        return self

    def _existing(self) -> list[str]:
        return [f for f in self.files if (self.path / f).exists()]

    def _write_manifest(self) -> None:
        self.manifest["files"] = self._existing()
        text = json_dumps(self.manifest, indent=2) + "\n"
        if self.manifest.get("status") == "running":          # room for a final manifest on a full disk
            text += " " * max(0, RESERVE_BYTES - len(text.encode()))
        atomic_write_text(self.path / MANIFEST, text)

    def _write_manifest_in_place(self, why: OutputWriteError) -> None:
        """The final manifest, compact, over the running one's reserved bytes (no new disk blocks)."""
        keep = ("command", "status", "scene_hash", "scene", "started", "finished", "pid", "files", "streaming",
                "message", "success", "t_end_s")
        doc = {k: self.manifest[k] for k in keep if k in self.manifest}
        doc["summary_incomplete"] = f"the full summary could not be written: {why}"
        data = json_dumps(doc).encode() + b"\n"
        target = self.path / MANIFEST
        with interrupts_deferred():
            fd = os.open(target, os.O_WRONLY)
            try:
                size = os.fstat(fd).st_size
                if len(data) > size:
                    raise OutputWriteError(target, why, note="no room for even a short final manifest")
                os.pwrite(fd, data + b" " * (size - len(data)), 0)   # the old length: no new blocks needed
            finally:
                os.close(fd)

    def finish(self, status: str = "success", **info) -> dict:
        """Write the manifest a last time with ``status`` and ``info`` (the run's summary...) and
        release the folder's lock.

        On a full disk the final manifest goes, compact, over the running one's reserved bytes;
        when even that fails, :class:`~cablesys.atomic.OutputWriteError` says that ``summary.json``
        still says ``running`` (:func:`folder_state` then reports the set as killed).

        Parameters
        ----------
        status : str
            One of ``success``, ``failed``, ``interrupted``.
        **info
            Entries added to the manifest.

        Returns
        -------
        dict
            The manifest written.
        """
        if status not in STATUSES[1:]:
            raise ValueError(f"status must be one of {STATUSES[1:]}, not {status!r}")
        self.status = status
        self.manifest.update(info)
        partial = self.manifest.get("streaming")
        if partial and not (self.path / partial).exists():
            del self.manifest["streaming"]
        self.manifest.update(status=status, finished=_now())
        self.files = self._existing()
        try:
            with interrupts_deferred():
                try:
                    self._write_manifest()
                except OutputWriteError as err:
                    try:
                        self._write_manifest_in_place(err)
                    except OSError as again:
                        raise OutputWriteError(self.path / MANIFEST, err,
                                               note=f"it still says running ({again.strerror or again})") from None
        finally:
            self._release_lock()
        return self.manifest

    def __enter__(self) -> Self:
        if not self.manifest:
            self.start()
        return self

    def __exit__(self, kind, err, tb) -> bool:
        if self.status is None:
            if kind is None:
                self.finish("success")
                return False
            kept = self._close_streams()
            if issubclass(kind, KeyboardInterrupt):
                status = "interrupted"
                message = f"interrupted by {INTERRUPTS.names[-1]}" if INTERRUPTS.names else "interrupted"
                if not kept and not self._existing():
                    message += "; no results were kept"
            else:
                status, message = "failed", (str(err) if isinstance(err, OutputWriteError) else f"{kind.__name__}: {err}")
            if kept and kept not in message:
                message += f"; {kept}"
            try:
                self.finish(status, message=message)
            except OutputWriteError as again:       # the body's error goes on; this one is told
                log.error("%s", again)
        self._release_lock()
        return False

    def _close_streams(self) -> str:
        """Rename the open streams to their final names (the whole rows written); what they hold."""
        notes = []
        for stream in self._streams:
            if stream.rows and stream._fh is not None:
                with contextlib.suppress(OSError):
                    stream.close()
                    self.file(stream.path.name)
                notes.append(stream.kept())
        return "; ".join(notes)

    # -- files ------------------------------------------------------------------------------
    def file(self, name: str) -> Path:
        """Path of ``name`` in the folder, to be listed in the manifest once it exists.

        Parameters
        ----------
        name : str
            File name.

        Returns
        -------
        Path
        """
        if name not in self.files:
            self.files.append(name)
        return self.path / name

    @contextlib.contextmanager
    def writing(self, name: str):
        """Context manager: a temporary path, renamed to ``name`` when the block succeeds.

        Parameters
        ----------
        name : str
            Final file name in the folder.

        Returns
        -------
        contextmanager
            Yields the temporary path to write.
        """
        with atomic_path(self.path / name) as tmp:
            yield tmp
        self.file(name)

    def write_text(self, name: str, text: str) -> Path:
        """Write a text file atomically.

        Parameters
        ----------
        name : str
            File name.
        text : str
            Content.

        Returns
        -------
        Path
        """
        path = atomic_write_text(self.path / name, text)
        self.file(name)
        return path

    def write_json(self, name: str, doc) -> Path:
        """Write a JSON document atomically (numpy values converted).

        Parameters
        ----------
        name : str
            File name.
        doc : object
            JSON-able (numpy values are converted).

        Returns
        -------
        Path
        """
        return self.write_text(name, json_dumps(doc, indent=2) + "\n")

    def stream_csv(self, name: str, table=None) -> CsvStream:
        """A :class:`CsvStream` for ``name`` (written as ``<stem>.partial.csv`` until closed).

        Parameters
        ----------
        name : str
            Final file name.
        table : callable, optional
            ``table(time, data) -> (header, rows)`` for each block (e.g. converted units).

        Returns
        -------
        CsvStream
        """
        stream = CsvStream(self.file(name), table)    # listed once closed under its name
        self._streams.append(stream)
        self.manifest["streaming"] = stream.partial.name
        self._write_manifest()
        return stream
