"""The compiled Dormand-Prince 5(4) integrator (cablesys.time_domain.explicit_rk): its coefficients'
order, its error control against closed forms, Wang's model against a tight CVODES run, its step
count at the stability limit of the undamped stretch mode, failures and the fallback."""

import dataclasses
import logging
import math
import re
import shutil
from fractions import Fraction
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from cablesys.errors import SolverError
from cablesys.model import build_model
from cablesys.scene import TopMotion, dale_scene
from cablesys.time_domain import IntegratorSettings, Simulator
from cablesys.time_domain.explicit_rk import ExplicitRKIntegrator
from cablesys.time_domain.integrators import compiled_dae, make_integrator
from cablesys.time_domain.run import initial_state

C_SOURCE = Path(__file__).resolve().parents[1] / "cablesys" / "time_domain" / "explicit_rk.c"
needs_cc = pytest.mark.skipif(shutil.which("cc") is None, reason="no C compiler")


def _tableau():
    """The coefficients as written in explicit_rk.c (a_ij, c_i, e_i = b_i - b^_i, d_i)."""
    text = C_SOURCE.read_text()
    co = {}
    for name, num, den in re.findall(r"cs_dp5_([a-e]\d+) = (-?[\d.]+) / ([\d.]+)", text):
        co[name] = Fraction(int(float(num)), int(float(den)))
    A = [[co.get(f"a{i}{j}", Fraction(0)) for j in range(1, 8)] for i in range(1, 8)]
    c = [Fraction(0)] + [co[f"c{i}"] for i in range(2, 6)] + [Fraction(1), Fraction(1)]
    b = A[6]
    e = [co.get(f"e{i}", Fraction(0)) for i in range(1, 8)]
    return A, b, c, e, co


def test_coefficients_satisfy_the_order_conditions():
    """Dormand & Prince (1980): b satisfies the 17 conditions of order 5 (Butcher's trees up to
    order 5, Hairer et al. Table II.2.2), the embedded b^ = b - e those of order 4, and c_i = sum_j
    a_ij (exact rational arithmetic on the coefficients the C driver uses)."""
    A, b, c, e, _ = _tableau()
    n = 7
    bh = [b[i] - e[i] for i in range(n)]
    assert all(sum(A[i]) == c[i] for i in range(n))

    def Ac(v):
        return [sum(A[i][j] * v[j] for j in range(n)) for i in range(n)]

    def dot(w, v):
        return sum(x * y for x, y in zip(w, v))

    def pw(k):
        return [ci ** k for ci in c]

    def mul(*vs):
        return [math.prod(x) for x in zip(*vs)]

    conditions = {  # order: [(value of the sum, 1 / gamma(tree))]
        1: [(sum, 1)],
        2: [(lambda w: dot(w, c), Fraction(1, 2))],
        3: [(lambda w: dot(w, pw(2)), Fraction(1, 3)), (lambda w: dot(w, Ac(c)), Fraction(1, 6))],
        4: [(lambda w: dot(w, pw(3)), Fraction(1, 4)), (lambda w: dot(w, mul(c, Ac(c))), Fraction(1, 8)),
            (lambda w: dot(w, Ac(pw(2))), Fraction(1, 12)), (lambda w: dot(w, Ac(Ac(c))), Fraction(1, 24))],
        5: [(lambda w: dot(w, pw(4)), Fraction(1, 5)), (lambda w: dot(w, mul(pw(2), Ac(c))), Fraction(1, 10)),
            (lambda w: dot(w, mul(c, Ac(pw(2)))), Fraction(1, 15)),
            (lambda w: dot(w, mul(c, Ac(Ac(c)))), Fraction(1, 30)),
            (lambda w: dot(w, mul(Ac(c), Ac(c))), Fraction(1, 20)),
            (lambda w: dot(w, Ac(pw(3))), Fraction(1, 20)), (lambda w: dot(w, Ac(mul(c, Ac(c)))), Fraction(1, 40)),
            (lambda w: dot(w, Ac(Ac(pw(2)))), Fraction(1, 60)), (lambda w: dot(w, Ac(Ac(Ac(c)))), Fraction(1, 120))],
    }
    for order, conds in conditions.items():
        for f, value in conds:
            assert f(b) == value, (order, value)
            if order <= 4:
                assert f(bh) == value, ("embedded", order, value)
    # the embedded pair differs at order 5 (else the error estimate would vanish)
    assert any(f(bh) != v for f, v in conditions[5])
    assert b[6] == 0 and A[6][:6] == b[:6]          # first same as last


