"""Chains of cable sections (Wang 1971 p. 32-33): checks against closed forms and against the 2-DOF model.

Each test uses a route independent of the chain assembly in ``cablesys/model/build.py``:
hand-written small-oscillation matrices of a double pendulum and a two-spring chain, the
combined 2-DOF system, energy conservation, hanging statics and the shared/per-section symmetry.
"""

import math

import numpy as np
import pytest

from cablesys.linear import modes
from cablesys.linear.linearization import linearize
from cablesys.linear.steady import steady_state
from cablesys.model import build_model
from cablesys.scene import Body, Cable, Numerics, Scene, Section, Sinusoid, TopMotion
from cablesys.scene.scene import single_section_scene
from cablesys.time_domain import simulate


def _cable(length, ae, *, w=0.0, m=0.0, mass=True, d=0.01, cd=0.0, ct=0.0, ci=0.0, floor=0.0):
    return Cable(length=length, tension_ref=0.0, ae=ae, diameter=d, mass_per_length=m, weight_per_length=w,
                 cd_normal=cd, ct_tangential=ct, internal_damping=ci, tension_floor=floor,
                 cable_mass_switch=1.0 if mass else -1.0, added_mass_factor=1.0 if mass else 0.0)


def _body(w, m, cda=0.0):
    return Body(weight=w, mass_x=m, mass_y=m, drag_area_normal=cda, drag_area_tangential=cda)


def _freqs(scene):
    model = build_model(scene)
    lin = linearize(model, model.parameters(scene))
    return modes(lin), lin, model


# -- closed forms: massless cables with two point bodies -------------------------------------
W1, M1, W2, M2, L1, L2, AE1, AE2 = 100.0, 20.0, 50.0, 8.0, 10.0, 5.0, 1e6, 2e6


def _two_body_scene(angles):
    return Scene(sections=(Section(cable=_cable(L1, AE1, mass=False), body=_body(W1, M1)),
                           Section(cable=_cable(L2, AE2, mass=False), body=_body(W2, M2))), angles=angles)


def _loaded_lengths():
    k1, k2 = AE1 / L1, AE2 / L2
    return L1 + (W1 + W2) / k1, L2 + W2 / k2, k1, k2


def _eig(K, M):
    return np.sort(np.sqrt(np.linalg.eigvals(np.linalg.solve(M, K)).real))


def test_per_section_chain_is_a_double_pendulum_on_a_two_spring_chain():
    """Small oscillations about phi = 0 decouple: swing = double pendulum, heave = masses on two springs."""
    l1, l2, k1, k2 = _loaded_lengths()
    # T = M1/2 (l1 a')^2 + M2/2 (l1 a' + l2 b')^2,  V = (W1 + W2) l1 a^2/2 + W2 l2 b^2/2
    swing = _eig(np.diag([(W1 + W2) * l1, W2 * l2]),
                 np.array([[(M1 + M2) * l1**2, M2 * l1 * l2], [M2 * l1 * l2, M2 * l2**2]]))
    # y1 = u1, y2 = u1 + u2:  T = M1/2 u1'^2 + M2/2 (u1' + u2')^2,  V = k1 u1^2/2 + k2 u2^2/2
    heave = _eig(np.diag([k1, k2]), np.array([[M1 + M2, M2], [M2, M2]]))
    md, _, _ = _freqs(_two_body_scene("per_section"))
    np.testing.assert_allclose(md.omega_undamped, np.sort(np.r_[swing, heave]), rtol=1e-9)


def test_shared_angle_chain_is_one_rigid_pendulum_with_two_springs():
    """Shared angle: both bodies on one line, M = M1 l1^2 + M2 (l1 + l2)^2, K = W1 l1 + W2 (l1 + l2)."""
    l1, l2, k1, k2 = _loaded_lengths()
    swing = math.sqrt((W1 * l1 + W2 * (l1 + l2)) / (M1 * l1**2 + M2 * (l1 + l2) ** 2))
    heave = _eig(np.diag([k1, k2]), np.array([[M1 + M2, M2], [M2, M2]]))
    md, _, model = _freqs(_two_body_scene("shared"))
    assert model.q_labels == ("phi", "u_1", "u_2")
    np.testing.assert_allclose(md.omega_undamped, np.sort(np.r_[swing, heave]), rtol=1e-9)


