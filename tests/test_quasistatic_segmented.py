"""The segmented cable in element coordinates and its quasi-static stretch reduction (issue 12).

Checks: the element-coordinates model is the node model in other coordinates (same trajectory);
the quasi-static segmented chain meets closed forms (hanging chain: Bessel-J0 zeros at order 2 in N;
N = 1: the lumped pendulum and the spring amplification 1 / (1 - (omega / omega_1)^2)); on the Dale
scene it agrees with the node model where the stretch does not matter.
"""

import dataclasses
import math

import numpy as np
import pytest
from scipy.special import jn_zeros
from test_quasistatic import heave_tension_amplitudes

from cablesys.ladder import metrics as M
from cablesys.ladder.rungs import build_rung, rung_scene
from cablesys.linear import linearize, modes
from cablesys.model import build_model
from cablesys.model.element_coordinates import build_element_model
from cablesys.model.quasistatic import (
    CHORD_TOLERANCE,
    axial_frequencies,
    build_quasistatic,
    chord_iterations,
    least_tension_margin,
)
from cablesys.model.segmented import build_segmented_model
from cablesys.scene import Body, Cable, Environment, Numerics, dale_scene
from cablesys.scene.scene import single_section_scene
from cablesys.time_domain import simulate
from cablesys.time_domain.initial import initial_state


def _dale(n, duration):
    """Wang's Dale scene with the smooth start of the benchmarks (3 forcing periods)."""
    sc = dale_scene(duration=duration)
    period = 2 * math.pi / sc.top_motion.x[0].frequency
    sc = dataclasses.replace(sc, top_motion=dataclasses.replace(sc.top_motion, ramp_s=3 * period))
    return sc.replace_section(0, cable={"segments": n}), period


def _chain(n, length=10.0):
    """A hanging uniform chain in vacuum (no added mass, no drag), g = w / m = 9.81, a negligible body."""
    cable = Cable(length=length, tension_ref=50.0, ae=1e8, diameter=0.01, mass_per_length=1.0,
                  weight_per_length=9.81, cd_normal=0.0, ct_tangential=0.0, added_mass_factor=0.0, segments=n)
    body = Body(weight=1e-3, mass_x=1e-4, mass_y=1e-4, drag_area_normal=0.0, drag_area_tangential=0.0)
    return single_section_scene(cable=cable, body=body, environment=Environment(density=1025.0),
                                numerics=Numerics(duration=10.0, output_step=0.05))


def _pendulum(n, ae=2e5):
    """20 m cable of 5 kg/m (40 N/m in water) with a 200 kg body (1500 N in water), no drag."""
    cable = Cable(length=20.0, tension_ref=1900.0, ae=ae, diameter=0.03, mass_per_length=5.0,
                  weight_per_length=40.0, cd_normal=0.0, ct_tangential=0.0, segments=n)
    body = Body(weight=1500.0, mass_x=260.0, mass_y=240.0, drag_area_normal=0.0, drag_area_tangential=0.0)
    return single_section_scene(cable=cable, body=body, environment=Environment(density=1025.0),
                                numerics=Numerics(duration=20.0, output_step=0.05))


@pytest.mark.parametrize("n", [1, pytest.param(4, marks=pytest.mark.slow)])
def test_element_coordinates_reproduce_the_node_model(n):
    """Same physics, other coordinates: 1.5 s of the Dale scene from the same catenary, body position and
    end tensions within 1e-6 of the node model's (both integrated at rtol 1e-10)."""
    sc, _ = _dale(n, 1.5)
    node = build_segmented_model(sc)
    ec = build_element_model(sc, node)
    p = node.parameters(sc)
    a = simulate(sc, model=node, rtol=1e-10, atol=1e-13)
    b = simulate(sc, model=ec, x0=initial_state(sc, ec, p), rtol=1e-10, atol=1e-13)
    assert a.success and b.success
    for lbl in ("x_b", "y_b"):
        scale = np.max(np.abs(a[lbl]))
        assert np.max(np.abs(b[lbl] - a[lbl])) <= 1e-6 * scale
    for lbl in ("tension_top", "tension_bottom"):
        assert np.max(np.abs(b[lbl] - a[lbl])) <= 1e-6 * np.max(a[lbl])
    # the maps are inverse to each other at any state
    x = initial_state(sc, ec, p) + 1e-3 * np.arange(4 * n)
    e = np.array(ec.top(1.0, p)).ravel()
    assert np.allclose(np.array(ec.from_nodes(ec.to_nodes(x, e, p), e, p)).ravel(), x, rtol=0, atol=1e-12)


