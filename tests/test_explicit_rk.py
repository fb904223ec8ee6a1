"""The Bogacki-Shampine 3(2) pair (``rk23``) of the compiled explicit-RK driver
(cablesys.time_domain.explicit_rk, explicit_rk.c): its coefficients' order and stability on the imaginary
axis, its error control against closed forms, Wang's model against a tight CVODES run, its step
count at the stability limit of the undamped stretch mode and failures (the fallback without a compiler is
tested with DOPRI5 in test_dopri5.py, whose helpers this module shares)."""

import math
import re
from fractions import Fraction

import numpy as np
import pytest
from test_dopri5 import (
    C_SOURCE,
    _lambda_max,
    _oscillator_exact,
    as_accurate_as_cvodes,
    dale_ramped,  # noqa: F401  (fixture)
    needs_cc,
    oscillator_error,
)

from cablesys.errors import SolverError
from cablesys.time_domain import IntegratorSettings, Simulator
from cablesys.time_domain.integrators import make_integrator


def _tableau():
    """BS3's coefficients as written in explicit_rk.c (a_ij, c_i, e_i = b_i - b^_i; b = a_4j)."""
    co = {name: Fraction(int(float(num)), int(float(den)))
          for name, num, den in re.findall(r"cs_bs3_([a-e]\d+) = (-?[\d.]+) / ([\d.]+)", C_SOURCE.read_text())}
    A = [[co.get(f"a{i}{j}", Fraction(0)) for j in range(1, 5)] for i in range(1, 5)]
    c = [Fraction(0), co["c2"], co["c3"], Fraction(1)]
    e = [co.get(f"e{i}", Fraction(0)) for i in range(1, 5)]
    return A, A[3], c, e


def _dot(w, v):
    return sum(x * y for x, y in zip(w, v))


def _Av(A, v):
    return [_dot(row, v) for row in A]


def test_coefficients_satisfy_the_order_conditions():
    """Bogacki & Shampine (1989): b satisfies the 4 conditions of order 3 (Hairer et al. Table
    II.2.2), the embedded b^ = b - e those of order 2 and not both of order 3, c_i = sum_j a_ij,
    first same as last (exact rational arithmetic on the coefficients the C driver uses)."""
    A, b, c, e = _tableau()
    bh = [bi - ei for bi, ei in zip(b, e)]
    assert all(sum(A[i]) == c[i] for i in range(4))
    c2 = [ci ** 2 for ci in c]
    order3 = [(_dot(b, [1] * 4), 1), (_dot(b, c), Fraction(1, 2)), (_dot(b, c2), Fraction(1, 3)),
              (_dot(b, _Av(A, c)), Fraction(1, 6))]
    assert all(v == exact for v, exact in order3)
    assert sum(bh) == 1 and _dot(bh, c) == Fraction(1, 2)
    assert (_dot(bh, c2), _dot(bh, _Av(A, c))) != (Fraction(1, 3), Fraction(1, 6))   # a true 2nd-order estimate
    assert bh == [Fraction(7, 24), Fraction(1, 4), Fraction(1, 3), Fraction(1, 8)]       # the paper's b^
    assert b[3] == 0 and A[3][:3] == b[:3]


def test_stable_on_the_imaginary_axis_up_to_sqrt3():
    """The stability function R(z) = 1 + sum_k b A^(k-1) 1 z^k of the C coefficients is
    1 + z + z^2/2 + z^3/6 (3 effective stages), so |R(iy)|^2 - 1 = y^4 (y^2 - 3) / 36: stable
    on the imaginary axis exactly up to |y| = sqrt(3) (DOPRI5's region only touches it), which
    is why the pair suits the undamped stretch mode."""
    A, b, _, _ = _tableau()
    v, coeff = [Fraction(1)] * 4, []
    for _ in range(4):
        coeff.append(_dot(b, v))
        v = _Av(A, v)
    assert coeff == [1, Fraction(1, 2), Fraction(1, 6), 0]

    def growth(y2):            # |R(iy)|^2 - 1 in y^2, exactly
        re_, im2 = 1 - y2 / 2, (1 - y2 / 6) ** 2 * y2
        return re_ ** 2 + im2 - 1
    assert growth(Fraction(3)) == 0
    assert all(growth(Fraction(k, 10)) < 0 for k in range(1, 30))
    assert growth(Fraction(31, 10)) > 0


def _bs3_step(f, t, y, h):
    """One BS3 step with the C file's coefficients (floats): (3rd-order y1, error estimate)."""
    A, b, c, e = (np.array(v, dtype=float) for v in _tableau())
    k = []
    for i in range(4):
        k.append(f(t + c[i] * h, y + h * sum(A[i][j] * k[j] for j in range(i))))
    return y + h * sum(b[i] * k[i] for i in range(4)), h * sum(e[i] * k[i] for i in range(4))


def test_a_single_step_is_third_order():
    """One step on y1' = 1 + y1^2 (tan t), y2' = y2 cos t (e^(sin t)): local error ~ h^4 (order 3),
    the error estimate ~ h^3 (the embedded 2nd-order solution)."""
    def f(t, y):
        return np.array([1.0 + y[0] ** 2, y[1] * math.cos(t)])

    def exact(t):
        return np.array([math.tan(t), math.exp(math.sin(t))])
    hs = [0.04, 0.02, 0.01, 0.005]
    err = [np.max(np.abs(_bs3_step(f, 0.3, exact(0.3), h)[0] - exact(0.3 + h))) for h in hs]
    est = [np.max(np.abs(_bs3_step(f, 0.3, exact(0.3), h)[1])) for h in hs]
    s_err, s_est = (np.polyfit(np.log(hs), np.log(v), 1)[0] for v in (err, est))
    assert 3.7 < s_err < 4.4, s_err
    assert 2.8 < s_est < 3.3, s_est


