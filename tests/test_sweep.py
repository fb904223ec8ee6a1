"""Parameter sweeps: equal to the same cases run one by one, failures recorded, resumable, one model per structure."""

import json

import numpy as np
import pytest

import cablesys
from cablesys import units as U
from cablesys.errors import ParameterError
from cablesys.scene import OMEGA_N_MEASURED, dale_scene
from cablesys.sweeps import Grid, backends, parse_values, parse_vary
from cablesys.sweeps.worker import process_cache

DURATION = 19.0          # 6 periods at 1.8 omega_n: amplitudes over the last 3
RATIOS = (1.8, 2.2)
AE = (5.0 * U.LBF, 500.0 * U.LBF)
FREQ = {"top_motion.x[0].frequency": [r * OMEGA_N_MEASURED for r in RATIOS],
        "top_motion.y[0].frequency": [r * OMEGA_N_MEASURED for r in RATIOS]}
ZIP = [("top_motion.x[0].frequency", "top_motion.y[0].frequency")]
METRICS = ["tension_mid_max_N", "tension_mid_min_N", "amplitude_x_b", "amplitude_y_b"]


def base():
    return dale_scene(duration=DURATION)


def one_by_one(ae, ratio):
    """The case built and run independently: its own scene, model and simulator."""
    scene = dale_scene(omega_ratio=ratio, duration=DURATION).replace_section(0, cable={"ae": ae})
    r = cablesys.simulate(scene)        # the door the sweep runs: the scene's numerics.model (as built here)
    w = r.window_mask()                 # the run's one statistics window, which the sweep's amplitudes use too
    half = lambda y: 0.5 * (np.max(y[w]) - np.min(y[w]))
    s = r.summary()                     # its extremes located between samples (cablesys.time_domain.peaks)
    return {"tension_mid_max_N": s["tension_mid_max_N"], "tension_mid_min_N": s["tension_mid_min_N"],
            "amplitude_x_b": half(np.asarray(r["x_b"])), "amplitude_y_b": half(np.asarray(r["y_b"]))}


def test_sweep_equals_the_cases_run_one_by_one():
    ds = cablesys.sweep(base(), {"cable.ae": list(AE), **FREQ}, "run", zip=ZIP, metrics=METRICS,
                        workers=2, progress=False)
    assert ds.attrs["backend"] == "processes"
    assert ds["status"].dims == ("cable.ae", "top_motion.x[0].frequency") and ds["status"].shape == (2, 2)
    assert ds["cable.ae"].attrs["units"] == "N" and ds["top_motion.x[0].frequency"].attrs["units"] == "rad/s"
    assert ds["tension_mid_max_N"].attrs["units"] == "N" and ds["amplitude_x_b"].attrs["units"] == "m"
    assert (ds["status"] == "ok").all()
    for i, ae in enumerate(AE):
        for j, ratio in enumerate(RATIOS):
            ref = one_by_one(ae, ratio)
            for name in METRICS:
                np.testing.assert_allclose(float(ds[name][i, j]), ref[name], rtol=1e-10, err_msg=name)


def test_one_model_per_structure_values_only_through_p(monkeypatch):
    monkeypatch.setenv("CABLESYS_COMPILE", "0")      # counting model builds: no need to compile each structure to C
    cache = process_cache()
    n0 = len(cache.rungs)                            # the run analysis builds through the ladder's cache
    scene = dale_scene(duration=1.0).with_numerics(model="as-built")
    ds = cablesys.sweep(scene, {"cable.ae": [20.0, 40.0, 80.0], "body.weight": [0.2, 0.3]},
                        "run", metrics=["tension_mid_max_N"], workers=1, progress=False)
    assert (ds["status"] == "ok").all() and len(cache.rungs) - n0 <= 1
    n1 = len(cache.rungs)
    ds = cablesys.sweep(scene, {"numerics.drag_segments": [3, 5, 7]}, "run",
                        metrics=["tension_mid_max_N"], workers=1, progress=False)
    assert (ds["status"] == "ok").all() and len(cache.rungs) - n1 == 3      # the structure changes: one model each


