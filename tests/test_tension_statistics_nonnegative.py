"""No reported tension statistic is negative, extremes bound each other, and every model reports its slack: a
generated set of small scenes (the 2-DOF cable slack and snapping, a rope made to push by a -inf floor, a
two-section chain, the segmented 300 m wire slack at its body end, the linear sea route), short durations,
models in CasADi's VM."""

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
from test_time_domain_slack import bouncing_scene

import cablesys
from cablesys import verdict as vd
from cablesys.scene import Numerics, Sinusoid, TopMotion, load_scene
from cablesys.scene.limits import Limits
from cablesys.scene.sea import SeaSpectrum
from cablesys.time_domain import simulate

HEAVE = Path(cablesys.__file__).parent / "data" / "heave_300m.toml"
LIMITS = Limits(statistics_start=None, safe_working_load=1e9, least_tension=0.0)


def _heave(segments: int, duration: float, floor: float = 0.0):
    """The 300 m wire with its 2 t sphere heaved 1 m at T = 6 s after a 18 s ramp (its body end goes slack)."""
    sc = load_scene(HEAVE)
    sc = dataclasses.replace(sc, top_motion=dataclasses.replace(sc.top_motion, ramp_s=18.0))
    sc = sc.with_numerics(duration=duration, output_step=0.05)
    return sc.replace_section(0, cable={"segments": segments, "tension_floor": floor})


def _chain():
    from test_chain_model import _body, _cable
    from cablesys.scene import Scene, Section
    secs = (Section(cable=_cable(10.0, 1e4, mass=False), body=_body(100.0, 20.0)),
            Section(cable=_cable(5.0, 1e4, mass=False), body=_body(50.0, 8.0)))
    return Scene(sections=secs, top_motion=TopMotion(y=(Sinusoid(amplitude=0.3, frequency=6.0),)),
                 numerics=Numerics(duration=3.0, output_step=0.02, drag_segments=2))


SCENES = {
    "2dof-slack": lambda: bouncing_scene(duration=3.0, heave=0.05),
    "2dof-rope-pushes": lambda: bouncing_scene(duration=2.0).replace_section(0, cable={"tension_floor": -math.inf}),
    "chain-heaved": _chain,
    "segmented-slack": lambda: _heave(4, 26.0),
}


def _tension_numbers(tree, path=()):
    """(path, value) of every number in ``tree`` that is a tension (N): a key or group naming a tension, or
    ending in _N; rates (N/s) and counts are not."""
    if isinstance(tree, dict):
        for k, v in tree.items():
            yield from _tension_numbers(v, path + (str(k),))
    elif isinstance(tree, (list, tuple)):
        for k, v in enumerate(tree):
            yield from _tension_numbers(v, path + (str(k),))
    elif isinstance(tree, (int, float)) and not isinstance(tree, bool):
        key = path[-1] if path else ""
        tension_path = any(p.startswith("tension") or p == "force_N" or p == "snap_loads" for p in path)
        skip = key in ("time", "rate", "section", "element", "std", "zero_upcrossing_period_s", "slack_time_s",
                       "slack_probability", "events", "snap_loads") or key.endswith("_s") or "fraction" in key
        if not skip and (tension_path or key.endswith("_N")):
            yield "/".join(path), float(tree)


def _pairs_bound(stats: dict):
    """Every statistics entry with max and min has max >= min, and each x_max_N >= x_min_N."""
    for path, entry in _dicts(stats):
        if "max" in entry and "min" in entry:
            assert entry["max"] >= entry["min"], path
        for k in entry:
            if k.endswith("_max_N") and k.replace("_max_N", "_min_N") in entry:
                assert entry[k] >= entry[k.replace("_max_N", "_min_N")], f"{path}/{k}"


def _dicts(tree, path=""):
    if isinstance(tree, dict):
        yield path, tree
        for k, v in tree.items():
            yield from _dicts(v, f"{path}/{k}")
    elif isinstance(tree, (list, tuple)):
        for k, v in enumerate(tree):
            yield from _dicts(v, f"{path}/{k}")


