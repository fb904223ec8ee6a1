"""The slack extrapolation's plan (cablesys.ladder.extrapolation.plan): checked before the first run.

Injected limits with a known outcome: an output limit between the scene's grid and the statistics grid
coarsens the statistics step (to the finest integer fraction of the scene's step that fits) and says so; a
limit below the scene's own grid refuses the plan as the plan's (PlanRefused, not a ParameterError of the
user's input) before any run; a time budget below the plan's predicted cost (an injected cost per step)
halves N until the plan fits, or refuses at once. The candidate run on the statistics grid gives the
caller the scene's grid (streamed and returned) and the same series as a run on that grid to the RK4
step's error; each run's description names its place in the plan.
"""

import math
from pathlib import Path

import numpy as np
import pytest

import cablesys
from cablesys.errors import ParameterError
from cablesys.ladder import RungCache, metrics
from cablesys.ladder import extrapolation as X
from cablesys.ladder import richardson as R
from cablesys.ladder.choice import choose
from cablesys.scene import load_scene
from cablesys.time_domain import record


def slack_scene(duration: float = 12.0):
    """The 300 m / 2 t heave at T = 6 s on a rope 33x softer with 3x the sphere's drag: partial slack predicted
    (the scene of tests/test_ladder_extrapolation.py, output step 0.25 s: 4 statistics steps in one)."""
    heave = load_scene(Path(cablesys.__file__).parent / "data" / "heave_300m.toml")
    c, b = heave.cable, heave.body
    sc = heave.replace_section(0, cable={"ae": 0.03 * c.ae, "internal_damping": c.internal_damping * math.sqrt(0.03)},
                               body={"drag_area_normal": 3 * b.drag_area_normal,
                                     "drag_area_tangential": 3 * b.drag_area_tangential})
    return sc.with_numerics(duration=duration, output_step=0.25)


@pytest.fixture(scope="module")
def planned():
    scene = slack_scene()
    cache = RungCache()
    choice = choose(scene, cache=cache)
    assert X.applies(choice, auto=True)
    return scene, choice, cache


def _outputs(scene, step):
    return int(math.floor(scene.numerics.duration / step + 1e-9)) + 1


