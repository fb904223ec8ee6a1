"""The README starts with two commands (install and run the main job; install and run the tests), and `.ci/run`
runs exactly the second one."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _quick_start_blocks() -> list[str]:
    text = (ROOT / "README.md").read_text()
    start = text.index("## Quick start")
    end = text.index("\n## ", start + 1)
    return [b.strip() for b in re.findall(r"```bash\n(.*?)```", text[start:end], flags=re.S)]


def test_ci_runs_exactly_the_readmes_test_command():
    blocks = _quick_start_blocks()
    assert len(blocks) == 2, blocks
    ci = [ln for ln in (ROOT / ".ci" / "run").read_text().splitlines() if ln and not ln.startswith(("#", "set ", "cd "))]
    assert ci == [blocks[1]]
    assert "pytest" in blocks[1] and ".[test" in blocks[1]
    # the first installs the package and runs the main job on the built-in default scene (no scene file given)
    assert blocks[0].endswith("cablesys run") and "pytest" not in blocks[0]
