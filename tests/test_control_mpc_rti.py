"""The MPC's Gauss-Newton real-time iteration (cablesys.control.rti.GaussNewtonMPC) and its top-motion
predictor without preview (ARPredictor, burg)."""

import math

import numpy as np
import pytest

from cablesys.control import WinchLimits, heave_problem
from cablesys.control.mpc import compare_compensation
from cablesys.control.prediction import ARPredictor
from cablesys.control.rti import GaussNewtonMPC
from cablesys.control.payout import payout_nlp
from cablesys.errors import ParameterError
from cablesys.examples import example_path
from cablesys.scene import Sinusoid, TopMotion, load_scene

OMEGA = 2 * math.pi / 10


def _scene(ramp=10.0, duration=60.0):
    sc = load_scene(example_path("rov-lift")).with_numerics(duration=duration, drag_segments=1)
    return sc.replace(top_motion=TopMotion(y=(Sinusoid(amplitude=1.0, frequency=OMEGA, phase=0.0),), ramp_s=ramp))


def test_gauss_newton_iterated_reaches_the_full_nlp_optimum():
    """Gauss-Newton SQP (full steps, the real-time iteration's step repeated) on one 8 s horizon from a
    state off rest, with the speed limit (0.5 m/s) below the tip's 0.63 m/s peak heave rate so that it binds,
    converges to the KKT point IPOPT finds with exact Hessians on the same NLP (constrain_first=False):
    two independent routes to one optimum. Tolerance 1e-5 of the largest control, well above IPOPT's 1e-8
    and the Gauss-Newton iteration's linear rate after 15 steps."""
    prob = heave_problem(_scene(), WinchLimits(speed=0.5, acceleration=1.0), dt=0.5, model="wang")
    N, t0 = 16, 20.0
    E = prob.exogenous(t0 + prob.dt * np.arange(N + 1))
    x0 = prob.x_rest + np.r_[0.01, 0.05, 0.0, 0.02, 0.0, 0.1]
    nlp = payout_nlp(prob, N, constrain_first=False)
    U0 = np.zeros(N)
    ref = nlp.solve(x0, E, (np.vstack([x0, np.array(prob.step.mapaccum(N)(x0, U0[None, :], E[:N].T)).T]), U0[:, None]))
    assert ref.success, ref.status
    U, ok = GaussNewtonMPC(prob, N, iterations=15).step(x0, E, U0)
    assert ok
    speed = np.array(prob.step.mapaccum(N)(x0, U[None, :], E[:N].T))[-1]
    assert np.max(np.abs(speed)) == pytest.approx(0.5, abs=1e-6)        # the speed limit binds
    assert np.max(np.abs(U - ref.U.ravel())) < 1e-5 * np.max(np.abs(ref.U))


def test_real_time_iteration_closed_loop_equals_ipopt_mpc():
    """In closed loop (1 m, 10 s tip heave, 4 s horizon, 12 s run; the plant the 2-DOF model by CVODES), one
    Gauss-Newton QP per step from the shifted plan gives the body heave of IPOPT solving each step's NLP
    to convergence (6.6 iterations a step) to 1e-4 m, against 1 m of uncompensated heave and ~1.3e-3 m left by either, and the same heave
    reduction to 0.1 dB: the real-time iteration tracks the optimum as the horizon recedes."""
    sc = _scene(ramp=5.0, duration=30.0)
    runs = {scheme: compare_compensation(sc, WinchLimits(speed=1.0, acceleration=1.0), duration=12.0, horizon=4.0,
                                         dt=0.5, plant_segments=1, strategies=("none", "mpc"), mpc_scheme=scheme,
                                         plant_model="wang")
            for scheme in ("ipopt", "gauss-newton")}
    ref, rti = runs["ipopt"], runs["gauss-newton"]
    assert ref.success and rti.success, (ref.message, rti.message)
    assert np.max(np.abs(ref.heave["none"])) > 0.9
    assert np.max(np.abs(rti.heave["mpc"] - ref.heave["mpc"])) < 1e-4
    assert rti.metrics["mpc"]["heave_reduction_db"] == pytest.approx(ref.metrics["mpc"]["heave_reduction_db"], abs=0.1)
    assert ref.metrics["mpc"]["iterations_per_step_mean"] > 1 and rti.metrics["mpc"]["iterations_per_step_mean"] == 1