def _rk_step(f, t, y, h):
    """One DOPRI5 step with the C file's coefficients (floats): (5th-order y1, error estimate)."""
    A, b, c, e, _ = _tableau()
    A = [[float(x) for x in row] for row in A]
    k = []
    for i in range(7):
        yi = y + h * sum(A[i][j] * k[j] for j in range(i))
        k.append(f(t + float(c[i]) * h, yi))
    y1 = y + h * sum(float(b[i]) * k[i] for i in range(7))
    return y1, h * sum(float(e[i]) * k[i] for i in range(7))


def test_a_single_step_is_fifth_order():
    """One step with the C file's coefficients on a nonlinear, non-autonomous system with a
    closed form (y1' = 1 + y1^2, y1 = tan t; y2' = y2 cos t, y2 = e^(sin t)): local error ~ h^6
    (order 5), the error estimate ~ h^5 (the embedded 4th-order solution)."""
    def f(t, y):
        return np.array([1.0 + y[0] ** 2, y[1] * math.cos(t)])

    def exact(t):
        return np.array([math.tan(t), math.exp(math.sin(t))])

    def slope(hs, which):
        vals = [np.max(np.abs(_rk_step(f, 0.3, exact(0.3), h)[0] - exact(0.3 + h))) if which == "error"
                else np.max(np.abs(_rk_step(f, 0.3, exact(0.3), h)[1])) for h in hs]
        return np.polyfit(np.log(hs), np.log(vals), 1)[0]
    # step errors reach rounding (1e-16) below h = 0.02, the estimate (larger) below 0.005
    s_err = slope([0.16, 0.08, 0.04, 0.02], "error")
    s_est = slope([0.04, 0.02, 0.01, 0.005], "estimate")
    assert 5.6 < s_err < 6.8, s_err           # local error O(h^6) of a 5th-order method (4th order: 5)
    assert 4.6 < s_est < 5.4, s_est           # the 4th-order embedded solution's O(h^5)


@dataclasses.dataclass
class _Oscillator:
    """A duck-typed model for the driver: x'' = -w^2 x - 2 zeta w x' with (w, zeta) in p."""

    nq: int = 1
    layout: tuple = ("w", "zeta")
    kind: str = "test"

    def __post_init__(self):
        self._cache = {}

    def ode(self, x, t, p):
        w, z = p[0], p[1]
        return ca.vertcat(x[1], -w ** 2 * x[0] - 2 * z * w * x[1])

    def derive(self, key, build):
        if key not in self._cache:
            self._cache[key] = build()
        return self._cache[key]


def _oscillator_exact(t, w, zeta):
    """x(0) = 1, x'(0) = 0 (underdamped)."""
    wd = w * math.sqrt(1 - zeta ** 2)
    env = np.exp(-zeta * w * t)
    x = env * (np.cos(wd * t) + zeta * w / wd * np.sin(wd * t))
    v = -env * (w ** 2 / wd) * np.sin(wd * t)
    return np.vstack([x, v])


def oscillator_error(method, rtol, zeta):
    """(largest global error relative to the amplitude, stats) of ``method`` on the linear oscillator
    (closed form) over 10 periods, 200 outputs, atol = rtol on the unscaled states."""
    model, w = _Oscillator(), 2 * math.pi
    grid = np.linspace(0.0, 10.0, 201)
    F = make_integrator(model, IntegratorSettings(method=method, rtol=rtol, atol=rtol, scaled=False,
                                                  max_num_steps=10**5), grid)
    assert isinstance(F, ExplicitRKIntegrator)
    X = np.array(F(x0=[1.0, 0.0], p=np.array([w, zeta, 0.0, 1.0]))["xf"])
    scale = np.array([[1.0], [w]])
    return float(np.max(np.abs(X - _oscillator_exact(grid[1:], w, zeta)) / scale)), F.stats()


def as_accurate_as_cvodes(dale_ramped, method):
    """Wang's model, ramped Dale, 20 s: ``method`` at rtol 1e-6 is at least as accurate (within 2x per
    state) as CVODES at rtol 1e-6 (same atol, scaled) against CVODES at rtol 1e-12."""
    scene, model, p, x0 = dale_ramped
    times = scene.output_times[scene.output_times <= 20.0 + 1e-9]

    def run(name, rtol, atol):
        rec = Simulator(model, times, IntegratorSettings(method=name, rtol=rtol, atol=atol,
                                                         max_num_steps=10**6)).run(p, x0)
        assert rec.success, rec.message
        return rec
    ref = run("cvodes", 1e-12, 1e-13).states
    cv, ex = run("cvodes", 1e-6, 1e-7), run(method, 1e-6, 1e-7)
    assert ex.stats["compiled"] and ex.stats["nsteps"] > 0
    e_cv, e_ex = (np.max(np.abs(r.states - ref), axis=1) for r in (cv, ex))
    assert np.all(e_ex <= 2 * e_cv), (e_ex, e_cv)


