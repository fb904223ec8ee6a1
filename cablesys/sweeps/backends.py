"""Where chunks of cases run: this process, a local process pool, or a Dask cluster.

All three call :func:`.worker.run_chunk` and hand back each chunk's records as soon as it
finishes, so the caller writes it to disk and advances the progress bar. Local workers are
forked where the platform can (a script without a ``__main__`` guard and a notebook both
work, and no worker imports the package again) and spawned elsewhere; the pool is made
before any model is built in the workers, each of which builds its models once and keeps
them for every later chunk. Dask is imported only when asked for.

Local workers die with the sweep: each asks the kernel for SIGKILL when its parent dies
(Linux ``prctl(PR_SET_PDEATHSIG)``) and, on every platform, watches its parent's pid, so a
killed sweep leaves no worker computing or holding its terminal or pipe; a worker's stdout
is /dev/null (its messages go to the log on stderr). Workers ignore SIGINT: Ctrl-C reaches
the whole process group, and the parent alone decides, killing the workers and keeping the
chunks that finished.
"""

from __future__ import annotations

import concurrent.futures as cf
import contextlib
import ctypes
import ctypes.util
import multiprocessing
import os
import signal
import sys
import threading
import time

from .worker import process_cache, run_case, run_chunk

PR_SET_PDEATHSIG = 1          # <linux/prctl.h>
PARENT_POLL_S = 0.5           # how often a worker looks for its parent where the kernel cannot tell it


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


def worker_start(parent: int) -> None:
    """Set up a local pool worker: die with ``parent``, leave SIGINT to it, write nothing on its stdout."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)     # Ctrl-C is the parent's to handle
    signal.signal(signal.SIGTERM, signal.SIG_DFL)    # not a forked copy of the CLI's SIGTERM -> KeyboardInterrupt
    if sys.platform.startswith("linux"):
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6", use_errno=True)
        libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    if os.getppid() != parent:                       # the parent died before the line above
        os._exit(1)
    threading.Thread(target=_watch_parent, args=(parent,), name="parent-watch", daemon=True).start()
    devnull = os.open(os.devnull, os.O_WRONLY)
    with contextlib.suppress(OSError, ValueError):
        sys.stdout.flush()
    os.dup2(devnull, 1)
    os.close(devnull)


def _watch_parent(parent: int) -> None:
    """Exit this worker once ``parent`` is gone (its children are handed to another process)."""
    while os.getppid() == parent:
        time.sleep(PARENT_POLL_S)
    os._exit(1)


def run_processes(spec, parts, n_workers: int):
    """On a pool of ``n_workers`` local processes; a crashed worker fails only its chunks.

    Leaving early (KeyboardInterrupt, the caller closing the generator) kills the workers at once:
    the chunks already handed back are the sweep's finished cases, the others are not computed."""
    methods = multiprocessing.get_all_start_methods()
    ctx = multiprocessing.get_context("fork" if "fork" in methods else "spawn")
    pool = cf.ProcessPoolExecutor(max_workers=n_workers, mp_context=ctx, initializer=worker_start,
                                  initargs=(os.getpid(),))
    complete = False
    try:
        futures = {pool.submit(run_chunk, spec, part): part for part in parts}
        for fut in cf.as_completed(futures):
            yield futures[fut], _result(fut, futures[fut])
        complete = True
    finally:
        if not complete:
            kill_workers(pool)
        pool.shutdown(wait=True, cancel_futures=True)


def kill_workers(pool: cf.ProcessPoolExecutor) -> None:
    """SIGKILL every worker process of ``pool`` (their running chunks are lost, nothing is half-written:
    only the parent writes)."""
    kill = getattr(pool, "kill_workers", None)       # Python >= 3.14
    if kill is not None:
        kill()
        return
    for proc in list((getattr(pool, "_processes", None) or {}).values()):
        with contextlib.suppress(OSError, ValueError, AttributeError):
            proc.kill()


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
