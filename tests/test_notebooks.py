"""Notebooks run top to bottom in their quick mode (stored without outputs; they call the package).

``CABLESYS_QUICK=1`` tells each notebook to use fewer and shorter cases that still show the
physics (the resonance peak of the parameter sweep, the boundary of the operability chart);
the numbers behind them are checked by the tests of the package, not in notebook cells.
"""

from pathlib import Path

import pytest

NOTEBOOKS = sorted((Path(__file__).resolve().parents[1] / "notebooks").glob("*.ipynb"))


def test_there_are_notebooks():
    assert {p.name for p in NOTEBOOKS} >= {"parameter_sweep.ipynb", "isolation_design.ipynb", "operability.ipynb",
                                           "model_ladder.ipynb"}


@pytest.mark.slow
@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_notebook_runs(path, monkeypatch):
    nbformat = pytest.importorskip("nbformat", reason="install the test extras: pip install -e '.[test]'")
    nbclient = pytest.importorskip("nbclient")
    nb = nbformat.read(path, as_version=4)
    assert all(not c.get("outputs") for c in nb.cells if c.cell_type == "code"), "store notebooks without outputs"
    assert not any("assert" in c.source for c in nb.cells if c.cell_type == "code"), "checks belong in tests"
    monkeypatch.setenv("CABLESYS_QUICK", "1")
    monkeypatch.setenv("MPLBACKEND", "Agg")
    # each notebook meets new model structures (a realised sea, ladder rungs): CasADi's virtual machine runs
    # these few short cases sooner than compiling every structure to C on a cold cache (same equations)
    monkeypatch.setenv("CABLESYS_COMPILE", "0")
    nbclient.NotebookClient(nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(path.parent)}}).execute()
    # tqdm's notebook bar without ipywidgets warns "IProgress not found" in every sweep cell: the notebooks ask for
    # a bar only where ipywidgets is installed
    stderr = "".join(o.get("text", "") for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])
                     if o.get("output_type") == "stream" and o.get("name") == "stderr")
    assert "IProgress" not in stderr, stderr[:500]
