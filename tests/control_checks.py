"""Checks shared by the heave-compensation tests (tests/test_control_*.py).

:func:`assert_compiled_optimum_equals_vm`: the open-loop optimum through the compiled kernels
(:mod:`cablesys.control.kernels`) against the same NLP in CasADi's virtual machine (inlined SX functions,
CasADi's full AD): two routes to the derivatives IPOPT sees, one optimum. Run it under the ``quick_compile``
fixture (tests/conftest.py), which switches compilation on.
"""

import numpy as np
import pytest

from cablesys.control import optimal_payout


def assert_compiled_optimum_equals_vm(problem, horizon: float, *, atol: float):
    """The optimum of ``problem`` over ``horizon`` s through its compiled kernels equals the virtual machine's: both
    converge, the objectives agree to 1e-8 relative, IPOPT takes the same iterations, and the controls agree to
    ``atol`` (m/s^2). Each route is checked to be the one it names (``HeaveProblem.nlp_functions``' flag) before
    it runs. Returns (compiled, vm), the two :class:`cablesys.control.PayoutResult`."""
    assert problem.nlp_functions()[2], "the compiled kernels did not build"
    fast = optimal_payout(problem, horizon)
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("CABLESYS_COMPILE", "0")
        assert not problem.nlp_functions()[2]
        slow = optimal_payout(problem, horizon)
    assert fast.success and slow.success, (fast.message, slow.message)
    assert fast.objective == pytest.approx(slow.objective, rel=1e-8)
    assert fast.stats["iterations"] == slow.stats["iterations"]
    np.testing.assert_allclose(fast.acceleration, slow.acceleration, atol=atol)
    return fast, slow
