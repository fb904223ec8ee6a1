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
