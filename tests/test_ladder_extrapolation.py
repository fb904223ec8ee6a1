"""Richardson extrapolation of the slack segmented cable's statistics (cablesys.ladder.extrapolation).

Closed forms: a first-order sequence f* + a / N is extrapolated to f* exactly; with a second-order
remainder b / N^2 the stated error of the extrapolated value, |L(N/2) - L(N)| / (2^2 - 1), is its
error exactly. On a short scene that converges at first order in N (partial slack predicted): auto's
extrapolated statistics are closer to a finer reference (the limit of 2N, 4N) than its N run, and its
stated errors are within 2x of the actual ones where those are resolved. The run command writes the
block into summary.json.
"""

import json
import math
from pathlib import Path

import numpy as np
import pytest

import cablesys
from cablesys.ladder import RungCache, metrics, simulate
from cablesys.ladder import estimate as est
from cablesys.ladder import extrapolation as X
from cablesys.ladder import richardson as R
from cablesys.ladder.choice import choose
from cablesys.scene import load_scene

KEYS = ("x_b_amplitude", "y_b_amplitude", "tension_top_max", "tension_top_min", "tension_bottom_max",
        "tension_bottom_min")
LIMIT = dict(zip(KEYS, (0.0, 1.4, 54000.0, 250.0, 43000.0, 30.0)))


def _sequence(a: dict, b: dict, ns=(8, 16, 32)) -> dict:
    """{N: f* + a_k / N + b_k / N^2} for every statistic."""
    return {n: {k: LIMIT[k] + a[k] / n + b[k] / n**2 for k in KEYS} for n in ns}


def test_first_order_sequence_recovers_its_limit():
    a = dict(zip(KEYS, (0.0, 2.0, 9.0e4, 4.0e3, 6.0e4, 900.0)))
    block = R.extrapolate(_sequence(a, dict.fromkeys(KEYS, 0.0)), 32)
    for k in KEYS:
        assert block["statistics"][k] == pytest.approx(LIMIT[k], rel=1e-12, abs=1e-9)
        assert block["statistics_coarse"][k] == pytest.approx(LIMIT[k], rel=1e-12, abs=1e-9)
    assert block["observed_order"]["y_b_amplitude"] == pytest.approx(1.0, rel=1e-12)
    assert block["asymptotic"] and block["segments"] == [8, 16, 32]
    assert block["estimated_error"]["body"] < 1e-12 and block["estimated_error"]["tension"] < 1e-12
    # the time series' own error is the N run's first-order one: |f(N) - f*| relative
    assert block["time_series_error"]["body"] == pytest.approx(a["y_b_amplitude"] / 32 / LIMIT["y_b_amplitude"],
                                                               rel=1e-9)


def test_remainder_estimate_is_exact_on_a_second_order_remainder():
    """f = f* + a / N + b / N^2: L(N) - f* = -2 b / N^2 and L(N/2) - L(N) = -6 b / N^2, so the stated
    |L(N/2) - L(N)| / 3 is the extrapolated value's error."""
    a = dict(zip(KEYS, (0.0, 2.0, 9.0e4, -4.0e3, 6.0e4, 900.0)))
    b = dict(zip(KEYS, (0.0, -4.0, 1.8e5, 8.0e3, -1.2e5, 1.8e3)))     # 1/4 of the leading term at N = 8
    block = R.extrapolate(_sequence(a, b), 32)
    assert block["remainder_factor"] == pytest.approx(1.0 / 3.0)
    for k in KEYS[1:]:
        err = block["statistics"][k] - LIMIT[k]
        assert err == pytest.approx(-2.0 * b[k] / 32**2, rel=1e-9)
        assert (block["statistics_coarse"][k] - block["statistics"][k]) / 3.0 == pytest.approx(err, rel=1e-9)
    # the relative figures: the stated error against the actual error of the extrapolated statistics
    actual = metrics.errors(block["statistics"], LIMIT)
    for k in ("body", "tension"):
        assert block["estimated_error"][k] == pytest.approx(actual[k], rel=0.01)


