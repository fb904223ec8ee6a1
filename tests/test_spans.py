"""A span between two supports on the shared cable (the node model): statics and modes.

Checks against independent routes and closed forms: the lumped chain's energy NLP and its Hessian
(cablesys.slack.statics, the same discrete equations by another formulation), the vertical force
balance, Triantafyllou's Table 1 (in water, inclined), Irvine & Caughey's closed forms with second-order convergence, and the exact decoupling of the
out-of-plane motion about a plane equilibrium. Tables 2-5 (the 1985 codes' band) run through the
shared cable in tests/test_slack_study.py (cablesys.slack.converge is this route).
"""

import csv
import math
import sys
from pathlib import Path

import numpy as np
import pytest

from cablesys.errors import ParameterError
from cablesys.slack import irvine, shared
from cablesys.slack.scene import PointMass, SlackCable, SlackScene
from cablesys.slack.statics import solve_equilibrium
from cablesys.slack.vibration import converge, modes as chain_modes
from cablesys.statics.span import span_matrices

ROOT = Path(__file__).resolve().parents[1]
REF = ROOT / "cablesys" / "data"
SPAN, M, EA, G = 22.9, 1.14, 8.9e5, 9.80665


def scene(l_over_L=0.962, masses=(), n=24, **kw):
    return SlackScene(cable=SlackCable(length=SPAN / l_over_L, mass_per_length=M, ae=EA, **kw.pop("cable", {})),
                      span=SPAN, masses=tuple(masses), n_elements=n, **kw)


def thirds(L, **kw):
    return [PointMass(position=L * k / 3, mass=4.5, **kw) for k in (1, 2)]


@pytest.mark.parametrize("rise", [0.0, 8.0])
def test_node_model_equals_the_energy_chain_on_the_same_nodes(rise):
    """Masses at the third points and 24 elements: both routes have the same nodes; the node model's
    KINSOL statics and AD Jacobian equal the chain's energy minimum and Hessian (in air)."""
    sc = scene(masses=thirds(SPAN / 0.962), rise=rise)
    a = shared.analyze(sc, 12)
    eq_c = solve_equilibrium(sc)
    b = chain_modes(eq_c, 12)
    assert np.max(np.hypot(a.equilibrium.x - eq_c.x, a.equilibrium.z - eq_c.z)) < 1e-7 * SPAN
    assert np.max(np.abs(a.modes.omega / b.omega - 1)) < 1e-7
    assert a.modes.mode_type == b.mode_type


def test_supports_carry_the_weight_and_planes_decouple():
    """Vertical balance: the end elements' vertical pulls carry the cable (less the half elements lumped
    on the supports) and the masses' weight in water (eq. 26); z decouples from (x, y) exactly."""
    L = SPAN / 0.962
    sc = scene(masses=thirds(L, specific_gravity=4.0), medium="water", rise=-5.0, n=30,
               cable=dict(specific_gravity=7.8))
    eq = shared.equilibrium(sc)
    w = M * G * (1 - 1 / 7.8)
    d = eq.discretization
    W = w * (L - (d.L0[0] + d.L0[-1]) / 2) + 2 * 4.5 * G * (1 - 1 / 4.0)
    t0 = np.array([eq.x[1] - eq.x[0], eq.z[1] - eq.z[0]]) / eq.element_lengths[0]
    t1 = np.array([eq.x[-1] - eq.x[-2], eq.z[-1] - eq.z[-2]]) / eq.element_lengths[-1]
    assert eq.tension[-1] * t1[1] - eq.tension[0] * t0[1] == pytest.approx(W, rel=1e-8)
    mats = span_matrices(*eq.node_state)
    assert mats["coupling"] < 1e-12


def test_anchored_span_hangs_in_space_as_in_the_plane():
    """The 3-D node model's anchor (x, y, 0): the span's nodes in space equal the planar model's, z = 0."""
    import dataclasses

    from cablesys.model import build_model
    from cablesys.statics.catenary import segmented_equilibrium
    eq = shared.equilibrium(scene(masses=thirds(SPAN / 0.962), rise=3.0))
    model3, q3, _ = eq.node_state
    main = shared.to_scene(scene(masses=thirds(SPAN / 0.962), rise=3.0))
    flat = dataclasses.replace(main, numerics=dataclasses.replace(main.numerics, dimensions=2), sections=tuple(
        dataclasses.replace(s, body=dataclasses.replace(s.body, mass_z=None)) for s in main.sections))
    model2 = build_model(flat)
    r3 = q3.reshape(-1, 3)
    q2, _ = segmented_equilibrium(model2, model2.parameters(flat), guess=(r3[:, :2] * (1 + 1e-4)).ravel())
    assert model3.dim == 3 and model2.dim == 2
    assert np.max(np.abs(r3[:, :2] - q2.reshape(-1, 2))) < 1e-9 * SPAN and np.max(np.abs(r3[:, 2])) == 0.0


