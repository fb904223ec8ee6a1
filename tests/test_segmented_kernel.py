"""The segmented cable's element-kernel right-hand side (cablesys.model.segmented_kernel) is the
same function as its element-by-element ``ode``: equal to rounding on random states (positions off
the straight line, random velocities, random times, in a current), one and two sections, and a
compiled RK4 loop over it steps like the loop over the SX ``ode``; its Jacobian by the chain rule over the
elements (``kernel_jacobian``) is AD of the element-by-element ``ode`` to rounding."""

import dataclasses
import math
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

import cablesys
from cablesys.model.segmented import KERNEL_MIN_ELEMENTS, build_segmented_model
from cablesys.scene import Section, dale_scene, load_scene

HEAVE = Path(cablesys.__file__).parent / "data" / "heave_300m.toml"


def _random_states(model, scene, rng, count=4):
    """Nodes scattered about the straight vertical line (a tenth of an element's length, so some
    elements are slack and some stretched), velocities of order 1 m/s, times in the first minute."""
    n = model.nq // 2
    lengths = [s.cable.length for s in scene.sections]
    segs = [s.cable.segments for s in scene.sections]
    y = np.concatenate([np.cumsum([L / k] * k) + sum(lengths[:i]) for i, (L, k) in enumerate(zip(lengths, segs))])
    h = min(L / k for L, k in zip(lengths, segs))
    for _ in range(count):
        q = np.column_stack([np.zeros(n), y]).ravel() + rng.normal(0.0, 0.1 * h, 2 * n)
        yield np.concatenate([q, rng.normal(0.0, 1.0, 2 * n)]), rng.uniform(0.0, 60.0)


def _scenes():
    """Dale (Wang 1971 Table 1) in a current; the 300 m / 2 t slack-and-snap heave scene."""
    return {"dale": dale_scene().with_environment(current_speeds=(0.2,)), "slack": load_scene(HEAVE)}


@pytest.mark.parametrize("name", ["dale", "slack"])
@pytest.mark.parametrize("n", [1, 4, 20, 80])
def test_kernel_ode_equals_the_element_by_element_ode(name, n):
    scene = _scenes()[name].replace_section(0, cable={"segments": n})
    model = build_segmented_model(scene)
    p = model.parameters(scene)
    rng = np.random.default_rng(n)
    for x, t in _random_states(model, scene, rng):
        a = np.array(model.ode(x, t, p)).ravel()
        b = np.array(model.kernel_ode(x, t, p)).ravel()
        assert np.all(np.isfinite(a))
        # accelerations of order 1e2-1e5 m/s^2 here: the sums differ only in their order
        assert np.max(np.abs(b - a)) <= 1e-12 * np.max(np.abs(a)), (name, n)
    assert (model.loop_ode is model.kernel_ode) == (n >= KERNEL_MIN_ELEMENTS)


def _ad_jacobian(model):
    """d ode / d x of the element-by-element SX ode by CasADi's AD (the independent route)."""
    x, t, p = ca.SX.sym("x", model.ode.size1_in(0)), ca.SX.sym("t"), ca.SX.sym("p", model.ode.size1_in(2))
    return ca.Function("ode_jac", [x, t, p], [ca.jacobian(model.ode(x, t, p), x)])


def _same_jacobian(model, scene, states):
    """The kernel's chain-rule Jacobian against AD of the SX ode at ``states``: the same matrix to rounding, and
    no structural nonzero outside the three-node band (the pattern the linear solver gets)."""
    ad = _ad_jacobian(model)
    p = model.parameters(scene)
    for x, t in states:
        a, b = np.array(ad(x, t, p)), model.kernel_jacobian(x, t, p)
        assert np.max(np.abs(np.array(b) - a)) <= 1e-11 * np.max(np.abs(a))
        n, dim = model.nq // model.dim, model.dim
        rows, cols = b.sparsity().get_triplet()
        node = lambda i: (i % (dim * n)) // dim    # noqa: E731 - the free node of a state index
        assert all(abs(node(r) - node(c)) <= 1 for r, c in zip(rows, cols))


@pytest.mark.parametrize("name", ["dale", "slack"])
@pytest.mark.parametrize("n", [1, 4, 20])
def test_kernel_jacobian_equals_ad_of_the_element_by_element_ode(name, n):
    scene = _scenes()[name].replace_section(0, cable={"segments": n})
    model = build_segmented_model(scene)
    _same_jacobian(model, scene, _random_states(model, scene, np.random.default_rng(n), count=2))


def test_kernel_ode_two_sections_with_a_joint_body():
    """The joint node gets the last element of the upper section, the joint body and the first element
    of the lower section (each section its own kernel)."""
    scene = dale_scene().with_environment(current_speeds=(0.2,))
    s = scene.sections[0]
    upper = dataclasses.replace(s.cable, length=s.cable.length / 2, segments=3)
    lower = dataclasses.replace(s.cable, length=s.cable.length / 2, segments=4, diameter=1.5 * s.cable.diameter)
    joint = dataclasses.replace(s.body, weight=0.01, mass_x=0.002, mass_y=0.003)
    two = scene.replace(sections=(Section(cable=upper, body=joint), Section(cable=lower, body=s.body)))
    model = build_segmented_model(two)
    p = model.parameters(two)
    for x, t in _random_states(model, two, np.random.default_rng(7)):
        a, b = (np.array(f(x, t, p)).ravel() for f in (model.ode, model.kernel_ode))
        assert np.max(np.abs(b - a)) <= 1e-12 * np.max(np.abs(a))
    _same_jacobian(model, two, _random_states(model, two, np.random.default_rng(8), count=2))


def test_rk4_loop_over_the_kernel_steps_like_the_loop_over_the_sx_ode(monkeypatch):
    """One output interval of the compiled RK4 loop, which steps the kernel (``loop_ode``), against the
    loop over the SX ode in CasADi's VM (which the VM keeps: the kernel's map calls cost more there)."""
    from cablesys.time_domain.initial import initial_state
    from cablesys.time_domain.integrators import rk4_interval

    scene = load_scene(HEAVE).replace_section(0, cable={"segments": KERNEL_MIN_ELEMENTS})
    model = build_segmented_model(scene)
    p = model.parameters(scene)
    x0 = np.asarray(initial_state(scene, model, p), dtype=float)
    sx = rk4_interval(model, 8, compiled=False)
    monkeypatch.setenv("CABLESYS_COMPILE", "1")
    kern = rk4_interval(model, 8, compiled=True)
    if not kern.compiled:
        pytest.skip(f"no compiled code here: {kern.note}")
    pp = np.concatenate([p, [20.0, 0.05]])           # 20 s into the run, one 0.05 s interval
    a, b = (np.array(c.functions["cablesys_rk4_interval"](x0, 0.0, 1.0, pp)).ravel() for c in (sx, kern))
    assert np.max(np.abs(b - a)) <= 1e-12 * np.max(np.abs(a))
    assert not math.isclose(np.max(np.abs(a - x0)), 0.0)      # it moved
