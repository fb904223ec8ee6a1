"""One registry of integration methods; a user method is an IntegratorMethod (as solve_ivp takes an OdeSolver)."""

import numpy as np
import pytest

from cablesys.errors import ParameterError
from cablesys.integration import METHODS, IntegratorMethod, resolve
from cablesys.scene import INTEGRATORS, Numerics, dale_scene
from cablesys.time_domain import IntegratorSettings, simulate


def test_the_scene_checks_names_against_the_one_registry():
    assert INTEGRATORS == tuple(METHODS)
    with pytest.raises(ParameterError, match="numerics.integrator"):
        Numerics(integrator="euler")
    with pytest.raises(ParameterError, match="IntegratorMethod"):
        IntegratorSettings(method="euler")
    assert resolve("idas").implicit and not resolve("rk").adaptive


def test_a_user_method_runs_and_agrees_with_the_built_in_one():
    """CVODES BDF with a different Newton convergence coefficient: the same trajectory within tolerance."""
    scene = dale_scene(duration=3.0, output_step=0.05)
    mine = IntegratorMethod(name="cvodes-loose-newton", plugin="cvodes",
                            options={"linear_multistep_method": "bdf", "nonlin_conv_coeff": 0.5})
    a = simulate(scene, method=mine, rtol=1e-9, atol=1e-12)
    b = simulate(scene, method="cvodes", rtol=1e-9, atol=1e-12)
    assert a.success and b.success
    assert a.stats["method"] == "cvodes-loose-newton"
    assert np.max(np.abs(a["x_b"] - b["x_b"])) < 1e-6 * np.max(np.abs(b["x_b"]))


def test_bdf_capped_at_order_two_steps_over_the_undamped_stretch_mode():
    """BDF orders 3-5 are not A-stable: on the Dale scene (undamped stretch mode, 254 rad/s) the
    variable-order BDF is held to steps of about 0.6/omega_stretch at any tolerance, while BDF of
    order <= 2 (A-stable) steps with the forcing; both stay within the loose tolerance's error."""
    import math

    from cablesys.scene import TopMotion
    base = dale_scene(duration=20.0, output_step=0.05)
    tm = base.top_motion
    scene = base.replace(top_motion=TopMotion(x=tm.x, y=tm.y, ramp_s=3 * 2 * math.pi / tm.x[0].frequency))
    ref = simulate(scene, method="cvodes", rtol=1e-10, atol=1e-13)
    # atol of each state's natural scale (scaled states): 1e-4 of the stretch is 7e-9 m
    runs = {m: simulate(scene, method=m, rtol=1e-4, atol=1e-4) for m in ("cvodes", "cvodes-bdf2")}
    assert ref.success and all(r.success for r in runs.values())
    assert runs["cvodes-bdf2"].stats["nsteps"] * 5 < runs["cvodes"].stats["nsteps"]
    amp = np.max(np.abs(ref["x_b"]))
    for r in runs.values():
        assert np.max(np.abs(r["x_b"] - ref["x_b"])) < 1e-2 * amp
