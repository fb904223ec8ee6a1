"""The sampled top-motion series: SX not-a-knot spline equal to SciPy's, samples stay parameters."""

import casadi as ca
import numpy as np
import pytest
from scipy.interpolate import make_interp_spline

from cablesys.model import build_model
from cablesys.model.top_motion import spline_expression
from cablesys.scene import TimeSeries, TopMotion, dale_scene


@pytest.mark.parametrize("n", [4, 5, 9, 60])
def test_spline_equals_scipy_not_a_knot_with_derivatives(n):
    rng = np.random.default_rng(n)
    tk = np.sort(rng.uniform(0.0, 10.0, n))
    y = rng.normal(size=n)
    t, ys = ca.SX.sym("t"), ca.SX.sym("y", n)
    e = spline_expression(tk, [ys[i] for i in range(n)], t)
    f = ca.Function("f", [t, ys], [e, ca.jacobian(e, t), ca.jacobian(ca.jacobian(e, t), t)])
    ref = make_interp_spline(tk, y, k=3)
    tt = np.concatenate([np.linspace(tk[0], tk[-1], 301), tk])     # including the knots and both ends
    F = [np.array(v).ravel() for v in f.map(tt.size)(tt[None, :], np.tile(y[:, None], (1, tt.size)))]
    scale = np.max(np.abs(y))
    for d in range(3):
        assert np.max(np.abs(F[d] - ref(tt, d))) < 1e-10 * scale * (1 + np.max(np.abs(ref(tt, d))))
    # held at the end values outside the sampled span, with zero rates
    out = [np.array(v).ravel() for v in f(tk[0] - 1.0, y)] + [np.array(v).ravel() for v in f(tk[-1] + 1.0, y)]
    assert out[0][0] == pytest.approx(y[0]) and out[3][0] == pytest.approx(y[-1])
    assert out[1][0] == out[2][0] == out[4][0] == out[5][0] == 0.0


def test_series_model_is_sx_and_samples_are_parameters():
    w, a = 1.1, 0.05
    t = np.linspace(0.0, 20.0, 81)
    series = TimeSeries(times=tuple(t), x=tuple(a * np.cos(w * t)), y=tuple(0 * t))
    scene = dale_scene().replace(top_motion=TopMotion(series=series))
    model = build_model(scene)
    assert model.symbolic is ca.SX and model.ode.is_a("SXFunction")
    p = model.parameters(scene)
    e1 = np.array(model.top(7.3, p)).ravel()
    p[model.layout.index("top_motion.series.x[30]")] += 1e-3      # a new sample value, same function
    e2 = np.array(model.top(7.3, p)).ravel()
    # the spline is linear in the samples: a change at one sample moves x_s, nothing moves y_s
    assert e1[1] == pytest.approx(a * np.cos(w * 7.3), abs=1e-5) and e2[1] != e1[1] and e2[2] == e1[2] == 0.0
    # compilable: C code generation succeeds (the MX bspline + csparse path could not be generated)
    cg = ca.CodeGenerator("ode_series.c")
    cg.add(model.ode)
    assert "ode(" in cg.dump()
