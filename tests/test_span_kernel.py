"""A span's node model in its element-kernel form (cablesys.model.segmented_kernel with an ``[anchor]``,
cablesys.statics.span.SpanKernel) is the element-by-element node model (cablesys.model.segmented): on an anchored
chain of three sections (two point masses between the top and the anchor), its ``kernel_ode`` equals the ``ode`` on
random states (in the plane in a current, in space in water), ``kernel_jacobian`` equals CasADi's AD of that ``ode``,
and the statics' forces, mass blocks and stiffness (``kernel_statics``) equal the ``dynamics`` and its AD Jacobian,
each to rounding; the span's equilibrium and frequencies from the two forms agree to the statics' tolerance and to
rounding (the independent route is the element-by-element SX expression and AD of it)."""

import dataclasses

import casadi as ca
import numpy as np
import pytest

from cablesys.model import build_model
from cablesys.model.segmented import drag_points
from cablesys.model.segmented_kernel import kernel_statics
from cablesys.slack import shared
from cablesys.slack.modal import _eig
from cablesys.slack.scene import PointMass, SlackCable, SlackScene
from cablesys.statics.span import span_equilibrium, span_kernel, span_matrices

SPAN = 22.9


def _slack(medium="water", n=15):
    """A 22.9 m span, l/L = 0.962, rise 3 m, masses of 4.5 and 2 kg at the third points (cut into 3 sections)."""
    L = SPAN / 0.962
    masses = (PointMass(position=L / 3, mass=4.5, specific_gravity=4.0),
              PointMass(position=2 * L / 3, mass=2.0, specific_gravity=4.0))
    return SlackScene(cable=SlackCable(length=L, mass_per_length=1.14, ae=8.9e5, specific_gravity=7.8),
                      span=SPAN, rise=3.0, masses=masses, medium=medium, n_elements=n)


def _planar(main):
    """The same span in the plane (2-D nodes, no out-of-plane virtual mass), in a 0.4 m/s current."""
    flat = dataclasses.replace(main, numerics=dataclasses.replace(main.numerics, dimensions=2), sections=tuple(
        dataclasses.replace(s, body=dataclasses.replace(s.body, mass_z=None)) for s in main.sections))
    return flat.with_environment(current_speeds=(0.4,))


def _states(model, q0, rng, count=3):
    """The span's guess moved by a fortieth of an element's length, velocities of order 1 m/s, times in a minute."""
    h = SPAN / model.n_elements
    for _ in range(count):
        yield np.concatenate([q0 + rng.normal(0.0, h / 40, q0.size), rng.normal(0.0, 1.0, q0.size)]), rng.uniform(0, 60)


@pytest.mark.parametrize("dim", [2, 3])
def test_anchored_kernel_ode_and_jacobian_equal_the_element_by_element_ode(dim):
    main = shared.to_scene(_slack())
    scene = main if dim == 3 else _planar(main)
    model = build_model(scene)
    assert model.anchored and model.dim == dim
    ode, jac = model.kernel_ode, model.kernel_jacobian        # an anchored line has its kernel (segmented.has_kernel)
    assert ode is not None and model.loop_ode is ode
    xs, ts, ps = ca.SX.sym("x", model.ode.size1_in(0)), ca.SX.sym("t"), ca.SX.sym("p", model.ode.size1_in(2))
    ad = ca.Function("ad", [xs, ts, ps], [ca.jacobian(model.ode(xs, ts, ps), xs)])
    p = model.parameters(scene)
    from cablesys.statics.catenary import anchored_guess
    for x, t in _states(model, anchored_guess(model, p), np.random.default_rng(dim)):
        a, b = np.array(model.ode(x, t, p)).ravel(), np.array(ode(x, t, p)).ravel()
        assert np.all(np.isfinite(a)) and np.max(np.abs(a)) > 1.0
        assert np.max(np.abs(b - a)) <= 1e-12 * np.max(np.abs(a))
        A, B = np.array(ad(x, t, p)), np.array(ca.densify(jac(x, t, p)))
        assert np.max(np.abs(B - A)) <= 1e-12 * np.max(np.abs(A))


def test_kernel_statics_equal_the_element_by_element_forces_and_their_jacobian():
    main = shared.to_scene(_slack())
    model = build_model(main)
    forces, stiffness = kernel_statics(main, lambda n: drag_points(main, n))
    p = model.parameters(main)
    from cablesys.statics.catenary import anchored_guess
    q = anchored_guess(model, p) + np.random.default_rng(0).normal(0.0, 0.01, model.nq)
    e = np.zeros(model.top.size1_out(0))
    M, f = (np.array(v) for v in model.dynamics(q, np.zeros_like(q), e, p))
    qs = ca.SX.sym("q", model.nq)
    K = -np.array(ca.Function("k", [qs], [ca.jacobian(model.dynamics(qs, np.zeros_like(q), e, p)[1], qs)])(q))
    blocks, fk = (np.array(v) for v in forces(q, p))
    Kk = np.array(ca.densify(stiffness(q, p)))
    Mk = np.zeros_like(M)
    for j in range(blocks.shape[1]):
        Mk[3 * j:3 * j + 3, 3 * j:3 * j + 3] = blocks[:, j].reshape(3, 3, order="F")
    assert np.max(np.abs(fk.ravel() - f.ravel())) <= 1e-12 * np.max(np.abs(f))
    assert np.max(np.abs(Kk - K)) <= 1e-12 * np.max(np.abs(K))
    assert np.max(np.abs(Mk - M)) <= 1e-14 * np.max(np.abs(M))


@pytest.mark.parametrize("medium", ["air", "water"])
def test_span_statics_and_modes_equal_on_both_forms(medium):
    """KINSOL from the same guess on both forms; M and K about the one equilibrium; the 8 lowest frequencies."""
    sc = _slack(medium)
    main = shared.to_scene(sc)
    model, kern = build_model(main), span_kernel(main)
    p = model.parameters(main)
    eq = shared.equilibrium(sc)               # the kernel form
    assert isinstance(eq.node_state[0], type(kern))
    guess = eq.node_state[1] * (1 + 1e-4)
    q_m, r_m = span_equilibrium(model, p, guess=guess)
    q_k, r_k = span_equilibrium(kern, p, guess=guess)
    assert max(r_m, r_k) < 1e-10
    assert np.max(np.abs(q_k - q_m)) < 1e-9 * SPAN
    a, b = span_matrices(model, q_m, p), span_matrices(kern, q_m, p)
    for key in ("M_in", "K_in", "M_out", "K_out"):
        assert abs(a[key] - b[key]).max() <= 1e-12 * abs(a[key]).max(), key
    for plane in ("in", "out"):
        w_m = _eig(a[f"K_{plane}"], a[f"M_{plane}"], 8, "dense")[0]
        w_k = _eig(b[f"K_{plane}"], b[f"M_{plane}"], 8, "dense")[0]
        assert np.max(np.abs(w_k / w_m - 1)) < 1e-9, plane
