"""The a posteriori check's integration part (cablesys.ladder.checks): the integration error of a run at rtol / 10,
estimated from its difference with the run at rtol (global error ~ Tol^(p/(p+1)), Hairer, Norsett & Wanner I,
sec. II.4), against the independent route: the same model run at a far tighter rtol."""

import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

from cablesys.ladder import checks, metrics, run_rung
from cablesys.ladder import estimate as est

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies"))


@pytest.fixture(scope="module")
def runs():
    """The quick generated wire (26 m surged in a sheared current, ladder_generated --quick, seed 22) as the node
    model with N = 4, BDF2 at rtol 1e-3 (the loose run), 1e-4 (the kept one) and 1e-8 (the reference)."""
    import ladder_generated as lg
    label, scene, _ = lg.scenes(22, 1, lg.QUICK)[0]
    period, ramp = metrics.forcing_period(scene), scene.top_motion.effective_ramp_s
    out = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for rtol in (1e-3, 1e-4, 1e-8):
            r = run_rung(scene, "segmented", 4, method="cvodes-bdf2", rtol=rtol, atol=rtol / 10)
            out[rtol] = metrics.statistics(r, period, ramp)
    return out


def test_the_stated_integration_error_is_at_least_half_the_actual_one(runs):
    """The kept run's stated integration error is at least half its actual one (against rtol 1e-8) on every quantity
    where that exceeds 3 x est.RESOLUTION, and with that floor, which every stated error has (the Richardson part is
    at least it), on every quantity. Measured here: the top tension maximum 1.3e-3 stated / 1.7e-3 actual, the surge
    amplitude 8.6e-4 / 8.3e-4; the rule is rough below the floor (the body-end tension maximum 2.5e-5 / 1.0e-4). The
    run at a tenth of the rtol is nearer the reference on the quantity the loose run misses most (the rule's
    premise)."""
    _, stated = checks.integration_errors(runs[1e-4], runs[1e-3], "cvodes-bdf2")
    actual = metrics.quantity_errors(runs[1e-4], runs[1e-8])
    loose = metrics.quantity_errors(runs[1e-3], runs[1e-8])
    worst = max(loose, key=loose.get)
    assert actual[worst] < loose[worst] and loose[worst] > 1e-3, (worst, loose[worst], actual[worst])
    resolved = {k: v for k, v in actual.items() if v > 3 * est.RESOLUTION}
    assert len(resolved) >= 2, actual
    low = {k: (stated[k], v) for k, v in resolved.items() if not stated[k] >= 0.5 * v}
    assert not low, low
    low = {k: (stated[k], v) for k, v in actual.items() if not stated[k] + est.RESOLUTION >= 0.5 * v}
    assert not low, low


def test_the_integration_factor_is_the_tolerance_rule():
    """1 / (10^(p/(p+1)) - 1): p = 2 for BDF2 (0.275), p = 1 for variable-order CVODES (0.462); fixed-step methods
    have none."""
    assert checks.integration_factor("cvodes-bdf2") == pytest.approx(1 / (10 ** (2 / 3) - 1), rel=1e-12)
    assert checks.integration_factor("cvodes") == pytest.approx(1 / (np.sqrt(10) - 1), rel=1e-12)
    assert not checks.adaptive("rk") and checks.adaptive("rk23")


def test_a_body_quantity_is_judged_on_the_motions_scale():
    """metrics.quantity_errors' body floor, worked by hand: in a steady turn of 75 m radius the depth amplitude is zero
    and a 4 mm integrator wobble there is 4e-3 / 7.5 of the motion (a tenth of the largest amplitude), not 40 % of a
    centimetre; under a 1 m heave a 3 cm surge amplitude off by half of itself (1.5 cm) is judged on a decimetre and
    is still 15 % off; with no motion at all the floor is 1 cm; tension extremes keep 1 % of the top tension."""
    turn = {"x_b_amplitude": 75.0, "z_b_amplitude": 75.0, "y_b_amplitude": 0.0, "y_b_mean": 48.6,
            "tension_top_max": 3725.0, "tension_top_min": 3725.0}
    wobble = dict(turn, y_b_amplitude=0.004, tension_top_min=3725.0 - 37.25)
    e = metrics.quantity_errors(wobble, turn)
    assert e["y_b_amplitude"] == pytest.approx(0.004 / 7.5, rel=1e-12)
    assert e["tension_top_min"] == pytest.approx(0.01, rel=1e-12) and e["x_b_amplitude"] == 0.0
    heave = {"x_b_amplitude": 0.03, "y_b_amplitude": 1.0, "x_b_mean": 0.0, "tension_top_max": 1e4}
    e = metrics.quantity_errors(dict(heave, x_b_amplitude=0.045, x_b_mean=0.002), heave)
    assert e["x_b_amplitude"] == pytest.approx(0.15, rel=1e-12) and e["x_b_mean"] == pytest.approx(0.02, rel=1e-12)
    still = {"x_b_amplitude": 0.0, "y_b_amplitude": 0.0, "x_b_mean": 0.5, "tension_top_max": 1e4}
    assert metrics.quantity_errors(dict(still, y_b_amplitude=0.001), still)["y_b_amplitude"] == pytest.approx(0.1)
    assert metrics.body_floor(still) == metrics.LENGTH_FLOOR_M