@pytest.mark.filterwarnings("ignore::cablesys.errors.NumericalWarning")    # RK4 above its limit: on purpose
def test_failures_are_recorded_and_the_sweep_completes():
    """An integrator failure (explicit RK4 far above its stability limit) and an invalid value
    (a body lighter than water with TENS = 0) fail their cases only."""
    scene = dale_scene(duration=2.0).with_numerics(integrator="rk", steps_per_output=1, model="as-built")
    ds = cablesys.sweep(scene, {"cable.ae": [22.0, 1e5], "body.weight": [0.11, -1.0]}, "run",
                        metrics=["tension_*"], workers=1, progress=False)
    status, msg = ds["status"].values, ds["message"].values
    assert status[0, 0] == "ok" and np.isfinite(float(ds["tension_mid_max_N"][0, 0]))
    assert status[1, 0] == "failed" and "rk failed" in msg[1, 0] and "stability limit" in msg[1, 0]
    assert list(status[:, 1]) == ["error", "error"]
    assert all("body.weight" in m and "tension_floor" in m for m in msg[:, 1])
    assert ds.attrs["n_ok"] == 1


@pytest.mark.slow
def test_an_infeasible_design_is_recorded():
    from cablesys.isolation.example import dual_scene, example_settings
    ds = cablesys.sweep(dual_scene(), {"design.n_sigma": [40.0]}, "design", workers=1, progress=False,
                        options={"settings": example_settings(n_starts=1, outer_iterations=1)})
    assert ds["status"].values[0] == "infeasible"
    assert "slack_1" in ds["message"].values[0] and "cannot be met" in ds["message"].values[0]


def _interrupt_after(n, monkeypatch):
    real = backends.run_case
    calls = []

    def run_case(spec, k, cache):
        if len(calls) == n:
            raise KeyboardInterrupt
        calls.append(k)
        return real(spec, k, cache)
    monkeypatch.setattr(backends, "run_case", run_case)


def test_an_interrupted_sweep_resumes_with_the_missing_cases_only(tmp_path, monkeypatch):
    scene, vary = dale_scene(duration=1.0), {"cable.ae": [20.0, 40.0, 80.0], "body.weight": [0.2, 0.3]}
    kw = {"metrics": ["tension_mid_max_N"], "workers": 1, "progress": False, "out": tmp_path, "chunk_size": 1}
    _interrupt_after(4, monkeypatch)
    with pytest.raises(KeyboardInterrupt):
        cablesys.sweep(scene, vary, "run", **kw)
    monkeypatch.undo()
    assert len(list((tmp_path / "cases").glob("chunk-*.nc"))) == 4
    (tmp_path / "cases" / "chunk-99999999-damaged.nc").write_bytes(b"CDF\x01 truncated")   # a torn write
    ds = cablesys.sweep(scene, vary, "run", **kw)
    assert ds.attrs["n_computed"] == 2 and (ds["status"] == "ok").all()
    fresh = cablesys.sweep(scene, vary, "run", metrics=["tension_mid_max_N"], workers=1, progress=False)
    np.testing.assert_array_equal(ds["tension_mid_max_N"].values, fresh["tension_mid_max_N"].values)
    again = cablesys.sweep(scene, vary, "run", **kw)
    assert again.attrs["n_computed"] == 0
    with pytest.raises(ParameterError, match="different sweep"):
        cablesys.sweep(scene, {"cable.ae": [20.0]}, "run", **kw)
    assert json.loads((tmp_path / "sweep.json").read_text())["analysis"] == "run"
    assert (tmp_path / "sweep.nc").exists()


def test_grid_outer_product_and_zip():
    g = Grid.build({"a": [1, 2, 3], "b": [10.0, 20.0], "c": [5, 6]}, zip=[("a",)])
    assert g.shape == (3, 2, 2) and len(g) == 12
    assert g.case(7) == {"a": 2, "b": 20.0, "c": 6}
    z = Grid.build({"a": [1, 2], "b": [3, 4]}, zip=True)
    assert z.shape == (2,) and z.dims == ("a",) and z.case(1) == {"a": 2, "b": 4}
    with pytest.raises(ParameterError, match="equal lengths"):
        Grid.build({"a": [1, 2], "b": [3]}, zip=True)


def test_cli_value_specs():
    np.testing.assert_allclose(parse_values("1e5:1e7:log:3"), [1e5, 1e6, 1e7])
    np.testing.assert_allclose(parse_values("0:1:lin:5"), [0, 0.25, 0.5, 0.75, 1.0])
    assert parse_values("2000,3000,4000") == [2000, 3000, 4000]
    assert parse_vary(["numerics.integrator=cvodes,idas"]) == {"numerics.integrator": ["cvodes", "idas"]}
    with pytest.raises(ParameterError):
        parse_values("1:2:cubic:4")


