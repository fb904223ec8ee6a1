"""Sea-trial runs: reading run tables, the model per run, and fits of c_n (Kennedy & Strahan (1981) p. 27-35).

A run is a cable of horizontal length L (m) towed at U (m/s) with tow-point forcing at
f (mHz); the model value is the transfer function at the far pinger, ``xi = 1``:
``|H(1, omega)|`` (eq. 26) and ``c*(1, omega)`` (eq. 27b), ``omega = 2 pi f L / U``.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy.optimize import minimize_scalar

from ..errors import ParameterError, require_positive
from .equation import REPORT_SEA_TRIAL, TowedCable
from .transfer import fine_xi, transfer_grid

__all__ = ["Run", "REQUIRED_COLUMNS", "read_runs", "model_runs", "CnFit", "fit_normal_drag"]

REQUIRED_COLUMNS = ("L_m", "U_mps", "f_mHz")
_UNITS = {"L_m": "m", "U_mps": "m/s", "f_mHz": "mHz"}


@dataclass(frozen=True, kw_only=True)
class Run:
    """One row of a run table, SI (frequency in Hz); ``columns`` keeps every input column as text."""

    label: str
    length: float
    speed: float
    frequency: float
    columns: dict = field(default_factory=dict)

    def __post_init__(self):
        require_positive(f"run {self.label}: length", self.length, "m")
        require_positive(f"run {self.label}: speed", self.speed, "m/s")
        require_positive(f"run {self.label}: frequency", self.frequency, "Hz")


def read_runs(path) -> list[Run]:
    """Read a CSV with columns L_m, U_mps, f_mHz (others kept, lines starting with '#' skipped).

    Errors name the file, the row (1-based data row and file line) and the column.
    """
    path = Path(path)
    try:
        text = path.read_text()
    except OSError as err:
        raise ParameterError("RUNS.csv", str(path), f"cannot be read: {err.strerror}") from None
    lines = [(i + 1, ln) for i, ln in enumerate(text.splitlines())
             if ln.strip() and not ln.lstrip().startswith("#")]
    if not lines:
        raise ParameterError(f"{path}", "empty", "needs a header with columns " + ", ".join(REQUIRED_COLUMNS))
    reader = csv.DictReader([ln for _, ln in lines])
    header = [h.strip() for h in (reader.fieldnames or [])]
    missing = [c for c in REQUIRED_COLUMNS if c not in header]
    if missing:
        raise ParameterError(f"{path}: header", header,
                             f"missing column(s) {', '.join(missing)}; need {', '.join(REQUIRED_COLUMNS)}")
    runs = []
    for k, (row, (lineno, _)) in enumerate(zip(reader, lines[1:]), start=1):
        row = {(key or "").strip(): (val or "").strip() for key, val in row.items()}
        vals = {}
        for col in REQUIRED_COLUMNS:
            where = f"{path.name} row {k} (line {lineno}), column {col}"
            raw = row.get(col, "")
            try:
                v = float(raw)
            except ValueError:
                raise ParameterError(where, raw, f"must be a number ({_UNITS[col]})") from None
            if not math.isfinite(v) or v <= 0:
                raise ParameterError(where, raw, f"must be > 0 ({_UNITS[col]})")
            vals[col] = v
        label = row.get("run") or str(k)
        runs.append(Run(label=label, length=vals["L_m"], speed=vals["U_mps"],
                        frequency=vals["f_mHz"] * 1e-3, columns=row))
    if not runs:
        raise ParameterError(f"{path}", "no data rows", "needs at least one run")
    return runs


def model_runs(runs, **coefficients):
    """Model ``|H|`` and ``c*`` at ``xi = 1`` for each run (eq. 26, 27b).

    ``coefficients`` override the report's sea-trial values ``REPORT_SEA_TRIAL``
    (diameter, c_t, c_n, c_t_drogue, beta).  Returns ``(H_abs, c_star, omega)`` arrays.
    """
    kw = {**REPORT_SEA_TRIAL, **coefficients}
    H, cs, om = [], [], []
    for r in runs:
        cable = TowedCable(length=r.length, speed=r.speed, **kw)
        w = float(cable.omega(r.frequency))
        # one pass along the cable gives both H(1) and the unwrapped phase lag psi(1)
        g = transfer_grid(cable.coefficients(), fine_xi(1.0, w), np.array([w]))
        H.append(abs(complex(g.H[-1, 0])))
        cs.append(float(g.c_star[-1, 0]))
        om.append(w)
    return np.array(H), np.array(cs), np.array(om)


@dataclass(frozen=True, kw_only=True)
class CnFit:
    """Best c_n for one target ('amplitude', 'phase' or 'both') and the errors it leaves."""

    target: str
    c_n: float
    rms_H: float
    rms_c_star: float
    cost: float
    success: bool


def _cost(target, H, cs, H_data, c_data):
    eH = np.mean((H - H_data) ** 2)
    ec = np.mean((cs - c_data) ** 2)
    if target == "amplitude":
        return eH
    if target == "phase":
        return ec
    # both: each mean-square error relative to the variance of its data (1 - R^2 like)
    return eH / np.var(H_data) + ec / np.var(c_data)


def fit_normal_drag(runs, H_data, c_data, targets=("amplitude", "phase", "both"), *,
                    bounds=(0.01, 3.0), n_scan: int = 25, xatol: float = 1e-4,
                    **coefficients) -> dict:
    """Fit c_n (the effective c_n* of eq. 39) to amplitude, phase and/or both (scipy.optimize).

    One log-spaced scan of c_n brackets each target's global minimum; ``minimize_scalar``
    (bounded) refines it.  Returns ``{target: CnFit}``.
    """
    for t in targets:
        if t not in ("amplitude", "phase", "both"):
            raise ParameterError("target", t, "must be 'amplitude', 'phase' or 'both'")
    H_data = np.asarray(H_data, dtype=float)
    c_data = np.asarray(c_data, dtype=float)
    cache = {}

    def model(logc):
        if logc not in cache:
            cache[logc] = model_runs(runs, **{**coefficients, "c_n": 10.0**logc})[:2]
        return cache[logc]

    grid = np.linspace(math.log10(bounds[0]), math.log10(bounds[1]), n_scan)
    for g in grid:
        model(float(g))
    out = {}
    for target in targets:
        def f(logc):
            return _cost(target, *model(float(logc)), H_data, c_data)

        vals = [f(g) for g in grid]
        i = int(np.argmin(vals))
        lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, n_scan - 1)]
        res = minimize_scalar(f, bounds=(lo, hi), method="bounded", options={"xatol": xatol})
        H, cs = model(float(res.x))
        out[target] = CnFit(target=target, c_n=float(10.0 ** res.x),
                            rms_H=float(np.sqrt(np.mean((H - H_data) ** 2))),
                            rms_c_star=float(np.sqrt(np.mean((cs - c_data) ** 2))),
                            cost=float(res.fun), success=bool(res.success))
    return out