def test_plan_runs_the_candidate_on_the_statistics_grid(planned):
    scene, choice, cache = planned
    _, kw = X.plan(scene, choice, cache, {}, measure=False)
    p = kw["extrapolation_plan"]
    n, h = choice.segments, scene.numerics.output_step
    assert [(r.segments, r.candidate) for r in p.runs] == [(n, True), (n // 2, False), (n // 4, False)]
    assert p.shared and p.statistics_step == pytest.approx(X.statistics_step(scene)) and p.base_step == h
    assert all(r.outputs == _outputs(scene, p.statistics_step) and r.output_step == p.statistics_step for r in p.runs)
    # the step floor is the scene's steps per output of the scene's step: h_rk4 <= h / steps_per_output
    for r in p.runs:
        assert r.output_step / r.steps_per_output <= h / scene.numerics.steps_per_output * (1 + 1e-12)
        assert r.steps == r.steps_per_output * (r.outputs - 1) and r.predicted_s is None
    # the statistics runs at N / 2, N / 4 step no longer than the N run: their time error is below its own, so the
    # differences in N that the extrapolation reads are not the time steps'
    h_n = p.runs[0].output_step / p.runs[0].steps_per_output
    assert all(r.output_step / r.steps_per_output <= h_n * (1 + 1e-12) for r in p.runs[1:])
    assert p.max_step() == pytest.approx(h_n)


def test_an_output_limit_coarsens_the_statistics_grid_and_says_so(planned, monkeypatch):
    scene, choice, cache = planned
    h = scene.numerics.output_step
    best = round(h / X.statistics_step(scene))
    assert best >= 3
    fits = best - 1                              # the finest fraction h / k within the limit below
    monkeypatch.setattr(record, "MAX_OUTPUTS", _outputs(scene, h / fits))
    _, kw = X.plan(scene, choice, cache, {}, measure=False)
    p = kw["extrapolation_plan"]
    assert p.statistics_step == pytest.approx(h / fits)
    assert all(r.outputs <= record.MAX_OUTPUTS for r in p.runs)
    assert any("statistics runs at output step" in note for note in p.notes)


def test_a_plan_that_cannot_fit_is_refused_before_any_run_as_the_plans(planned, monkeypatch):
    scene, choice, cache = planned
    monkeypatch.setattr(record, "MAX_OUTPUTS", _outputs(scene, scene.numerics.output_step) - 1)
    runs = []
    with pytest.raises(X.PlanRefused, match="nothing was run") as err:
        cablesys.simulate(scene, cache=cache, on_run=lambda d, c: runs.append(d))
    assert not isinstance(err.value, ParameterError) and runs == []


def _inject_step_cost(monkeypatch, per_element_s):
    """A known cost per step (``per_element_s`` x N) in place of the measured one."""
    monkeypatch.setattr(X, "_step_seconds", lambda model, *a: per_element_s * model.n_elements)


def test_a_time_budget_halves_n_until_the_predicted_plan_fits(planned, monkeypatch):
    scene, choice, _ = planned
    cache = RungCache()
    n = choice.segments
    _inject_step_cost(monkeypatch, 1e-2)
    _, kw = X.plan(scene, choice, cache, {})
    full = sum(r.predicted_s for r in kw["extrapolation_plan"].runs)
    _, kw = X.plan(scene, choice.__class__(choice.name, n // 2, choice.reason, choice.estimated_error, choice.numbers),
                   cache, {})
    half = sum(r.predicted_s for r in kw["extrapolation_plan"].runs)
    assert n // 2 >= X.MIN_SEGMENTS and half <= 0.5 * full * (1 + 1e-12)     # steps x per-step cost (N / 2: half)
    budget = 0.5 * (half + full)       # fits N / 2, not N (planning itself takes far less than the margin)
    assert full - budget > 5.0 and budget - half > 5.0
    got, kw = X.plan(scene.with_numerics(time_budget_s=budget), choice, cache, {})
    p = kw["extrapolation_plan"]
    assert got.segments == n // 2 and [r.segments for r in p.runs] == [n // 2, n // 4, n // 8]
    assert sum(r.predicted_s for r in p.runs) == pytest.approx(half)
    assert f"time budget {budget:g} s" in got.reason and f"N = {n}" in got.reason


def test_a_budget_no_plan_fits_is_refused_at_once(planned, monkeypatch):
    scene, choice, _ = planned
    cache = RungCache()
    _inject_step_cost(monkeypatch, 1e-3)
    runs = []
    with pytest.raises(X.PlanRefused, match="time budget 0.001 s"):
        cablesys.simulate(scene.with_numerics(time_budget_s=1e-3), cache=cache, on_run=lambda d, c: runs.append(d))
    assert runs == []


def test_every_keeps_the_scene_grid_of_a_finer_run(planned):
    """The shared candidate (the statistics grid) subsampled to the scene's grid: the same times, and the same
    series as a run on the scene's grid to the RK4 step's error (both RK4 within its stability limit)."""
    scene, choice, cache = planned
    n = choice.segments // 4
    _, kw = X.plan(scene, choice, cache, {}, measure=False)
    p = kw["extrapolation_plan"]
    blocks, names = [], []

    def on_run(description, candidate):
        names.append(description)
        return (lambda t, d: blocks.append(np.asarray(t))), None
    kw["on_run"] = on_run
    p.runs.insert(0, X.PlannedRun(n, p.statistics_step, p.runs[0].outputs, 1, None, 0.0, True))
    shared = X.run(scene, n, cache, kw)
    direct = X.run(scene, n, cache, {})
    assert names == [f"segmented N = {n} (run 1 of 4)"]
    assert np.array_equal(np.concatenate(blocks), scene.output_times)
    assert np.allclose(shared.time, scene.output_times, rtol=0, atol=1e-12) and shared.states.shape == direct.states.shape
    assert n in p.statistics and set(shared.profiles) == set(direct.profiles)
    for k in ("y_b", "tension_top"):
        scale = np.ptp(direct[k])
        assert np.max(np.abs(shared[k] - direct[k])) < 1e-4 * scale, k
    period = metrics.forcing_period(scene)
    assert metrics.errors(p.statistics[n], R.statistics(direct, period))["body"] < 1e-4


def test_a_failed_doubling_keeps_the_extrapolation_made_before(planned, monkeypatch):
    """An injected failure of the 2 N run (a tolerance no N meets makes N double): the N run and its extrapolation
    from N / 4, N / 2, N are returned, the failure said in the reason."""
    import dataclasses
    scene, choice, cache = planned
    n = choice.segments
    real = X.run

    def failing(sc, m, cache_, kw=None, candidate=True):
        r = real(sc, m, cache_, kw, candidate)
        return dataclasses.replace(r, success=False, message="injected fault") if m == 2 * n else r
    monkeypatch.setattr(X, "run", failing)
    _, kw = X.plan(scene, choice, cache, {}, measure=False)
    first = X.run(scene, n, cache, kw)
    result, got = X.until_done(scene, choice, (1e-12, 1e-12), first, cache, kw)
    assert result is first and result.success
    assert got.segments == n and got.numbers["extrapolated"]["segments"] == [n // 4, n // 2, n]
    assert f"N = {2 * n} failed (injected fault)" in got.reason
    assert got.estimated_error == pytest.approx(got.numbers["extrapolated"]["estimated_error"])


def test_a_doubling_past_the_memory_limit_replans_on_a_coarser_grid(planned, monkeypatch):
    """An injected memory limit that the plan at N fits on the statistics grid and the runs at 2 N do not: the
    doubling replans 2 N, N, N / 2 on a coarser grid (an integer fraction of the scene's step), says so, and
    extrapolates from them; the doubling stops at 2 N (MAX_SEGMENTS)."""
    scene, choice, _ = planned
    cache = RungCache()
    n = choice.segments
    _, kw = X.plan(scene, choice, cache, {}, measure=False)
    p = kw["extrapolation_plan"]
    fine = p.statistics_step
    monkeypatch.setattr(record, "MAX_MEMORY_BYTES", 1.01 * max(r.memory_bytes for r in p.runs))
    monkeypatch.setattr(X, "MAX_SEGMENTS", 2 * n)
    first = X.run(scene, n, cache, kw)
    result, got = X.until_done(scene, choice, (1e-12, 1e-12), first, cache, kw)
    block = got.numbers["extrapolated"]
    assert got.segments == 2 * n and block["segments"] == [n // 2, n, 2 * n]
    h = scene.numerics.output_step
    assert p.statistics_step > fine and round(h / p.statistics_step) * p.statistics_step == pytest.approx(h)
    assert any(note.startswith(f"from N = {2 * n}: statistics runs at output step") for note in p.notes)
    assert all(r.memory_bytes <= record.MAX_MEMORY_BYTES for r in p.runs[3:])
    assert [(r.segments, r.status) for r in p.runs[3:]] == [(2 * n, "success"), (n, "success"), (n // 2, "success")]
    assert np.allclose(result.time, scene.output_times)