def test_hanging_chain_bessel_zeros_at_second_order():
    """Hanging uniform chain, free end: omega_k = j_{0,k} / 2 sqrt(g / L). The quasi-static segmented
    chain (lumped masses) converges to the first at order 2 in N, the second approaches it."""
    exact = jn_zeros(0, 2) / 2 * math.sqrt(9.81 / 10.0)
    errs = []
    for n in (2, 4, 8):
        sc = _chain(n)
        qs = build_quasistatic(sc)
        w = np.sort(modes(linearize(qs, qs.parameters(sc))).omega_undamped)
        assert w.size == n                          # the swing/string modes only: no stretch left
        errs.append(np.abs(w[:2] / exact - 1))
    order = np.log2(errs[-2][0] / errs[-1][0])
    assert 1.9 < order < 2.1
    assert errs[-1][0] < 5e-3 and errs[-1][1] < errs[-2][1] < errs[-3][1] and errs[-1][1] < 0.06


def _n1_quasistatic(sc):
    """The quasi-static reduction of the one-element node model (not Wang's cable: lumped masses), its
    stretch solved to round-off (8 chord iterations) for the closed forms."""
    node = build_segmented_model(sc)
    return node, build_quasistatic(sc, full=build_element_model(sc, node), iterations=8)


def test_one_element_rigid_pendulum_frequency():
    """N = 1, stiff: a pendulum of length l with the body and half the element lumped at its end
    (Wang 1971 eq. 5, 12, 23-24 per element): omega^2 = (W_b + W_c / 2) / (l (M_bx + (m_c + m_a) / 2)),
    m_a = gamma rho pi d^2 / 4 l the element's added mass (normal to it, i.e. along the swing)."""
    sc = _pendulum(1, ae=1e9)
    _, qs = _n1_quasistatic(sc)
    p = qs.parameters(sc)
    w = modes(linearize(qs, p)).omega_undamped
    assert w.size == 1
    c, b, rho = sc.cable, sc.body, sc.environment.density
    from cablesys.statics.steady import steady_state
    length = c.length_zero + steady_state(qs, p).outputs["u"]
    m_a = c.added_mass_factor * rho * math.pi * c.diameter**2 / 4 * length
    w2 = (b.weight + c.total_weight / 2) / (length * (b.mass_x + (c.total_mass + m_a) / 2))
    assert w[0] == pytest.approx(math.sqrt(w2), rel=1e-6)


@pytest.mark.parametrize("ratio", [0.2, 0.5])
def test_one_element_spring_amplification(ratio):
    """N = 1 heave: the node model's stretch is one spring k = AE / l_r with the body and half the cable,
    omega_1^2 = k / (M_bvy + m_c / 2); the quasi-static body-element tension is (M_bvy + m_c / 2) omega^2
    per metre of heave, the dynamic one 1 / (1 - (omega / omega_1)^2) times more."""
    sc = _pendulum(1)
    node, qs = _n1_quasistatic(sc)
    p = node.parameters(sc)
    c, b = sc.cable, sc.body
    mass = b.mass_y + c.total_mass / 2
    w1 = math.sqrt(c.ae / c.length / mass)
    omega = ratio * w1
    amp = heave_tension_amplitudes((node, qs), p, omega)
    assert amp["quasi-static"] == pytest.approx(mass * omega**2, rel=1e-9)
    assert amp["segmented"] / amp["quasi-static"] == pytest.approx(1 / (1 - ratio**2), rel=1e-9)


def test_four_elements_spring_amplification_is_second_order():
    """N = 4 heave: the quasi-static body-element tension is (M_bvy + m_c / 2N) omega^2 exactly; the node
    model's exceeds it by (omega / omega_ax)^2 to leading order, omega_ax Wang's axial frequency (eq. 22,
    25): the constant is 1 within the lumped chain's modal participation (10 %)."""
    sc = _pendulum(4)
    node = build_model(sc)
    qs = build_quasistatic(sc, iterations=8)
    p = node.parameters(sc)
    c, b = sc.cable, sc.body
    w_ax = axial_frequencies(sc)[0]
    for ratio in (0.05, 0.1):
        omega = ratio * w_ax
        amp = heave_tension_amplitudes((node, qs), p, omega)
        assert amp["quasi-static"] == pytest.approx((b.mass_y + c.total_mass / 8) * omega**2, rel=1e-9)
        assert (amp["segmented"] / amp["quasi-static"] - 1) / ratio**2 == pytest.approx(1.0, rel=0.1)