# -- a rigid, massless, very short lower section: the 2-DOF model of the combined body ---------
HEAVY = dict(w=20.0, m=3.0, d=0.03, cd=1.2, ct=0.01)     # synthetic-rope-like, 100 m


@pytest.mark.parametrize("angles", ["shared", "per_section"])
def test_rigid_short_lower_section_reproduces_the_2dof_model_of_the_combined_body(angles):
    wb1, mb1, wb2, mb2 = 2000.0, 300.0, 1000.0, 150.0
    ref = single_section_scene(cable=_cable(100.0, 5e6, **HEAVY), body=_body(wb1 + wb2, mb1 + mb2))
    chain = Scene(sections=(Section(cable=_cable(100.0, 5e6, **HEAVY), body=_body(wb1, mb1)),
                            Section(cable=_cable(0.01, 5e9, mass=False, d=1e-4), body=_body(wb2, mb2))),
                  angles=angles)
    md_ref, lin_ref, _ = _freqs(ref)
    md, lin, model = _freqs(chain)
    # the two slow modes (pendulum, stretch) of the chain are the 2-DOF ones, to O(l_2 / l_1)
    np.testing.assert_allclose(md.omega_undamped[:2], md_ref.omega_undamped, rtol=3e-4)
    # the third mode is the rigid section's spring (shared) or its short pendulum (per section)
    assert md.omega_undamped[2] > 3 * md_ref.omega_undamped[1]
    # the forced response of the lower body (undamped RAO off resonance) is the 2-DOF one; the
    # heave check includes a frequency half-way to the stretch mode
    w0, w1 = md_ref.omega_undamped
    cases = ((("x_b", "x_b_2"), np.array([0.3, 0.7, 3.0]) * w0),
             (("y_b", "y_b_2"), np.array([0.3, 3.0, 0.5 * w1 / w0]) * w0),
             (("tension_mid", "tension_mid_1"), np.array([0.3, 3.0, 0.5 * w1 / w0]) * w0))
    for (out_ref, out), w in cases:
        a = lin_ref.transfer(w)[1][:, lin_ref.output_labels.index(out_ref), :2]
        b = lin.transfer(w)[1][:, lin.output_labels.index(out), :2]
        np.testing.assert_allclose(np.abs(b), np.abs(a), rtol=2e-3, atol=1e-6 * np.abs(a).max())


# -- statics: each section carries the weight hanging below it ---------------------------------
@pytest.mark.parametrize("angles", ["shared", "per_section"])
def test_hanging_chain_tensions_equal_the_weights_below(angles):
    secs = (Section(cable=_cable(120.0, 4e6, w=15.0, m=2.0), body=_body(-300.0, 200.0)),     # a buoy
            Section(cable=_cable(60.0, 2e6, w=25.0, m=3.0), body=_body(800.0, 120.0)),
            Section(cable=_cable(30.0, 1e6, w=10.0, m=1.0), body=_body(2500.0, 400.0)))
    scene = Scene(sections=secs, angles=angles)
    model = build_model(scene)
    ss = steady_state(model, model.parameters(scene))
    below = 0.0
    for i in reversed(range(3)):
        c, b = secs[i].cable, secs[i].body
        # eq. 49b: k u = W_b + W_c/2 for one section; the bodies and cables below add their weight
        assert ss.outputs[f"tension_mid_{i + 1}"] == pytest.approx(below + b.weight + 0.5 * c.total_weight, rel=1e-9)
        assert ss.outputs[f"phi_{i + 1}"] == pytest.approx(0.0, abs=1e-12)
        below += b.weight + c.total_weight
    depth = sum(s.cable.length_zero for s in secs) + sum(ss.q[[j for j, l in enumerate(model.q_labels) if l.startswith("u")]])
    assert ss.outputs["y_b_3"] == pytest.approx(depth, rel=1e-12)


