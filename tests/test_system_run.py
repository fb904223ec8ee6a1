"""A cable system through every door: ``cablesys run`` on the shipped clump-span example (the ladder runs the node model
of a graph of lines and says why; outputs named per point and per line in the CSV, netCDF, summary and figure) and
the Python API on the same scene."""

import json
import tomllib

import numpy as np
import pytest

import cablesys
from cablesys.cli import main
from cablesys.examples import example_path
from cablesys.scene import dump_scene, load_scene, scene_from_dict

pytestmark = pytest.mark.filterwarnings("ignore")


def short(scene, duration=12.0):
    return scene.with_numerics(duration=duration, output_step=0.1)


def test_cablesys_run_on_a_system_names_its_model_points_and_lines(tmp_path, capsys):
    f = tmp_path / "span.toml"
    f.write_text(dump_scene(short(load_scene(example_path("clump-span")))))
    out = tmp_path / "out"
    assert main(["run", str(f), "--out", str(out)]) == 0
    console = capsys.readouterr().out
    summary = json.loads((out / "summary.json").read_text())
    model = summary["model"]
    assert model["name"] == "segmented" and "system of lines joined at points" in model["reason"]
    assert model["checked"].startswith("a posteriori")       # N checked against N / 2 on every point and line end
    assert "point.clump.y_mean" in model["estimated_error_per_quantity"]
    assert "line.drop.tension_from_max" in model["estimated_error_per_quantity"]
    lengths, forces = summary["statistics"]["length_m"], summary["statistics"]["force_N"]
    assert {"point.ring.x", "point.clump.y"} <= set(lengths) and "point.post.x" not in lengths   # free points only
    assert {f"line.{ln}.tension_{e}" for ln in ("left", "right", "drop") for e in ("from", "to")} == set(forces)
    assert "line.drop.tension_from" in console and "system of lines" in console
    header = (out / "timeseries.csv").read_text().splitlines()[0].split(",")
    assert "point.clump.x [m]" in header and "line.left.tension_from [N]" in header and "point.post.y [m]" in header
    import xarray as xr
    with xr.open_dataset(out / "timeseries.nc", engine="scipy") as ds:
        assert ds["point.ring.y"].attrs["units"] == "m" and ds["line.drop.tension_to"].attrs["units"] == "N"
        assert ds["node_x"].shape[1] == 4 + 3 * (model["segments"] - 1)   # points + interior nodes of the three lines
    assert (out / "timeseries.png").stat().st_size > 20000


def test_the_python_api_runs_the_same_scene_and_the_ring_balances_its_lines():
    """cablesys.simulate on the scene (the node model at the scene's N, as built): the drop line hangs below the ring,
    its tension at the ring is the clump's weight and its own while the top is at rest (before the smooth start moves
    it), and the run follows the top's heave."""
    scene = short(load_scene(example_path("clump-span")), 30.0)
    assert scene.system is not None and scene_from_dict(__import__("tomllib").loads(dump_scene(scene))) == scene
    r = cablesys.simulate(scene, model="as-built")
    assert r.success and r.stats["model"]["name"] == "segmented"
    assert r["line.drop.tension_from"][0] == pytest.approx(4000.0 + 20.0 * 20.0, rel=1e-6)
    assert np.allclose(r["point.crane.y"], r["y_s"]) and np.ptp(r["point.post.x"]) == 0.0
    late = r.time > 20.0
    assert np.ptp(r["point.clump.y"][late]) > 0.3          # the 0.5 m heave reaches the clump


def test_cablesys_run_as_built_plots_the_scenes_own_lines(tmp_path):
    """--model as-built runs the scene's own N per line section (8 here): the figure and the netCDF scene are that
    scene's (the run's model info counts all 24 elements, which is no N per section)."""
    f = tmp_path / "span.toml"
    f.write_text(dump_scene(short(load_scene(example_path("clump-span")), 4.0)))
    out = tmp_path / "out"
    assert main(["run", str(f), "--out", str(out), "--model", "as-built"]) == 0
    import xarray as xr
    with xr.open_dataset(out / "timeseries.nc", engine="scipy") as ds:
        assert ds["node_x"].shape[1] == 4 + 3 * 7
        assert scene_from_dict(__import__("tomllib").loads(ds.attrs["scene_toml"])).system.line[0].section[0].segments == 8
    assert (out / "timeseries.png").stat().st_size > 20000


def _span_toml(post_y: float = 10.0, segments: int = 3) -> str:
    text = example_path("clump-span").read_text()
    text = text.replace("y = 10.0 ", f"y = {post_y!r} ").replace("segments = 8", f"segments = {segments}")
    assert f"y = {post_y!r}" in text
    return text


def test_cablesys_rao_on_a_system_reports_its_points_and_lines(tmp_path, capsys):
    """``cablesys rao`` on the clump span (3 elements a line): RAO tables and figures per free point and line end (not
    the held points, whose motion is the input or zero), the describing function declined by name. At the band's
    lowest frequency (0.21 rad/s, a third of the first mode's) the clump's heave per unit crane heave is the static
    sensitivity: the crane down by d moves the post up by d relative to it, so RAO = 1 - d y_clump / d y_post (the
    statics of two spans, central difference), within 1e-3."""
    from cablesys.linear import linearize, rao
    from cablesys.model import build_model
    from cablesys.statics.system import system_steady
    f = tmp_path / "span.toml"
    f.write_text(_span_toml())
    out = tmp_path / "rao"
    assert main(["rao", str(f), "--out", str(out)]) == 0
    console = capsys.readouterr().out
    assert "describing function: not computed for a system of lines" in console
    doc = json.loads((out / "rao_summary.json").read_text())
    assert "system of lines" in doc["linearizations"]["describing function"]
    for name in ("point.clump.y_y_s", "point.ring.x_x_s", "line.drop.tension_from_y_s", "line.left.tension_to_x_s"):
        assert (out / f"rao_{name}.png").exists(), name
    assert not list(out.glob("rao_point.post.*")) and not list(out.glob("rao_point.crane.*"))
    rows = (out / "rao_exact_y_s.csv").read_text().splitlines()
    head, first = rows[0].split(","), np.array(rows[1].split(","), float)
    rao_low = first[head.index("point.clump.y_amp [m/m]")]
    assert first[0] < 0.4 * doc["natural_frequencies_rad_s"][0]
    d = 0.01
    y = [system_steady(m, m.parameters(sc)).outputs["point.clump.y"] for sc in
         (scene_from_dict(tomllib.loads(_span_toml(10.0 + s))) for s in (d, -d)) for m in [build_model(sc)]]
    static = 1.0 - (y[0] - y[1]) / (2 * d)
    assert 0.3 < static < 1.0                       # the clump follows the crane, less than one for one
    # at 0.21 rad/s the heave modes (3.15 rad/s and up) add at most (0.21 / 3.15)^2 = 0.45 %: measured 0.086 %
    assert rao_low == pytest.approx(static, rel=5e-3), (rao_low, static)
    sc = load_scene(f)                               # the API's linearization at 1e-3 rad/s: the static limit itself
    lin = linearize(m := build_model(sc), m.parameters(sc))
    assert abs(rao(lin, np.array([1e-3]))("point.clump.y", "y_s")[0]) == pytest.approx(static, rel=1e-5)
