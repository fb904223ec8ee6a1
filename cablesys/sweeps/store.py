"""Finished cases on disk, and the labelled Dataset assembled from case records.

Every finished chunk of cases is written at once as its own netCDF-3 file (scipy backend:
no netCDF C library) under ``OUT/cases/``, first to a temporary name and then renamed, so a
file is either complete or absent. ``OUT/sweep.json`` holds a fingerprint of the sweep
(scene, analysis, options, grid, metrics): a later call with the same sweep and folder
reads the finished cases and computes only the missing ones; a different sweep in the
same folder is refused. The folder is checked as every sub-command's ``--out`` is
(:class:`cablesys.outputs.OutputDir`) and made before any case runs.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import logging
import os
import uuid
from pathlib import Path

import numpy as np

from ..errors import ParameterError
from ..outputs import OutputDir
from .metrics import metric_unit

log = logging.getLogger(__name__)
FIELDS = ("status", "message", "wall_s")


def fingerprint(spec) -> str:
    """A hash of what defines the sweep's cases and their numbers."""
    from ..scene import Scene, dump_scene
    scene = dump_scene(spec.scene) if isinstance(spec.scene, Scene) else repr(dataclasses.asdict(spec.scene))
    doc = {"scene": scene, "analysis": spec.analysis, "options": repr(sorted(spec.options.items())),
           "names": spec.grid.names, "values": repr(spec.grid.values), "metrics": spec.metrics}
    return hashlib.sha256(json.dumps(doc, sort_keys=True, default=repr).encode()).hexdigest()[:16]


class CaseStore:
    """The folder of a sweep: finished chunks (netCDF) and the sweep's fingerprint."""

    def __init__(self, out, spec):
        self.out = Path(out)
        self.cases_dir = self.out / "cases"
        self.key = fingerprint(spec)
        try:                                        # a file, an uncreatable or unwritable place, another command's folder
            OutputDir(self.out, "sweep", self.key)
        except ParameterError as err:               # (a sweep has no --overwrite: the hint is another folder)
            raise ParameterError(err.field, err.value, err.allowed, "choose another folder" if err.hint else "") from None
        try:
            self.cases_dir.mkdir(parents=True, exist_ok=True)
            self._claim(spec)
        except OSError as err:                      # what the check cannot see (a read-only file system, root)
            raise ParameterError("--out", str(self.out), f"cannot be written ({err.strerror or err})") from None

    def _claim(self, spec) -> None:
        """Write the sweep's fingerprint, or refuse a folder that holds another sweep."""
        meta = self.out / "sweep.json"
        if meta.exists():
            old = json.loads(meta.read_text()).get("fingerprint")
            if old != self.key:
                raise ParameterError("--out", str(self.out), "holds a different sweep (scene, analysis, options or "
                                                           "values differ): choose another folder or empty it")
        else:
            meta.write_text(json.dumps({"fingerprint": self.key, "analysis": spec.analysis,
                                        "vary": {n: list(v) for g, vs in zip(spec.grid.names, spec.grid.values)
                                                 for n, v in zip(g, vs)}}, indent=1))

    def finished(self) -> dict:
        """{case: record} of every readable chunk file."""
        import xarray as xr
        done = {}
        for f in sorted(self.cases_dir.glob("chunk-*.nc")):
            try:
                with xr.open_dataset(f, engine="scipy") as ds:
                    done.update({r["case"]: r for r in records_of(ds.load())})
            except Exception as err:  # noqa: BLE001 -- any damaged file (torn write, not netCDF): recompute its cases
                log.warning("ignoring unreadable %s (%s)", f, err)
        return done

    def write(self, records: list) -> Path:
        """Write one chunk of finished records atomically."""
        ds = chunk_dataset(records)
        path = self.cases_dir / f"chunk-{records[0]['case']:08d}-{uuid.uuid4().hex[:8]}.nc"
        tmp = path.with_suffix(".tmp")
        ds.to_netcdf(tmp, engine="scipy")
        os.replace(tmp, path)
        return path


