"""Slack and snap: located switch times and snap tension against a closed form (Wang 1971 eq. 54)."""

import math

import numpy as np
import pytest

from cablesys.scene import (
    Body,
    Cable,
    Environment,
    Initial,
    Numerics,
    Sinusoid,
    TopMotion,
    single_section_scene,
)
from cablesys.time_domain import simulate

M, W, K, L, U0 = 10.0, 50.0, 1000.0, 10.0, -0.2      # kg, N, N/m, m, m (starts slack)


def bouncing_scene(duration=3.0, method="cvodes", ci=0.0, heave=0.0, drag=0.0):
    cable = Cable(length=L, tension_ref=0.0, ae=K * L, diameter=0.01, mass_per_length=0.0,
                  weight_per_length=0.0, cd_normal=drag, ct_tangential=0.0, internal_damping=ci,
                  tension_floor=0.0, cable_mass_switch=-1.0)
    body = Body(weight=W, mass_x=M, mass_y=M, drag_area_normal=drag, drag_area_tangential=drag)
    top = TopMotion(y=(Sinusoid(amplitude=heave, frequency=5.0),) if heave else ())
    return single_section_scene(cable=cable, body=body, environment=Environment(density=1000.0), top_motion=top,
                                initial=Initial(phi=0.0, u=U0),
                                # atol relative to each state's scale (the 0.05 m static stretch: 5e-12 m;
                                # 1e-12 of it would be ~25 ulp of the 10 m length, which IDAS cannot meet)
                                numerics=Numerics(duration=duration, output_step=0.05, rtol=1e-10, atol=1e-10,
                                                  integrator=method, drag_segments=2))


