"""The README's performance table is the benchmark's JSON, written by studies/readme_tables.py (never typed)."""

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_the_readme_table_is_the_committed_benchmark_json():
    proc = subprocess.run([sys.executable, str(ROOT / "studies" / "readme_tables.py"), "--bench",
                           str(ROOT / "studies" / "results"), "--check"], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr


def test_the_table_states_each_cases_measured_ratio(tmp_path):
    sys.path.insert(0, str(ROOT / "studies"))
    import readme_tables
    bench = json.loads((ROOT / "studies" / "results" / "bench_vs_moordyn.json").read_text())
    block = readme_tables.table(bench, "x.json")
    for case in bench["cases"]:
        assert f"| {case['case']} |" in block and f"{case['auto_speedup']:.3g}x" in block
    readme = tmp_path / "README.md"
    readme.write_text("a\n<!-- bench:begin -->\nold\n<!-- bench:end -->\nb\n")
    new = readme_tables.rewrite(readme.read_text(), block)
    assert new.startswith("a\n") and new.endswith("\nb\n") and "old" not in new


def test_the_table_holds_the_other_ends_and_3d_runs_with_their_equal_n_ratios():
    """The mooring/lowering and 3-D runs (their own files, one run each) are rows of the same table, each with the
    segmented cable's equal-N speed-up of its own JSON, and the note names every file."""
    sys.path.insert(0, str(ROOT / "studies"))
    import readme_tables
    res = ROOT / "studies" / "results"
    files = [f for f in readme_tables.FILES if (res / f).exists()]
    benches = [json.loads((res / f).read_text()) for f in files]
    block = readme_tables.table(benches, files)
    for f, bench in zip(files, benches):
        assert f in block
        for case in bench["cases"]:
            row = next(line for line in block.splitlines() if line.startswith(f"| {case['case']} |"))
            if "by_n" in case:
                assert f"N = {case['by_n'][0]['segments']}: {case['by_n'][0]['speedup']:.3g}x" in row
            else:         # a slack plan case (_bench_slack.bench_plan_case): auto's and the equal-N ratios
                assert f"{case['auto_speedup']:.3g}x" in row and f"{case['speedup']:.3g}x" in row
