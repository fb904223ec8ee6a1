"""``cablesys towed RUNS.csv [--json]``: |H| and c* at the far end for every run.

RUNS.csv needs columns ``L_m`` (horizontal cable length, m), ``U_mps`` (tow speed, m/s)
and ``f_mHz`` (forcing frequency, mHz); other columns are passed through.  Coefficients
default to the report's sea-trial values (Kennedy & Strahan (1981) p. 31) and each can
be overridden.
"""

from __future__ import annotations

import json
import math
import sys

from ..options import option_number
from .equation import REPORT_SEA_TRIAL

__all__ = ["register", "run"]


# (flag, attribute, lower, upper, lower bound excluded)
OPTION_RANGES = (("--c-n", "c_n", 1e-3, 10.0, False), ("--c-t", "c_t", 1e-4, 1.0, False),
                 ("--c-t-drogue", "c_t_drogue", 0.0, 1e5, False), ("--beta", "beta", 1e-3, 1.0, False),
                 ("--diameter", "diameter", 1e-4, 1.0, False))


def register(sub) -> None:
    """Add the ``towed`` sub-command to ``sub`` (an argparse subparsers object)."""
    d = REPORT_SEA_TRIAL
    p = sub.add_parser(
        "towed",
        help="towed-cable transfer function |H| and c* per run (Kennedy & Strahan 1981)",
        description="For every row of RUNS.csv (columns L_m, U_mps, f_mHz) print the "
                    "transfer-function magnitude H = |H(xi=1, omega)| (eq. 26) and the "
                    "nondimensional phase velocity c_star (eq. 27b) of the exact "
                    "complex-order solution.")
    p.add_argument("runs", metavar="RUNS.csv", help="CSV with columns L_m, U_mps, f_mHz")
    p.add_argument("--json", action="store_true",
                   help="print a JSON list of objects: input columns plus H and c_star")
    p.add_argument("--c-n", type=float, default=d["c_n"],
                   help=f"effective normal drag coefficient c_n*, in [0.001, 10] (default {d['c_n']})")
    p.add_argument("--c-t", type=float, default=d["c_t"],
                   help=f"tangential drag coefficient c_t, in [0.0001, 1] (default {d['c_t']})")
    p.add_argument("--c-t-drogue", type=float, default=d["c_t_drogue"],
                   help=f"drogue term c_t', in [0, 1e5] (default {d['c_t_drogue']})")
    p.add_argument("--beta", type=float, default=d["beta"],
                   help=f"added-mass ratio beta = M/(M+m), in [0.001, 1] (default {d['beta']})")
    p.add_argument("--diameter", type=float, default=d["diameter"],
                   help=f"cable diameter d_c in m, in [0.0001, 1] (default {d['diameter']})")
    p.set_defaults(func=run)


def _number(text):
    """Input cell as int, float or the original text (run labels like '5A' stay text)."""
    for kind in (int, float):
        try:
            v = kind(text)
        except (TypeError, ValueError, OverflowError):
            continue
        return v if math.isfinite(v) else text      # 'nan', 'inf' stay text: JSON has no such numbers
    return text


def run(args) -> int:
    """Evaluate every run; errors in the CSV or options raise ParameterError."""
    from .runs import model_runs, read_runs     # SciPy's optimizer: imported when the command runs
    # physically meaningful ranges (cable drag coefficients are O(1e-3..1)); outside them the
    # complex-order solution is meaningless or cannot be evaluated (c_n = 1e-300 gave c* off by 1e290)
    for flag, name, lo, hi, lo_open in OPTION_RANGES:
        option_number(flag, getattr(args, name), lo=lo, hi=hi, lo_open=lo_open)
    runs = read_runs(args.runs)
    H, cs, _ = model_runs(runs, c_n=args.c_n, c_t=args.c_t, c_t_drogue=args.c_t_drogue,
                          beta=args.beta, diameter=args.diameter)
    if args.json:
        rows = [{**{k: _number(v) for k, v in r.columns.items()}, "H": float(h), "c_star": float(c)}
                for r, h, c in zip(runs, H, cs)]
        json.dump(rows, sys.stdout, indent=2, allow_nan=False)
        print()
        return 0
    print(f"{'run':>6} {'L_m':>9} {'U_mps':>7} {'f_mHz':>7} {'H':>8} {'c_star':>7}")
    for r, h, c in zip(runs, H, cs):
        print(f"{r.label:>6} {r.length:9.1f} {r.speed:7.2f} {r.frequency * 1e3:7.2f} {h:8.4f} {c:7.3f}")
    return 0
