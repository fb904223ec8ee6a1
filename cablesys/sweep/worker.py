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


def run_case(spec: SweepSpec, k: int, cache: ModelCache) -> dict:
    """Record of case ``k``: {case, status, message, wall_s, metrics}.

    status: ``ok``; ``failed`` (the analysis ran but did not succeed: integrator failure,
    no convergence); ``infeasible`` (a design with no feasible point); ``error`` (a bad value or
    a solver error before any result).
    """
    t0 = time.perf_counter()
    values = spec.grid.case(k)
    metrics, status, message = {}, "ok", ""
    try:
        scene, case_options = apply_values(spec.scene, values, spec.analysis)
        options = dict(spec.options, **case_options)
        summary, success, message = ANALYSIS[spec.analysis](scene, options, cache)
        metrics = select(flatten(summary), spec.metrics)
        status = "ok" if success else "failed"
    except CablesysError as err:
        status = "infeasible" if type(err).__name__ == "DesignInfeasible" else "error"
        message = f"{type(err).__name__}: {err}"
    except (RuntimeError, ValueError, ArithmeticError) as err:   # CasADi errors, LinAlgError, overflow
        status, message = "error", f"{type(err).__name__}: {err}"
    if status != "ok":
        log.info("case %d %s: %s", k, status, message)
    return {"case": int(k), "status": status, "message": str(message), "wall_s": time.perf_counter() - t0,
            "metrics": metrics}


def run_chunk(spec: SweepSpec, cases) -> list:
    """Records of ``cases`` computed in this process, reusing its cached models."""
    cache = process_cache()
    return [run_case(spec, int(k), cache) for k in cases]