@needs_cc
@pytest.mark.parametrize("zeta", [0.0, 0.05])
def test_global_error_follows_the_tolerance(compiling, zeta):
    """Linear oscillator over 10 periods, closed form, outputs by the Hermite dense output: the
    largest global error (relative to the amplitude) falls in proportion with rtol (error per
    step ~ rtol^(4/3) at h ~ rtol^(1/3): global ~ rtol; rtol 1e-4 to 1e-8: by 10^3.5-10^4.5), is
    below 200 rtol (10 periods of phase error, ~10 rtol a period), and is within a factor 2 of
    SciPy's RK23 (the same pair, error norm and step control) at the same tolerances."""
    from scipy.integrate import solve_ivp

    w = 2 * math.pi
    grid = np.linspace(0.0, 10.0, 201)
    exact = _oscillator_exact(grid[1:], w, zeta)
    scale = np.array([[1.0], [w]])
    errs = {}
    for rtol in (1e-4, 1e-6, 1e-8):
        errs[rtol], st = oscillator_error("rk23", rtol, zeta)
        assert st["status"] == 0 and st["nfevals"] <= 3 * (st["nsteps"] + st["n_rejected"]) + 2
        assert errs[rtol] < 200 * rtol, (rtol, errs[rtol])
        sp = solve_ivp(lambda t, y: [y[1], -w * w * y[0] - 2 * zeta * w * y[1]], (0.0, 10.0), [1.0, 0.0],
                       method="RK23", rtol=rtol, atol=rtol, t_eval=grid[1:])
        e_sp = float(np.max(np.abs(sp.y - exact) / scale))
        assert 0.5 * e_sp < errs[rtol] < 2 * e_sp, (rtol, errs[rtol], e_sp)
    assert 10 ** 3.5 < errs[1e-4] / errs[1e-8] < 10 ** 4.5, errs


@needs_cc
def test_wang_dale_as_accurate_as_cvodes(dale_ramped):  # noqa: F811
    """Wang's model, ramped Dale, 20 s: rk23 at rtol 1e-6 is at least as accurate as CVODES at
    rtol 1e-6 (same atol, scaled) against CVODES at rtol 1e-12 (each state's largest error)."""
    as_accurate_as_cvodes(dale_ramped, "rk23")


@needs_cc
def test_step_count_at_the_stability_limit(dale_ramped):  # noqa: F811
    """60 s of the ramped Dale scene at rtol 1e-3 and 1e-4: the undamped stretch mode (|lambda|
    ~ 254 rad/s) bounds the step at |h lambda| <= sqrt(3) (the slow swing is resolved far
    tighter), so the accepted steps lie between T |lambda| / 1.9 and T |lambda| / 1.4 (~9k) at
    either rtol, and each costs 3 new evaluations against DOPRI5's 6 at |h lambda| ~ 1.35: fewer
    than 0.6 of DOPRI5's right-hand sides."""
    scene, model, p, x0 = dale_ramped
    T = scene.output_times[-1] - scene.output_times[0]
    lam = _lambda_max(model, x0, p)
    grid = scene.output_times - scene.output_times[0]
    pp = np.concatenate([p, [scene.output_times[0], 1.0]])
    stats = {}
    for method, rtol in (("rk23", 1e-3), ("rk23", 1e-4), ("dopri5", 1e-4)):
        F = make_integrator(model, IntegratorSettings(method=method, rtol=rtol, atol=rtol / 10), grid)
        F(x0=x0, p=pp)
        stats[method, rtol] = F.stats()
    for rtol in (1e-3, 1e-4):
        n = stats["rk23", rtol]["nsteps"]
        assert T * lam / 1.9 < n < T * lam / 1.4, (rtol, n, T * lam)
    assert stats["rk23", 1e-4]["nfevals"] < 0.6 * stats["dopri5", 1e-4]["nfevals"], stats


@needs_cc
def test_step_budget_failure_names_the_method_and_time(dale_ramped):  # noqa: F811
    """max_num_steps per output interval too small: SolverError naming rk23, the flag and the
    time, the states reached kept; the Simulator reports the budget and keeps the results."""
    scene, model, p, x0 = dale_ramped
    times = scene.output_times[:41]
    grid = times - times[0]
    st = IntegratorSettings(method="rk23", rtol=1e-6, atol=1e-7, max_num_steps=3)
    F = make_integrator(model, st, grid)
    with pytest.raises(SolverError, match=r'rk23 returned "TOO_MUCH_WORK" at t = [0-9.e-]+') as info:
        F(x0=x0, p=np.concatenate([p, [times[0], 1.0]]))
    err = info.value
    assert 0.0 <= err.time < times[-1]
    assert err.states.shape[1] == len(err.times) < len(grid) - 1 and np.all(np.isfinite(err.states))
    rec = Simulator(model, times, st).run(p, x0)
    assert not rec.success
    assert "step budget exhausted: rk23" in rec.message and "(at t = " in rec.message
    assert rec.time.size < times.size