def test_per_quantity_statement_is_exact_on_a_second_order_remainder():
    """The same closed form per number (means included): each extrapolated number's stated error, relative to its
    own value (metrics.quantity_errors' floors), is its actual error; an exact limit states the resolution floor."""
    keys = KEYS + ("x_b_mean", "y_b_mean")
    lim = dict(LIMIT, x_b_mean=12.0, y_b_mean=58.0)
    a = dict(zip(keys, (0.0, 2.0, 9.0e4, -4.0e3, 6.0e4, 900.0, 8.0, -3.0)))
    b = dict(zip(keys, (0.0, -4.0, 1.8e5, 8.0e3, -1.2e5, 1.8e3, -16.0, 6.0)))
    seq = {n: {k: lim[k] + a[k] / n + b[k] / n**2 for k in keys} for n in (8, 16, 32)}
    block = R.extrapolate(seq, 32)
    per, actual = block["estimated_error_per_quantity"], metrics.quantity_errors(block["statistics"], lim)
    assert set(per) == set(keys)
    for k in keys[1:]:
        assert actual[k] > 1e-4 and per[k] == pytest.approx(actual[k], rel=0.01), k     # relative to L(N), not f*
    assert per["x_b_amplitude"] == est.RESOLUTION and actual["x_b_amplitude"] < 1e-12
    # the N run's own per number: |f(N) - L(N)| relative, the first-order estimate of its error
    ts = block["time_series_error_per_quantity"]
    assert ts["x_b_mean"] == pytest.approx(abs(seq[32]["x_b_mean"] - seq[16]["x_b_mean"]) / block["statistics"]["x_b_mean"],
                                           rel=1e-9)


def test_a_number_outside_the_order_range_states_its_whole_difference():
    """Leading numbers first order (asymptotic), one tension minimum not (f(N/4) > f(N/2) < f(N): observed order
    below the range): its own statement is the whole difference of the two limits, at least the correction, not the
    remainder estimate the leading numbers earn."""
    a = dict(zip(KEYS, (0.0, 2.0, 9.0e4, 0.0, 6.0e4, 900.0)))
    seq = _sequence(a, dict.fromkeys(KEYS, 0.0))
    for n, v in zip((8, 16, 32), (1400.0, 1200.0, 1670.0)):
        seq[n]["tension_top_min"] = v
    block = R.extrapolate(seq, 32)
    assert block["asymptotic"] and block["observed_order"]["tension_top_min"] < R.ORDER_RANGE[0]
    fine, coarse = block["statistics"], block["statistics_coarse"]
    assert fine["tension_top_min"] == pytest.approx(2 * 1670.0 - 1200.0)
    floor = metrics.TENSION_FLOOR_FRACTION * fine["tension_top_max"]
    whole = abs(coarse["tension_top_min"] - fine["tension_top_min"]) / max(fine["tension_top_min"], floor)
    corr = abs(1670.0 - fine["tension_top_min"]) / max(fine["tension_top_min"], floor)
    assert block["estimated_error_per_quantity"]["tension_top_min"] == pytest.approx(max(whole, corr))
    # the leading numbers keep the remainder estimate (their differences are exactly first order: their limit's)
    assert block["estimated_error_per_quantity"]["tension_top_max"] == est.RESOLUTION


def test_not_asymptotic_states_the_whole_difference_and_floors_tension_minima():
    """Differences growing from N/4 to N (observed order below 0.5): not in the asymptotic range, the stated
    error is the whole difference of the two limits, at least the extrapolation's own correction; a limit
    below the tension floor is set to it."""
    seq = {4: dict(LIMIT), 8: dict(LIMIT, y_b_amplitude=1.45, tension_top_max=60000.0),
           16: dict(LIMIT, y_b_amplitude=1.55, tension_top_max=58000.0, tension_bottom_min=10.0)}
    block = R.extrapolate(seq, 16, floor=0.0)
    assert not block["asymptotic"] and block["remainder_factor"] == 1.0
    assert block["statistics"]["tension_bottom_min"] == 0.0          # 2 x 10 - 30 = -10 < floor
    diff = metrics.errors(block["statistics_coarse"], block["statistics"])
    corr = metrics.errors(seq[16], block["statistics"])
    assert block["estimated_error"] == pytest.approx({k: max(diff[k], corr[k]) for k in diff})


