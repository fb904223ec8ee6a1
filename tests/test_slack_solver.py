"""Numerical statics and modes against each other, Irvine-Caughey, symmetry and convergence."""

import math

import numpy as np
import pytest

from cablesys.errors import ParameterError, SolverError
from cablesys.slack import irvine
from cablesys.slack.vibration import converge, modes
from cablesys.slack.scene import SlackCable, PointMass, SlackScene
from cablesys.slack.statics import solve_equilibrium, solve_equilibrium_shooting

SPAN, M, EA = 22.9, 1.14, 8.9e5


def scene(l_over_L=0.987, masses=(), n=96, **kw):
    return SlackScene(cable=SlackCable(length=SPAN / l_over_L, mass_per_length=M, ae=EA),
                      span=SPAN, masses=tuple(masses), n_elements=n, **kw)


@pytest.mark.parametrize("rise", [0.0, 8.0, -6.0])
def test_nlp_equals_shooting(rise):
    sc = scene(0.962, [PointMass(position=5.0, mass=4.5), PointMass(position=14.0, mass=2.0)], rise=rise)
    a = solve_equilibrium(sc)
    d = a.discretization
    b = solve_equilibrium_shooting(sc)
    assert np.max(np.hypot(a.x - b.x, a.z - b.z)) < 1e-7 * SPAN
    # vertical force balance: the end elements carry cable + point masses, less the
    # half elements lumped onto the supports themselves
    W = M * 9.80665 * (sc.cable.length - (d.L0[0] + d.L0[-1]) / 2) + (4.5 + 2.0) * 9.80665
    t0 = np.array([a.x[1] - a.x[0], a.z[1] - a.z[0]]) / a.element_lengths[0]
    t1 = np.array([a.x[-1] - a.x[-2], a.z[-1] - a.z[-2]]) / a.element_lengths[-1]
    assert a.tension[-1] * t1[1] - a.tension[0] * t0[1] == pytest.approx(W, rel=1e-8)


def test_hessian_is_stiffness_matches_finite_difference_of_forces():
    from cablesys.slack.statics import _energy_functions, _params, stiffness_inplane
    import casadi as ca
    sc = scene(0.97, n=12)
    eq = solve_equilibrium(sc)
    d = eq.discretization
    K = stiffness_inplane(eq, d).toarray()
    w, p, V, fV, _ = _energy_functions(d.n_elements)
    g = ca.Function("g", [w, p], [ca.gradient(V, w)])
    w0 = np.concatenate([eq.x[1:-1], eq.z[1:-1]])
    pr = _params(sc, d)
    h = 1e-6
    Kfd = np.column_stack([(np.asarray(g(w0 + h * e, pr)) - np.asarray(g(w0 - h * e, pr))).ravel() / (2 * h)
                           for e in np.eye(len(w0))])
    assert np.allclose(K, Kfd, rtol=1e-5, atol=1e-6 * np.abs(K).max())
    assert np.allclose(K, K.T)


def test_irvine_agreement_small_sag():
    """Converged in-plane and out-of-plane frequencies vs eq. 6 / string, within 1 %."""
    for one_minus in (0.0005, 0.0012, 0.0024):          # lambda^2 ~ 10 .. 80, across 4 pi^2
        sc = scene(1 - one_minus)
        eq = solve_equilibrium(sc.replace(n_elements=96))
        c = converge(sc, 6, levels=(24, 48, 96))
        ref = irvine.irvine_modes(8, lambda2=eq.lambda2, span=SPAN, H=eq.horizontal_tension, m=M)
        for t in "OAS":
            num = sorted(w for tt, w in zip(c.mode_type, c.richardson) if tt == t)
            th = [m.omega for m in ref if m.mode_type == t][:len(num)]
            assert num, t
            assert np.max(np.abs(np.array(num) / np.array(th) - 1)) < 0.01, (one_minus, t)


def test_convergence_order_two_and_richardson():
    c = converge(scene(0.987), 30, levels=(40, 80, 160))
    assert len(c.richardson) == 30
    # lumped-mass chain: h^2 convergence for (nearly) every mode
    assert np.median(c.order) == pytest.approx(2.0, abs=0.05)
    assert np.mean(np.abs(c.order - 2) < 0.1) > 0.8
    # Richardson improves on the finest level by at least ~10x for the low modes
    err_fine = np.abs(c.omega[-1] - c.richardson)
    err_mid = np.abs(c.omega[-2] - c.richardson)
    assert np.all(err_mid[:10] > 3.5 * err_fine[:10])


def test_symmetry_classification_and_eq25_normalization():
    sc = scene(0.962, [PointMass(position=SPAN / 0.962 / 3, mass=4.5),
                       PointMass(position=2 * SPAN / 0.962 / 3, mass=4.5)], n=60)
    eq = solve_equilibrium(sc)
    d = eq.discretization
    ms = modes(eq, 9)
    assert "".join(ms.mode_type) == "OAOSOAOSO"
    inplane = ~np.isnan(ms.symmetric_fraction)
    f = ms.symmetric_fraction[inplane]
    assert np.all((f > 1 - 1e-8) | (f < 1e-8))   # exact mirror symmetry of a symmetric scene
    # eq. 25: sum over nodes of psi^2 dm = 1 with dm including the point masses (air: isotropic lumped mass)
    for k in range(len(ms)):
        assert np.sum(d.mass[:, None] * ms.shapes[k] ** 2) == pytest.approx(1.0, rel=1e-9)


