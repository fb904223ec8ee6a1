"""The sampled top-motion series: SX not-a-knot spline equal to SciPy's, O(1) table lookup, compilable."""

import casadi as ca
import numpy as np
import pytest
from scipy.interpolate import make_interp_spline

from cablesys.errors import ParameterError
from cablesys.model import build_model
from cablesys.model.top_motion import series_expressions, spline_expression
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


def test_series_model_is_sx_and_samples_are_constants():
    w, a = 1.1, 0.05
    t = np.linspace(0.0, 20.0, 81)
    series = TimeSeries(times=tuple(t), x=tuple(a * np.cos(w * t)), y=tuple(0 * t))
    scene = dale_scene().replace(top_motion=TopMotion(series=series))
    model = build_model(scene)
    assert model.symbolic is ca.SX and model.ode.is_a("SXFunction")
    p = model.parameters(scene)
    e = np.array(model.top(7.3, p)).ravel()
    assert e[1] == pytest.approx(a * np.cos(w * 7.3), abs=1e-5) and e[2] == 0.0
    # the samples are constants of the model: another series on the same grid is another
    # structure (a model built for one series refuses the other's parameter vector)
    other = scene.replace(top_motion=TopMotion(series=TimeSeries(times=series.times, x=tuple(2 * a * np.cos(w * t)),
                                                                  y=series.y)))
    with pytest.raises(ParameterError):
        model.parameters(other)
    # the model's cost does not grow with the record: the same motion sampled 25x longer
    t_long = np.linspace(0.0, 500.0, 2001)
    long = scene.replace(top_motion=TopMotion(series=TimeSeries(times=tuple(t_long), x=tuple(a * np.cos(w * t_long)),
                                                                 y=tuple(0 * t_long))))
    assert build_model(long).ode.n_instructions() == model.ode.n_instructions()
    # compilable: C code generation succeeds (the MX bspline + csparse path could not be generated)
    cg = ca.CodeGenerator("ode_series.c")
    cg.add(model.ode)
    assert "ode(" in cg.dump()


@pytest.mark.parametrize("n", [4, 7, 60, 2000])
def test_table_lookup_equals_reference_cubic(n):
    """The O(1) lookup is the same cubic as the O(n) telescoping-sum form and SciPy's
    not-a-knot spline (values and three t-derivatives, the event locator's order), to 1e-12
    relative, at random times, every sample time, both ends, and held outside."""
    rng = np.random.default_rng(100 + n)
    tk = np.cumsum(rng.uniform(0.05, 0.5, n))                       # non-uniform grid
    ys = [rng.normal(size=n), 3.0 + rng.normal(size=n)]
    t = ca.SX.sym("t")
    e = ca.vertcat(*series_expressions(tk, ys, t))
    ders = [e]
    for _ in range(3):
        ders.append(ca.jacobian(ders[-1], t))
    f = ca.Function("f", [t], ders)
    tt = np.concatenate([rng.uniform(tk[0], tk[-1], 400), tk, [np.nextafter(tk[0], np.inf),
                                                               np.nextafter(tk[-1], -np.inf)]])
    F = [np.array(v) for v in f.map(tt.size)(tt[None, :])]
    for j, y in enumerate(ys):
        ref = make_interp_spline(tk, y, k=3)
        for d in range(4):
            r = ref(tt, d)
            assert np.max(np.abs(F[d][j] - r)) <= 1e-12 * np.max(np.abs(r)), (j, d)
    if n <= 60:                                                      # the previous O(n) form
        ysym = ca.SX.sym("y", n)
        old = spline_expression(tk, [ysym[i] for i in range(n)], t)
        g = ca.Function("g", [t, ysym], [old])
        v_old = np.array(g.map(tt.size)(tt[None, :], np.tile(ys[0][:, None], (1, tt.size)))).ravel()
        assert np.max(np.abs(F[0][0] - v_old)) <= 1e-12 * np.max(np.abs(ys[0]))
    out = [np.array(v).ravel() for v in f(tk[0] - 1.0)] + [np.array(v).ravel() for v in f(tk[-1] + 1.0)]
    assert list(out[0]) == [ys[0][0], ys[1][0]] and list(out[4]) == [ys[0][-1], ys[1][-1]]
    assert not np.any(np.concatenate(out[1:4] + out[5:8]))           # zero rates outside