def test_statistics_step_samples_the_snap():
    """The 300 m steel wire's axial travel time 300 sqrt(2.5 / 4e7) = 0.075 s: 6 samples in it need a step
    <= 0.0125 s; the scene file's 0.05 s is divided by 4."""
    heave = load_scene(Path(cablesys.__file__).parent / "data" / "heave_300m.toml")
    assert X.statistics_step(heave) == pytest.approx(0.0125)
    assert X.statistics_step(heave.with_numerics(output_step=0.01)) == pytest.approx(0.01)


def slack_scene(duration: float = 40.0):
    """The 300 m / 2 t heave at T = 6 s on a rope 33x softer (AE 1.2e6 N, internal damping scaled by
    sqrt(AE)) with 3x the sphere's drag: partial slack predicted, and RK4 runs cheap in CasADi's VM
    (its stable step follows the axial wave, 7x slower)."""
    heave = load_scene(Path(cablesys.__file__).parent / "data" / "heave_300m.toml")
    c, b = heave.cable, heave.body
    sc = heave.replace_section(0, cable={"ae": 0.03 * c.ae, "internal_damping": c.internal_damping * math.sqrt(0.03)},
                               body={"drag_area_normal": 3 * b.drag_area_normal,
                                     "drag_area_tangential": 3 * b.drag_area_tangential})
    return sc.with_numerics(duration=duration, output_step=0.05)


