"""Regenerate the README's performance table from benchmark outputs (the README states no timing by hand).

    python studies/readme_tables.py --bench studies/results [--readme README.md] [--check]

Reads ``bench_vs_moordyn.json`` (``studies/bench_vs_moordyn.py --out DIR``) from ``--bench``, and beside it the
other ends', the 3-D cases' and the slack plans' files when present (``bench_vs_moordyn_ends.json``: ``--case mooring
--case lowering``; ``bench_vs_moordyn_3d.json``: ``--case turn --case crane_rao --case current45``;
``bench_vs_moordyn_plan.json``: ``--case light_lift --case harsh_sea``, each a copy of that run's
``bench_vs_moordyn.json``), and rewrites the block between
``<!-- bench:begin -->`` and ``<!-- bench:end -->`` of the README: per case, auto's model and its wall time per
simulated second against MoorDyn's at the case's smallest N at its largest stable step, the speed-up measured in
that one run, the segmented cable's speed-up at equal N (matched accuracy), and auto's error against the
converged reference. Each file is one run; the note under the table names them. ``--check`` fails (exit 1) when the
README's block differs from what the JSON gives, so that a test can hold the two together.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

BEGIN, END = "<!-- bench:begin -->", "<!-- bench:end -->"
FILES = ("bench_vs_moordyn.json", "bench_vs_moordyn_ends.json", "bench_vs_moordyn_3d.json",    # main, other ends, 3-D,
         "bench_vs_moordyn_plan.json")                                                        # the slack plans


def _pct(v) -> str:
    return "n/a" if v is None else f"{100 * v:.2g} %"


def _x(v) -> str:
    return "n/a" if v is None else f"{v:.3g}x"


def _equal_n(r: dict) -> str:
    """The segmented cable's speed-up over MoorDyn at each N of the case (matched accuracy), "n/a" without one."""
    got = [f"N = {e['segments']}: {_x(e['speedup'])}" for e in r.get("by_n") or [] if e.get("speedup") is not None]
    return ", ".join(got) or "n/a"


def _bound(r: dict) -> str:
    """The most auto could reach by stepping the node model (``_bench_auto.auto_bound``): MoorDyn's wall over the fastest run keeping auto's
    tolerance on every quantity, choice and checks free, with its N; "n/a" where the case did not measure it."""
    b = r.get("auto_bound") or {}
    if b.get("speedup_bound") is None:
        return "n/a" if not b.get("why") else "none below the reference N"
    v = b["speedup_bound"]
    shown = f"{v:.0f}x" if v >= 1000 else _x(v)          # 1226x, not 1.23e+03x
    return f"{shown} (N = {b['fastest']['segments']})"


def _plan_row(r: dict) -> str:
    """A plan case's row (``_bench_slack.bench_plan_case``: MoorDyn at its largest N, auto at its default tolerance,
    the segmented cable at that N)."""
    auto, n = r["auto_default"], max(int(k) for k in r["moordyn"])
    md = r["moordyn"][str(n)]
    name = (auto.get("model") or "?") + (f" N = {auto['segments']}" if (auto.get("segments") or 1) > 1 else "")
    err = auto.get("estimated_error") or {}
    eq = r.get(r.get("speedup_of") or "segmented_equal_n") or {}
    how = f" ({eq['method']}, rtol {eq['rtol']:g})" if eq.get("rtol") else ""
    return (f"| {r['case']} | {name} | {auto['wall_s'] / r['duration_s']:.3g} | N = {n}, {md['s_per_s']:.3g} | "
            f"{_x(r.get('auto_speedup'))} | N = {eq.get('segments', n)}{how}: {_x(r.get('speedup'))} | "
            f"{_pct(err.get('body'))} / {_pct(err.get('tension'))} (stated) | {_bound(r)} |")


def table(bench: dict | list, source: str | list) -> str:
    """The Markdown block for ``bench`` (the content of ``bench_vs_moordyn.json``), or for a list of such contents
    with a list of their sources (one run each)."""
    benches, sources = (bench, source) if isinstance(bench, list) else ([bench], [source])
    rows = ["| case | auto's model | auto, s per simulated s | MoorDyn (N, s/s) | auto speed-up | segmented at equal N "
            "| auto error body / tension | most auto can reach |",
            "|---|---|---|---|---|---|---|---|"]
    for r in (r for b in benches for r in b.get("cases", []) if "auto_default" in r and "moordyn" in r):
        rows.append(_plan_row(r))
    for r in (r for b in benches for r in b.get("cases", []) if "by_n" in r):
        auto = r.get("auto", {})
        md = (r.get("by_n") or [{}])[0]
        err = r.get("auto_error") or {}
        model = auto.get("model") or {}
        name = model.get("name", "?") + (f" N = {model['segments']}" if (model.get("segments") or 1) > 1 else "")
        md_s = md.get("moordyn_s_per_s")
        rows.append(f"| {r.get('case')} | {name} | {auto.get('s_per_s', float('nan')):.3g} | "
                    f"N = {md.get('segments', '?')}, {md_s if md_s is None else f'{md_s:.3g}'} | "
                    f"{_x(r.get('auto_speedup'))} | {_equal_n(r)} | {_pct(err.get('body'))} / {_pct(err.get('tension'))} | "
                    f"{_bound(r)} |")
    bound = ("Most auto can reach by stepping: MoorDyn's time over the fastest run of the node model at the least N that "
             "keeps auto's tolerance on every quantity against the converged reference (`_bench_auto.auto_bound`), "
             "with no choice and no check counted. No auto that steps the node model and keeps its stated error can "
             "pass it; only a cheaper rung that keeps the tolerance can (the steady rung on the turn).")
    runs = "; ".join(f"{src}{', quick mode' if b.get('quick') else ''}" for b, src in zip(benches, sources))
    note = (f"Measured in {'one run' if len(benches) == 1 else 'runs'} of `studies/bench_vs_moordyn.py` ({runs}; each "
            "file one run, its ratios measured in that run); regenerate with `python studies/readme_tables.py --bench DIR`.")
    return "\n".join([BEGIN, *rows, "", bound, "", note, END])


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
    path = args.bench / FILES[0]
    paths = [path] + [args.bench / f for f in FILES[1:] if (args.bench / f).exists()]
    benches, srcs = [], []
    for p in paths:
        benches.append(json.loads(p.read_text()))
        try:
            srcs.append(str(p.resolve().relative_to(args.readme.resolve().parent)))
        except ValueError:
            srcs.append(str(p))
    text = args.readme.read_text()
    new = rewrite(text, table(benches, srcs))
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