@needs_cc
@pytest.mark.parametrize("zeta", [0.0, 0.05])
def test_global_error_follows_the_tolerance(compiling, zeta):
    """Linear oscillator over 10 periods, closed form: the largest global error (relative to the
    amplitude) is within a small multiple of rtol and falls ~ in proportion with it (rtol from
    1e-4 to 1e-9: the error falls by more than 1e4 and less than 1e6.5)."""
    errs = {}
    for rtol in (1e-4, 1e-6, 1e-9):
        errs[rtol], st = oscillator_error("dopri5", rtol, zeta)
        assert st["status"] == 0 and st["nsteps"] > 0
        assert errs[rtol] < 50 * rtol, (rtol, errs[rtol])
    ratio = errs[1e-4] / errs[1e-9]
    assert 1e4 < ratio < 10 ** 6.5, errs


def _ramped_dale(duration):
    base = dale_scene(duration=duration)
    tm = base.top_motion
    return base.replace(top_motion=TopMotion(x=tm.x, y=tm.y, ramp_s=3 * 2 * math.pi / tm.x[0].frequency))


@pytest.fixture(scope="module")
def dale_ramped(compiling):
    scene = _ramped_dale(60.0)
    model = build_model(scene)
    p = model.parameters(scene)
    return scene, model, p, initial_state(scene, model, p)


def _lambda_max(model, x, p):
    xs = ca.SX.sym("x", 2 * model.nq)
    J = ca.Function("J", [xs], [ca.jacobian(model.ode(xs, 0.0, p), xs)])
    return float(np.max(np.abs(np.linalg.eigvals(np.array(J(x))))))


@needs_cc
def test_wang_dale_as_accurate_as_cvodes(dale_ramped):
    """Wang's model, ramped Dale, 20 s: dopri5 at rtol 1e-6 is at least as accurate as CVODES at
    rtol 1e-6 (same atol, scaled) against CVODES at rtol 1e-12 (each state's largest error)."""
    as_accurate_as_cvodes(dale_ramped, "dopri5")


@needs_cc
def test_step_count_at_the_stability_limit(dale_ramped):
    """60 s of the ramped Dale scene: the undamped stretch mode (|lambda| ~ 254 rad/s, on the
    imaginary axis) bounds the step, so the count hardly depends on rtol and lies between
    T |lambda| / 3.4 (DOPRI5 is unstable beyond its real-axis limit 3.3) and T |lambda| / 1 (its
    stability region touches the imaginary axis up to |h lambda| ~ 1, |R(iy)| - 1 < 2e-6 there);
    CVODES (BDF orders 3-5 unstable there) takes ~30-44k."""
    scene, model, p, x0 = dale_ramped
    T = scene.output_times[-1] - scene.output_times[0]
    lam = _lambda_max(model, x0, p)
    assert 240 < lam < 270
    grid = scene.output_times - scene.output_times[0]
    steps = {}
    for rtol in (1e-3, 1e-5):
        F = make_integrator(model, IntegratorSettings(method="dopri5", rtol=rtol, atol=rtol / 10), grid)
        F(x0=x0, p=np.concatenate([p, [scene.output_times[0], 1.0]]))
        steps[rtol] = F.stats()["nsteps"]
        assert T * lam / 3.4 < steps[rtol] < T * lam / 1.0, (rtol, steps[rtol], T * lam)
    assert steps[1e-5] < 1.3 * steps[1e-3], steps


@needs_cc
def test_step_budget_failure_names_the_time_and_keeps_the_states(dale_ramped):
    """max_num_steps per output interval too small: make_integrator's call raises SolverError
    naming the flag and time, with the states reached; the Simulator reports the budget and keeps
    the results up to the failure."""
    scene, model, p, x0 = dale_ramped
    times = scene.output_times[:41]                       # 2 s at 0.05 s: ~10 steps per output
    grid = times - times[0]
    F = make_integrator(model, IntegratorSettings(method="dopri5", rtol=1e-6, atol=1e-7, max_num_steps=3), grid)
    with pytest.raises(SolverError, match=r'"TOO_MUCH_WORK" at t = [0-9.e-]+') as info:
        F(x0=x0, p=np.concatenate([p, [times[0], 1.0]]))
    err = info.value
    assert 0.0 <= err.time < times[-1]
    assert err.states.shape[1] == len(err.times) < len(grid) - 1
    assert np.all(np.isfinite(err.states))
    sim = Simulator(model, times, IntegratorSettings(method="dopri5", rtol=1e-6, atol=1e-7, max_num_steps=3))
    rec = sim.run(p, x0)
    assert not rec.success
    assert "step budget exhausted: dopri5" in rec.message and "(at t = " in rec.message
    assert rec.time.size < times.size


