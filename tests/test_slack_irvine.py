"""Closed forms of Irvine-Caughey theory (Griffin & Rosenthal 1985 eqs. 4-28)."""

import math

import numpy as np
import pytest

from cablesys.errors import ParameterError
from cablesys.slack import irvine


@pytest.mark.parametrize("lam2", [0.5, 4.0, 30.0, 4 * math.pi ** 2, 100.0, 36 * math.pi ** 2, 1e4])
def test_symmetric_roots_one_per_branch_and_satisfy_eq6(lam2):
    x = irvine.symmetric_roots(lam2, 12)
    k = np.arange(1, 13)
    assert np.all(x > (k - 0.5) * math.pi) and np.all(x < (k + 0.5) * math.pi)
    resid = np.tan(x) - (x - 4 * x ** 3 / lam2)
    assert np.max(np.abs(resid / (1 + np.abs(x) ** 3 / lam2))) < 1e-8


def test_crossover_at_4pi2():
    # first symmetric root equals the first antisymmetric value beta l / 2 = pi
    assert irvine.symmetric_roots(irvine.LAMBDA2_CROSSOVER, 1)[0] == pytest.approx(math.pi, rel=1e-12)
    assert irvine.symmetric_roots(0.99 * irvine.LAMBDA2_CROSSOVER, 1)[0] < math.pi
    assert irvine.symmetric_roots(1.01 * irvine.LAMBDA2_CROSSOVER, 1)[0] > math.pi


def test_limits_taut_and_inextensible():
    # eq. 9: lambda^2 -> 0 gives (2k-1) pi / 2; eq. 11: tan x = x, first root 4.4934
    assert irvine.symmetric_roots(1e-8, 3) == pytest.approx([math.pi / 2, 3 * math.pi / 2, 5 * math.pi / 2], rel=1e-6)
    assert irvine.symmetric_roots(math.inf, 1)[0] == pytest.approx(4.493409457909064, rel=1e-12)


def test_36pi2_example_third_crossover():
    # section 3: at lambda^2 = 36 pi^2 the third symmetric and antisymmetric modes coincide (x = 3 pi)
    assert irvine.symmetric_roots(36 * math.pi ** 2, 3)[2] == pytest.approx(3 * math.pi, rel=1e-12)


def test_onset_constants():
    assert irvine.lambda2_onset(1) == pytest.approx(1.26, abs=0.01)                         # eq. 13 / 17b
    W, EA, l = 1000.0, 1e7, 50.0
    assert irvine.critical_tension(weight=W, EA=EA) == pytest.approx(0.93 * (W ** 2 * EA) ** (1 / 3), rel=5e-3)
    assert irvine.critical_sag(weight=W, EA=EA, span=l) == pytest.approx(0.134 * (W / EA) ** (1 / 3) * l, rel=1e-2)
    th = math.radians(30)
    assert irvine.critical_chord_tension(weight=W, EA=EA, theta=th) == pytest.approx(
        0.93 * math.cos(th) ** (2 / 3) * (W ** 2 * EA) ** (1 / 3), rel=5e-3)             # eq. 24


def test_lambda2_consistency_inclined_reduces_to_horizontal():
    a = irvine.lambda_squared(m=1.0, g=9.8, span=10.0, H=100.0, EA=1e5, Le=10.0)
    b = irvine.lambda_squared_inclined(m=1.0, g=9.8, chord=10.0, theta=0.0, H1=100.0, EA=1e5)
    assert a == pytest.approx(b, rel=1e-14)
    assert a == pytest.approx((9.8 * 10 / 100) ** 2 * 10 / (100 * 10 / 1e5))


def test_added_mass_roundtrip():
    S, C = 7.8, 1.0
    wa = 3.0
    ww = irvine.omega_in_water(wa, added_mass_factor=C, specific_gravity=S)
    assert ww == pytest.approx(wa / math.sqrt(1 + C / S))
    assert irvine.added_mass_factor(omega_air=wa, omega_water=ww, specific_gravity=S) == pytest.approx(C)


def test_irvine_modes_ordering_and_types():
    modes = irvine.irvine_modes(9, lambda2=625.0, span=22.9, H=447.0, m=1.14)
    # Table 2 content: 5 O, 2 A, 2 S (A_k ties with O_2k in the flat-sag theory)
    assert sorted(m.mode_type for m in modes) == sorted("OAOSOAOSO")
    assert all(a.omega <= b.omega for a, b in zip(modes, modes[1:]))
    o = [m.omega for m in modes if m.mode_type == "O"]
    a = [m.omega for m in modes if m.mode_type == "A"]
    assert a == pytest.approx([o[1], o[3]], rel=1e-14)


def test_bad_input():
    with pytest.raises(ParameterError, match="lambda2"):
        irvine.symmetric_roots(-1.0, 3)
    with pytest.raises(ParameterError, match="odd"):
        irvine.lambda2_onset(2)


def test_irvine_modes_are_a_result_and_a_sequence():
    """The closed form keeps the result protocol; indexing and iterating give the same modes."""
    import json

    res = irvine.irvine_modes(9, lambda2=625.0, span=22.9, H=447.0, m=1.14)
    assert res.success and res.message == "" and len(res) == 9
    assert [m.omega for m in res] == list(res.omega) and res[2].mode_type == res.mode_type[2]
    # the first out-of-plane mode is the taut string's: (pi / l) sqrt(H / m)
    assert res[0].mode_type == "O" and res[0].omega == pytest.approx(math.pi / 22.9 * math.sqrt(447.0 / 1.14),
                                                                     rel=1e-14)
    ds = res.to_xarray()
    assert ds["omega"].attrs["units"] == "rad/s" and ds.attrs["lambda2"] == 625.0
    assert json.loads(json.dumps(res.summary()))["modes"][0]["omega_rad_s"] == res[0].omega
