"""The ``cablesys sweep`` sub-command: a parameter sweep of a scene file, a Dataset and plots."""

from __future__ import annotations

import sys
from pathlib import Path

EXIT_INTERRUPTED = 130     # the shell's code for a run stopped by SIGINT, as the cablesys command uses


def register(sub) -> None:
    """Add ``sweep SCENE --vary NAME=VALUES ... [--analysis A] [--out DIR]`` to the cablesys parser."""
    p = sub.add_parser("sweep", help="run an analysis over a grid of parameter values (parallel, resumable)",
                       description="Run ANALYSIS for every combination of the --vary values (outer product; --zip "
                                   "to advance the lists in step) on all local cores or a Dask cluster. Writes "
                                   "OUT/sweep.nc (one dimension per varied label, metrics, per-case status and message), "
                                   "OUT/sweep.csv (name [unit] columns), one summary figure OUT/plots/sweep.png, and keeps finished "
                                   "cases in OUT/cases/ so that running the same command again computes only the missing "
                                   "ones. Values of the wrong type for their label, a label given twice and an --out that "
                                   "cannot be written are refused before any case runs. Ctrl-C stops the workers, keeps "
                                   "the finished cases and exits with 130.")
    from .analyses import ANALYSES, SCENES
    offered = [n for n, a in ANALYSES.items() if a.cli]
    p.add_argument("scene", type=Path, help="scene TOML file of the kind the analysis takes: a Wang scene (`cablesys "
                                            "scene --example`), a slack scene (--analysis slack) or a towed scene "
                                            "(--analysis towed)")
    p.add_argument("--vary", action="append", required=True, metavar="NAME=VALUES",
                   help="a labelled value and its values: a list (body.weight=2000,3000,4000) or a range "
                        "start:stop:lin|log:count (cable.ae=1e5:1e7:log:20); repeat for more dimensions")
    p.add_argument("--analysis", default="run", choices=offered,
                   help="; ".join(f"{n} ({SCENES[ANALYSES[n].scene].name}): {ANALYSES[n].text}" for n in offered))
    p.add_argument("--metric", action="append", default=None, metavar="PATTERN",
                   help="keep metrics matching this glob (repeatable; default all, e.g. 'tension_*')")
    p.add_argument("--model", default="scene",
                   help="run analysis: the model ladder rung, as for `cablesys run` (default: the scene's "
                        "numerics.model; 'auto', a rung name, or 'built' for the scene's model as built)")
    p.add_argument("--zip", action="store_true", help="advance all --vary lists in step (one dimension)")
    p.add_argument("--out", type=Path, default=Path("sweep-out"), help="output folder (default: sweep-out)")
    p.add_argument("--workers", type=int, default=None, help="local processes (default: all cores)")
    p.add_argument("--scheduler", default=None, help="Dask scheduler address (tcp://host:8786) instead of local processes")
    p.add_argument("--duration", type=float, default=None, help="simulated time in s (overrides the scene)")
    p.add_argument("--no-plots", action="store_true", help="skip the figures")
    p.set_defaults(func=run)


def run(args) -> int:
    from ..errors import ParameterError
    from . import sweep
    from .analyses import ANALYSES, SCENES
    from .api import SweepInterrupted
    from .grid import parse_vary
    from .plots import plot_sweep
    from .store import write_csv
    vary = parse_vary(args.vary)           # a label given twice: refused before the scene is even read
    kind = ANALYSES[args.analysis].scene
    if args.duration is not None and kind != "wang":
        raise ParameterError("--duration", args.duration, f"sets a time run's duration; the {args.analysis} analysis "
                             f"takes {SCENES[kind].text}, which has none")
    scene = SCENES[kind].load(args.scene)
    if args.duration is not None:          # 0 or negative is refused by the scene, not ignored
        scene = scene.with_numerics(duration=args.duration)
    options = {"model": None if args.model == "built" else args.model} if args.analysis == "run" else {}
    try:
        ds = sweep(scene, vary, args.analysis, metrics=args.metric, zip=args.zip, out=args.out,
                   workers=args.workers, scheduler=args.scheduler, progress=sys.stderr.isatty(), options=options)
    except SweepInterrupted as stop:
        print(f"cablesys sweep: interrupted: {stop}", file=sys.stderr)
        return EXIT_INTERRUPTED
    write_csv(ds, args.out / "sweep.csv")
    figs = [] if args.no_plots else plot_sweep(ds, args.out / "plots")
    status = ds["status"].values.ravel()
    print(f"{ds.attrs['scene']}: {ds.attrs['analysis']} over {' x '.join(f'{d} ({n})' for d, n in ds.sizes.items())} = "
          f"{ds.attrs['n_cases']} cases, {ds.attrs['n_computed']} computed now ({ds.attrs['backend']}, "
          f"{ds.attrs['wall_s']:.1f} s); ok {int((status == 'ok').sum())}, not ok {int((status != 'ok').sum())}")
    for k in [i for i, s in enumerate(status) if s != "ok"][:5]:
        print(f"  case {k}: {status[k]}: {ds['message'].values.ravel()[k]}")
    print(f"wrote {args.out}/sweep.nc, sweep.csv{f' and {figs[0]}' if figs else ''}")
    return 0 if (status == "ok").all() else 1
