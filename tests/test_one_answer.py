"""One scene, one answer: the Python API, ``cablesys run`` and ``sweep`` run the same model on the same scene,
compiled as users run it, and say which model ran and why in the same words."""

import json

import numpy as np
import pytest
import xarray as xr

import cablesys
from cablesys.cli import main
from cablesys.scene import dale_scene, dump_scene


@pytest.fixture(scope="module")
def scene():
    # the Dale scene above its resonance, smooth start: the ladder picks a quasi-static segmented cable (compiled, rk23)
    return dale_scene(omega_ratio=1.5, duration=20.0).with_numerics(model="auto")


def _same(a, b, path="model"):
    """``a`` equals ``b``: every string, count and key exactly, every float to 1e-4 relative."""
    if isinstance(a, dict):
        assert set(a) == set(b), path
        for k in a:
            _same(a[k], b[k], f"{path}.{k}")
    elif isinstance(a, list):
        assert len(a) == len(b), path
        for i, (x, y) in enumerate(zip(a, b)):
            _same(x, y, f"{path}[{i}]")
    elif isinstance(a, float):
        assert a == pytest.approx(b, rel=1e-4, abs=1e-12), path
    else:
        assert a == b, path


def test_api_run_and_sweep_run_the_same_model_and_give_the_same_numbers(scene, tmp_path, compiling):
    api = cablesys.simulate(scene)
    model = api.stats["model"]
    assert set(model) >= {"name", "segments", "reason", "estimated_error"}

    path = tmp_path / "scene.toml"
    path.write_text(dump_scene(scene))
    assert main(["run", str(path), "--out", str(tmp_path / "run")]) == 0
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    # the same block, word for word; its numbers to 1e-4: the CLI streams its runs in blocks (each a call of the
    # integrator), the API runs each in one call, and the check's stated errors, differences of runs, carry that
    # rounding-level difference amplified
    _same(summary["model"], json.loads(json.dumps(model)))
    with xr.open_dataset(tmp_path / "run" / "timeseries.nc") as ds:    # SI, full precision
        np.testing.assert_allclose(ds["time"].values, api.time, rtol=0, atol=1e-12)
        for lbl in ("x_b", "y_b", "tension_top"):
            np.testing.assert_allclose(ds[lbl].values, api[lbl], rtol=1e-12, atol=1e-12 * np.max(np.abs(api[lbl])))

    ae = float(scene.sections[0].cable.ae)
    ds = cablesys.sweep(scene, {"cable.ae": [ae]}, workers=1, progress=False)
    assert str(ds["model_name"].values.ravel()[0]) == model["name"]
    assert int(ds["model_segments"].values.ravel()[0]) == model["segments"]
    assert str(ds["model_reason"].values.ravel()[0]) == model["reason"]
    for axis in ("x", "y"):
        for what in ("amplitude", "mean"):
            got = float(ds[f"body_{axis}_{what}_m"].values.ravel()[0])
            assert got == pytest.approx(summary["body"][f"{axis}_{what}_m"], rel=1e-12, abs=1e-15)


def test_simulate_honours_numerics_model_and_names_what_ran(compiling):
    base = dale_scene(omega_ratio=1.5, duration=6.0)
    qs = cablesys.simulate(base.with_numerics(model="quasi-static"))
    assert qs.stats["model"]["name"] == "quasi-static" and "requested" in qs.stats["model"]["reason"]
    built = cablesys.simulate(base.with_numerics(model="as-built"))
    assert built.stats["model"]["name"] == "wang" and "as built" in built.stats["model"]["reason"]
    assert built.stats["model"]["estimated_error"] == {"body": None, "tension": None}     # not estimated: says so
    assert built.summary()["model"]["name"] == "wang"
    # a built model runs as built, and the frequency rung's result is the same kind as every other rung's
    freq = cablesys.simulate(base, model="frequency")
    assert type(freq) is type(built) and freq.summary()["model"]["name"] == "frequency"
