"""Segmented cable in the time domain: axial wave speed, energy conservation, profiles and summary."""

import numpy as np
import pytest

from cablesys.model import build_model
from cablesys.scene import Body, Cable, Environment, Numerics, Sinusoid, TopMotion
from cablesys.scene.scene import single_section_scene
from cablesys.statics import steady_state
from cablesys.time_domain import simulate
from cablesys.time_domain.integrators import IntegratorSettings
from cablesys.time_domain.run import Simulator

G = 9.80665


def _scene(n, *, length, m, ae, w, body_m, body_w, top=None, numerics=None):
    cable = Cable(length=length, tension_ref=0.0, ae=ae, diameter=0.01, mass_per_length=m, weight_per_length=w,
                  added_mass_factor=0.0, cd_normal=0.0, ct_tangential=0.0, segments=n)
    body = Body(weight=body_w, mass_x=body_m, mass_y=body_m)
    return single_section_scene(cable=cable, body=body, environment=Environment(density=1e-3, gravity=G),
                                top_motion=top or TopMotion(), numerics=numerics or Numerics())


def _run(scene, model, x0, method="cvodes"):
    """A run in CasADi's virtual machine (no C compilation of the larger segmented models in tests)."""
    num = scene.numerics
    sim = Simulator(model, scene.output_times, IntegratorSettings(method=method, rtol=num.rtol, atol=num.atol,
                                                                  compiled=False))
    return simulate(scene, model=model, x0=x0, simulator=sim)


def test_axial_wave_front_arrives_at_l_over_c():
    """The top starts moving up at v = a omega from a cable at rest: the tension front (impedance jump
    sqrt(EA m) v) reaches the body element at (L - h/2) / sqrt(EA/m)."""
    n, length, m, ae = 100, 100.0, 1.0, 1e6
    a, om = -0.01, 0.5                                   # up (y is down): y_s = a sin(omega t)
    scene = _scene(n, length=length, m=m, ae=ae, w=m * G, body_m=1e4, body_w=1e4 * G,
                   top=TopMotion(y=(Sinusoid(amplitude=a, frequency=om),), ramp_s=0.0),   # a velocity step
                   numerics=Numerics(duration=0.2, output_step=1e-4, rtol=1e-8, atol=1e-11))
    model = build_model(scene)
    st = steady_state(model, model.parameters(scene))
    r = _run(scene, model, st.x, method="cvodes-adams")    # at rest: the top's velocity is a step; the wave is resolved
    assert r.success
    T = r.profiles["element_tension"]
    jump = np.sqrt(ae * m) * abs(a) * om
    c = np.sqrt(ae / m)
    for k, s in ((0, 0.5), (n // 2, n // 2 + 0.5), (n - 1, n - 0.5)):
        rise = T[:, k] - T[0, k]
        t_half = r.time[np.argmax(rise > 0.5 * jump)]
        assert t_half == pytest.approx(s * length / n / c, abs=3 * length / n / c), k
    # behind the front (before the reflection returns) the top element carries the impedance jump
    behind = (r.time > 0.02) & (r.time < 0.09)
    assert np.mean(T[behind, 0] - T[0, 0]) == pytest.approx(jump, rel=0.03)


@pytest.mark.slow
def test_energy_conserved_without_drag_and_damping():
    """No drag, no damping, top at rest: K + V (gravity and strain energy) stays constant to 1e-6 of
    the oscillation energy over 100 periods of the swing mode (N = 20)."""
    n, length = 20, 1.0
    scene = _scene(n, length=length, m=0.1, ae=200.0, w=0.1 * G, body_m=1.0, body_w=G,
                   numerics=Numerics(duration=100 * 2 * np.pi * np.sqrt(length / G), output_step=0.05,
                                     rtol=1e-11, atol=1e-13))
    model = build_model(scene)
    p = model.parameters(scene)
    st = steady_state(model, p)
    v = np.zeros(model.nq)
    v[0::2] = 0.05 * np.arange(1, n + 1) / n                  # a sideways swing, linear along the cable
    x0 = np.concatenate([st.q, v])
    r = _run(scene, model, x0, method="cvodes-adams")   # high order, no numerical damping of its own
    assert r.success
    E = np.array([sum(float(v) for v in model.energy(x, np.zeros(7), p)) for x in r.states.T])
    K0 = float(model.energy(x0, np.zeros(7), p)[0])
    assert np.max(np.abs(E - E[0])) < 1e-6 * K0
