"""The ladder's integrator for the quasi-static rungs (cablesys.ladder.stiffness, auto.integrator_settings):
the explicit pairs' stability polynomials and regions against closed forms, the stiffness guard's decision
on scenes where it must accept and must refuse, the fallback, and (compiled) the chosen pair's accuracy on the
Dale rung against its own tight run, a small fraction of the stated model error; the compiled describing
function against the VM's."""

import math
from fractions import Fraction

import numpy as np
import pytest
from test_dopri5 import _tableau, needs_cc

from cablesys.ladder import auto, metrics
from cablesys.ladder import simulate as simulate_chosen
from cablesys.ladder import stiffness as G
from cablesys.ladder.rungs import RungCache, rung_scene
from cablesys.scene import TopMotion, dale_scene
from cablesys.time_domain import simulate
from cablesys.time_domain.initial import initial_state

RTOL = 1e-4          # auto's rtol at the default 1 % body tolerance (auto.AUTO_RTOL)


def test_stability_polynomials_are_the_pairs():
    """rk23: 3 stages of order 3, R = the exponential's Taylor polynomial of degree 3 (unique); dopri5: order
    5 (1/k! up to z^5) and its z^6 coefficient b^T A^5 1 from the tableau in explicit_rk.c, 1/600."""
    assert G.STABILITY_POLYNOMIALS["rk23"] == tuple(1 / math.factorial(k) for k in range(4))
    c = G.STABILITY_POLYNOMIALS["dopri5"]
    assert c[:6] == pytest.approx([1 / math.factorial(k) for k in range(6)], rel=1e-15)
    A, b, *_ = _tableau()
    v = [Fraction(1)] * 7
    for _ in range(5):
        v = [sum(A[i][j] * v[j] for j in range(7)) for i in range(7)]
    assert sum(bi * vi for bi, vi in zip(b, v)) == Fraction(1, 600) == Fraction(c[6]).limit_denominator(10**6)


def test_stability_radii_meet_the_closed_forms():
    """Real axis: the negative root of R(z) = +-1 nearest 0 (rk23: -2.5127, dopri5: -3.3066); rk23 on the
    imaginary axis: |R(iy)|^2 = 1 - y^4/12 + y^6/36, so sqrt(3)."""
    for method in ("rk23", "dopri5"):
        roots = []
        for sign in (1.0, -1.0):
            coef = np.array(G.STABILITY_POLYNOMIALS[method][::-1])
            coef[-1] += sign                                 # R(z) = -sign
            roots += [r.real for r in np.roots(coef) if abs(r.imag) < 1e-7 and r.real < -1e-9]
        assert G.stability_radius(method, math.pi) == pytest.approx(-max(roots), rel=1e-6)
    assert G.stability_radius("rk23", math.pi / 2) == pytest.approx(math.sqrt(3), rel=1e-5)   # GROWTH: 1.3e-6
    assert G.stability_radius("rk23", 0.3) == 0.0          # a ray into the right half-plane leaves at once
    # the stability step of an eigenvalue set is the tightest one's
    lam = np.array([-10.0, 5j, -5j, -1 + 1j])
    assert G.stability_step("rk23", lam) == pytest.approx(min(2.5127 / 10, math.sqrt(3) / 5), rel=1e-4)


def _ramped_dale(duration=60.0):
    base = dale_scene(duration=duration)
    tm = base.top_motion
    return base.replace(top_motion=TopMotion(x=tm.x, y=tm.y, ramp_s=3 * 2 * math.pi / tm.x[0].frequency))


@pytest.fixture(scope="module")
def rungs():
    """{N: (rung scene, model, p, x0)} of the ramped Dale scene's quasi-static rung."""
    scene, cache, out = _ramped_dale(), RungCache(), {}
    for n in (4, 8):
        sc, model = rung_scene(scene, "quasi-static", n), cache.model(scene, "quasi-static", n)
        p = model.parameters(sc)
        out[n] = (sc, model, p, initial_state(sc, model, p))
    return out


