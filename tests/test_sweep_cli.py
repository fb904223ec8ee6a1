"""``cablesys sweep``: the sweep from the command line writes the Dataset, a CSV and one summary figure."""

import xarray as xr

from cablesys.cli import main
from cablesys.scene import dale_scene, dump_scene


def test_cli_sweep_writes_dataset_csv_and_plots(tmp_path, capsys):
    scene = tmp_path / "dale.toml"
    scene.write_text(dump_scene(dale_scene(duration=2.0)))
    out = tmp_path / "sw"
    code = main(["sweep", str(scene), "--vary", "cable.ae=10:1000:log:3", "--vary", "body.weight=0.2,0.3,-1",
                 "--metric", "tension_mid_max_N", "--metric", "tension_mid_min_N", "--workers", "1", "--out", str(out)])
    text = capsys.readouterr().out
    assert code == 1                                   # the -1 N body is refused: not every case is ok
    assert "9 cases" in text and "ok 6, not ok 3" in text and "body.weight" in text
    ds = xr.open_dataset(out / "sweep.nc", engine="scipy")
    assert ds["tension_mid_max_N"].dims == ("cable.ae", "body.weight")
    assert abs(float(ds["cable.ae"][1]) - 100.0) < 1e-9
    assert (out / "sweep.csv").read_text().splitlines()[0].startswith("cable.ae [N],body.weight [N],status")
    assert {p.name for p in (out / "plots").glob("*.png")} == {"sweep.png"}      # one summary figure per sweep
    # the same command again: everything is stored, nothing is computed
    assert main(["sweep", str(scene), "--vary", "cable.ae=10:1000:log:3", "--vary", "body.weight=0.2,0.3,-1",
                 "--metric", "tension_mid_max_N", "--metric", "tension_mid_min_N", "--workers", "1", "--out", str(out),
                 "--no-plots"]) == 1
    assert "0 computed now" in capsys.readouterr().out
