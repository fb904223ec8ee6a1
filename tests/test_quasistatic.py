"""The quasi-static stretch rung: closed forms it must meet and agreement with Wang's 2-DOF model."""

import math

import numpy as np
import pytest

from cablesys.linear import linearize, modes, steady_state
from cablesys.model import build_model
from cablesys.model.quasistatic import axial_frequencies, build_quasistatic
from cablesys.scene import (
    Body,
    Cable,
    Environment,
    Numerics,
    Sinusoid,
    TopMotion,
    dale_scene,
)
from cablesys.scene.scene import single_section_scene
from cablesys.time_domain import simulate


def _pendulum(ae=1e9, cd=0.0, cda=0.0, heave=None, duration=20.0):
    """20 m cable of 5 kg/m (40 N/m in water) with a 200 kg body (1500 N in water)."""
    cable = Cable(length=20.0, tension_ref=1900.0, ae=ae, diameter=0.03, mass_per_length=5.0,
                  weight_per_length=40.0, cd_normal=cd, ct_tangential=0.0)
    body = Body(weight=1500.0, mass_x=260.0, mass_y=240.0, drag_area_normal=cda, drag_area_tangential=cda)
    top = TopMotion(y=(Sinusoid(amplitude=0.5, frequency=heave),)) if heave else TopMotion()
    return single_section_scene(cable=cable, body=body, environment=Environment(density=1025.0),
                                top_motion=top, numerics=Numerics(duration=duration, output_step=0.05))



def heave_tension_amplitudes(models, p, omega, inp="y_s"):
    """{model.kind: |tension / y_s|} of each model's linearization at the heave frequency ``omega``
    (the tension of the body's element per metre of top heave, N/m: the lowest ``element_tension[k]`` of a
    segmented cable, Wang's spring force ``tension_mid`` of his one-element cable); per metre of ``inp``."""
    amp = {}
    for m in models:
        lin = linearize(m, p)
        _, Y = lin.transfer([omega])
        els = [o for o in lin.output_labels if o.startswith("element_tension[")]
        out = max(els, key=lambda o: int(o[len("element_tension["):-1])) if els else "tension_mid"
        amp[m.kind] = abs(Y[0, lin.output_labels.index(out), lin.input_labels.index(inp)])
    return amp

def test_rigid_compound_pendulum_frequency():
    """A stiff cable swings as a compound pendulum: omega^2 = (W_b + W_c/2) l / (M_bvx l^2 + M_cv l^2 / 3),
    M_cv the cable mass plus its added mass (Wang 1971 eq. 22-25)."""
    scene = _pendulum()
    qs = build_quasistatic(scene)
    p = qs.parameters(scene)
    st = steady_state(qs, p)
    c, b, rho = scene.cable, scene.body, scene.environment.density
    length = c.length_zero + st.outputs["u"]
    m_cv = c.total_mass + rho * math.pi * c.diameter**2 / 4 * length
    w2 = (b.weight + c.total_weight / 2) * length / (b.mass_x * length**2 + m_cv * length**2 / 3)
    assert modes(linearize(qs, p)).omega_undamped[0] == pytest.approx(math.sqrt(w2), rel=1e-6)


@pytest.mark.parametrize("ratio", [0.2, 0.5, 0.8])
def test_quasistatic_spring_amplification(ratio):
    """Heave of a spring with mass: Wang's stretch responds 1 / (1 - (omega / omega_ax)^2) times the
    quasi-static one, omega_ax^2 = k / (M_bvy + M_c / 3) (the u-equation of eq. 47-48 at phi = 0)."""
    scene = _pendulum(ae=2e5)
    w_ax = axial_frequencies(scene)[0]
    full = build_model(scene)
    qs = build_quasistatic(scene, full=full)
    p = full.parameters(scene)
    omega = ratio * w_ax
    amp = heave_tension_amplitudes((full, qs), p, omega)
    c, b = scene.cable, scene.body
    assert amp["quasi-static"] == pytest.approx((b.mass_y + c.total_mass / 2) * omega**2, rel=1e-9)
    assert amp["wang"] / amp["quasi-static"] == pytest.approx(1.0 / (1.0 - ratio**2), rel=1e-9)