def test_a_systems_body_group_is_judged_on_the_body_floor():
    """metrics.errors on a system's points (point.NAME.x, ...), which may all stand still (a buoy moored in a current):
    the body group's difference is relative to the larger of the largest amplitude and metrics.body_floor, so 2 mm on a
    still system is 0.2 of a centimetre, on a buoy swinging 0.5 m 2 mm / 0.5 m; a chain's body group keeps its body's
    amplitude (2 mm on 5 mm is 0.4)."""
    still = {"point.buoy.x_amplitude": 0.0, "point.buoy.y_amplitude": 0.0, "point.anchor.x_amplitude": 0.0,
             "line.leg.tension_from_max": 1e5}
    off = dict(still, **{"point.buoy.x_amplitude": 0.002})
    assert metrics.errors(off, still)["body"] == pytest.approx(0.2, rel=1e-12)
    swing = dict(still, **{"point.buoy.y_amplitude": 0.5})
    assert metrics.errors(dict(swing, **{"point.buoy.x_amplitude": 0.002}), swing)["body"] == pytest.approx(0.004)
    chain = {"x_b_amplitude": 0.0, "y_b_amplitude": 0.005, "tension_top_max": 1e5}
    assert metrics.errors(dict(chain, x_b_amplitude=0.002), chain)["body"] == pytest.approx(0.4, rel=1e-12)


def _seq(f, ns):
    """Statistics of runs at N in ``ns`` for a body amplitude y(N) = f(N) beside a fixed 10 m heave and top tension."""
    return [{"x_b_amplitude": f(n), "y_b_amplitude": 10.0, "tension_top_max": 1e4} for n in ns]


def test_the_third_run_states_the_error_of_a_power_law_exactly():
    """richardson_triple on y(N) = 1 + c N^-q (q = 2, 1): the observed order is q, and the estimate of the N = 16 run is
    its exact error (c 16^-q, relative to y(16)); an oscillating sequence states the whole last difference, and in an
    irregular sea the larger of the last difference and the one before over 2^p."""
    from types import SimpleNamespace
    choice = SimpleNamespace(name="segmented", numbers={})
    for q, c in ((2.0, 3.0), (1.0, 0.4)):
        fine, coarse, quarter = _seq(lambda n: 1.0 + c * n ** -q, (16, 8, 4))
        e, per, orders = checks.richardson_triple(fine, coarse, quarter, choice)
        assert orders["x_b_amplitude"] == pytest.approx(q, rel=1e-12)
        assert per["x_b_amplitude"] == pytest.approx(c * 16 ** -q / fine["x_b_amplitude"], rel=1e-9)   # of y(16)
        assert e["body"] == pytest.approx(c * 16 ** -q / 10.0, rel=1e-9)   # the group: over the largest amplitude
    fine, coarse, quarter = _seq(lambda n: 1.0 + 0.05 * (-1) ** (n // 4) / n, (16, 8, 4))
    _, per, _ = checks.richardson_triple(fine, coarse, quarter, choice)
    assert per["x_b_amplitude"] == pytest.approx(abs(coarse["x_b_amplitude"] / fine["x_b_amplitude"] - 1.0), rel=1e-12)
    fine, coarse, quarter = _seq(lambda n: {16: 1.0, 8: 1.001, 4: 1.2}[n], (16, 8, 4))
    _, per, _ = checks.richardson_triple(fine, coarse, quarter, choice, irregular=True)
    assert per["x_b_amplitude"] == pytest.approx(0.199 / 4.0, rel=1e-9)
    _, per_pair = checks.richardson(fine, coarse, choice, irregular=True)
    assert per_pair["x_b_amplitude"] == pytest.approx(0.001, rel=1e-9)