def test_ar_prediction_of_a_sinusoid_matches_it_over_the_horizon():
    """A sinusoid (no ramp) obeys an AR(2) recursion exactly; Burg's fit on 60 s of samples at 0.5 s
    predicts its position 20 s ahead to 1e-4 m of a 1 m amplitude, and the cubic spline through the
    samples gives the rate and acceleration to its interpolation error, O((omega h)^3) and O((omega h)^2)
    relative with omega h = 0.31: 1e-2 a omega and 5e-2 a omega^2."""
    prob = heave_problem(_scene(ramp=0.0), WinchLimits(), dt=0.5, model="wang")
    pred = ARPredictor(prob, order=8)
    k, n_h = 120, 40
    for j in range(k + 1):
        pred.measure(j * prob.dt)
    E, E_true = pred.exogenous(k, n_h), prob.exogenous(prob.dt * (k + np.arange(n_h + 1)))
    ne = 7
    rows = lambda A, i: A.reshape(-1, ne)[:, i]
    assert np.allclose(rows(E, 0), rows(E_true, 0))                             # the stage times
    assert np.max(np.abs(rows(E, 2) - rows(E_true, 2))) < 1e-4
    assert np.max(np.abs(rows(E, 4) - rows(E_true, 4))) < 1e-2 * OMEGA
    assert np.max(np.abs(rows(E, 6) - rows(E_true, 6))) < 5e-2 * OMEGA ** 2


def test_bad_mpc_options_are_refused_before_any_work():
    sc = _scene(duration=30.0)
    for kw, field in (({"mpc_scheme": "newton"}, "mpc_scheme"), ({"mpc_iterations": 0}, "mpc_iterations"),
                      ({"ar_order": 0}, "ar_order"),
                      ({"mpc_scheme": "ipopt", "mpc_iterations": 3}, "mpc_iterations")):
        with pytest.raises(ParameterError, match=field):
            compare_compensation(sc, WinchLimits(), duration=10.0, horizon=5.0, strategies=("mpc",), **kw)


def test_compiled_gauss_newton_kernel_equals_the_virtual_machine(quick_compile):
    """The compiled linearization kernel gives the condensed QP of the SX function in CasADi's virtual
    machine (the same expressions: to rounding, 1e-9 relative), and a problem with other numbers (another
    speed limit and tension weight) loads the same compiled kernel: the cache is keyed by structure."""
    from cablesys.control.kernels import gauss_newton_kernel
    sc = load_scene(example_path("rov-lift")).with_numerics(drag_segments=1, duration=30.0)
    prob = heave_problem(sc, WinchLimits(speed=1.0, acceleration=1.0), dt=0.5, model="wang")
    N = 12
    E = prob.exogenous(10.0 + prob.dt * np.arange(N + 1))
    x0, U = prob.x_rest, 0.1 * np.sin(np.arange(N))
    fast = GaussNewtonMPC(prob, N)
    assert gauss_newton_kernel(prob).class_name() == "External"
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("CABLESYS_COMPILE", "0")
        slow = GaussNewtonMPC(prob, N)
    for a, b in zip(fast.linearization(x0, E, U), slow.linearization(x0, E, U)):
        assert np.array_equal(np.isinf(a), np.isinf(b))            # the one-sided rows' infinite bounds
        a, b = a[np.isfinite(b)], b[np.isfinite(b)]
        np.testing.assert_allclose(a, b, rtol=1e-9, atol=1e-9 * np.max(np.abs(b)))
    other = heave_problem(sc, WinchLimits(speed=0.8, acceleration=1.0), dt=0.5, tension_weight=0.1, model="wang")
    assert gauss_newton_kernel(other) is gauss_newton_kernel(prob)