def test_inclined_cable_has_hybrid_modes_horizontal_does_not():
    cab = SlackCable(length=330.0, mass_per_length=5.56, ae=1.06e8)
    for th, expect_hybrid in ((0.0, False), (60.0, True)):
        sc = SlackScene.from_chord(cable=cab, chord=330 * 0.99966, theta_deg=th, n_elements=60)
        eq = solve_equilibrium_shooting(sc)
        types = modes(eq, 6).mode_type
        assert ("H" in types) == expect_hybrid, (th, types)


def test_water_added_mass_lowers_transverse_frequencies_by_eq27():
    # taut-ish horizontal cable: out-of-plane modes scale by sqrt(m_W/m_A) at equal weight
    cab_air = SlackCable(length=100.0, mass_per_length=2.0, ae=1e7)
    cab_w = SlackCable(length=100.0, mass_per_length=2.0, ae=1e7, specific_gravity=4.0,
                  added_mass_factor=1.0, weight_per_length=2.0 * 9.80665)
    a = modes(solve_equilibrium(SlackScene(cable=cab_air, span=99.9, n_elements=60)), 4)
    w = modes(solve_equilibrium(SlackScene(cable=cab_w, span=99.9, medium="water", n_elements=60)), 4)
    ratio = irvine.virtual_mass_ratio(added_mass_factor=1.0, specific_gravity=4.0)
    assert a.of_type("O")[0] / w.of_type("O")[0] == pytest.approx(math.sqrt(ratio), rel=1e-6)


def test_sparse_equals_dense():
    sc = scene(0.962, [PointMass(position=8.0, mass=4.5)], n=200)
    eq = solve_equilibrium(sc)
    a = modes(eq, 12, solver="dense")
    b = modes(eq, 12, solver="sparse")
    assert np.allclose(a.omega, b.omega, rtol=1e-9)
    assert a.mode_type == b.mode_type


@pytest.mark.parametrize("kw, field", [
    (dict(span=40.0), "scene.chord"),
    (dict(span=-1.0), "scene.span"),
    (dict(masses=(PointMass(position=30.0, mass=1.0),)), "masses[0].position"),
    (dict(medium="oil"), "scene.medium"),
])
def test_bad_scene_names_the_field(kw, field):
    base = dict(cable=SlackCable(length=23.8, mass_per_length=M, ae=EA), span=22.9)
    base.update(kw)
    with pytest.raises(ParameterError) as err:
        SlackScene(**base)
    assert err.value.field == field


@pytest.mark.parametrize("kw, field", [(dict(length=0.0), "cable.length"),
                                       (dict(mass_per_length=-1.0), "cable.mass_per_length")])
def test_bad_cable(kw, field):
    base = dict(length=23.8, mass_per_length=M, ae=EA)
    base.update(kw)
    with pytest.raises(ParameterError) as err:
        SlackCable(**base)
    assert err.value.field == field


def test_bad_mass_and_nonconverging_nlp():
    with pytest.raises(ParameterError, match="mass.mass"):
        PointMass(position=1.0, mass=0.0)
    with pytest.raises(SolverError, match="did not converge"):
        solve_equilibrium(scene(0.962, n=40), max_iter=1)


def test_analyze_is_one_result_with_units_and_the_same_numbers_as_its_parts():
    """slack.analyze = the shared cable's equilibrium then its modes (one result); the old tuple unpacking warns."""
    import json

    import cablesys.slack as slack
    from cablesys.slack import shared

    sc = scene(0.962, [PointMass(position=8.0, mass=4.5)], n=48)
    res = slack.analyze(sc, 6)
    assert isinstance(res, slack.SlackAnalysis) and res.success and res.message == ""
    eq = shared.equilibrium(sc)
    parts = shared.modes(eq, 6)
    assert np.array_equal(res.modes.omega, parts.omega) and res.modes.mode_type == parts.mode_type
    assert res.equilibrium.horizontal_tension == pytest.approx(eq.horizontal_tension, rel=1e-12)
    ds = res.to_xarray()
    assert ds["omega"].attrs["units"] == "rad/s" and ds["tension"].attrs["units"] == "N"
    assert ds["x"].dims == ("node",) and ds["shape"].dims == ("mode", "node", "dof")
    doc = json.loads(json.dumps(res.summary()))
    assert [r["omega_rad_s"] for r in doc["modes"]] == pytest.approx(list(parts.omega), rel=1e-15)
    assert res.stats["wall_time_s"] >= res.modes.stats["wall_time_s"]
    with pytest.warns(DeprecationWarning, match="unpacking slack.analyze"):
        eq_old, modes_old = res
    assert eq_old is res.equilibrium and modes_old is res.modes
    # the chain's modes need the element layout: an Equilibrium without one is refused by name
    import dataclasses
    with pytest.raises(ParameterError, match="eq.discretization"):
        modes(dataclasses.replace(solve_equilibrium(sc), discretization=None))