def test_guard_accepts_dale_n4_and_refuses_n8(rungs):
    """N = 4: rk23's stability step (drag-damped elements in motion, -52 1/s) is above its accuracy step at
    rtol 1e-4 and 1.14 rad/s: accepted. N = 8: its string modes (undamped at rest) are fast enough that the
    pair's imaginary-axis limit sqrt(3) / omega sets the step (measured compiled: 1950 steps for 60 s at any
    rtol from 1e-3 to 1e-4, i.e. 0.031 s): refused. The accuracy step is rtol^(1/3) / omega."""
    fit4 = G.explicit_fit(*rungs[4][1:], RTOL, "rk23")
    fit8 = G.explicit_fit(*rungs[8][1:], RTOL, "rk23")
    assert fit4.accepted and not fit8.accepted, (fit4.reason, fit8.reason)
    omega = dale_scene().top_motion.x[0].frequency
    assert fit4.omega == pytest.approx(omega, rel=1e-9)
    assert fit4.accuracy_step == pytest.approx(RTOL ** (1 / 3) / omega, rel=1e-9)
    assert fit8.stability_step == pytest.approx(60.0 / 1950, rel=0.03)


def test_guard_sees_the_drag_in_motion(rungs):
    """Without current the drag slope vanishes at rest: the static Jacobian's eigenvalues lie on the imaginary
    axis; moving, quadratic drag 2 c |v| gives real eigenvalues that grow with the speed (about in proportion),
    so at three times the rate scales the drag, not the string, sets the step and the guard refuses N = 4."""
    _, model, p, x0 = rungs[4]
    J0 = G.probe_function(model)(x0, p, 1.0)[0].full()
    rest = np.linalg.eigvals(J0)
    assert np.all(np.abs(rest.real) <= 1e-8 * np.max(np.abs(rest)))

    def fastest_real(motion):
        _, J, _ = (a.full() for a in G.probe_function(model)(x0, p, motion))
        lam = np.linalg.eigvals(J)
        return -np.min(lam.real)
    assert 2.5 < fastest_real(3.0) / fastest_real(1.0) < 3.5
    assert not G.explicit_fit(model, p, x0, RTOL, "rk23", motion=3.0).accepted


def test_settings_fall_back_to_cvodes_without_compilation_or_a_model(rungs, monkeypatch):
    """The explicit pair runs compiled only: without compilation (the suite's default), without the model, or
    past COMPILE_MAX_ELEMENTS the quasi-static rungs run QUASI_STATIC_FALLBACK; other rungs AUTO_METHOD; a
    caller's method wins."""
    sc, model, _, x0 = rungs[4]
    tol = (0.01, 0.02)
    monkeypatch.setenv("CABLESYS_COMPILE", "0")
    assert auto.integrator_settings(sc, tol, 4, rung="quasi-static", model=model, x0=x0).method == auto.QUASI_STATIC_FALLBACK
    monkeypatch.setenv("CABLESYS_COMPILE", "1")
    assert auto.integrator_settings(sc, tol, 4, rung="quasi-static").method == auto.QUASI_STATIC_FALLBACK
    big = auto.EXPLICIT_MAX_ELEMENTS + 1      # past it the string modes set the step and the probe grows as N^3
    assert auto.integrator_settings(sc, tol, big, rung="quasi-static", model=model, x0=x0).method == auto.QUASI_STATIC_FALLBACK
    assert auto.integrator_settings(sc, tol, 4, rung="wang").method == auto.AUTO_METHOD
    assert auto.integrator_settings(sc, tol, 4, rung="quasi-static", model=model, x0=x0, method="rk").method == "rk"


