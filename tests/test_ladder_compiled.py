"""The ladder run compiled, as users run it (a C compiler present), where its choice differs from the VM's.

The suite runs CasADi's VM (tests/conftest.py); the ladder's decisions are asserted both ways without a build
(tests/ladder_pricing.py). The runs here take the compiled choice where it is not the VM's: the quasi-static
rung where nothing drives the swing (below); the quasi-static segmented cable stepped by the rk23 pair is run
compiled by tests/test_ladder_plan.py (test_compiled_auto_on_the_heavy_wire_within_tolerance).
Every test of this module runs compiled (the ``compiling`` fixture is module scoped).
"""

import shutil
import warnings

import pytest
from ladder_pricing import both
from test_ladder import _wire_300m

from cablesys.errors import NumericalWarning
from cablesys.ladder import choose, metrics, run_rung, simulate

pytestmark = pytest.mark.skipif(shutil.which("cc") is None, reason="no C compiler")
TOL = (0.01, 0.02)


def test_compiled_pure_heave_runs_the_quasi_static_rung_within_its_estimate(compiling):
    """300 m wire, 2 t sphere, 1 m heave at T = 10 s (omega/omega_ax = 0.0996): compiled, auto runs the
    quasi-static rung (nothing drives the swing: it steps no stretch), where the VM runs Wang's model. Against
    Wang's model (the stretch stepped, CVODES rtol 1e-7) its tension extremes differ by the quasi-static spring's
    r^2 / |1 - r^2| of the dynamic tension (estimated 0.18 %, actual 0.16 %): within 2x of the estimate and
    within the tolerance, as is the body motion. The choice the environment makes (CABLESYS_COMPILE=1, the
    describing function compiled) is the one priced compiled without a build."""
    scene = _wire_300m(10.0)
    period = 10.0
    with warnings.catch_warnings():
        warnings.simplefilter("error", NumericalWarning)          # within its validity: no warning
        got = simulate(scene)
    m = got.stats["model"]
    assert (m["name"], m["segments"]) == ("quasi-static", 1), m["reason"]
    assert "nothing drives the swing" in m["reason"] and "compiled code is off" not in m["reason"]
    ref = run_rung(scene, "wang", method="cvodes-bdf2", rtol=1e-7, atol=1e-10)
    actual = metrics.errors(metrics.statistics(got, period), metrics.statistics(ref, period))
    assert actual["body"] <= TOL[0] and actual["tension"] <= TOL[1]
    assert 0.5 <= m["estimated_error"]["tension"] / actual["tension"] <= 2.0
    real = choose(scene)
    priced_compiled, vm = both(scene)
    assert (real.name, real.segments) == (priced_compiled.name, priced_compiled.segments)
    assert real.reason == priced_compiled.reason
    assert (vm.name, vm.segments) == ("wang", 1)
