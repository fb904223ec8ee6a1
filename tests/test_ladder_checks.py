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