# -- energy: no drag, no damping, top at rest -> K + V constant --------------------------------
@pytest.mark.parametrize("angles", ["shared", "per_section"])
def test_chain_conserves_energy_without_drag(angles):
    secs = (Section(cable=_cable(50.0, 2e5, w=10.0, m=1.5, floor=-math.inf), body=_body(400.0, 80.0)),
            Section(cable=_cable(30.0, 1e5, w=10.0, m=1.5, floor=-math.inf), body=_body(600.0, 100.0)))
    scene = Scene(sections=secs, angles=angles, numerics=Numerics(duration=30.0, output_step=0.1, rtol=1e-10, atol=1e-12))
    model = build_model(scene)
    p = model.parameters(scene)
    q0 = steady_state(model, p).q
    q = q0 + np.where([l.startswith("phi") for l in model.q_labels], 0.0, 0.02)
    q[[i for i, l in enumerate(model.q_labels) if l.startswith("phi")]] = [0.3, -0.2][: 1 if angles == "shared" else 2]
    res = simulate(scene, model=model, x0=np.r_[q, np.zeros_like(q)])
    assert res.success
    n = model.n_sections
    def state(k):
        if angles == "shared":
            qs = [res["phi_1"][k]] + [res[f"u_{i + 1}"][k] for i in range(n)]
            qds = [res["phi_rate_1"][k]] + [res[f"u_rate_{i + 1}"][k] for i in range(n)]
        else:
            qs = [v for i in range(n) for v in (res[f"phi_{i + 1}"][k], res[f"u_{i + 1}"][k])]
            qds = [v for i in range(n) for v in (res[f"phi_rate_{i + 1}"][k], res[f"u_rate_{i + 1}"][k])]
        return np.r_[qs, qds]
    E = np.array([float(sum(model.energy(state(k), np.zeros(7), p))) for k in range(res.time.size)])
    K = np.array([float(model.energy(state(k), np.zeros(7), p)[0]) for k in range(res.time.size)])
    assert K.max() > 50.0                                   # a real motion exchanging energy
    assert np.ptp(E) < 1e-6 * K.max()
    assert np.ptp(res["phi_2"]) > 0.3                       # the lower section swings


# -- pure heave: by symmetry the angles stay zero, so shared and per-section must agree ---------
def test_shared_and_per_section_agree_in_pure_heave():
    secs = (Section(cable=_cable(80.0, 3e6, w=12.0, m=2.0, cd=1.2, ct=0.02, ci=2e4), body=_body(-200.0, 400.0, cda=0.8)),
            Section(cable=_cable(40.0, 1e6, w=12.0, m=2.0, cd=1.2, ct=0.02, ci=1e4), body=_body(3000.0, 500.0, cda=0.5)))
    top = TopMotion(y=(Sinusoid(amplitude=1.0, frequency=1.2),))
    num = Numerics(duration=20.0, output_step=0.1, rtol=1e-9, atol=1e-11)
    res = {a: simulate(Scene(sections=secs, angles=a, top_motion=top, numerics=num)) for a in ("shared", "per_section")}
    for r in res.values():
        assert r.success and not r.events
    assert np.ptp(res["shared"]["y_b_2"]) > 0.5
    for lbl in ("y_b_1", "y_b_2", "tension_mid_1", "tension_mid_2", "u_2"):
        np.testing.assert_allclose(res["per_section"][lbl], res["shared"][lbl], rtol=1e-6,
                                   atol=1e-6 * np.abs(res["shared"][lbl]).max())
    assert np.abs(res["per_section"]["phi_2"]).max() < 1e-9
