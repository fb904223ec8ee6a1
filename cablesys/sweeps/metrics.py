"""Metrics of one case: a result's ``summary()`` dict flattened to named scalars.

Every analysis result offers a ``summary()``-like dict; nested groups become names joined
by ``_`` (``stats`` -> ``stats_wall_s``; a verdict group ``verdict: {allowed: ...}`` ->
``verdict_allowed``), lists of numbers one name per entry, lists of records their count.
New groups added to a summary therefore appear in sweeps without changes here.
"""

from __future__ import annotations

import fnmatch
import math
import re

import numpy as np

from ..results import unit_of

SKIP = ("scene", "message", "result")   # in the Dataset as attributes/status already, or the result's class name
RESERVED = ("status", "wall_s", "case")  # the sweep's own per-case variables: a summary's namesake is renamed result_*


def flatten(summary: dict, prefix: str = "") -> dict:
    """{name: int | float | str | 1-D array} from a nested summary dict."""
    out = {}
    for key, val in summary.items():
        name = f"{prefix}{key}".replace(".", "_").replace(" ", "_").replace("-", "_")
        if not prefix and key in SKIP:
            continue
        if name in RESERVED:
            name = f"result_{name}"
        if isinstance(val, dict):
            out.update(flatten(val, name + "_"))
        elif isinstance(val, (bool, np.bool_)):
            out[name] = int(val)
        elif isinstance(val, (int, float, np.integer, np.floating)):
            out[name] = float(val) if isinstance(val, (float, np.floating)) else int(val)
        elif isinstance(val, str):
            if key not in ("text", "unit"):       # labels of a verdict entry: constant, not data
                out[name] = val
        elif isinstance(val, (list, tuple, np.ndarray)):
            items = list(val)
            if items and all(isinstance(v, dict) for v in items):
                out[f"{name}_count"] = len(items)
            elif all(isinstance(v, (int, float, np.integer, np.floating, bool, np.bool_)) for v in items):
                if not items:
                    out[f"{name}_count"] = 0
                for i, v in enumerate(items):
                    out[f"{name}_{i}"] = float(v)
    return out


def select(metrics: dict, patterns) -> dict:
    """Keep the names matching any glob pattern (``None``: keep all)."""
    if patterns is None:
        return metrics
    if isinstance(patterns, str):
        patterns = [patterns]
    return {k: v for k, v in metrics.items() if any(fnmatch.fnmatchcase(k, p) for p in patterns)}


def metric_unit(name: str) -> str:
    """Unit of a metric from its name: a ``_N``/``_s``/``_m``/``_m_s``/``_rad_s`` suffix (before an entry's index,
    ``c_star_m_s_1``) or an output label in it."""
    stem = re.sub(r"_\d+$", "", name)
    for suffix, unit in (("_rad_s", "rad/s"), ("_m_s", "m/s"), ("_N", "N"), ("_s", "s"), ("_m", "m")):
        if stem.endswith(suffix):
            return unit
    for head in ("amplitude_", "std_", "mean_", "significant_"):
        if name.startswith(head):
            return unit_of(name[len(head):])
    if name.startswith("rao_"):
        return ""
    return ""


def is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) or (isinstance(v, float) and math.isnan(v))