def test_probe_runs_in_the_vm_past_its_compile_size(rungs, monkeypatch):
    """The guard's dense probe Jacobian grows as N^3 (Dale N = 4 / 8: 1.2 / 4.7 MB serialized; heavy1000 N = 20:
    404 MB, whose 120 MB of C ran the compiler out of memory): past PROBE_COMPILE_MAX it is not compiled."""
    monkeypatch.setenv("CABLESYS_COMPILE", "1")
    _, model, p, x0 = rungs[8]
    F = G.probe_function(model)
    assert len(F.serialize()) > G.PROBE_COMPILE_MAX and not F.is_a("external")
    J0, _, _ = F(x0, p, 1.0)
    assert np.all(np.isfinite(np.array(J0)))


def test_rtol_stays_well_below_the_stated_error(rungs):
    """Every rung's rtol is at most the stated body error / STATED_ROOM, rounded down to a decade (the run must
    not add an error comparable to the one it states; one simulator per decade); a stated error that leaves
    room, or none, keeps rtol = min(AUTO_RTOL, body tolerance / 100)."""
    sc, model, _, x0 = rungs[4]
    tol = (0.01, 0.02)
    s = lambda stated, rung="quasi-static": auto.integrator_settings(sc, tol, 4, rung=rung, model=model, x0=x0,
                                                                      stated=stated)
    assert s(4e-3).rtol == auto.AUTO_RTOL                       # Dale's stated 0.4 %: room enough
    assert s(1.26e-4).rtol == pytest.approx(1e-6)        # random short-3's, at the floor: 6.3e-6 -> 1e-6
    assert s(3e-4).rtol == s(1e-3).rtol == pytest.approx(1e-5)
    assert s(1.26e-4).atol == pytest.approx(s(1.26e-4).rtol / 10)
    assert s(1.34e-3, rung="wang").rtol == pytest.approx(1e-5)   # random short-2's (BDF2 at a swing resonance)
    assert s(4e-3, rung="wang").rtol == s(None, rung="segmented").rtol == auto.AUTO_RTOL


# --------------------------------------------------------------------------------------------------
# compiled
# --------------------------------------------------------------------------------------------------
@needs_cc
@pytest.mark.slow
def test_auto_runs_the_dale_rung_explicitly_well_within_its_stated_error(compiling):
    """Compiled, auto on the ramped Dale scene (20 s) runs the quasi-static rung with rk23 (the guard accepts
    it), and that run's body amplitudes and tension extremes differ from the same rung's CVODES run at rtol
    1e-10 by under 5 % of the stated model error (measured 60 s: 0.2 % body, 0.4 % tension)."""
    scene = _ramped_dale(20.0)
    cache = RungCache()
    res = simulate_chosen(scene, cache=cache)
    m = res.stats["model"]
    assert m["name"] == "quasi-static" and m["segments"] > 1
    assert res.stats["method"] == auto.QUASI_STATIC_METHOD
    sc = rung_scene(scene, "quasi-static", m["segments"])
    tight = simulate(sc, model=cache.model(scene, "quasi-static", m["segments"]), method="cvodes", rtol=1e-10, atol=1e-11)
    period = metrics.forcing_period(scene)
    err = metrics.errors(metrics.statistics(res, period), metrics.statistics(tight, period))
    stated = m["estimated_error"]
    assert err["body"] < 0.05 * stated["body"] and err["tension"] < 0.05 * stated["tension"], (err, stated)


@needs_cc
def test_compiled_describing_function_equals_the_vm(compiling, monkeypatch):
    """The harmonic balance with its residual and Jacobians compiled gives the VM's amplitudes (Dale)."""
    from cablesys.linear import harmonic_response
    from cablesys.linear.periodic import scene_input_amplitude
    from cablesys.model import build_model
    scene = dale_scene()
    omega, Z = scene_input_amplitude(scene)
    out = {}
    for flag in ("1", "0"):
        monkeypatch.setenv("CABLESYS_COMPILE", flag)
        model = build_model(scene)            # a new model: its derived functions are built under the flag
        h = harmonic_response(model, model.parameters(scene), [omega], Z, n_theta=16, ladder=1)
        assert h.success
        out[flag] = h.output_amplitude
    np.testing.assert_allclose(np.abs(out["1"]), np.abs(out["0"]), rtol=1e-8, atol=1e-12)