@needs_cc
@pytest.mark.slow
def test_quasistatic_and_segmented_models_run(compiling):
    """Any model's ODE: the quasi-static reduction and a 2-element segmented cable, 3 s of the
    ramped Dale scene at rtol 1e-7, agree with CVODES (Adams, rtol 1e-11) to 1e-3 of each state's
    range (the segmented cable's undamped axial ringing accumulates the per-step errors of ~6k
    steps: ~3e-4 of the range of an element's axial rate)."""
    from cablesys.model.quasistatic import build_quasistatic
    from cablesys.model.segmented import build_segmented_model

    scene = _ramped_dale(3.0)
    seg_scene = scene.replace_section(0, cable={"segments": 2})
    for model, sc in ((build_quasistatic(scene), scene), (build_segmented_model(seg_scene), seg_scene)):
        p = model.parameters(sc)
        x0 = initial_state(sc, model, p)
        # the reference in CasADi's virtual machine: compiling the DAE and its Jacobian costs more than the run
        recs = {m: Simulator(model, sc.output_times, IntegratorSettings(method=m, rtol=r, atol=r / 10, compiled=comp,
                                                                         max_num_steps=10**6)).run(p, x0)
                for m, r, comp in (("dopri5", 1e-7, True), ("cvodes-adams", 1e-11, False))}
        assert all(r.success for r in recs.values()), model.kind
        assert recs["dopri5"].stats["compiled"], model.kind
        ref = recs["cvodes-adams"].states
        err = np.max(np.abs(recs["dopri5"].states - ref), axis=1)
        assert np.all(err <= 1e-3 * np.ptp(ref, axis=1)), (model.kind, err / np.ptp(ref, axis=1))


@pytest.mark.parametrize("method", ["dopri5", "rk23"])
def test_without_compilation_falls_back_to_cvodes_with_one_notice(caplog, monkeypatch, method):
    """CABLESYS_COMPILE=0 (the suite's default): either pair of the driver runs CVODES, one logged notice
    per model naming the pair, and the run succeeds."""
    monkeypatch.setenv("CABLESYS_COMPILE", "0")
    scene = _ramped_dale(2.0)
    model = build_model(scene)
    p = model.parameters(scene)
    st = IntegratorSettings(method=method, rtol=1e-6, atol=1e-7)
    with caplog.at_level(logging.WARNING, logger="cablesys.time_domain.explicit_rk"):
        sim = Simulator(model, scene.output_times, st)
        rec = sim.run(p, initial_state(scene, model, p))
    assert rec.success and not rec.stats["compiled"]
    notices = [r for r in caplog.records if f"{method} needs" in r.getMessage() and "running CVODES" in r.getMessage()]
    assert len(notices) == 1
    assert not isinstance(make_integrator(model, st, [0.0, 1.0]), ExplicitRKIntegrator)
    assert compiled_dae(model, st).compiled is False


class _BlowUp(_Oscillator):
    """y' = y^2, y(0) = 1: y = 1 / (1 - t) blows up at t = 1; z' = sqrt(1 - t) z is not real after t = 1."""

    def ode(self, x, t, p):
        return ca.vertcat(x[0] ** 2 * p[0], p[1] * ca.sqrt(1.0 - p[1] * t) * x[1])


@needs_cc
@pytest.mark.parametrize(("p", "flag"), [([1.0, 0.0], "ERR_FAILURE"), ([0.0, 1.0], "NONFINITE")])
def test_blow_up_and_nonfinite_fail_at_the_time(compiling, p, flag):
    """A solution that blows up at t = 1 (y' = y^2) and a right-hand side that is NaN after t = 1:
    SolverError at t = 1 (to 1e-5) with the flag, the states at the output times before it kept
    (and equal to the closed form)."""
    F = make_integrator(_BlowUp(), IntegratorSettings(method="dopri5", rtol=1e-8, atol=1e-8, scaled=False,
                                                      max_num_steps=10**5), np.linspace(0.0, 2.0, 5))
    with pytest.raises(SolverError, match=f'"{flag}"') as info:
        F(x0=[1.0, 1.0], p=[*p, 0.0, 1.0])
    err = info.value
    assert err.time == pytest.approx(1.0, abs=1e-5)
    assert err.times[0] == 0.5 and np.all(err.times <= err.time)
    exact = [1.0 / (1.0 - 0.5), 1.0] if p[0] else [1.0, math.exp(-2.0 / 3.0 * (0.5 ** 1.5 - 1.0))]
    np.testing.assert_allclose(err.states[:, 0], exact, rtol=1e-6)
