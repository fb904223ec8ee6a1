"""Periodic steady state under the top motion: frequency sweep by continuation, smooth start ignored."""

import numpy as np

from cablesys.linear.periodic import periodic_steady_state, periodic_sweep, scene_input_amplitude
from cablesys.scene import TopMotion


def test_sweep_by_continuation_equals_independent_solves(dale):
    scene, model, p = dale
    w0, Z = scene_input_amplitude(scene)
    omegas = w0 * np.array([0.6, 0.8, 1.0, 1.3])
    sweep = periodic_sweep(model, p, omegas, Z, n_harmonics=10)
    assert all(s.success for s in sweep)
    # continuation needs fewer Newton iterations than the cold starts from the linear guess
    assert sum(s.stats["newton_iterations"] for s in sweep[1:]) < 0.8 * sum(
        periodic_steady_state(model, _at(scene, model, w), w, input_amplitude=Z, n_harmonics=10)
        .stats["newton_iterations"] for w in omegas[1:])
    for w, s in zip(omegas, sweep):
        ref = periodic_steady_state(model, _at(scene, model, w), w, input_amplitude=Z, n_harmonics=10)
        assert ref.success and np.max(np.abs(s.q - ref.q)) < 1e-9 * (1 + np.max(np.abs(ref.q)))
    # at the scene's own frequency the sweep solves the scene's problem
    own = periodic_steady_state(model, p, w0, input_amplitude=Z, n_harmonics=10)
    assert np.max(np.abs(sweep[2].q - own.q)) < 1e-9


def test_periodic_state_ignores_the_smooth_start(dale):
    scene, model, p = dale
    w, Z = scene_input_amplitude(scene)
    tm = scene.top_motion
    ramped = scene.replace(top_motion=TopMotion(x=tm.x, y=tm.y, ramp_s=50.0))
    a = periodic_steady_state(model, p, w, input_amplitude=Z, n_harmonics=10)
    b = periodic_steady_state(model, model.parameters(ramped), w, input_amplitude=Z, n_harmonics=10)
    assert a.success and b.success and np.max(np.abs(a.q - b.q)) < 1e-12


def _at(scene, model, w):
    """The scene's parameters with both sinusoids at frequency w (same amplitudes and phases)."""
    p = model.parameters(scene).copy()
    for ax in ("x", "y"):
        p[model.layout.index(f"top_motion.{ax}[0].frequency")] = w
    return p