@pytest.mark.slow
def test_auto_extrapolates_closer_to_a_finer_reference():
    scene = slack_scene()
    assert X.applies(choose(scene), auto=True)          # partial slack predicted: first order in N
    cache = RungCache()
    r = simulate(scene, cache=cache)
    model = r.stats["model"]
    block = model["extrapolated"]
    n = model["segments"]
    assert block["segments"] == [n // 4, n // 2, n] and block["asymptotic"]
    assert model["estimated_error"] == pytest.approx(block["estimated_error"])
    period = metrics.forcing_period(scene)
    fine = scene.with_numerics(output_step=X.statistics_step(scene))
    ref_runs = {m: R.statistics(X.run(fine, m, cache), period) for m in (2 * n, 4 * n)}
    reference = R.limits(ref_runs[2 * n], ref_runs[4 * n])
    got, series = metrics.errors(block["statistics"], reference), metrics.errors(R.statistics(r, period), reference)
    # the reference's own error: the remainder estimate of its pair, from the limits of (N, 2N) and (2N, 4N)
    unc = {k: v / 3.0 for k, v in metrics.errors(R.limits(R.statistics(r, period), ref_runs[2 * n]), reference).items()}
    tol = {"body": 0.01, "tension": 0.02}
    for k in ("body", "tension"):
        assert got[k] < 0.5 * series[k], (k, got, series)       # the extrapolated statistics are closer
        assert got[k] <= tol[k]
        stated = model["estimated_error"][k]
        if got[k] > max(0.1 * tol[k], 2 * unc[k]):              # resolved: within a factor 2
            assert 0.5 <= stated / got[k] <= 2.0, (k, stated, got)
        else:
            assert stated <= tol[k]
        ts = model["estimated_error_time_series"][k]             # the N run's own, stated apart
        assert 0.5 <= ts / series[k] <= 2.0, (k, ts, series)
    assert np.all(np.isfinite(r["y_b"]))


@pytest.mark.slow
def test_run_command_writes_the_extrapolated_block(tmp_path, capsys):
    from cablesys.cli import main
    from cablesys.scene import dump_scene
    path = tmp_path / "slack.toml"
    path.write_text(dump_scene(slack_scene(24.0)))
    out = tmp_path / "out"
    assert main(["run", str(path), "--out", str(out)]) == 0
    model = json.loads((out / "summary.json").read_text())["model"]
    block = model["extrapolated"]
    assert model["name"] == "segmented" and block["segments"][-1] == model["segments"]
    assert model["estimated_error"] == pytest.approx(block["estimated_error"])
    assert model["estimated_error_time_series"] == pytest.approx(block["time_series_error"])
    assert "extrapolated" in model["estimated_error_refers_to"] and "extrapolated" in model["reason"]
    assert set(KEYS) <= set(block["statistics"]) and block["window_s"][1] == pytest.approx(24.0)
    # the console line: the extrapolated statistics' error first, the N run's series' own apart
    assert "statistics extrapolated from N = " + ", ".join(map(str, block["segments"])) in capsys.readouterr().out


def test_a_triple_far_below_the_tolerance_keeps_its_conservative_error_whatever_its_order():
    """Differences of 1e-5 relative whose observed order is outside ORDER_RANGE (the time-step error of the coarse
    runs, not their N): the conservative error (factor 1) is stated and N does not double under the default tolerance;
    under a tolerance within 10x of it, or with differences as large as the tolerance, it doubles."""
    tiny = {4: dict(LIMIT), 8: dict(LIMIT, y_b_amplitude=1.4 * (1 + 2e-5), tension_top_max=54000.0 * (1 + 1e-5)),
            16: dict(LIMIT, y_b_amplitude=1.4 * (1 + 2.5e-5), tension_top_max=54000.0 * (1 + 1.9e-5))}
    block = R.extrapolate(tiny, 16)
    assert not block["asymptotic"] and block["remainder_factor"] == 1.0
    assert block["leading_orders"]["tension_top_max"] < R.ORDER_RANGE[0]          # log2(1 / 0.9) = 0.15
    e = block["estimated_error"]
    assert 1e-6 < e["body"] < 1e-4 and 1e-6 < e["tension"] < 1e-4
    assert not R.needs_doubling(block, (0.01, 0.02)) and block["settled_in_noise"]
    assert R.needs_doubling(block, (5 * e["body"], 5 * e["tension"])) and not block["settled_in_noise"]
    large = {4: dict(LIMIT), 8: dict(LIMIT, y_b_amplitude=1.45, tension_top_max=60000.0),
             16: dict(LIMIT, y_b_amplitude=1.55, tension_top_max=58000.0)}
    assert R.needs_doubling(R.extrapolate(large, 16), (0.01, 0.02))


def test_a_triple_converging_faster_than_first_order_keeps_its_conservative_error():
    """Differences of one sign shrinking 16x per doubling (observed order 4, above ORDER_RANGE): the conservative
    error (factor 1) holds the tail (at most 1/15 of the last difference) and N does not double when it is within the
    tolerance; the same sizes with alternating signs (a crossing, not convergence) double."""
    amp, top = LIMIT["y_b_amplitude"], LIMIT["tension_top_max"]

    def seq(d8, d16):
        return {4: dict(LIMIT, y_b_amplitude=amp * (1 - 0.0016), tension_top_max=top * (1 - 0.008)),
                8: dict(LIMIT, y_b_amplitude=amp * (1 - d8), tension_top_max=top * (1 - 0.004)),
                16: dict(LIMIT, y_b_amplitude=amp * (1 - d16), tension_top_max=top * (1 - 0.002))}
    block = R.extrapolate(seq(0.0001, 0.00000625), 16)
    assert block["leading_orders"]["y_b_amplitude"] == pytest.approx(4.0, rel=0.01) and not block["asymptotic"]
    assert block["converging"]
    e, actual = block["estimated_error"], metrics.errors(block["statistics"], LIMIT)
    assert e["body"] >= actual["body"] and e["tension"] >= actual["tension"] and e["body"] < 0.01
    assert not R.needs_doubling(block, (0.01, 0.02)) and block["kept_converging"]
    # f(8) above f(16) above f(4) at the same distances: the differences change sign
    block = R.extrapolate(seq(0.0001, 0.0001 + 0.0015 / 16), 16)
    assert not block["converging"] and R.needs_doubling(block, (0.01, 0.02))
