"""The residual Jacobian of a linear model: the one inverse of from_jacobian (shared by design)."""

import numpy as np

from cablesys.linear import linearize
from cablesys.linear.linearization import (
    from_jacobian,
    functions,
    operating_xi,
    residual_jacobian,
    taut_parameters,
)
from cablesys.model import build_model
from cablesys.scene import dale_scene


def test_residual_jacobian_is_the_model_jacobian_and_inverts_from_jacobian():
    scene = dale_scene()
    model = build_model(scene)
    p = taut_parameters(model, model.parameters(scene))
    lin = linearize(model, p)
    J = residual_jacobian(lin)
    # the CasADi Jacobian dr/dxi at the operating point, taken directly
    J_direct = np.array(functions(model)["jac"](operating_xi(model, lin.q0), p))
    assert J.shape == J_direct.shape
    assert np.allclose(J, J_direct, rtol=1e-12, atol=1e-12 * np.abs(J_direct).max())
    # and it round-trips through from_jacobian
    Jy = np.hstack([lin.Cq, lin.Cv, np.zeros_like(lin.Cq), lin.D0[:, :2], lin.D1[:, :2], lin.D2[:, :2], lin.D0[:, 2:]])
    again = from_jacobian(model, J, Jy, lin.q0, lin.y0, kind="exact")
    for name in ("M", "C", "K", "F0", "F1", "F2"):
        assert np.array_equal(getattr(again, name), getattr(lin, name)), name
