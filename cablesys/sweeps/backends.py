"""Where chunks of cases run: this process, a local process pool, or a Dask cluster.

All three call :func:`.worker.run_chunk` and hand back each chunk's records as soon as it
finishes, so the caller writes it to disk and advances the progress bar. Local workers are
forked where the platform can (a script without a ``__main__`` guard and a notebook both
work, and no worker imports the package again) and spawned elsewhere; the pool is made
before any model is built in the workers, each of which builds its models once and keeps
them for every later chunk. Dask is imported only when asked for.
"""

from __future__ import annotations

import concurrent.futures as cf
import multiprocessing
import os

from .worker import process_cache, run_case, run_chunk


def local_cores() -> int:
    """Cores this process may use."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:      # pragma: no cover (macOS, Windows)
        return os.cpu_count() or 1


def chunks(cases: list, n_workers: int, chunk_size: int | None) -> list:
    """Split ``cases`` into chunks: about 8 per worker (load balance), at most 64 cases each."""
    if chunk_size is None:
        chunk_size = max(1, min(64, -(-len(cases) // (8 * max(1, n_workers)))))
    return [cases[i:i + chunk_size] for i in range(0, len(cases), chunk_size)]


def run_serial(spec, parts):
    """In this process (its model cache persists across calls)."""
    cache = process_cache()
    for part in parts:
        if spec.analysis == "rao":          # one mapped linearization per chunk
            yield part, run_chunk(spec, part)
        else:
            yield part, [run_case(spec, int(k), cache) for k in part]


def run_processes(spec, parts, n_workers: int):
    """On a pool of ``n_workers`` local processes; a crashed worker fails only its chunks."""
    methods = multiprocessing.get_all_start_methods()
    ctx = multiprocessing.get_context("fork" if "fork" in methods else "spawn")
    pool = cf.ProcessPoolExecutor(max_workers=n_workers, mp_context=ctx)
    try:
        futures = {pool.submit(run_chunk, spec, part): part for part in parts}
        for fut in cf.as_completed(futures):
            yield futures[fut], _result(fut, futures[fut])
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


def _result(fut, part):
    try:
        return fut.result()
    except Exception as err:  # noqa: BLE001 -- a dead worker, a pickling or cluster error: report the chunk, do not store it
        return [{"case": int(k), "status": "error", "message": f"worker failed: {type(err).__name__}: {err}",
                 "wall_s": float("nan"), "metrics": {}, "transient": True} for k in part]


def dask_client(scheduler):
    """A ``distributed.Client`` from a client or a scheduler address (imported lazily)."""
    try:
        from distributed import Client
    except ImportError as err:     # pragma: no cover
        from ..errors import ParameterError
        raise ParameterError("scheduler", scheduler, "needs dask.distributed: pip install 'cablesys[sweep]'") from err
    if isinstance(scheduler, Client):
        return scheduler, False
    return Client(scheduler), True


def run_dask(spec, parts, scheduler):
    """On a Dask cluster: one task per chunk; each worker process keeps its own model cache."""
    from distributed import as_completed
    client, own = dask_client(scheduler)
    try:
        spec_f = client.scatter(spec, broadcast=True)
        futures = {}
        for part in parts:
            futures[client.submit(run_chunk, spec_f, part, pure=False)] = part
        for fut in as_completed(list(futures)):
            yield futures[fut], _result(fut, futures[fut])
    finally:
        if own:
            client.close()