def closed_form(n_events):
    """Free fall while slack (u'' = W/M), harmonic while taut (M u'' = W - k u): switch times, snap load."""
    g = W / M
    w = math.sqrt(K / M)
    t1 = math.sqrt(2 * abs(U0) / g)
    v1 = g * t1
    ue = W / K
    A, B = -ue, v1 / w
    R = math.hypot(A, B)
    theta = math.atan2(B, A)
    taut_span = (theta + math.acos(-ue / R)) / w      # from u = 0 rising to u = 0 falling
    slack_span = 2 * v1 / g                           # ballistic up and back down to u = 0
    times, t, kinds = [], t1, []
    for i in range(n_events):
        times.append(t)
        kinds.append("taut" if i % 2 == 0 else "slack")
        t += taut_span if i % 2 == 0 else slack_span
    peaks = [t1 + theta / w + j * (taut_span + slack_span) for j in range((n_events + 1) // 2)]
    return np.array(times), kinds, K * (ue + R), np.array(peaks)


@pytest.mark.parametrize("method", ["cvodes", "cvodes-adams", "idas"])
def test_switch_times_and_snap_tension_match_closed_form(method):
    r = simulate(bouncing_scene(method=method))
    assert r.success, r.message
    times, kinds, snap, peaks = closed_form(len(r.events))
    assert len(r.events) >= 5
    assert [e.kind for e in r.events] == kinds
    np.testing.assert_allclose([e.time for e in r.events], times, atol=2e-8)
    np.testing.assert_allclose([s.tension for s in r.snaps], snap, rtol=1e-6)
    np.testing.assert_allclose([s.time for s in r.snaps], peaks[: len(r.snaps)], atol=1e-6)
    # while slack the reported tension is TENS = 0
    during = (r.time > times[1] + 1e-3) & (r.time < times[2] - 1e-3)
    assert np.all(r["tension_mid"][during] == 0.0)


def test_time_slack_closed_form():
    r = simulate(bouncing_scene(duration=1.5))
    times, kinds, _, _ = closed_form(len(r.events))
    # slack from t=0 to t1, then between each slack and the next taut event
    expected = times[0] + sum(times[i + 1] - times[i] for i in range(1, len(times) - 1, 2))
    if kinds[-1] == "slack":
        expected += r.time[-1] - times[-1]
    assert r.time_slack() == pytest.approx(expected, abs=1e-7)


def test_damped_driven_slack_agrees_between_integrators():
    """Voigt damping, drag and top heave: CVODES and IDAS locate the same switches and snap loads."""
    runs = [simulate(bouncing_scene(duration=4.0, method=m, ci=200.0, heave=0.3, drag=0.5)) for m in ("cvodes", "idas")]
    for r in runs:
        assert r.success, r.message
    a, b = runs
    assert len(a.events) == len(b.events) >= 2
    np.testing.assert_allclose([e.time for e in a.events], [e.time for e in b.events], atol=1e-6)
    np.testing.assert_allclose([s.tension for s in a.snaps], [s.tension for s in b.snaps], rtol=1e-5)
    # with C_I > 0 the cable goes taut while u < 0: F_bc = k u + (C_I/l_r) u' crosses 0 first (eq. 54)
    for e in a.events:
        if e.kind == "taut":
            assert e.rate > 0


def test_integrator_failure_keeps_results_and_says_where():
    """RK4 far above its stability limit: success False, time and remedy in the message, data kept."""
    scene = bouncing_scene(duration=2.0, method="rk").replace_section(0, cable={"ae": 1e9, "tension_floor": -math.inf})
    scene = scene.replace(initial=Initial(phi=0.0, u=0.01), numerics=Numerics(
        duration=2.0, output_step=0.05, integrator="rk", steps_per_output=2, drag_segments=2))
    from cablesys.errors import NumericalWarning
    with pytest.warns(NumericalWarning, match=r"RK4 stability limit\): expect growth; use steps_per_output >= \d+"):
        r = simulate(scene)
    assert not r.success
    assert "failed between t =" in r.message and "steps_per_output" in r.message
    assert 0 < r.time.size < 41
    assert np.all(np.isfinite(r["u"]))


def test_step_budget_is_reported_not_multiplied():
    """One output interval needing more steps than max_num_steps: a named failure that keeps the results
    so far and names the budget; a budget large enough for the interval reaches the reference state."""
    from cablesys.model import build_model
    from cablesys.scene import dale_scene
    from cablesys.time_domain import IntegratorSettings, Simulator
    from cablesys.time_domain.run import initial_state
    scene = dale_scene()
    model = build_model(scene)
    p = model.parameters(scene)
    x0 = initial_state(scene, model, p)
    r = Simulator(model, [0.0, 0.5, 60.5], IntegratorSettings(max_num_steps=2000)).run(p, x0)
    assert not r.success and r.status == "failed"
    assert "step budget exhausted" in r.message and "max_num_steps = 2000" in r.message
    assert r.time.tolist() == [0.0, 0.5] and r.stats["max_num_steps"] == 2000
    r = Simulator(model, [0.0, 60.0, 60.5], IntegratorSettings(max_num_steps=100000)).run(p, x0)
    assert r.success, r.message
    ref = simulate(scene, times=np.linspace(0.0, 60.5, 1211))
    np.testing.assert_allclose(r.states[:2, -1], [ref["phi"][-1], ref["u"][-1]], rtol=1e-4, atol=1e-7)
    # rates: the stretch rate is the stiff mode's, a tolerance-level stretch error times omega_u ~ 200 rad/s
    # (the undamped mode's ringing left at the end differs by ~1e-6 m/s between the two runs' step sequences)
    np.testing.assert_allclose(r.states[2:, -1], [ref["phi_rate"][-1], ref["u_rate"][-1]], rtol=1e-4, atol=5e-6)


def test_unstable_rk_with_slack_fails_instead_of_chattering():
    """Above RK4's stability limit a slack-capable cable must not 'succeed' through endless switches."""
    from cablesys.errors import NumericalWarning
    from cablesys.scene import dale_scene
    scene = dale_scene(duration=5.0).with_numerics(integrator="rk", steps_per_output=2)
    with pytest.warns(NumericalWarning):
        r = simulate(scene)
    assert not r.success
    assert ("chattering" in r.message) or ("failed between" in r.message)
    assert "stability" in r.message or "steps_per_output" in r.message
    stable = simulate(scene.with_numerics(integrator="rk", steps_per_output=20))
    assert stable.success and not stable.events
