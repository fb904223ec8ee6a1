"""The segmented cable against closed forms: elastic catenary, straight towed line, hanging-chain,
chain-with-end-mass and taut-string modes (with the observed order in N), the axial wave speed and
energy conservation."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq
from scipy.special import j0, j1, jn_zeros, y0, y1

from cablesys.linear import linearize, modes
from cablesys.model import build_model
from cablesys.scene import Body, Cable, Environment, Numerics, TopMotion
from cablesys.scene.scene import single_section_scene
from cablesys.statics import elastic_catenary, steady_state

G = 9.80665


def _scene(n, *, length=100.0, w=10.0, m=1.0, ae=1e6, cd=0.0, body_w=500.0, body_m=100.0, cda=0.0,
           current=0.0, speed=0.0, rho=1025.0, gamma=0.0, top=None, numerics=None):
    cable = Cable(length=length, tension_ref=0.0, ae=ae, diameter=0.02, mass_per_length=m, weight_per_length=w,
                  added_mass_factor=gamma, cd_normal=cd, ct_tangential=0.0, segments=n)
    body = Body(weight=body_w, mass_x=body_m, mass_y=body_m, drag_area_normal=cda, drag_area_tangential=cda)
    return single_section_scene(cable=cable, body=body, environment=Environment(
        density=rho, gravity=G, current_speeds=(current,), system_speed=speed),
        top_motion=top or TopMotion(), numerics=numerics or Numerics())


def _body_offset(n, **kw):
    scene = _scene(n, **kw)
    model = build_model(scene)
    st = steady_state(model, model.parameters(scene))
    return np.array([st.outputs["x_b"], st.outputs["y_b"], st.outputs["tension_top"]])


def test_elastic_catenary_closed_form():
    """A drag-free cable with a body pushed by a current (H = body drag) hangs in an elastic catenary
    (Irvine 1981): the body offset and top tension converge at second order in 1/N and their
    Richardson extrapolation meets the closed form to 1e-6."""
    rho, cda, u = 1025.0, 1.0, 0.8
    H = 0.5 * rho * cda * u**2
    x, z, T = elastic_catenary(100.0, weight_per_length=10.0, ea=1e6, horizontal=H, bottom_weight=500.0)
    exact = np.array([x, z, T])
    a, b = (_body_offset(n, cda=cda, current=u) for n in (40, 80))
    err_a, err_b = np.abs(a - exact) / np.abs(exact), np.abs(b - exact) / np.abs(exact)
    order = np.log2(err_a[:2] / err_b[:2])
    assert np.all(order > 1.9) and np.all(order < 2.1), order
    extrapolated = (4 * b - a) / 3
    np.testing.assert_allclose(extrapolated[:2], exact[:2], rtol=1e-6)
    # the top force (end element tension plus the lumped half element) is exact up to round-off:
    # horizontal H throughout, vertical W_b + w L
    assert err_b[2] < 1e-9 and err_a[2] < 1e-9


def test_towed_straight_line_balance():
    """A weightless, drag-free cable towing a body is straight: tan(phi) = D / W_b and the stretch is
    T / k (closed-form balance of a straight-drag line in the limit of a negligible cable)."""
    speed, cda, wb, ae, length = 1.5, 0.4, 800.0, 2e6, 50.0
    xb, yb, _ = _body_offset(10, length=length, w=0.0, ae=ae, body_w=wb, cda=cda, speed=speed)
    D = 0.5 * 1025.0 * cda * speed**2
    tension = math.hypot(D, wb)
    stretched = length * (1 + tension / ae)
    assert xb == pytest.approx(-stretched * D / tension, rel=1e-9)    # towed in +x: the body trails
    assert yb == pytest.approx(stretched * wb / tension, rel=1e-9)


def _transverse_frequencies(scene, k):
    model = build_model(scene)
    md = modes(linearize(model, model.parameters(scene)))
    w = [om for om, lbl in zip(md.omega_undamped, md.dominant) if lbl.startswith("x[")]
    return np.array(w[:k])


def _chain_end_mass_roots(L, ratio, k):
    """omega of a hanging chain (length L, mass m per length) with an end mass M = ratio m L:
    y = A J0(xi) + B Y0(xi), xi = 2 omega sqrt(z/g), z from the virtual free end (a = M/m below the
    mass); y(a + L) = 0 and -omega^2 y(a) = g y'(a) at the mass."""
    a = ratio * L

    def det(w):
        xt, xa = 2 * w * np.sqrt((a + L) / G), 2 * w * np.sqrt(a / G)
        s = w * np.sqrt(G / a)
        return j0(xt) * (w**2 * y0(xa) - s * y1(xa)) - y0(xt) * (w**2 * j0(xa) - s * j1(xa))
    grid = np.linspace(0.05, 12.0, 4000) * np.sqrt(G / L)
    vals = det(grid)
    roots = [brentq(det, grid[i], grid[i + 1]) for i in range(grid.size - 1) if vals[i] * vals[i + 1] < 0]
    return np.array(roots[:k])


@pytest.mark.parametrize("ratio", [1e-6, 0.5])
def test_hanging_chain_modes(ratio):
    """Hanging chain (Bessel J0 zeros: omega_k = j_0k / 2 sqrt(g/L)) and chain with an end mass (its
    J0/Y0 equation): the first three transverse frequencies converge at second order in 1/N."""
    L, m = 10.0, 1.0
    exact = _chain_end_mass_roots(L, ratio, 3)
    if ratio < 1e-3:
        np.testing.assert_allclose(exact, jn_zeros(0, 3) / 2 * np.sqrt(G / L), rtol=1e-3)
    errs = []
    for n in (20, 40):
        sc = _scene(n, length=L, w=m * G, m=m, ae=1e9, body_w=ratio * m * L * G, body_m=ratio * m * L, rho=1e-3)
        errs.append(np.abs(_transverse_frequencies(sc, 3) / exact - 1))
    order = np.log2(errs[0] / errs[1])
    assert errs[1].max() < 0.02
    assert np.all(order > 1.5), order


def test_taut_string_modes():
    """Weightless string under its body's weight, top fixed, body free: tan(kL) = m / (M k),
    omega = k sqrt(T/m); second order in 1/N."""
    L, m, M = 10.0, 1.0, 20.0
    T = M * G
    f = lambda k: np.tan(k * L) - m / (M * k)
    ks = [brentq(f, (j * np.pi + 1e-9) / L, ((j + 0.5) * np.pi - 1e-9) / L) for j in range(3)]
    exact = np.array(ks) * np.sqrt(T / m)
    errs = []
    for n in (20, 40):
        sc = _scene(n, length=L, w=0.0, m=m, ae=1e9, body_w=T, body_m=M, rho=1e-3)
        errs.append(np.abs(_transverse_frequencies(sc, 3) / exact - 1))
    order = np.log2(errs[0] / errs[1])
    assert errs[1].max() < 0.01
    assert np.all(order > 1.8) and np.all(order < 2.2), order
