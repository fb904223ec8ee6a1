"""The results namespace forms no import cycle: ``cablesys.results`` re-exports the protocol and the time-domain
result, and neither of those imports it back (function-local imports included)."""

import importlib
import subprocess
import sys

from test_architecture import PKG, imports_of, module_name

RESULTS = ("cablesys.results", "cablesys.result_protocol", "cablesys.time_result")


def _edges():
    """{module: set of cablesys modules it imports} for every module of the package."""
    out = {}
    for path in sorted(PKG.rglob("*.py")):
        mod = module_name(path)
        out[mod] = {target for _, target in imports_of(path, mod)}
    return out


def test_no_module_reachable_from_results_imports_it_back():
    edges = _edges()
    for start in RESULTS:
        seen, todo = set(), [start]
        while todo:
            mod = todo.pop()
            for target in edges.get(mod, ()):
                assert target != start, f"{start} is imported back by {mod}"
                if target not in seen:
                    seen.add(target)
                    todo.append(target)


def test_time_result_is_importable_first_and_from_results():
    """In a fresh interpreter, either order works and both names are the same class."""
    code = ("import cablesys.time_result as tr; from cablesys.results import TimeResult, SnapLoad; "
            "assert TimeResult is tr.TimeResult and SnapLoad is tr.SnapLoad")
    subprocess.run([sys.executable, "-c", code], check=True)
    res = importlib.import_module("cablesys.results")
    assert res.TimeResult is importlib.import_module("cablesys.time_result").TimeResult
