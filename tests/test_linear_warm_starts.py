"""Warm starts and cheap starts of the nonlinear linear-analysis solvers (issue 13): they change the
work done, never the answer. Work is counted in iterations (never timed)."""

import numpy as np
import pytest

from cablesys.isolation.example import dual_scene, example_settings
from cablesys.linear.linearization import xi_blocks
from cablesys.linear.periodic import (
    _linear_guess,
    _with_sinusoids,
    periodic_steady_state,
    periodic_sweep,
    scene_input_amplitude,
)
from cablesys.linear.spectra import jonswap
from cablesys.linear.stochastic import stochastic_response
from cablesys.model import build_model


def test_coarse_start_gives_the_orbit_of_the_linear_start(dale):
    """The 3-harmonic coarse start and the plain linear start converge to the same orbit (to the
    Newton tolerance on the node values), and the coarse start leaves at most 3 full steps."""
    s, m, p = dale
    w, Z = scene_input_amplitude(s)
    cold = periodic_steady_state(m, p, w, input_amplitude=Z, n_harmonics=20)
    assert cold.success and cold.stats["starts"] == ["coarse"]
    assert cold.stats["full_newton_iterations"] <= 3 < cold.stats["coarse_newton_iterations"] + 1
    times = cold.time
    lin = periodic_steady_state(m, p, w, n_harmonics=20, guess=_linear_guess(m, p, w, Z, times))
    assert lin.success and lin.stats["full_newton_iterations"] > cold.stats["full_newton_iterations"]
    np.testing.assert_allclose(lin.q, cold.q, rtol=0, atol=1e-9 * (1 + np.abs(cold.q).max()))
    # the truncation indicator falls with the harmonics kept (the orbit converges)
    assert 0 < periodic_steady_state(m, p, w, input_amplitude=Z, n_harmonics=30).stats["harmonic_tail"] \
        < cold.stats["harmonic_tail"] < 1e-3
    # too few harmonics for a coarse level: the linear start is used directly
    low = periodic_steady_state(m, p, w, input_amplitude=Z, n_harmonics=3)
    assert low.success and low.stats["starts"] == ["linear"] and low.stats["coarse_newton_iterations"] == 0


def test_sweep_secant_predictor_needs_few_newton_steps(dale):
    """Along a sweep each orbit starts from the secant extrapolation of its two neighbours: at most
    3 Newton steps per frequency after the first two, and the same orbits as cold solves."""
    s, m, p = dale
    w0, Z = scene_input_amplitude(s)
    omegas = w0 * np.linspace(0.7, 1.4, 8)
    sweep = periodic_sweep(m, p, omegas, Z, n_harmonics=12)
    assert all(x.success for x in sweep)
    assert max(x.stats["newton_iterations"] for x in sweep[2:]) <= 3
    k = 5
    cold = periodic_steady_state(m, _with_sinusoids(m, p, omegas[k], Z), omegas[k], input_amplitude=Z, n_harmonics=12)
    np.testing.assert_allclose(sweep[k].q, cold.q, rtol=0, atol=1e-9 * (1 + np.abs(cold.q).max()))


@pytest.fixture(scope="module")
def dual():
    s = dual_scene()
    m = build_model(s)
    return s, m, m.parameters(s), example_settings()


def test_stochastic_warm_start_reaches_the_same_fixed_point(dual):
    """Warm-started from a neighbouring design (AE of the top rope +30 %), the Gaussian equivalent
    linearization settles in fewer iterations on the fixed point a tight cold iteration finds."""
    _, m, p, st = dual
    w = st.omega
    S = jonswap(w, st.hs, st.tp, st.gamma)
    near = stochastic_response(m, p, w, S, n_log2=7, tol=1e-3)
    n_xi = xi_blocks(m)["n"]
    assert near.covariance.shape == (n_xi, n_xi) and near.mean_shift.shape == (m.nq,)
    p2 = p.copy()
    p2[m.layout.index("sections[0].cable.ae")] *= 1.3
    cold = stochastic_response(m, p2, w, S, n_log2=7, tol=1e-3)
    warm = stochastic_response(m, p2, w, S, n_log2=7, tol=1e-3, start=near)
    tight = stochastic_response(m, p2, w, S, n_log2=7, tol=1e-7, max_iter=200)
    assert cold.success and warm.success and tight.success and warm.stats["warm_start"]
    assert warm.iterations < cold.iterations
    for label in ("y_b_2", "tension_mid_1", "tension_mid_2", "u_1"):
        ref = tight.std(label)
        # both within a few tolerances of the fixed point (the relaxed iteration stops on its last change)
        assert warm.std(label) == pytest.approx(ref, rel=5e-3)
        assert cold.std(label) == pytest.approx(ref, rel=5e-3)
    # the mean shift (rectified drag) is carried: every output's mean agrees with the tight solution
    # to 3 % of its standard deviation (the slowest, the horizontal drift x_b of the plate, ~1.4 %)
    assert np.all(np.abs(warm.output_mean - tight.output_mean) <= 3e-2 * tight.output_std + 1e-12)