def test_unknown_labels_are_refused_before_any_computation():
    with pytest.raises(ParameterError, match="no scene field"):
        cablesys.sweep(dale_scene(), {"cable.stiffness": [1.0]}, progress=False)
    with pytest.raises(ParameterError, match="out of range"):
        cablesys.sweep(dale_scene(), {"top_motion.x[3].frequency": [1.0]}, progress=False)
    with pytest.raises(ParameterError, match="analysis"):
        cablesys.sweep(dale_scene(), {"cable.ae": [1.0]}, "fatigue", progress=False)


def test_rao_and_periodic_sweeps_give_the_physics():
    """Linear natural frequency vs AE (stretch mode sqrt(k / M)); periodic orbit amplitudes finite."""
    scene = dale_scene(duration=1.0)
    ds = cablesys.sweep(scene, {"cable.ae": [50.0, 200.0, 800.0]}, "rao", workers=1, progress=False)
    assert (ds["status"] == "ok").all()
    w_max = ds[[v for v in ds.data_vars if v.startswith("omega_n_")]].to_array().max("variable").values
    np.testing.assert_allclose(w_max[1:] / w_max[:-1], 2.0, rtol=0.02)     # omega_u ~ sqrt(AE / l): x2 per x4
    # a chunk linearized in one mapped CasADi call equals the cases linearized one by one
    one = cablesys.sweep(scene, {"cable.ae": [50.0, 200.0, 800.0], "body.weight": [0.2, 0.3]}, "rao", workers=1,
                         progress=False, chunk_size=1)
    mapped = cablesys.sweep(scene, {"cable.ae": [50.0, 200.0, 800.0], "body.weight": [0.2, 0.3]}, "rao", workers=1,
                            progress=False, chunk_size=6)
    for v in one.data_vars:
        if one[v].dtype.kind == "f" and v != "wall_s":
            np.testing.assert_allclose(mapped[v].values, one[v].values, rtol=1e-12, err_msg=v)
    per = cablesys.sweep(scene, {"top_motion.x[0].frequency": [2.5], "top_motion.y[0].frequency": [2.5]}, "periodic",
                         zip=True, workers=1, progress=False)
    assert per["status"].values[0] == "ok" and 0 < float(per["amplitude_x_b"][0]) < 0.1


@pytest.mark.slow
def test_the_model_chosen_is_recorded():
    """As built: Wang's 2-DOF model; under the model ladder (the default, as cablesys.simulate): its choice for each case."""
    from cablesys.ladder import choose
    scene = dale_scene(duration=2.0)
    vary = {"cable.ae": [20.0, 2e3]}
    built = cablesys.sweep(scene, vary, "run", metrics=["model_*"], workers=1, progress=False,
                           options={"model": "as-built"})
    assert list(built["model_name"].values) == ["wang", "wang"]
    auto = cablesys.sweep(scene, vary, "run", metrics=["model_*"], workers=1, progress=False)
    for i, ae in enumerate(vary["cable.ae"]):
        choice = choose(scene.replace_section(0, cable={"ae": ae}))
        assert auto["model_name"].values[i] == choice.name and float(auto["model_segments"][i]) == choice.segments


def test_ladder_sweep_maps_the_choice_without_running():
    """The ladder analysis equals cablesys.ladder.choose case by case (a cheap map of which model when)."""
    from cablesys.ladder import choose
    scene = dale_scene()
    w = [0.3 * OMEGA_N_MEASURED, 3.0 * OMEGA_N_MEASURED]
    ds = cablesys.sweep(scene, {FX: w, FY: w}, "ladder", zip=True, workers=1, progress=False)
    for i, wi in enumerate(w):
        c = choose(dale_scene(omega_ratio=wi / OMEGA_N_MEASURED))
        assert ds["model_name"].values[i] == c.name and float(ds["model_segments"][i]) == c.segments
    # slow forcing needs less model (the quasi-static rung names both the straight and the segmented cable)
    rungs = [(ds["model_name"].values[i], float(ds["model_segments"][i])) for i in range(2)]
    assert rungs[0] != rungs[1]


FX, FY = "top_motion.x[0].frequency", "top_motion.y[0].frequency"
