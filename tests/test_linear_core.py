"""Linearization, modes, RAOs, equivalent linearization, spectra and bad input (cablesys.linear)."""

import math

import numpy as np
import pytest

from cablesys.errors import ParameterError, SolverError
from cablesys.linear import modes, rao
from cablesys.linear.equivalent import (
    describing_function,
    describing_matrices,
    harmonic_response,
)
from cablesys.linear.linearization import linearize
from cablesys.linear.periodic import periodic_steady_state, scene_input_amplitude
from cablesys.linear.spectra import (
    jonswap,
    pierson_moskowitz,
    significant_amplitude,
    slack_probability,
    spectral_moment,
)
from cablesys.linear.steady import steady_state
from cablesys.time_domain import simulate


def test_closed_form_frequencies(dale):
    """Compound pendulum (Wang 1971 eq. 25 at phi = 0) and stretch sqrt(k / (M_by + M_c/3))."""
    s, m, p = dale
    lin = linearize(m, p)
    md = modes(lin)
    c, b = s.cable, s.body
    L = c.length_zero + lin.q0[1]
    m_cv = c.total_mass + 1000.0 * math.pi * c.diameter**2 / 4 * L
    w_pend = math.sqrt((b.weight + c.total_weight / 2) / (L * (b.mass_x + m_cv / 3)))
    w_str = math.sqrt(c.spring_constant / (b.mass_y + c.total_mass / 3))
    assert md.frequency_of("phi") == pytest.approx(w_pend, rel=1e-9)
    assert md.frequency_of("u") == pytest.approx(w_str, rel=1e-9)
    assert np.allclose(md.damping_ratio, 0.0, atol=1e-12)          # no drag slope in still water
    assert 1.14 < md.frequency_of("phi") < 1.14 * 1.2                # measured 1.14 rad/s; model ~15 % stiffer


def test_state_space_matches_second_order_and_tension_is_weights(dale):
    s, m, p = dale
    lin = linearize(m, p)
    w = np.linspace(0.1, 5, 7)
    assert np.allclose(lin.transfer_state_space(w), lin.transfer(w)[1], rtol=1e-10, atol=1e-12)
    T0 = lin.y0[m.output_labels.index("tension_mid")]
    assert T0 == pytest.approx(s.body.weight + s.cable.total_weight / 2, rel=1e-9)
    r = rao(lin, w)
    assert r.to_xarray().dims == ("omega", "output", "input")
    assert r.amplitude("y_b", "y_s")[0] == pytest.approx(1.0, rel=1e-3)   # stiff stretch: body follows heave


def test_current_gives_exact_drag_damping(dale):
    s, m, p = dale
    sc = s.with_environment(current_speeds=(0.2,))
    st = steady_state(m, m.parameters(sc))
    assert st.q[0] < -0.05                                            # streamed downstream
    md = modes(linearize(m, m.parameters(sc)))
    assert md.damping_ratio[0] > 0.05


def test_describing_function_and_gaussian_scalar_limits():
    """|v| v: N = 8 V / (3 pi) (harmonic) from the model-free helpers."""
    theta = 2 * np.pi * np.arange(256) / 256
    V = 0.7
    v = V * np.sin(theta)
    J = (2 * np.abs(v))[:, None, None]                               # d(|v|v)/dv along the cycle
    J0, J2 = describing_matrices(J, theta)
    N = describing_function(J0, J2, np.array([-1j * V]))
    assert N[0, 0].real == pytest.approx(8 * V / (3 * np.pi), rel=1e-3)


def test_small_amplitude_rao_matches_time_domain(dale):
    """RAO x amplitude within 1 % of the nonlinear steady-state amplitude (0.8 omega_n, 1.3 mm)."""
    s, m, p = dale
    w = 0.8 * modes(linearize(m, p)).frequency_of("phi")
    a = 0.02 * 2.5 * 0.0254
    sc = s.replace(top_motion=type(s.top_motion)(x=(type(s.top_motion.x[0])(amplitude=a, frequency=w, phase=0.0),),
                                                 y=(type(s.top_motion.x[0])(amplitude=0.0, frequency=w, phase=0.0),)))
    T = 2 * np.pi / w
    res = simulate(sc, times=np.arange(0, 25 * T, T / 200))
    td = res.steady_amplitude("x_b", T, 2)
    h = harmonic_response(m, p, [w], np.array([a, 0.0], complex))
    assert h.amplitude("x_b")[0] == pytest.approx(td, rel=0.01)
    assert h.converged


def test_periodic_matches_time_domain_and_dale_equivalent(dale):
    s, m, p = dale
    w, Z = scene_input_amplitude(s)
    per = periodic_steady_state(m, p, w, input_amplitude=Z)
    assert per.success
    T = 2 * np.pi / w
    times = np.concatenate([np.arange(0.0, 11 * T, T / 40), 11 * T + per.time])
    res = simulate(s, times=times)
    err = np.max(np.abs(res["x_b"][-per.time.size:] - per.outputs["x_b"])) / per.amplitude("x_b")
    assert err < 1e-4
    h = harmonic_response(m, p, [w], Z)
    td_amp = res.steady_amplitude("x_b", T, 1)
    assert h.amplitude("x_b")[0] == pytest.approx(td_amp, rel=0.05)
    assert h.amplitude("y_b")[0] == pytest.approx(res.steady_amplitude("y_b", T, 1), rel=0.01)


def test_spectra_and_statistics():
    w = np.linspace(0.05, 6, 4000)
    for S in (pierson_moskowitz(w, 2.0, 8.0), jonswap(w, 2.0, 8.0, 3.3)):
        assert 4 * math.sqrt(spectral_moment(w, S)) == pytest.approx(2.0, rel=0.03)   # Hs = 4 sqrt(m0)
    assert significant_amplitude(w, pierson_moskowitz(w, 2.0, 8.0)) == pytest.approx(1.0, rel=0.02)
    assert w[np.argmax(jonswap(w, 2.0, 8.0))] == pytest.approx(2 * math.pi / 8.0, rel=0.01)
    assert slack_probability(1.0, 0.5, 0.0) == pytest.approx(0.02275, rel=1e-3)


@pytest.mark.parametrize("hs,tp,gamma,field", [(0.0, 8.0, 3.3, "spectrum.hs"), (1.0, -2.0, 3.3, "spectrum.tp"),
                                                (1.0, 8.0, 0.5, "spectrum.gamma")])
def test_bad_spectrum(hs, tp, gamma, field):
    with pytest.raises(ParameterError) as err:
        jonswap([0.5, 1.0], hs, tp, gamma)
    assert err.value.field == field


def test_no_equilibrium_errors(dale):
    s, m, p = dale
    with pytest.raises(ParameterError, match="no taut"):
        s.replace_section(0, body={"weight": -1.0})
    # a rootfinder that does not converge (here: one that returns NaN) gives a clear SolverError
    import casadi as ca
    q, pp = ca.SX.sym("q", m.nq), ca.SX.sym("p", len(m.layout))
    diverging = ca.Function("diverging", [q, pp], [q * np.nan])
    with pytest.raises(SolverError, match="steady state not found.*give an initial guess"):
        steady_state(m, p, solver=diverging)
