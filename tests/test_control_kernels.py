"""The compiled per-interval kernels of the heave-compensation NLP (cablesys.control.kernels.interval_kernels):
their restricted derivatives against CasADi's own AD, and the compiled NLP's optimum against the virtual machine's."""

import numpy as np
import casadi as ca
import pytest
from control_checks import assert_compiled_optimum_equals_vm

from cablesys.derivatives import state_derivatives
from cablesys.control import WinchLimits, heave_problem
from cablesys.control.kernels import interval_kernels
from cablesys.examples import example_path
from cablesys.scene import load_scene


def _function():
    """A small nonlinear f(x, u, p) -> (y, z) with a parameter input p."""
    x, u, p = ca.SX.sym("x", 3), ca.SX.sym("u"), ca.SX.sym("p", 2)
    y = ca.vertcat(ca.sin(x[0] * x[1]) + p[0] * u ** 2, ca.exp(x[2] / p[1]) * u)
    return ca.Function("f", [x, u, p], [y, x[0] * x[2] ** 2 + p[1] * u], ["x", "u", "p"], ["y", "z"])


def test_restricted_derivatives_equal_casadi_ad():
    """fwd1/adj1/fwd1_adj1 restricted to (x, u) equal CasADi's forward(1), reverse(1) and
    reverse(1).forward(1) when the parameter's seeds are zero (the NLP's case), and the adjoint of p
    is structurally zero (the restriction is visible, not a wrong number)."""
    f = _function()
    f0, fwd, adj, fadj = state_derivatives(f, ("x", "u"))
    assert (fwd.name(), adj.name(), fadj.name()) == ("fwd1_f", "adj1_f", "fwd1_adj1_f")
    rng = np.random.default_rng(1)
    x, u, p = rng.normal(size=3), rng.normal(), np.array([0.7, 1.3])
    y, z = f(x, u, p)
    sx, su, sp = rng.normal(size=3), rng.normal(), np.zeros(2)
    ref = f.forward(1)(x, u, p, y, z, sx, su, sp)
    got = fwd(x, u, p, y, z, sx, su, rng.normal(size=2))         # p's seeds are ignored
    for a, b in zip(got, ref):
        np.testing.assert_allclose(np.array(a), np.array(b), rtol=1e-13, atol=1e-13)
    ay, az = rng.normal(size=2), rng.normal()
    ref = f.reverse(1)(x, u, p, y, z, ay, az)
    got = adj(x, u, p, y, z, ay, az)
    for a, b in zip(got[:2], ref[:2]):
        np.testing.assert_allclose(np.array(a), np.array(b), rtol=1e-13, atol=1e-13)
    assert adj.sparsity_out(2).nnz() == 0
    # forward over reverse: the Hessian-vector product of ay.y + az.z in direction (sx, su) and the
    # adjoint's own seeds' direction (day, daz)
    R = f.reverse(1)
    rv = R(x, u, p, y, z, ay, az)
    day, daz = rng.normal(size=2), rng.normal()
    seeds = [sx, su, sp, np.zeros(2), 0.0, day, daz]
    ref = R.forward(1)(x, u, p, y, z, ay, az, *rv, *seeds)
    got = fadj(x, u, p, y, z, ay, az, *got, *seeds)
    for a, b in zip(got[:2], ref[:2]):
        np.testing.assert_allclose(np.array(a), np.array(b), rtol=1e-12, atol=1e-13)


def test_compiled_kernels_find_the_same_optimum(quick_compile):
    """The 30 s ROV-lift optimum (Wang's 2-DOF winch; 1 m/s, 1 m/s^2 winch, JONSWAP sea) through the compiled kernels and
    their restricted derivatives equals the virtual machine's (inlined SX, CasADi's full AD) to 1e-8 in
    the objective, in the same number of IPOPT iterations; the library is keyed by structure: a second
    problem with other numbers (another tension weight, another speed limit) loads the same kernels."""
    scene = load_scene(example_path("rov-lift")).with_numerics(drag_segments=1, duration=30.0)
    pr = heave_problem(scene, WinchLimits(speed=1.0, acceleration=1.0), dt=0.5, model="wang")
    kernels = interval_kernels(pr.interval)
    assert kernels is not None and kernels.compiled, kernels and kernels.note
    assert_compiled_optimum_equals_vm(pr, 30.0, atol=1e-6)
    other = heave_problem(scene, WinchLimits(speed=0.8, acceleration=1.0), dt=0.5, tension_weight=0.1, model="wang")
    assert interval_kernels(other.interval).library == kernels.library