def _columns(records: list) -> dict:
    names = {}
    for r in records:
        for k in r["metrics"]:
            names.setdefault(k, None)
    cols = {}
    for k in names:
        vals = [r["metrics"].get(k) for r in records]
        if any(isinstance(v, str) for v in vals):
            cols[k] = np.array(["" if v is None else str(v) for v in vals], dtype=object)
        else:
            cols[k] = np.array([np.nan if v is None else float(v) for v in vals], dtype=float)
    return cols


def chunk_dataset(records: list):
    """Records as a Dataset along ``case``."""
    import xarray as xr
    data = {"status": ("case", np.array([r["status"] for r in records], dtype=object)),
            "message": ("case", np.array([r["message"] for r in records], dtype=object)),
            "wall_s": ("case", np.array([r["wall_s"] for r in records], float))}
    data.update({f"m__{k}": ("case", v) for k, v in _columns(records).items()})
    return xr.Dataset(data, coords={"case": np.array([r["case"] for r in records], dtype=np.int64)})


def records_of(ds) -> list:
    """Inverse of :func:`chunk_dataset` (NaN and empty strings mean 'not computed')."""
    out = []
    metric_vars = [v for v in ds.data_vars if v.startswith("m__")]
    for i, k in enumerate(ds["case"].values):
        m = {}
        for v in metric_vars:
            x = ds[v].values[i]
            if isinstance(x, (bytes, np.bytes_)):
                x = x.decode()
            if isinstance(x, str):
                if x:
                    m[v[3:]] = x
            elif np.isfinite(x):
                m[v[3:]] = float(x)
        msg = ds["message"].values[i]
        st = ds["status"].values[i]
        out.append({"case": int(k), "status": st.decode() if isinstance(st, bytes) else str(st),
                    "message": msg.decode() if isinstance(msg, bytes) else str(msg),
                    "wall_s": float(ds["wall_s"].values[i]), "metrics": m})
    return out


def assemble(spec, records: dict, units: dict, attrs: dict, long_names: dict | None = None):
    """The sweep's Dataset: one dimension per varied name (zipped names share one), metrics, status, message;
    each coordinate with its SI ``units`` and ``long_name``."""
    import xarray as xr
    grid = spec.grid
    shape = grid.shape
    order = [records[k] for k in sorted(records)]
    cols = _columns(order) if order else {}
    idx = np.array(sorted(records), dtype=np.int64)
    dims = grid.dims

    def cube(values, fill, dtype):
        a = np.full(len(grid), fill, dtype=dtype)
        a[idx] = values
        return a.reshape(shape)

    data = {"status": (dims, cube(np.array([r["status"] for r in order], dtype=object), "missing", object),
                       {"doc": "ok | failed (analysis ran, did not succeed) | infeasible | error | missing"}),
            "message": (dims, cube(np.array([r["message"] for r in order], dtype=object), "", object)),
            "wall_s": (dims, cube(np.array([r["wall_s"] for r in order], float), np.nan, float), {"units": "s"})}
    for k, v in cols.items():
        if v.dtype == object:
            data[k] = (dims, cube(v, "", object))
        else:
            data[k] = (dims, cube(v, np.nan, float), {"units": metric_unit(k)})
    coords = {}
    for g, vs in zip(grid.names, grid.values):
        for j, (n, v) in enumerate(zip(g, vs)):
            arr = np.array(v, dtype=object if any(isinstance(x, str) for x in v) else float)
            coords[n] = (g[0], arr, {"units": units.get(n, ""), "long_name": (long_names or {}).get(n, n)})
    return xr.Dataset(data, coords=coords, attrs=attrs)


def write_csv(ds, path) -> Path:
    """The sweep as a CSV table, one row per case: ``name [unit]`` columns (the varied labels first), written
    atomically."""
    from ..atomic import atomic_write_text
    df = ds.to_dataframe()
    head = lambda n: f"{n} [{ds[n].attrs['units']}]" if ds[n].attrs.get("units", "-") not in ("", "-") else n  # noqa: E731
    df.index = df.index.set_names([head(n) for n in df.index.names])
    df = df.rename(columns={c: head(c) for c in df.columns})
    return atomic_write_text(Path(path), df.to_csv())
