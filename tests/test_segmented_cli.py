"""A segmented scene (`segments = N` in [cable]) runs from `cablesys run` and writes its profiles
and the summary groups (tension, slack, body, model, window)."""

import json
from pathlib import Path

import cablesys
from cablesys.cli import main

SCENE = Path(cablesys.__file__).parent / "data" / "heave_300m.toml"


def test_run_segmented_scene(tmp_path):
    out = tmp_path / "heave"
    assert main(["run", str(SCENE), "--out", str(out), "--duration", "3", "--method", "rk",
                 "--model", "segmented", "--window", "1", "3"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["window_s"] == [1.0, 3.0]
    assert "segmented" in json.dumps(summary["model"])
    t = summary["tension"]
    assert 0 < t["top_min_N"] <= t["top_max_N"] and 0 <= t["bottom_min_N"] <= t["bottom_max_N"]
    assert t["top_max_N"] > 1937.0 + 19.6 * 300 * 0.9          # the top carries the cable's weight
    assert 0.0 <= summary["slack"]["time_fraction"] <= 1.0
    assert summary["body"]["y_mean_m"] > 290.0
    import xarray as xr
    with xr.open_dataset(out / "timeseries.nc") as ds:
        assert ds["element_tension"].dims == ("time", "element")
        assert float(ds["element_s"][-1]) < 300.0 < float(ds["node_s"][-1]) + 1.0
