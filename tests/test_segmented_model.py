"""The segmented cable (cablesys.model.segmented): N = 1 against Wang's 2-DOF model, scene input,
sparsity and the hanging equilibrium."""

import numpy as np
import pytest

from cablesys.errors import ParameterError
from cablesys.model import build_model
from cablesys.model.segmented import SegmentedModel, build_segmented_model
from cablesys.scene import dale_scene
from cablesys.statics import steady_state
from cablesys.time_domain import simulate

PERIOD = 2 * np.pi / 1.71


def test_segments_field_is_validated():
    scene = dale_scene()
    for bad in (0, 2001, 2.5, True):
        with pytest.raises(ParameterError, match="cable.segments"):
            scene.replace_section(0, cable={"segments": bad})
    assert isinstance(build_model(scene.replace_section(0, cable={"segments": 3})), SegmentedModel)
    assert not isinstance(build_model(scene), SegmentedModel)          # N = 1: Wang's model itself


def test_one_element_is_wangs_model():
    """One straight element with Wang's (massless-cable) terms and no tangential drag is the 2-DOF model
    in other coordinates: same body path to the integrator tolerance. (Wang's cable mass is distributed
    along the straight cable, eq. 16-25; the element lumps it at its ends, see the next test.)"""
    scene = dale_scene(omega_ratio=1.5, duration=12.0).replace_section(
        0, cable={"cable_mass_switch": -1.0, "ct_tangential": 0.0})
    wang = simulate(scene, rtol=1e-10, atol=1e-12)
    seg = simulate(scene, model=build_segmented_model(scene), rtol=1e-10, atol=1e-12)
    assert seg.success and wang.success
    for lbl in ("x_b", "y_b", "phi", "u"):
        assert np.max(np.abs(seg[lbl] - wang[lbl])) < 1e-8, lbl
    # tension = k u: the stretch agrees to the position tolerance, times k
    assert np.max(np.abs(seg["tension_mid"] - wang["tension_mid"])) < 1e-8 * scene.cable.spring_constant


def test_one_element_lumped_mass_difference_is_bounded():
    """With the cable mass (m_c / m_b = 0.07 on the Dale scene) the lumped element differs from Wang's
    consistent mass by less than that ratio in body amplitude."""
    scene = dale_scene(omega_ratio=1.5, duration=12.0)
    wang = simulate(scene)
    seg = simulate(scene, model=build_segmented_model(scene))
    a_w, a_s = wang.steady_amplitude("x_b", PERIOD), seg.steady_amplitude("x_b", PERIOD)
    ratio = scene.cable.total_mass / scene.body.mass_x
    assert abs(a_s / a_w - 1) < ratio


def test_hanging_equilibrium_tensions_and_sparsity():
    """At rest the elements carry the weight below their mid-points (exact for lumped weights), the top
    carries W_b + W_c and the body W_b; the ODE Jacobian is banded (O(N) nonzeros)."""
    n = 40
    scene = dale_scene().replace_section(0, cable={"segments": n})
    model = build_model(scene)
    st = steady_state(model, model.parameters(scene))
    c, b = scene.cable, scene.body
    w = c.weight_per_length * c.length / n
    expect = b.weight + w * (n - np.arange(n) - 0.5)
    got = np.array([st.outputs[f"element_tension[{k}]"] for k in range(n)])
    np.testing.assert_allclose(got, expect, rtol=1e-9)
    assert st.outputs["tension_top"] == pytest.approx(b.weight + c.total_weight, rel=1e-9)
    assert st.outputs["tension_bottom"] == pytest.approx(b.weight, rel=1e-9)
    nnz = model.ode.sparsity_jac(0, 0).nnz()
    assert nnz < 40 * model.nq                       # banded: a few entries per state, not (4N)^2


def test_two_sections_with_a_joint_body():
    """Two segmented sections joined by a small body, in a current: the equilibrium is found, the
    lower body hangs below and downstream of the joint, and each cable's top force exceeds its
    bottom force by about that cable's weight (the current's drag is small here)."""
    import dataclasses

    from cablesys.scene import Section
    scene = dale_scene()
    s = scene.sections[0]
    cable = dataclasses.replace(s.cable, length=s.cable.length / 2, segments=5)
    joint = dataclasses.replace(s.body, weight=0.01, mass_x=0.002, mass_y=0.002)
    two = scene.replace(sections=(Section(cable=cable, body=joint), Section(cable=cable, body=s.body)))
    two = two.with_environment(current_speeds=(0.2,))
    model = build_model(two)
    st = steady_state(model, model.parameters(two)).outputs
    assert st["y_b_2"] > st["y_b_1"] > 0 and st["x_b_2"] > st["x_b_1"] > 0
    w = cable.total_weight
    for i in (1, 2):
        assert st[f"tension_top_{i}"] - st[f"tension_bottom_{i}"] == pytest.approx(w, rel=0.1)
    with pytest.raises(ParameterError, match="angles"):
        build_model(two.replace(angles="shared"))


@pytest.mark.parametrize("current, tol", [(0.0, 1e-9), (0.1, 2e-4), (0.3, 6e-3)])
def test_two_dof_end_forces_against_segmented_cable(current, tol):
    """The 2-DOF model's top force (derived from its straight cable's weight, drag and inertia) and body
    force agree with the segmented cable at N = 40 at rest (exactly) and in a current (the straight
    cable cannot bow: the difference grows with the current, 0.4 % at 0.3 m/s on the Dale scene)."""
    scene = dale_scene().with_environment(current_speeds=(current,))
    two = build_model(scene)
    a = steady_state(two, two.parameters(scene)).outputs
    seg_scene = scene.replace_section(0, cable={"segments": 40})
    seg = build_model(seg_scene)
    b = steady_state(seg, seg.parameters(seg_scene)).outputs
    assert b["tension_top"] == pytest.approx(a["tension_top"], rel=tol)
    assert b["tension_bottom"] == pytest.approx(a["tension_bottom"], rel=max(tol, 1e-8))
