"""``cablesys towed``: a towed scene (``SCENE.toml``) or a table of sea-trial runs (``RUNS.csv``).

``cablesys towed SCENE.toml --out DIR``: the cable in the Wang scene's terms (C_t, C_n, the
drogue's drag area; ``cablesys towed --example``), converted once to the theory's c_t, c_n, c_t'
and beta (:func:`cablesys.towed.equation.theory_coefficients`); writes ``towed.json``,
``towed.csv`` and ``towed.png`` (|H| and c* against frequency) to ``--out``.

``cablesys towed RUNS.csv [--json]``: |H| and c* at the far end for every run. RUNS.csv needs
columns ``L_m`` (horizontal cable length, m), ``U_mps`` (tow speed, m/s) and ``f_mHz``
(forcing frequency, mHz); other columns are passed through. The theory's coefficients default
to the report's sea-trial values (Kennedy & Strahan (1981) p. 31) and each can be overridden.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

from ..errors import ParameterError
from ..options import option_number
from .equation import REPORT_SEA_TRIAL

__all__ = ["register", "run", "run_runs", "run_scene"]


# (flag, attribute, lower, upper, lower bound excluded)
OPTION_RANGES = (("--c-n", "c_n", 1e-3, 10.0, False), ("--c-t", "c_t", 1e-4, 1.0, False),
                 ("--c-t-drogue", "c_t_drogue", 0.0, 1e5, False), ("--beta", "beta", 1e-3, 1.0, False),
                 ("--diameter", "diameter", 1e-4, 1.0, False))


def register(sub) -> None:
    """Add the ``towed`` sub-command to ``sub`` (an argparse subparsers object)."""
    d = REPORT_SEA_TRIAL
    p = sub.add_parser(
        "towed",
        help="towed cable: |H| and c* of a scene (SCENE.toml) or per sea-trial run (RUNS.csv) "
             "(Kennedy & Strahan 1981)",
        description="SCENE.toml (see --example): the cable's C_t, C_n and drogue drag area are converted to "
                    "the theory's c_t, c_n, c_t' and beta; the transfer function H (eq. 26), the phase "
                    "velocity c* (eq. 27b), the modes (eq. 18-20) and the damping time (eq. 23) go to "
                    "towed.json, towed.csv and towed.png in --out. RUNS.csv (columns L_m, U_mps, f_mHz): "
                    "print |H(xi=1, omega)| and the nondimensional c* of every run, with the theory's "
                    "coefficients from the options.")
    p.add_argument("runs", metavar="SCENE.toml|RUNS.csv", nargs="?",
                   help="a towed scene (.toml) or a CSV of runs with columns L_m, U_mps, f_mHz")
    p.add_argument("--example", action="store_true", help="print an example towed scene TOML and exit")
    p.add_argument("--out", default=None, help="output directory of a scene (default: towed_out)")
    p.add_argument("--overwrite", action="store_true", help="replace results of another scene in --out")
    p.add_argument("--json", action="store_true",
                   help="RUNS.csv: print a JSON list of objects: input columns plus H and c_star")
    # the theory's coefficients of RUNS.csv; a scene gives its own (None: not given)
    p.add_argument("--c-n", type=float, default=None,
                   help=f"RUNS.csv: effective normal drag coefficient c_n*, in [0.001, 10] (default {d['c_n']})")
    p.add_argument("--c-t", type=float, default=None,
                   help=f"RUNS.csv: tangential drag coefficient c_t, in [0.0001, 1] (default {d['c_t']})")
    p.add_argument("--c-t-drogue", type=float, default=None,
                   help=f"RUNS.csv: drogue term c_t', in [0, 1e5] (default {d['c_t_drogue']})")
    p.add_argument("--beta", type=float, default=None,
                   help=f"RUNS.csv: added-mass ratio beta = M/(M+m), in [0.001, 1] (default {d['beta']})")
    p.add_argument("--diameter", type=float, default=None,
                   help=f"RUNS.csv: cable diameter d_c in m, in [0.0001, 1] (default {d['diameter']})")
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
    """A scene (.toml) or every run of a CSV; errors in the input or options raise ParameterError."""
    if getattr(args, "example", False):
        from .scene import EXAMPLE_TOML
        sys.stdout.write(EXAMPLE_TOML)
        return 0
    if not args.runs:
        raise ParameterError("SCENE.toml|RUNS.csv", None, "a towed scene (.toml) or a runs table (.csv) is "
                             "required (or --example)")
    given = [flag for flag, name, *_ in OPTION_RANGES if getattr(args, name, None) is not None]
    if Path(args.runs).suffix.lower() == ".toml":
        if given or args.json:
            raise ParameterError(given[0] if given else "--json", getattr(args, given[0][2:].replace("-", "_"))
                                 if given else True,
                                 "applies to RUNS.csv only: a scene gives the cable's ct_tangential, cd_normal, "
                                 "drogue_drag_area and mass_per_length (see --example)")
        return run_scene(args)
    if args.out is not None or args.overwrite:
        raise ParameterError("--out", args.out, "applies to a SCENE.toml only: RUNS.csv prints its table "
                             "(use --json for a file)")
    return run_runs(args)


def _significant(x: float, digits: int = 6) -> str:
    """A number to ``digits`` significant digits: 3.8e-11 stays 3.8e-11, never 0.0000."""
    return f"{x:.{digits}g}"


def run_scene(args) -> int:
    """``cablesys towed SCENE.toml --out DIR``: analyse the scene and write JSON, CSV and a figure."""
    from ..outputs import OutputDir
    from .analysis import analyze
    from .plots import plot_response
    from .scene import load_towed_scene

    scene = load_towed_scene(args.runs)
    outdir = OutputDir(args.out or "towed_out", "towed", {"scene": scene}, overwrite=args.overwrite,
                       owned=("towed.json", "towed.csv", "towed.png"))
    with outdir.start(scene=str(args.runs)):
        res = analyze(scene)
        header, rows = res.table()
        doc = {"scene": str(args.runs), **res.summary(),
               "units": {"xi": "1 (x/L)", "omega_rad_s": "rad/s", "frequency_hz": "Hz", "omega_nd": "1 (omega L/U)",
                         "H": "1", "phase_lag_rad": "rad", "c_star": "1 (units of U)", "c_star_m_s": "m/s",
                         "damping_time_s": "s", "modes": "1 (omega L/U, complex)"},
               "damping_time_s": res.damping_time_s, "damping_time_report_s": res.damping_time_report_s,
               "response": {"xi": res.xi.tolist(), "omega_rad_s": res.omega.tolist(),
                            "frequency_hz": res.frequency.tolist(), "omega_nd": res.omega_nd.tolist(),
                            "H_real": res.H.real.tolist(), "H_imag": res.H.imag.tolist(),
                            "phase_lag_rad": res.phase_lag.tolist(), "c_star": res.c_star.tolist(),
                            "c_star_m_s": res.c_star_m_s.tolist()}}
        outdir.write_json("towed.json", doc)
        outdir.write_text("towed.csv", "\n".join([",".join(header)] + [",".join(repr(v) for v in r) for r in rows])
                          + "\n")
        with outdir.writing("towed.png") as tmp:
            plot_response(res, tmp)
    c = res.coefficients
    k = int(res.xi.argmax())
    lines = ["theory coefficients (Kennedy & Strahan 1981): " + ", ".join(
                 f"{name} = {_significant(c[key])}" for name, key in
                 (("c_t", "c_t"), ("c_n*", "c_n"), ("c_t'", "c_t_drogue"), ("beta", "beta"))),
             f"steady tension: tow point {_significant(res.tension_top)} N, drogue {_significant(res.tension_bottom)} N",
             f"damping time t_0 = {_significant(res.damping_time_s)} s (eq. 19, 23); "
             f"report's eq. 25: {_significant(res.damping_time_report_s)} s",
             f"at xi = {_significant(res.xi[k])}:  f (Hz)  omega (rad/s)  |H|  c* (m/s)"]
    step = max(1, len(res.omega) // 8)
    for j in list(range(0, len(res.omega), step))[:8] + [len(res.omega) - 1]:
        lines.append(f"  {_significant(res.frequency[j])}  {_significant(res.omega[j])}  "
                     f"{_significant(abs(res.H[k, j]))}  {_significant(res.c_star_m_s[k, j])}")
    if not res.success:
        lines.append(f"warning: {res.message}")
    lines.append(f"wrote {outdir.path / 'towed.json'}, towed.csv, towed.png")
    sys.stdout.write("\n".join(lines) + "\n")
    return 0


def run_runs(args) -> int:
    """``cablesys towed RUNS.csv``: |H| and c* at xi = 1 of every run."""
    from .runs import model_runs, read_runs     # SciPy's optimizer: imported when the command runs
    coefficients = {name: REPORT_SEA_TRIAL[name] if getattr(args, name, None) is None else getattr(args, name)
                    for _, name, *_ in OPTION_RANGES}
    # physically meaningful ranges (cable drag coefficients are O(1e-3..1)); outside them the
    # complex-order solution is meaningless or cannot be evaluated (c_n = 1e-300 gave c* off by 1e290)
    for flag, name, lo, hi, lo_open in OPTION_RANGES:
        option_number(flag, coefficients[name], lo=lo, hi=hi, lo_open=lo_open)
    runs = read_runs(args.runs)
    res = model_runs(runs, **coefficients)
    H, cs = res.H_abs, res.c_star
    if args.json:
        rows = [{**{k: _number(v) for k, v in r.columns.items()}, "H": float(h), "c_star": float(c)}
                for r, h, c in zip(runs, H, cs)]
        json.dump(rows, sys.stdout, indent=2, allow_nan=False)
        print()
        return 0
    print(f"{'run':>6} {'L_m':>9} {'U_mps':>7} {'f_mHz':>7} {'H':>12} {'c_star':>12}")
    for r, h, c in zip(runs, H, cs):
        print(f"{r.label:>6} {r.length:9.6g} {r.speed:7.4g} {r.frequency * 1e3:7.4g} "
              f"{_significant(h):>12} {_significant(c):>12}")
    return 0