def _table1_scene():
    sys.path.insert(0, str(ROOT / "studies"))
    try:
        import slack_tables
    finally:
        sys.path.pop(0)
    return slack_tables.table1_scene()


def test_table1_in_water_on_the_shared_cable():
    """Triantafyllou (1984b) via Griffin & Rosenthal Table 1: the five in-plane frequencies within 2 % of
    both printed columns, and within 0.2 % of the energy chain's (converged, its own nodes)."""
    sc = _table1_scene()
    c = converge(sc, 12, levels=(30, 60, 120))
    om = np.array([r["omega_rad_s"] for r in c.table() if r["mode_type"] != "O"][:5])
    with open(REF / "griffin_table1_inclined.csv") as f:
        for r in csv.DictReader(line for line in f if not line.startswith("#")):
            ref = np.array([float(r[f"omega_{k}"]) for k in range(1, 6)])
            assert np.max(np.abs(om / ref - 1)) < 0.02, r["source"]
    # the chain: its mass block uses the node tangent for the added mass, the node model the elements'
    # own normals (Wang 1971 eq. 23-24): the same limit at h -> 0
    chain = []
    for n in (60, 120, 240):
        ms = chain_modes(solve_equilibrium(sc, n_elements=n), 16)
        chain.append(ms.of_type("A", "S", "H")[:5])
    rich = chain[-1] + (chain[-1] - chain[-2]) / 3
    assert np.max(np.abs(om / rich - 1)) < 2e-3


def test_irvine_caughey_frequencies_converge_at_second_order():
    """A flat bare span (lambda^2 ~ 40): the node model's in-plane and out-of-plane frequencies tend to
    Irvine & Caughey's (1974) eq. 6 and the string's k pi / l sqrt(H / m), at observed order 2."""
    sc = scene(1 - 0.0012)
    c = converge(sc, 6, levels=(24, 48, 96))
    eq = shared.equilibrium(sc, n_elements=96)
    ref = irvine.irvine_modes(8, lambda2=eq.lambda2, span=SPAN, H=eq.horizontal_tension, m=M)
    for t in "OAS":
        num = sorted(w for tt, w in zip(c.mode_type, c.richardson) if tt == t)
        th = [m.omega for m in ref if m.mode_type == t][:len(num)]
        assert num, t
        assert np.max(np.abs(np.array(num) / np.array(th) - 1)) < 0.01, t
    assert np.all(np.abs(c.order - 2.0) < 0.1), c.order


def test_bad_input_is_named_before_any_work():
    with pytest.raises(ParameterError) as err:
        shared.to_scene("not a scene")
    assert err.value.field == "scene"
    with pytest.raises(ParameterError) as err:
        shared.to_scene(scene(), segments=(0,))
    assert err.value.field == "segments"
    with pytest.raises(ParameterError) as err:
        shared.to_scene(scene(masses=[PointMass(position=5.0, mass=1.0), PointMass(position=5.0, mass=2.0)]))
    assert err.value.field == "masses"
    with pytest.raises(ParameterError) as err:
        converge(scene(), 3, levels=(24, 36, 72))
    assert err.value.field == "levels"


def test_translation_keeps_every_load():
    """The main scene holds the cable's weight and mass and every point mass (weight in water, virtual mass
    M + C_am M / S, eq. 26); in water the cable's added mass per length is the scene's m_a."""
    L = SPAN / 0.962
    sc = scene(masses=thirds(L, specific_gravity=2.0, added_mass_factor=0.5), medium="water",
               cable=dict(specific_gravity=7.8, added_mass_factor=1.0))
    main = shared.to_scene(sc)
    assert sum(s.cable.length for s in main.sections) == pytest.approx(L, rel=1e-14)
    assert (main.anchor.x, main.anchor.y) == (SPAN, -0.0)
    bodies = [s.body for s in main.sections[:2]]
    assert all(b.weight == pytest.approx(4.5 * G * 0.5) and b.mass_x == pytest.approx(4.5 + 0.5 * 4.5 / 2) for b in bodies)
    c = main.sections[0].cable
    assert c.weight_per_length == pytest.approx(M * G * (1 - 1 / 7.8))
    assert c.added_mass_factor * main.environment.density * math.pi * c.diameter ** 2 / 4 == pytest.approx(M / 7.8)
    assert shared.to_scene(scene()).sections[0].cable.added_mass_factor == 0.0       # no added mass in air
