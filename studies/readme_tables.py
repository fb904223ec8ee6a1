"""Regenerate the README's performance table from benchmark outputs (the README states no timing by hand).

    python studies/readme_tables.py --bench studies/results [--readme README.md] [--check]

Reads ``bench_vs_moordyn.json`` (``studies/bench_vs_moordyn.py --out DIR``) from ``--bench`` and rewrites the block
between ``<!-- bench:begin -->`` and ``<!-- bench:end -->`` of the README: per case, auto's model and its wall
time per simulated second against MoorDyn's at the case's smallest N at its largest stable step, the speed-up
measured in that one run, and auto's error against the converged reference. ``--check`` fails (exit 1) when the
README's block differs from what the JSON gives, so that a test can hold the two together.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

BEGIN, END = "<!-- bench:begin -->", "<!-- bench:end -->"


def _pct(v) -> str:
    return "n/a" if v is None else f"{100 * v:.2g} %"


def _x(v) -> str:
    return "n/a" if v is None else f"{v:.3g}x"


def table(bench: dict, source: str) -> str:
    """The Markdown block for ``bench`` (the content of ``bench_vs_moordyn.json``)."""
    rows = ["| case | auto's model | auto, s per simulated s | MoorDyn (N, s/s) | auto speed-up | auto error body / tension |",
            "|---|---|---|---|---|---|"]
    for r in bench.get("cases", []):
        auto = r.get("auto", {})
        md = (r.get("by_n") or [{}])[0]
        err = r.get("auto_error") or {}
        model = auto.get("model") or {}
        name = model.get("name", "?") + (f" N = {model['segments']}" if (model.get("segments") or 1) > 1 else "")
        md_s = md.get("moordyn_s_per_s")
        rows.append(f"| {r.get('case')} | {name} | {auto.get('s_per_s', float('nan')):.3g} | "
                    f"N = {md.get('segments', '?')}, {md_s if md_s is None else f'{md_s:.3g}'} | "
                    f"{_x(r.get('auto_speedup'))} | {_pct(err.get('body'))} / {_pct(err.get('tension'))} |")
    note = (f"Measured in one run of `studies/bench_vs_moordyn.py` ({source}{', quick mode' if bench.get('quick') else ''});"
            " regenerate with `python studies/readme_tables.py --bench DIR`.")
    return "\n".join([BEGIN, *rows, "", note, END])


def rewrite(readme: str, block: str) -> str:
    """``readme`` with its bench block replaced by ``block`` (a ValueError when the markers are missing)."""
    a, b = readme.find(BEGIN), readme.find(END)
    if a < 0 or b < a:
        raise ValueError(f"the README has no {BEGIN} ... {END} block")
    return readme[:a] + block + readme[b + len(END):]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bench", type=Path, required=True, help="folder holding bench_vs_moordyn.json")
    ap.add_argument("--readme", type=Path, default=Path(__file__).resolve().parents[1] / "README.md")
    ap.add_argument("--check", action="store_true", help="only compare; exit 1 when the README differs")
    args = ap.parse_args(argv)
    path = args.bench / "bench_vs_moordyn.json"
    bench = json.loads(path.read_text())
    try:
        src = str(path.resolve().relative_to(args.readme.resolve().parent))
    except ValueError:
        src = str(path)
    text = args.readme.read_text()
    new = rewrite(text, table(bench, src))
    if args.check:
        if new != text:
            print(f"{args.readme}: the performance table differs from {path}: run studies/readme_tables.py", file=sys.stderr)
            return 1
        return 0
    args.readme.write_text(new)
    print(f"wrote the performance table of {args.readme} from {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
