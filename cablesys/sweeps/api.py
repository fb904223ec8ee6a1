"""``sweep(scene, vary=..., analysis=...)``: many cases of one analysis, as one labelled Dataset."""

from __future__ import annotations

import logging
import time

from ..errors import ParameterError
from . import backends
from .analyses import ANALYSES, SCENES, analyses_text
from .grid import Grid
from .store import CaseStore, assemble
from .values import check_labels, check_values, long_name_of_label, unit_of_label
from .worker import SweepSpec

log = logging.getLogger(__name__)


class SweepInterrupted(KeyboardInterrupt):
    """A sweep stopped by Ctrl-C or SIGTERM: ``dataset`` holds the cases that finished (the others have
    status ``missing``), ``n_finished`` of ``n_cases``; with ``out`` they are on disk, and calling the same
    sweep again computes only the rest."""

    def __init__(self, dataset, out=None):
        self.dataset, self.out = dataset, out
        self.n_cases = int(dataset.attrs["n_cases"])
        self.n_finished = int((dataset["status"] != "missing").sum())
        kept = f"kept in {out}/cases/; the same sweep again computes the other {self.n_cases - self.n_finished}" \
            if out is not None else "not stored (no out folder)"
        super().__init__(f"{self.n_finished} of {self.n_cases} cases finished, {kept}")