def test_time_domain_heave_amplification_matches_linear():
    """The same in the time domain at omega / omega_ax = 0.3, small amplitude: tension amplitudes of the
    two rungs differ by 1/(1 - 0.09) (stretch damped out by Voigt damping; transients excluded)."""
    scene = _pendulum(ae=2e5)
    w_ax = axial_frequencies(scene)[0]
    omega = 0.3 * w_ax
    scene = scene.replace(top_motion=TopMotion(y=(Sinusoid(amplitude=0.01, frequency=omega),)))
    scene = scene.replace_section(0, cable={"internal_damping": 0.05 * 2 * math.sqrt(2e5 / 20 * 250) * 20})
    full = build_model(scene)
    period = 2 * math.pi / omega
    amps = {}
    for m in (full, build_quasistatic(scene, full=full)):
        r = simulate(scene, model=m, times=np.linspace(0, 60 * period, 60 * 40 + 1))
        amps[m.kind] = r.steady_amplitude("tension_mid", period, 3)
    # the Voigt damper (eq. 46) is kept in the 2-DOF model only: |1 - r^2 + 2 i zeta r|
    zeta = 0.05 * math.sqrt(250 / (scene.body.mass_y + scene.cable.total_mass / 3))
    expect = abs((1 + 2j * zeta * 0.3) / (1 - 0.09 + 2j * zeta * 0.3))
    assert amps["wang"] / amps["quasi-static"] == pytest.approx(expect, rel=2e-3)


def test_agrees_with_wang_on_dale_in_far_fewer_steps():
    """Dale scene at 1.5 omega_n (stretch mode at 254 rad/s, 130x the forcing): body amplitude within
    1e-4 and top-tension extremes within 1e-3 of the 2-DOF model over the second half (the start
    rings the 2-DOF model's stretch mode, which the reduction removes), with 5x fewer CVODES steps."""
    scene = dale_scene(omega_ratio=1.5, duration=40.0)
    full = build_model(scene)
    period = 2 * math.pi / (1.5 * 1.14)
    res = {m.kind: simulate(scene, model=m) for m in (full, build_quasistatic(scene, full=full))}
    a, b = res["wang"], res["quasi-static"]
    for lbl in ("x_b", "y_b"):
        assert b.steady_amplitude(lbl, period) == pytest.approx(a.steady_amplitude(lbl, period), rel=1e-4)
    late = a.time > 20.0
    for lbl in ("tension_top", "tension_bottom"):
        assert b[lbl][late].max() == pytest.approx(a[lbl][late].max(), rel=1e-3)
        assert b[lbl][late].min() == pytest.approx(a[lbl][late].min(), rel=1e-3)
    assert a.stats["nsteps"] > 5 * b.stats["nsteps"]


@pytest.mark.parametrize("ae_lb", [5.0, 1000.0])
def test_stretch_rate_is_the_derivative_of_the_stretch_along_the_motion(ae_lb):
    """The quasi-static u' (implicit-function theorem at the converged stretch) is du/dt along the
    motion: a central difference of u over (s + eps s', s' + eps s'', z + eps z', z' + eps z'') at a
    swinging, drag-loaded state of the Dale scene (soft and stiff cable) agrees to O(eps^2)."""
    scene = dale_scene(ae_lb=ae_lb)
    qs = build_quasistatic(scene)
    p = qs.parameters(scene)
    labels = list(qs.output_labels)
    iu, iud = labels.index("u"), labels.index("u_rate")
    x = np.array([0.2, 0.5])                      # phi, phi' (rad, rad/s)
    t = 1.3
    e = np.array(qs.top(t, p)).ravel()            # (t, z, z', z'')
    sdd = float(np.array(qs.ode(x, t, p)).ravel()[1])
    direction_x = np.array([x[1], sdd])
    direction_e = np.concatenate([[0.0], e[3:5], e[5:7], [0.0, 0.0]])

    def u_at(eps):
        return float(np.array(qs.outputs(x + eps * direction_x, e + eps * direction_e, p)).ravel()[iu])
    eps = 1e-5
    fd = (u_at(eps) - u_at(-eps)) / (2 * eps)
    ud = float(np.array(qs.outputs(x, e, p)).ravel()[iud])
    assert abs(ud) > 0
    assert ud == pytest.approx(fd, rel=1e-5, abs=1e-12)