def test_rung_scene_keeps_segments_for_quasistatic():
    """build_rung(scene, 'quasi-static', segments=N) is the segmented reduction; N = 1 Wang's."""
    sc, _ = _dale(1, 10.0)
    assert rung_scene(sc, "quasi-static", 3).sections[0].cable.segments == 3
    qs = build_rung(sc, "quasi-static", segments=3)
    assert qs.kind == "quasi-static" and qs.n_elements == 3 and qs.q_labels == ("phi[0]", "phi[1]", "phi[2]")
    assert build_rung(sc, "quasi-static").q_labels == ("phi",)


@pytest.mark.slow
def test_dale_quasistatic_matches_node_model():
    """Dale, 60 s, N = 4: the stretch does not matter there (Wang 1971 p. 29), so the quasi-static
    reduction's body amplitudes and end-tension extremes are within 0.2 % of the node model's (last 5
    periods), in far fewer steps, and every element stays taut."""
    sc, period = _dale(4, 60.0)
    node = build_model(sc)
    qs = build_rung(sc, "quasi-static", segments=4)
    a = simulate(sc, model=node, rtol=1e-6, atol=1e-9)
    b = simulate(sc, model=qs, rtol=1e-6, atol=1e-9)
    assert a.success and b.success
    e = M.errors(M.statistics(b, period), M.statistics(a, period))
    assert e["body"] < 2e-3 and e["tension"] < 2e-3
    assert least_tension_margin(b, sc) > 0
    assert b.stats["nsteps"] * 4 < a.stats["nsteps"]
    # simulate() says which model ran, with its elements (no node profiles to infer it from)
    assert b.summary()["model"] == {"name": "quasi-static", "segments": 4}
    assert a.summary()["model"] == {"name": "segmented", "segments": 4}
    w = M.window(np.asarray(a.time), period)
    ta, tb = np.asarray(a.profiles["element_tension"])[w], np.asarray(b.profiles["element_tension"])[w]
    assert np.max(np.abs(tb - ta)) < 2e-3 * np.max(ta)


def test_default_chord_iterations_meet_their_tolerance():
    """The rung's chord iterations (eps^n <= CHORD_TOLERANCE, eps = T / AE = 0.0115 here: n = 3) give the
    element tensions of a large swing (0.4 rad, 5 s) within CHORD_TOLERANCE of the converged stretch
    (one iteration is 2e-4 off, two 3e-7: each gains about eps)."""
    sc = _pendulum(4)
    sc = dataclasses.replace(sc, initial=dataclasses.replace(sc.initial, phi=0.4)).with_numerics(duration=5.0)
    assert chord_iterations(sc) == 3
    T = [np.asarray(simulate(sc, model=qs, rtol=1e-10, atol=1e-12).profiles["element_tension"])
         for qs in (build_rung(sc, "quasi-static", segments=4), build_quasistatic(sc, iterations=8))]
    assert np.max(np.abs(T[0] - T[1])) <= CHORD_TOLERANCE * np.max(T[1])


def test_steady_state_in_a_current_is_the_node_models_catenary():
    """Statics: the quasi-static segmented cable's equilibrium in a 0.3 m/s current (every element inclined,
    drag-bowed: 0.70 rad at the top, 0.22 at the body) is the node model's elastic catenary (its own
    rootfinder, node coordinates): body position and end tensions within 1e-6."""
    from cablesys.statics.steady import steady_state
    sc, _ = _dale(4, 10.0)
    sc = dataclasses.replace(sc, environment=dataclasses.replace(sc.environment, current_speeds=(0.3,)))
    qs, node = build_rung(sc, "quasi-static", segments=4), build_model(sc)
    p = qs.parameters(sc)
    a, b = steady_state(qs, p), steady_state(node, p)
    assert a.q[0] < a.q[-1] < -0.1                       # bowed: the top element inclines most
    for k in ("x_b", "y_b", "tension_top", "tension_bottom"):
        assert a.outputs[k] == pytest.approx(b.outputs[k], rel=1e-6)
