"""The symbolic design objective: agrees with the library's stochastic linearization, exact gradients."""

import casadi as ca
import numpy as np
import pytest

from cablesys.isolation.example import baseline_scene, dual_scene, example_settings
from cablesys.isolation.objective import (
    complex_solve,
    nlp_functions,
    parameter_map,
    response_functions,
    sea_weights,
)
from cablesys.isolation.problem import variables
from cablesys.isolation.solve import equivalent_jacobian_shift
from cablesys.linear.steady import steady_state
from cablesys.model import build_model

ONE_ROPE = dict(ae_bounds=((1e5, 1e7),), damping_bounds=((1e3, 1e6),), strain_limit=(0.1,), working_load=(1.5e4,))


@pytest.fixture(scope="module")
def dual():
    scene, settings = dual_scene(), example_settings()
    model = build_model(scene)
    p = model.parameters(scene)
    dJ, st = equivalent_jacobian_shift(model, p, settings, n_log2=7)
    return scene, settings, model, p, dJ, st


def test_complex_solve_matches_numpy():
    rng = np.random.default_rng(3)
    A, B = rng.normal(size=(4, 4)) + 4 * np.eye(4), rng.normal(size=(4, 4))
    fr, fi = rng.normal(size=4), rng.normal(size=4)
    xr, xi = complex_solve(ca.DM(A), ca.DM(B), ca.DM(fr), ca.DM(fi))
    ref = np.linalg.solve(A + 1j * B, fr + 1j * fi)
    np.testing.assert_allclose(np.array(xr).ravel() + 1j * np.array(xi).ravel(), ref, rtol=1e-12)


@pytest.mark.parametrize("which", ["dual", "baseline"])
def test_objective_equals_the_stochastic_linearization(which, dual):
    """With dJ from the Gaussian linearization at the same design, the real-arithmetic transfer and
    spectral sums reproduce cablesys.linear.stochastic (only its small mean-drag shift of q_0 differs)."""
    if which == "dual":
        scene, settings, model, p, dJ, st = dual
        labels = ("y_b_2", "tension_mid_1", "tension_mid_2")
    else:
        scene, settings = baseline_scene(), example_settings(**ONE_ROPE)
        model = build_model(scene)
        p = model.parameters(scene)
        dJ, st = equivalent_jacobian_shift(model, p, settings, n_log2=7)
        labels = ("y_b", "tension_mid")
    q0 = steady_state(model, p).q
    omega, w_s, w_band = sea_weights(settings)
    obj, _, sigma, mean_t, strain = (np.array(a).ravel() for a in
                                     response_functions(model, omega.size)(q0, p, dJ, omega, w_s, w_band))
    np.testing.assert_allclose(sigma, [st.std(lbl) for lbl in labels], rtol=2e-3)
    assert obj[0] == pytest.approx(st.significant_amplitude(labels[0]), rel=2e-3)
    # statics: mean tension = weight below (eq. 49b); u_0 = T l_r / AE and l_0 = l_r (1 - T_r / AE) (eq. 1)
    below = 0.0
    for i in reversed(range(scene.n_sections)):
        s = scene.sections[i]
        t = below + s.body.weight + 0.5 * s.cable.total_weight
        assert mean_t[i] == pytest.approx(t, rel=1e-9)
        assert strain[i] == pytest.approx(t / (s.cable.ae - s.cable.tension_ref), rel=1e-9)
        below += s.body.weight + s.cable.total_weight


def test_rao_band_objective_is_the_band_rms_of_the_rao(dual):
    scene, settings, model, p, dJ, st = dual
    s2 = settings.replace(objective="rao_band", band=(0.5, 1.5))
    q0 = steady_state(model, p).q
    omega, w_s, w_band = sea_weights(s2)
    obj = float(response_functions(model, omega.size)(q0, p, dJ, omega, w_s, w_band)[1])
    w = settings.omega
    H2 = np.abs(st.transfer[:, st.output_labels.index("y_b_2")]) ** 2
    band = (w >= 0.5) & (w <= 1.5)
    ref = np.sqrt(np.trapezoid(H2[band], w[band]) / (w[band][-1] - w[band][0]))
    assert obj == pytest.approx(ref, rel=0.03)          # trapezoid weights vs the band-clipped rule
    assert 0.5 < obj < 2.0


def test_gradients_are_exact(dual):
    """AD through the rootfinder and the linearization matches central differences (a check only)."""
    scene, settings, model, p, dJ, _ = dual
    vars_ = variables(scene, settings)
    x, par, f, g, _ = nlp_functions(model, settings, vars_, p)
    F = ca.Function("F", [x, par], [ca.vertcat(f, g)])
    Jf = ca.Function("J", [x, par], [ca.jacobian(ca.vertcat(f, g), x)])
    pv = np.r_[dJ.ravel(order="F"), steady_state(model, p).q]
    x0 = np.array([0.3, 0.45, 0.6, 0.5])
    J = np.array(Jf(x0, pv))
    h = 1e-6
    fd = np.column_stack([(np.array(F(x0 + h * e, pv)) - np.array(F(x0 - h * e, pv))).ravel() / (2 * h)
                          for e in np.eye(4)])
    np.testing.assert_allclose(J, fd, rtol=1e-5, atol=1e-7 * np.abs(J).max())
    assert np.abs(J[0]).min() > 1e-4                       # every variable moves the objective


def test_intermediate_mass_variable_scales_the_body(dual):
    scene, settings, model, p, _, _ = dual
    s2 = settings.replace(intermediate_mass_bounds=(900.0, 3600.0))
    vars_ = variables(scene, s2)
    assert vars_[-1].name == "intermediate_mass"
    pm = np.array(parameter_map(model, vars_)(np.r_[0.5, 0.5, 0.5, 0.5, 0.5], p)).ravel()
    b = scene.sections[0].body
    m = 1800.0                                            # geometric middle of [900, 3600]
    idx = model.layout.index
    assert pm[idx("sections[0].body.mass_y")] == pytest.approx(m)
    assert pm[idx("sections[0].body.weight")] == pytest.approx(b.weight * m / b.mass_y)
    assert pm[idx("sections[0].body.mass_x")] == pytest.approx(b.mass_x * m / b.mass_y)
    assert pm[idx("sections[1].cable.ae")] == pytest.approx(np.sqrt(3e4 * 3e6))
