"""Run a chunk of cases in one process (local pool worker, Dask worker or the caller itself).

Each process keeps one :class:`~.analyses.ModelCache`: the first case of a structure builds
the model and simulator, every later case reuses them (values go in through ``p``). A case
never raises: its failure becomes a record with status and message.
"""

from __future__ import annotations

import dataclasses
import logging
import time

from ..errors import CablesysError
from .analyses import ANALYSIS, ModelCache
from .grid import Grid
from .metrics import flatten, select
from .values import apply_values

log = logging.getLogger(__name__)

CASE_ERRORS = (CablesysError, RuntimeError, ValueError, ArithmeticError)   # CasADi errors, LinAlgError, overflow
_CACHE: ModelCache | None = None      # one per process, created on first use (the per-worker model cache)


def process_cache() -> ModelCache:
    """This process's model cache."""
    global _CACHE
    if _CACHE is None:
        _CACHE = ModelCache()
    return _CACHE


@dataclasses.dataclass(frozen=True)
class SweepSpec:
    """Everything a worker needs to compute any case of a sweep (small and picklable)."""

    scene: object
    analysis: str
    grid: Grid
    options: dict = dataclasses.field(default_factory=dict)
    metrics: tuple | None = None


def _record(k: int, t0: float, outcome, patterns) -> dict:
    """The record of case ``k`` from (summary, success, message) or the exception that stopped it."""
    if isinstance(outcome, BaseException):
        err = outcome
        status = "infeasible" if type(err).__name__ == "DesignInfeasible" else "error"
        metrics, message = {}, f"{type(err).__name__}: {err}"
    else:
        summary, success, message = outcome
        metrics, status = select(flatten(summary), patterns), "ok" if success else "failed"
    if status != "ok":
        log.info("case %d %s: %s", k, status, message)
    return {"case": int(k), "status": status, "message": str(message), "wall_s": time.perf_counter() - t0,
            "metrics": metrics}


def run_case(spec: SweepSpec, k: int, cache: ModelCache) -> dict:
    """Record of case ``k``: {case, status, message, wall_s, metrics}.

    status: ``ok``; ``failed`` (the analysis ran but did not succeed: integrator failure,
    no convergence); ``infeasible`` (a design with no feasible point); ``error`` (a bad value or
    a solver error before any result).
    """
    t0 = time.perf_counter()
    try:
        scene, case_options = apply_values(spec.scene, spec.grid.case(k), spec.analysis)
        outcome = ANALYSIS[spec.analysis](scene, dict(spec.options, **case_options), cache)
    except CASE_ERRORS as err:
        outcome = err
    return _record(k, t0, outcome, spec.metrics)


def run_chunk(spec: SweepSpec, cases) -> list:
    """Records of ``cases`` computed in this process, reusing its cached models (RAO chunks: one mapped call)."""
    cache = process_cache()
    if spec.analysis == "rao" and len(cases) > 1:
        return rao_chunk_records(spec, [int(k) for k in cases], cache)
    return [run_case(spec, int(k), cache) for k in cases]


def rao_chunk_records(spec: SweepSpec, cases: list, cache: ModelCache) -> list:
    """RAO records of a chunk: the cases' linearizations in one mapped CasADi call (:mod:`.batched`)."""
    from .batched import rao_chunk
    t0 = time.perf_counter()
    prepared, bad = [], {}
    for k in cases:
        try:
            scene, opts = apply_values(spec.scene, spec.grid.case(k), spec.analysis)
            prepared.append((k, scene, dict(spec.options, **opts)))
        except CASE_ERRORS as err:
            bad[k] = err
    outcomes = dict(zip([k for k, _, _ in prepared],
                        rao_chunk([s for _, s, _ in prepared], [o for _, _, o in prepared], cache)))
    outcomes.update(bad)
    share = time.perf_counter() - t0
    recs = [_record(k, t0, outcomes[k], spec.metrics) for k in cases]
    for r in recs:
        r["wall_s"] = share / len(cases)          # the chunk's time, shared
    return recs