@pytest.fixture(scope="module", autouse=True)
def _vm_models():
    """Models in CasADi's VM (no C compile) for this module only."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("CABLESYS_COMPILE", "0")
        yield


@pytest.fixture(scope="module")
def runs(_vm_models):
    return {name: simulate(make()) for name, make in SCENES.items()}


@pytest.mark.parametrize("name", list(SCENES))
def test_no_tension_statistic_is_negative_and_extremes_bound_each_other(runs, name):
    r = runs[name]
    assert r.success, r.message
    out = {"summary": r.summary(), "report": vd.report(type("S", (), {"limits": LIMITS})(), r)}
    numbers = list(_tension_numbers(out))
    assert len(numbers) > 10                                   # the walk finds the tension statistics
    bad = [(p, v) for p, v in numbers if v < 0.0]
    assert not bad, bad[:5]
    _pairs_bound(out)
    # the verdict reads the extremes the warnings print: its peak is at least the window's largest snap load
    inside, _ = vd.window_snap_loads(r, LIMITS)
    assert out["report"]["verdict"]["peak_tension"]["value"] >= max((s.tension for s in inside), default=0.0)


def test_a_rope_made_to_push_reports_zero_and_its_slack_time(runs):
    """The injected fault: a -inf floor lets the 2-DOF cable push (it starts 0.2 m short, k = 1000 N/m: -200 N).
    The statistics say 0 N, the time it pushed as slack time (the output steps that start at a sample <= 0), the
    run's summary the same slack time, and the note names the raw minimum."""
    r = runs["2dof-rope-pushes"]
    raw = np.asarray(r["tension_mid"])
    assert raw.min() < -100.0                                  # the fault is there
    s = vd.run_statistics(r, Limits(statistics_start=0.0))["tension_mid"]
    assert s["min"] == 0.0 and s["mean"] >= 0.0
    assert s["slack_time_s"] == pytest.approx(float(np.sum(np.diff(r.time)[raw[:-1] <= 0.0])), abs=1e-12)
    assert s["slack_time_s"] > 0.1 and "fell to" in s["note"]
    assert not r.events                                         # no located switch at a -inf floor, yet:
    assert r.summary()["time_slack_s"] == pytest.approx(s["slack_time_s"], abs=1e-12)   # the summary says the same


def test_segmented_slack_comes_from_the_element_tensions(runs):
    """The segmented run's slack time, events and snap loads are filled: the slack time is the output time with
    any element slack (an independent sum over the samples' flags), the events alternate per element, every snap
    load is a tension peak at least the sampled tensions around it, and the bottom element is the slack one."""
    r = runs["segmented-slack"]
    s = r.summary()
    flags = r.profiles["element_slack"] > 0.5
    any_slack = np.any(flags, axis=1)
    assert any_slack.any()                                     # the case is slack
    assert s["time_slack_s"] == pytest.approx(float(np.sum(np.diff(r.time)[any_slack[:-1]])), abs=1e-9)
    assert s["slack_events"] and s["snap_loads"]
    for k in {e["element"] for e in s["slack_events"]}:
        kinds = [e["kind"] for e in s["slack_events"] if e["element"] == k]
        assert all(a != b for a, b in zip(kinds, kinds[1:]))   # slack, taut, slack, ...
    T = r.profiles["element_tension"]
    for snap in s["snap_loads"]:
        i = int(np.searchsorted(r.time, snap["time"]))
        assert snap["tension"] >= max(T[max(i - 1, 0), snap["element"]], T[min(i, T.shape[0] - 1), snap["element"]]) - 1e-6
    sl = s["slack"]
    n = flags.shape[1]
    assert sl["bottom_time_fraction"] == pytest.approx(sl["element_time_fraction"][n - 1])
    assert sl["top_time_fraction"] == pytest.approx(sl["element_time_fraction"][0])
    assert sl["bottom_time_fraction"] > 0.2 and sl["time_fraction"] >= sl["bottom_time_fraction"]
    assert sl["snap_loads"] == sum(1 for x in s["snap_loads"] if s["window_s"][0] <= x["time"] <= s["window_s"][1])
    w = vd.warnings_of(r)
    assert any("went slack" in x for x in w) and any("snap loads" in x for x in w)


def test_linear_sea_route_reports_no_negative_tension():
    """The 2-DOF 300 m wire in a steep sea (H_s 6 m): its Gaussian most probable minimum tension falls below 0
    (mean - sqrt(2 ln(T/T_z)) sigma < 0); the sea response, the grouped statistics and the verdict read 0 N with
    the slack probability."""
    from cablesys.linear import linearize
    from cablesys.linear.sea_response import sea_response
    from cablesys.model import build_model
    sc = _heave(1, 10.0)
    sc = sc.replace(top_motion=TopMotion(spectrum=SeaSpectrum(hs=6.0, tp=6.0, n_components=50)))
    model = build_model(sc)
    resp = sea_response(sc, linearize(model, model.parameters(sc)), exposure=3 * 3600.0)
    stats = {k: v for k, v in resp.statistics.items() if k.startswith("tension")}
    raw = [v["most_probable_min"] for v in stats.values()]
    gaussian = [v["mean"] - math.sqrt(2.0 * math.log(3 * 3600.0 / v["zero_upcrossing_period_s"])) * v["std"]
                for v in stats.values() if v.get("zero_upcrossing_period_s")]
    assert min(gaussian) < 0.0                                 # the Gaussian minimum is negative here ...
    assert min(raw) == 0.0                                     # ... and the sea response reports 0 N, saying so
    assert any("below 0: reported as 0" in v.get("note", "") for v in stats.values())
    grouped = vd.group_by_quantity(resp.statistics)
    assert not [(p, v) for p, v in _tension_numbers(grouped) if v < 0.0]
    assert all(0.0 < e["slack_probability"] < 1.0 for e in grouped["force_N"].values())
    v = vd.evaluate(Limits(least_tension=0.0, exposure=3 * 3600.0), resp.statistics)
    assert v["least_tension"]["value"] == 0.0
