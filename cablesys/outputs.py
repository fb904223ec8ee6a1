"""Output folders of the ``cablesys`` sub-commands: checked first, written safely, with a manifest.

Every sub-command that writes files goes through :class:`OutputDir`:

- the location is checked *before* any computation (a file, or a place that cannot be
  created or written, is a :class:`~cablesys.errors.ParameterError` naming ``--out``);
- a folder that holds another scene's results (another scene hash in its manifest, or
  result files without a manifest) is refused unless ``overwrite=True`` (``--overwrite``);
- the manifest ``summary.json`` is written first with ``status: "running"`` and last with
  ``"success"``, ``"failed"`` or ``"interrupted"``, so a stale or partial set is recognisable;
- every file is written under a temporary name and renamed into place (``os.replace``);
- long time series are streamed (:class:`CsvStream`) so that a killed run leaves a readable prefix.
"""

from __future__ import annotations

import contextlib
import dataclasses
import datetime as _dt
import hashlib
import json
import os
from pathlib import Path
from typing import Self

from .atomic import CsvStream, atomic_path, atomic_write_text, json_dumps
from .errors import ParameterError

__all__ = ["MANIFEST", "STATUSES", "CsvStream", "OutputDir", "atomic_path", "atomic_write_text", "scene_hash"]

MANIFEST = "summary.json"
STATUSES = ("running", "success", "failed", "interrupted")


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


class OutputDir:
    """One sub-command's output folder: checked before work, manifest first and last, atomic files.

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
    body passed to :meth:`finish` (default ``success``).
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
        self.check()

    # -- before any work ------------------------------------------------------------------
    def check(self) -> None:
        """Refuse a location that cannot hold the results (raises ParameterError naming ``--out``).

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
        if p.is_dir() and not self.overwrite:
            old = self._read_manifest()
            if old is not None and old.get("command") != self.command:
                raise ParameterError("--out", str(p), f"holds results of `cablesys {old.get('command', '?')}` "
                                     f"(see its {MANIFEST})", "choose another folder or pass --overwrite")
            if old is not None and old.get("scene_hash") != self.hash:
                raise ParameterError("--out", str(p), f"holds results of another scene ({old.get('scene', '?')!s}, "
                                     f"scene hash {old.get('scene_hash')}; this scene {self.hash})",
                                     "choose another folder or pass --overwrite")
            if old is None:
                clash = [f for f in self.owned if (p / f).exists()]
                if clash:
                    raise ParameterError("--out", str(p), f"holds result files without a {MANIFEST} "
                                         f"({', '.join(clash)})", "choose another folder or pass --overwrite")

    def _read_manifest(self) -> dict | None:
        try:
            doc = json.loads((self.path / MANIFEST).read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return None
        return doc if isinstance(doc, dict) else {}

    # -- the manifest -----------------------------------------------------------------------
    def start(self, **info) -> Self:
        """Create the folder and write the manifest with ``status: "running"``.

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
        old = self._read_manifest() or {}
        stale = [*old.get("files", []), old.get("streaming"), *self.owned] if isinstance(old, dict) else list(self.owned)
        for name in {n for n in stale if isinstance(n, str) and n and "/" not in n and n != MANIFEST}:
            with contextlib.suppress(OSError):     # the previous set goes: no mix of old and new files
                (self.path / name).unlink()
        self.manifest = {"command": self.command, "status": "running", "scene_hash": self.hash,
                         "started": _now(), "pid": os.getpid(), **info, "files": []}
        self._write_manifest()
        return self

    def _write_manifest(self) -> None:
        self.manifest["files"] = list(self.files)
        atomic_write_text(self.path / MANIFEST, json_dumps(self.manifest, indent=2) + "\n")

    def finish(self, status: str = "success", **info) -> dict:
        """Write the manifest a last time with ``status`` and ``info`` (the run's summary...).

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
        self._write_manifest()
        return self.manifest

    def __enter__(self) -> Self:
        if not self.manifest:
            self.start()
        return self

    def __exit__(self, kind, err, tb) -> bool:
        if self.status is None:
            if kind is None:
                self.finish("success")
            elif issubclass(kind, KeyboardInterrupt):
                self.finish("interrupted", message="interrupted")
            else:
                self.finish("failed", message=f"{kind.__name__}: {err}")
        return False

    # -- files ------------------------------------------------------------------------------
    def file(self, name: str) -> Path:
        """Path of ``name`` in the folder, recorded in the manifest's file list.

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
        with atomic_path(self.file(name)) as tmp:
            yield tmp

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
        return atomic_write_text(self.file(name), text)

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
        stream = CsvStream(self.file(name), table)
        self.manifest["streaming"] = stream.partial.name
        self._write_manifest()
        return stream
