"""Sea-trial runs: reading run tables, the model per run, and fits of c_n (Kennedy & Strahan (1981) p. 27-35).

A run is a cable of horizontal length L (m) towed at U (m/s) with tow-point forcing at
f (mHz); the model value is the transfer function at the far pinger, ``xi = 1``:
``|H(1, omega)|`` (eq. 26) and ``c*(1, omega)`` (eq. 27b), ``omega = 2 pi f L / U``.
"""

from __future__ import annotations

import csv
import math
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import ClassVar

import numpy as np
from scipy.optimize import minimize_scalar

from ..errors import ParameterError, SolverError, require_positive, require_range
from ..reader import read_text
from ..results import ResultBase, timed
from .equation import REPORT_SEA_TRIAL, TowedCable
from .transfer import MAX_OMEGA_ND, MAX_XI_POINTS, fine_xi, transfer_grid

__all__ = ["Run", "REQUIRED_COLUMNS", "MAX_RUNS", "read_runs", "model_runs", "RunsResponse", "CnFit", "fit_normal_drag"]

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
        require_range(f"run {self.label}: length", self.length, 0.0, MAX_LENGTH_M, "m", lo_open=True)
        require_positive(f"run {self.label}: speed", self.speed, "m/s")
        require_positive(f"run {self.label}: frequency", self.frequency, "Hz")
        _require_resolvable(f"run {self.label}", self.length, self.speed, self.frequency)


def _require_resolvable(where: str, length: float, speed: float, frequency: float) -> None:
    """Refuse a run whose omega L / U = 2 pi f L / U exceeds what the unwrapping grid resolves."""
    w = 2.0 * math.pi * frequency * length / speed
    if not w <= MAX_OMEGA_ND:
        raise ParameterError(f"{where}: omega L/U = 2 pi f L / U", w,
                             f"must be <= {MAX_OMEGA_ND:.6g} (L = {length:g} m, U = {speed:g} m/s, "
                             f"f = {frequency * 1e3:g} mHz): the phase lag is unwrapped on 8 points per radian "
                             f"along the cable, at most {MAX_XI_POINTS} points")


MAX_RUNS = 10_000      # rows of a run table (each run is one transfer-function evaluation)
#: Longest towed cable of a run (m): 100 km, ten times the longest towed arrays.
MAX_LENGTH_M = 1e5


def read_runs(path) -> list[Run]:
    """Read a CSV with columns L_m, U_mps, f_mHz (others kept, lines starting with '#' skipped).

    Parameters
    ----------
    path : str or Path
        A UTF-8 CSV file (a byte-order mark, as spreadsheets write it, is accepted).

    Returns
    -------
    list of Run
        One run per data row, SI.

    Raises
    ------
    ParameterError
        Naming the file, the row (1-based data row and file line), the column and the value:
        undecodable text, missing columns, a row with more or fewer fields than the header,
        a value that is not a number > 0, more than ``MAX_RUNS`` rows.
    """
    path = Path(path)
    text = read_text(path, "RUNS.csv")
    rows = _csv_records(text, path)
    if not rows:
        raise ParameterError(f"{path}", "empty", "needs a header with columns " + ", ".join(REQUIRED_COLUMNS))
    header_line, header = rows[0][0], [h.strip() for h in rows[0][1]]
    missing = [c for c in REQUIRED_COLUMNS if c not in header]
    if missing:
        raise ParameterError(f"{path}, line {header_line}: header", header,
                             f"missing column(s) {', '.join(missing)}; need {', '.join(REQUIRED_COLUMNS)}")
    dup = sorted({h for h in header if header.count(h) > 1})
    if dup:
        raise ParameterError(f"{path}, line {header_line}: header", header, f"column {dup[0]!r} appears twice")
    if len(rows) - 1 > MAX_RUNS:
        raise ParameterError(f"{path}", f"{len(rows) - 1} rows", f"at most {MAX_RUNS} runs per table")
    runs = []
    for k, (lineno, cells) in enumerate(rows[1:], start=1):
        if len(cells) != len(header):
            raise ParameterError(f"{path.name} row {k} (line {lineno})", ",".join(cells),
                                 f"has {len(cells)} fields; the header has {len(header)} ({', '.join(header)})")
        row = {key: val.strip() for key, val in zip(header, cells)}
        vals = {}
        for col in REQUIRED_COLUMNS:
            where = f"{path.name} row {k} (line {lineno}), column {col}"
            raw = row[col]
            try:
                v = float(raw)
            except ValueError:
                raise ParameterError(where, raw, f"must be a number ({_UNITS[col]})") from None
            if not math.isfinite(v) or v <= 0:
                raise ParameterError(where, raw, f"must be a finite number > 0 ({_UNITS[col]})")
            if col == "L_m" and v > MAX_LENGTH_M:
                raise ParameterError(where, raw, f"must be <= {MAX_LENGTH_M:g} (m)")
            vals[col] = v
        _require_resolvable(f"{path.name} row {k} (line {lineno})", vals["L_m"], vals["U_mps"], vals["f_mHz"] * 1e-3)
        label = row.get("run") or str(k)
        runs.append(Run(label=label, length=vals["L_m"], speed=vals["U_mps"],
                        frequency=vals["f_mHz"] * 1e-3, columns=row))
    if not runs:
        raise ParameterError(f"{path}", "no data rows", "needs at least one run")
    return runs