def sweep(scene, vary: dict, analysis: str = "run", *, metrics=None, zip=False, options: dict | None = None,
          out=None, workers: int | None = None, scheduler=None, chunk_size: int | None = None,
          progress: bool = True, retry_failed: bool = False):
    """Run ``analysis`` for every combination of the values in ``vary``; one labelled Dataset back.

    Parameters
    ----------
    scene : Scene, SlackScene or TowedScene
        The base scene, of the kind its analysis takes; each case replaces the varied values (SI)
        and is validated again.
    vary : dict
        {label: values}. Labels of the parameter vector (``cable.ae``, ``sections[1].body.weight``,
        ``top_motion.y[0].frequency``, ``environment.current_speeds[0]``), other scene fields
        (``numerics.drag_segments``: a model per structure; a slack scene's ``span``, ``cable.ae``,
        ``masses[0].mass``; a towed scene's ``speed``, ``cable.cd_normal``), or options of the analysis
        (``stochastic.hs``, ``stochastic.tp``, ``design.hs``, ``run.periods``, ``slack.solver``).
    analysis : str
        One of the registry :data:`cablesys.sweeps.analyses.ANALYSES`: {analyses}.
    metrics : list of str, optional
        Glob patterns of the metric names to keep (``["tension_*", "amplitude_x_b"]``); default all
        numbers and strings of the result's ``summary()`` (flattened, see :mod:`.metrics`).
    zip : bool or list of tuples
        False: outer product, one dimension per label. True: all lists in step (one dimension).
        A list of label groups: each group advances in step, groups and other labels are crossed.
    options : dict, optional
        Analysis options: run ``model`` (None: as built; "auto" or a rung: the model ladder), ``periods``;
        rao ``omega_max``, ``n_omega``; periodic ``n_harmonics``; stochastic ``hs``, ``tp``, ``gamma``,
        ``direction``; design ``settings``; ladder ``tolerance``; slack ``solver``; towed none.
    out : path, optional
        Folder for finished cases (netCDF per chunk, written as they finish) and ``sweep.nc``.
        Calling again with the same sweep and folder computes only the missing cases. Checked before
        any case runs (:class:`cablesys.outputs.OutputDir`: not a file, creatable, writable).
    workers : int, optional
        Local processes (default: all cores of this machine; 1 runs in this process).
    scheduler : distributed.Client or str, optional
        Run on a Dask cluster (a client or a scheduler address) instead of local processes.
    chunk_size : int, optional
        Cases per task (default: about 8 tasks per worker, at most 64 cases each).
    progress : bool
        A tqdm progress bar (terminal or Jupyter).
    retry_failed : bool
        With ``out``: compute again the stored cases whose status is not ``ok``.

    Returns
    -------
    xarray.Dataset
        Dimensions: one per varied label (zipped labels share the first one's); coordinates with
        SI ``units`` and a ``long_name`` in attributes; variables: the metrics, ``status``, ``message``,
        ``wall_s``. Attributes: ``analysis``, ``n_cases``, ``n_computed`` (this call), ``n_ok``, ``wall_s``,
        ``backend``.

    Raises
    ------
    ParameterError
        Before any case runs: a scene of another kind than the analysis takes, an unknown option of a
        slack or towed analysis, an unknown or repeated label, an entry of the wrong type for its label
        (text for a number, a fraction for an integer), an ``out`` that is a file or cannot be written.
    SweepInterrupted
        (a KeyboardInterrupt) on Ctrl-C or SIGTERM: the workers are stopped, the finished cases are on
        disk (with ``out``) and in the exception's ``dataset``.
    """
    if analysis not in ANALYSES:
        raise ParameterError("analysis", analysis, f"must be one of {tuple(ANALYSES)}")
    kind = SCENES[ANALYSES[analysis].scene]
    if not isinstance(scene, kind.cls):
        raise ParameterError("scene", type(scene).__name__, f"the {analysis} analysis takes {kind.text}")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise ParameterError("workers", workers, "must be an integer >= 1")
    grid = Grid.build(vary, zip)
    check_options(analysis, options, grid.all_names)
    check_labels(scene, grid.all_names, analysis)
    check_values(scene, grid, analysis)
    patterns = None if metrics is None else tuple([metrics] if isinstance(metrics, str) else metrics)
    spec = SweepSpec(scene=scene, analysis=analysis, grid=grid, options=dict(options or {}), metrics=patterns)
    t0 = time.perf_counter()
    store = CaseStore(out, spec) if out is not None else None      # the folder checked (and made) before any case
    records = store.finished() if store else {}
    if retry_failed:
        records = {k: r for k, r in records.items() if r["status"] == "ok"}
    todo = [k for k in range(len(grid)) if k not in records]
    n_workers = 1 if scheduler is not None else (workers or backends.local_cores())
    parts = backends.chunks(todo, n_workers if scheduler is None else 16, chunk_size)
    if scheduler is not None:
        backend, stream = "dask", backends.run_dask(spec, parts, scheduler)
    elif n_workers == 1 or len(parts) <= 1:
        backend, stream = "serial", backends.run_serial(spec, parts)
    else:
        backend, stream = "processes", backends.run_processes(spec, parts, min(n_workers, len(parts)))
    bar = _bar(len(todo), f"sweep {analysis}", progress)
    interrupted = False
    try:
        for _, recs in stream:
            keep = [r for r in recs if not r.pop("transient", False)]
            if store and keep:
                store.write(keep)
            records.update({r["case"]: r for r in recs})
            bar.update(len(recs))
            bad = sum(r["status"] != "ok" for r in recs)
            if bad:
                bar.set_postfix(not_ok=sum(r["status"] != "ok" for r in records.values()))
    except KeyboardInterrupt:
        interrupted = True
        stream.close()                   # workers killed; the chunks written so far stay
    finally:
        bar.close()
    units = {n: unit_of_label(scene, n, analysis) for n in grid.all_names}
    long_names = {n: long_name_of_label(scene, n, analysis) for n in grid.all_names}
    n_ok = sum(r["status"] == "ok" for r in records.values())
    attrs = {"analysis": analysis, "scene": getattr(scene, "name", type(scene).__name__), "n_cases": len(grid), "n_computed": len(todo),
             "n_ok": n_ok, "wall_s": time.perf_counter() - t0, "backend": backend,
             "workers": n_workers if scheduler is None else -1, "options": repr(sorted((options or {}).items()))}
    ds = assemble(spec, records, units, attrs, long_names)
    if interrupted:
        raise SweepInterrupted(ds, store.out if store else None)
    if store:
        ds.to_netcdf(store.out / "sweep.nc", engine="scipy")
    return ds


sweep.__doc__ = sweep.__doc__.replace("{analyses}", analyses_text())


def check_options(analysis: str, options: dict | None, labels) -> None:
    """Refuse an option the analysis does not read (given in ``options`` or varied as ``<analysis>.<name>``), for
    the analyses whose options the registry lists."""
    known = ANALYSES[analysis].options
    if known is None:
        return
    given = list(options or {}) + [n.split(".", 1)[1] for n in labels if n.split(".", 1)[0] == analysis and "." in n]
    for name in given:
        if name not in known:
            raise ParameterError(f"options[{name!r}]", (options or {}).get(name),
                                 f"is not an option of the {analysis} analysis; its options: {list(known) or 'none'}")


def _bar(total: int, desc: str, enabled: bool):
    """tqdm's bar: its notebook form (``tqdm.auto``) only where ipywidgets can draw it (without them tqdm.auto
    warns "IProgress not found" on import), else the text bar."""
    import importlib.util
    if enabled and importlib.util.find_spec("ipywidgets") is not None:
        from tqdm.auto import tqdm
    else:
        from tqdm import tqdm
    return tqdm(total=total, desc=desc, unit="case", disable=not enabled or total == 0, leave=True)
