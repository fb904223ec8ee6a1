"""The segmented cable's state scales (cablesys.model.scales: per-state absolute tolerances)."""

import math

import numpy as np
import pytest

from cablesys.model import build_model
from cablesys.model.scales import state_scale_values
from cablesys.scene import Body, Cable, Sinusoid, TopMotion
from cablesys.scene.scene import single_section_scene


def _scene(n, tension_ref=4877.0, top=None):
    cable = Cable(length=300.0, tension_ref=tension_ref, ae=4.0e7, diameter=0.025, mass_per_length=2.5,
                  weight_per_length=19.6, segments=n)
    body = Body(weight=1937.0, mass_x=2900.0, mass_y=2900.0)
    return single_section_scene(cable=cable, body=body, top_motion=top or TopMotion())


def test_position_scale_is_one_elements_stretch_and_its_tension():
    """delta = T h / AE: moving a node by delta along the element changes its tension by T (Wang eq. 46)."""
    n = 20
    sc = _scene(n, top=TopMotion(y=(Sinusoid(amplitude=1.0, frequency=2 * math.pi / 10),)))
    model = build_model(sc)
    S = state_scale_values(model, model.parameters(sc))
    assert S.shape == (2 * model.nq,)
    delta = 4877.0 * (300.0 / n) / 4.0e7
    np.testing.assert_allclose(S[: model.nq], delta, rtol=1e-12)
    # the top's velocity amplitude a omega
    np.testing.assert_allclose(S[model.nq:], 2 * math.pi / 10, rtol=1e-12)
    # the tension law of one element: a stretch of delta more is T_ref more (undamped, taut)
    p = model.parameters(sc)
    x = np.zeros(2 * model.nq)
    h0 = 300.0 / n - 4877.0 * (300.0 / n) / 4.0e7          # h_r - T_r h_r / AE: zero-tension length
    x[1:model.nq:2] = h0 * np.arange(1, n + 1)              # every element at its zero-tension length
    e = np.zeros(7)
    y0 = np.array(model.outputs(x, e, p)).ravel()
    x[1:model.nq:2] += S[1]                                  # every node below the top: element 0 stretches by delta
    y1 = np.array(model.outputs(x, e, p)).ravel()
    k = model.output_labels.index("element_tension[0]")
    assert y1[k] - y0[k] == pytest.approx(4877.0, rel=1e-9)


def test_without_motion_or_reference_tension_the_scales_stay_physical():
    """tension_ref = 0: the mean hanging tension W_b + w l / 2; no top motion: delta omega_e."""
    sc = _scene(10, tension_ref=0.0)
    model = build_model(sc)
    S = state_scale_values(model, model.parameters(sc))
    h = 30.0
    delta = (1937.0 + 19.6 * 300.0 / 2) * h / 4.0e7
    assert S[0] == pytest.approx(delta, rel=1e-12)
    assert S[-1] == pytest.approx(delta * math.sqrt(4.0e7 / (2.5 * h**2)), rel=1e-12)


def test_element_by_element_lagrange_equations_equal_the_whole_cables():
    """M q'' = f assembled element by element (segmented._element_inertia) equals Lagrange's equations
    of the whole cable's energies by AD (Wang 1971 eq. 8-9, lagrange.lagrange_equations), with the
    element-normal added mass of a thinning cable (eq. 3, 23-24) and no drag or damping, so that every
    generalized force is -dV/dq."""
    import casadi as ca

    from cablesys.model.lagrange import lagrange_equations
    from cablesys.scene import Environment
    n = 4
    cable = Cable(length=30.0, tension_ref=4877.0, ae=4.0e7, diameter=0.025, mass_per_length=2.5, weight_per_length=19.6,
                  thinning_ratio=0.3, added_mass_factor=1.0, cd_normal=0.0, ct_tangential=0.0, segments=n)
    body = Body(weight=1937.0, mass_x=2900.0, mass_y=2500.0, drag_area_normal=0.0, drag_area_tangential=0.0)
    sc = single_section_scene(cable=cable, body=body, environment=Environment(density=1025.0))
    model = build_model(sc)
    p = model.parameters(sc)
    nq = model.nq
    q, qd, e = ca.SX.sym("q", nq), ca.SX.sym("qd", nq), ca.SX.sym("e", 7)
    K, V = model.energy(ca.vertcat(q, qd), e, p)
    M_ref, f_ref = lagrange_equations(K - V, ca.SX.zeros(nq), q, qd, e[1:3], e[3:5], e[5:7])
    M, f = model.dynamics(q, qd, e, p)
    check = ca.Function("check", [q, qd, e], [M - M_ref, f - f_ref, f_ref])
    rng = np.random.default_rng(3)
    for _ in range(3):
        qv = np.zeros(nq)
        qv[1::2] = 7.6 * np.arange(1, n + 1) + 0.3 * rng.random(n)      # stretched, bowed: taut and oblique
        qv[0::2] = 0.5 * rng.normal(size=n)
        dM, df, fr = (np.array(a) for a in check(qv, rng.normal(size=nq), rng.normal(size=7)))
        assert np.max(np.abs(dM)) < 1e-9 * 2900.0
        assert np.max(np.abs(df)) < 1e-9 * np.max(np.abs(fr))