def _csv_records(text: str, path: Path) -> list[tuple[int, list[str]]]:
    """RFC 4180 records of ``text`` (quoted fields may hold commas, quotes and newlines) with the
    file line each starts on; blank lines and lines starting with '#' between records are skipped."""
    lines = text.splitlines(keepends=True)
    state = {"next": 0, "start": 0}

    def feed():          # csv.reader pulls lines lazily: between records, skip comments and blanks
        while state["next"] < len(lines):
            i = state["next"]
            state["next"] += 1
            if state["start"] is None:                 # inside a record (a quoted field spans lines)
                yield lines[i]
            elif lines[i].strip() and not lines[i].lstrip().startswith("#"):
                state["start"] = None
                state["line"] = i + 1
                yield lines[i]

    records = []
    reader = csv.reader(feed(), strict=True)
    try:
        for cells in reader:
            records.append((state["line"], cells))
            state["start"] = 0
    except csv.Error as err:
        raise ParameterError(f"{path}, line {state.get('line', reader.line_num)}", "not CSV",
                             f"cannot be parsed as RFC 4180 CSV ({err})") from None
    return records


@dataclass(frozen=True, kw_only=True)
class RunsResponse(ResultBase):
    """The model at the far pinger (xi = 1) of each sea-trial run, on dimension ``run``.

    ``H_abs`` = |H(1, omega)| (eq. 26), ``c_star`` = c*(1, omega) in units of the tow speed U
    (eq. 27b), ``omega`` = 2 pi f L / U (nondimensional, eq. 2); ``coefficients`` the theory's
    values used (diameter in m, c_t, c_n, c_t_drogue, beta). Unpacking it as
    ``H, cs, om = ...`` (the old tuple) still works, with a DeprecationWarning.
    """

    labels: tuple[str, ...]
    H_abs: np.ndarray
    c_star: np.ndarray
    omega: np.ndarray
    coefficients: dict
    success: bool = True
    message: str = ""
    stats: dict = field(default_factory=dict)

    VARIABLES: ClassVar[dict] = {"run": ("1", "run label"),
                                 "H_abs": ("1", "|H(xi = 1)|, transfer function magnitude at the far end (eq. 26)"),
                                 "c_star": ("1", "mean phase velocity c*(xi = 1) over the tow speed U (eq. 27b)"),
                                 "omega": ("1", "nondimensional angular frequency omega L/U = 2 pi f L / U")}

    def __iter__(self):
        warnings.warn("unpacking model_runs(...) as (H_abs, c_star, omega) is deprecated: use its .H_abs, "
                      ".c_star and .omega", DeprecationWarning, stacklevel=2)
        return iter((self.H_abs, self.c_star, self.omega))

    def summary(self) -> dict:
        """Per-run |H| and c* (units of U) with the coefficients used.

        Returns
        -------
        dict
            JSON-able.
        """
        return {**super().summary(), "coefficients": dict(self.coefficients),
                "runs": [{"run": r, "omega_nd": float(w), "H_abs": float(h), "c_star": float(c)}
                         for r, w, h, c in zip(self.labels, self.omega, self.H_abs, self.c_star)]}

    def to_xarray(self):
        """|H|, c* and omega on dimension ``run``.

        Returns
        -------
        xarray.Dataset
        """
        import xarray as xr
        return xr.Dataset({"H_abs": ("run", self.H_abs), "c_star": ("run", self.c_star),
                           "omega": ("run", self.omega)}, coords={"run": list(self.labels)},
                          attrs={f"coefficient_{k}": float(v) for k, v in self.coefficients.items()})


