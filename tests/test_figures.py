"""Every figure of run, rao and design, for the default scene and an irregular sea: written, and no
drawn curve is numerical noise (a response below 1e-9 of the largest on its axes is not drawn)."""

import numpy as np
import pytest

import cablesys.isolation.plots as design_plots
import cablesys.linear.plots as linear_plots
import cablesys.plots.time_domain as td_plots
from cablesys.cli import main
from cablesys.examples import example_text


def _is_reference_line(line) -> bool:
    """axvline/axhline markers (two points, constant x or y) and marker-only series."""
    x, y = np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)
    if line.get_linestyle() in ("None", "none", ""):
        return True
    return len(x) == 2 and (x[0] == x[1] or y[0] == y[1])


def _check(fig):
    for ax in fig.axes:
        curves = [np.asarray(ln.get_ydata(), float) for ln in ax.get_lines() if not _is_reference_line(ln)]
        for y in curves:
            assert np.isfinite(y).sum() >= 2, f"a curve with no finite points on '{ax.get_ylabel()}'"
        if ax.get_yscale() == "log" and curves:
            top = max(np.nanmax(np.abs(y)) for y in curves)
            for y in curves:
                assert np.nanmax(np.abs(y)) > 1e-9 * top, f"a noise curve drawn on '{ax.get_ylabel()}'"
                assert np.nanmin(y[np.isfinite(y)]) > 0


@pytest.fixture
def checked(monkeypatch):
    seen = []
    for mod in (linear_plots, design_plots, td_plots):
        original = mod.save_figure

        def wrapped(fig, path, _orig=original, **kw):
            _check(fig)
            seen.append(str(path))
            return _orig(fig, path, **kw)
        monkeypatch.setattr(mod, "save_figure", wrapped)
    return seen


def _pngs(folder):
    return sorted(p.name for p in folder.glob("*.png"))


@pytest.mark.slow
@pytest.mark.parametrize("which", ["default", "irregular"])
def test_every_figure_of_run_rao_and_design(tmp_path, capsys, checked, which):
    f = tmp_path / "scene.toml"
    if which == "default":
        assert main(["scene", "--example", "--design"]) == 0
        f.write_text(capsys.readouterr().out.replace("duration = 120.0", "duration = 20.0"))
    else:
        f.write_text(example_text("rov-lift").replace("duration = 600.0", "duration = 90.0")
                     .replace("n_components = 60", "n_components = 16").replace("n_starts = 3", "n_starts = 2"))
    assert main(["run", str(f), "--out", str(tmp_path / "run")]) == 0
    assert _pngs(tmp_path / "run") == ["timeseries.png"]
    assert main(["rao", str(f), "--out", str(tmp_path / "rao"), "--n", "120"]) == 0
    rao = _pngs(tmp_path / "rao")
    assert "modes.png" in rao and "rao_y_b_y_s.png" in rao and "rao_tension_top_y_s.png" in rao
    assert ("sea_response.png" in rao) == (which == "irregular")
    out = capsys.readouterr().out
    if which == "default":     # a straight-hanging Dale cable: heave does not move x_b (listed, not drawn)
        assert "x_b per unit y_s" in out and "rao_x_b_y_s.png" not in rao
    main(["design", str(f), "--out", str(tmp_path / "design")])
    assert _pngs(tmp_path / "design") == ["design_margins.png", "design_objective.png", "design_rao.png"]
    assert len(checked) == 1 + len(rao) + 3
