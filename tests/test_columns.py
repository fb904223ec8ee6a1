"""Columns: a CasADi function over many columns through FunctionBuffer equals CasADi's own call."""

import casadi as ca
import numpy as np
import pytest

from cablesys.errors import ParameterError
from cablesys.time_domain.columns import Columns


def _function():
    x, p = ca.SX.sym("x", 3), ca.SX.sym("p", 2)
    # second output has a structural zero (row 1), as the top motion of a heave-only scene does
    return ca.Function("f", [x, p], [ca.vertcat(ca.sin(x[0]) * p[0], x[1] ** 2, ca.exp(x[2] - p[1])),
                                     ca.vertcat(x[0] * p[1], 0, x[2])])


@pytest.mark.parametrize("n", [1, 5, 7, 20])        # fewer, exactly and more columns than a block (5)
def test_matches_casadi_map_with_broadcast_parameters(n):
    f = _function()
    rng = np.random.default_rng(n)
    X, p = rng.normal(size=(3, n)), rng.normal(size=2)
    y1, y2 = Columns(f, block=5)(X, p)
    ref = f.map(n)(X, np.tile(p[:, None], (1, n)))
    assert y1.shape == (3, n) and y2.shape == (3, n)
    np.testing.assert_array_equal(y1, np.array(ref[0]))
    np.testing.assert_array_equal(y2, np.array(ref[1]))
    assert np.all(y2[1] == 0.0)


def test_per_column_parameters():
    f = _function()
    X, P = np.linspace(0, 1, 33).reshape(3, 11), np.linspace(1, 2, 22).reshape(2, 11)
    y1, _ = Columns(f, block=4)(X, P)
    np.testing.assert_allclose(y1, np.array(f.map(11)(X, P)[0]), rtol=1e-15, atol=0)


def test_bad_inputs_are_named():
    cols = Columns(_function(), block=4)
    with pytest.raises(ParameterError):
        cols(np.zeros((3, 4)))                                 # one input missing
    with pytest.raises(ParameterError):
        cols(np.zeros((3, 4)), np.zeros((2, 3)))               # 4 and 3 columns
    M = ca.SX.sym("M", 2, 2)
    with pytest.raises(ParameterError):
        Columns(ca.Function("g", [M], [M[0]]))                 # a matrix input


def test_concurrent_calls_from_threads_do_not_mix():
    """One Columns (one set of buffers) shared by threads, as a cached Simulator in a threaded worker."""
    from concurrent.futures import ThreadPoolExecutor
    f = _function()
    cols = Columns(f, block=3)
    rng = np.random.default_rng(7)
    inputs = [(rng.normal(size=(3, 50)), rng.normal(size=2)) for _ in range(8)]
    with ThreadPoolExecutor(4) as pool:
        got = list(pool.map(lambda a: cols(*a)[0], inputs))
    for (X, p), y in zip(inputs, got):
        np.testing.assert_array_equal(y, np.array(f.map(50)(X, np.tile(p[:, None], (1, 50)))[0]))