@timed
def model_runs(runs, **coefficients) -> RunsResponse:
    """Model ``|H|`` and ``c*`` at ``xi = 1`` for each run (eq. 26, 27b).

    ``coefficients`` override the report's sea-trial values ``REPORT_SEA_TRIAL``
    (diameter, c_t, c_n, c_t_drogue, beta).

    Parameters
    ----------
    runs : sequence of Run
        Sea-trial runs (length m, speed m/s, frequency Hz), e.g. from :func:`read_runs`.
    **coefficients
        Overrides of ``REPORT_SEA_TRIAL`` (diameter in m; c_t, c_n, c_t_drogue, beta).

    Returns
    -------
    RunsResponse
        ``H_abs`` |H(1)|, ``c_star`` c*(1) in units of U and ``omega`` omega L / U per run.
    """
    kw = {**REPORT_SEA_TRIAL, **coefficients}
    H, cs, om = [], [], []
    for r in runs:
        cable = TowedCable(length=r.length, speed=r.speed, **kw)
        w = math.nan
        # one pass along the cable gives both H(1) and the unwrapped phase lag psi(1); an
        # overflow or invalid operation on the way is a numerical failure, named per run
        try:
            with np.errstate(over="raise", invalid="raise", divide="raise"):
                w = float(cable.omega(r.frequency))
                g = transfer_grid(cable.coefficients(), fine_xi(1.0, w), np.array([w]))
                H.append(abs(complex(g.H[-1, 0])))
                cs.append(float(g.c_star[-1, 0]))
        except (FloatingPointError, OverflowError) as err:
            raise SolverError(f"run {r.label}: the transfer function at xi = 1, omega = {w:.6g} cannot be evaluated "
                              f"({err}) with the coefficients {kw}: they lie outside the range where the "
                              "complex-order solution is computable") from None
        if not (math.isfinite(H[-1]) and math.isfinite(cs[-1])):
            raise SolverError(f"run {r.label}: the transfer function at xi = 1 is not finite (|H| = {H[-1]}, "
                              f"c* = {cs[-1]}) at omega = {w:.6g}; the coefficients {kw} are outside the range "
                              "where the complex-order solution can be evaluated")
        om.append(w)
    return RunsResponse(labels=tuple(r.label for r in runs), H_abs=np.array(H), c_star=np.array(cs),
                        omega=np.array(om), coefficients=kw)


@dataclass(frozen=True, kw_only=True)
class CnFit(ResultBase):
    """Best c_n for one target ('amplitude', 'phase' or 'both') and the errors it leaves.

    ``c_n`` the fitted effective normal drag coefficient c_n* (eq. 39); ``rms_H`` the rms error
    of |H| (1) and ``rms_c_star`` of c* (units of U) over the runs; ``cost`` the minimized
    objective; ``success`` and ``message`` from scipy.optimize.minimize_scalar.
    """

    target: str
    c_n: float
    rms_H: float
    rms_c_star: float
    cost: float
    success: bool
    message: str = ""
    stats: dict = field(default_factory=dict)

    VARIABLES: ClassVar[dict] = {"c_n": ("1", "fitted effective normal drag coefficient c_n* (eq. 39)"),
                                 "rms_H": ("1", "rms error of |H| over the runs"),
                                 "rms_c_star": ("1", "rms error of c* over the runs, units of U"),
                                 "cost": ("1", "minimized objective")}

    def to_xarray(self):
        """The fit's numbers as scalar variables.

        Returns
        -------
        xarray.Dataset
        """
        import xarray as xr
        return xr.Dataset({k: ((), getattr(self, k)) for k in ("c_n", "rms_H", "rms_c_star", "cost")},
                          attrs={"target": self.target})


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

    Parameters
    ----------
    runs : sequence of Run
        Sea-trial runs.
    H_data, c_data : array_like
        Measured |H| and c* (units of U) per run.
    targets : tuple of str, optional
        Any of 'amplitude', 'phase', 'both'.
    bounds : tuple of float, optional
        Search interval of c_n.
    n_scan : int, optional
        Points of the log-spaced scan.
    xatol : float, optional
        Absolute tolerance of the refined log10 c_n.
    **coefficients
        Overrides of ``REPORT_SEA_TRIAL`` other than c_n.

    Returns
    -------
    dict
        ``{target: CnFit}``.
    """
    for t in targets:
        if t not in ("amplitude", "phase", "both"):
            raise ParameterError("target", t, "must be 'amplitude', 'phase' or 'both'")
    H_data = np.asarray(H_data, dtype=float)
    c_data = np.asarray(c_data, dtype=float)
    cache = {}

    def model(logc):
        if logc not in cache:
            res = model_runs(runs, **{**coefficients, "c_n": 10.0**logc})
            cache[logc] = res.H_abs, res.c_star
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
                            cost=float(res.fun), success=bool(res.success),
                            message="" if res.success else str(getattr(res, "message", "not converged")),
                            stats={"iterations": int(getattr(res, "nit", 0)),
                                   "function_evaluations": int(getattr(res, "nfev", 0))})
    return out
