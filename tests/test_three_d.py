"""Wang's straight cable in three dimensions (Wang 1971 p. 32): the plane as the special case,
rotation about the vertical, the conical pendulum, energy, and the linearization out of the plane."""

import dataclasses
import math
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies"))
import three_d_checks as checks  # noqa: E402

from cablesys.model import build_model  # noqa: E402
from cablesys.model.params import structure_of  # noqa: E402
from cablesys.scene import Numerics, Sinusoid, TopMotion  # noqa: E402
from cablesys.time_domain.run import simulate  # noqa: E402


def test_a_planar_scene_builds_the_planar_equations():
    for sc in checks.planar_scenes():
        assert not sc.three_d and sc.three_d_fields() == ()
        key = structure_of(sc)
        assert len(key) == 10 and "3d" not in repr(key)          # the structure key of the planar build
        m = build_model(sc)
        assert not any(lb.startswith("phi_z") for lb in m.q_labels)
        assert not any(lb.startswith("z_b") for lb in m.output_labels) and m.top.size1_out(0) == 7
        forced = build_model(sc.with_numerics(dimensions=3))
        assert forced.top.size1_out(0) == 10 and any(lb.startswith("z_b") for lb in forced.output_labels)


def test_planar_scenes_run_by_the_3d_equations_equal_the_planar_run():
    r = checks.planar_equivalence(quick=True)
    assert r["run_max_abs"] < 1e-10          # fixed steps: same steps, the difference is the equations'
    assert r["max_rel"] < 1e-10              # right-hand sides and outputs at random states, per output size
    for case in r["cases"].values():
        assert case["run_out_of_plane_max_abs"] == 0.0


def test_a_scene_turned_about_the_vertical_gives_the_turned_answer():
    r = checks.rotation_invariance(quick=True)
    assert r["body_excursion_m"] > 0.5                   # the body does move (current, waves, top motion)
    assert r["equations_max_abs"] < 1e-10 and r["equations_scalars_max_rel"] < 1e-10
    assert r["run_position_max_abs_m"] < 1e-10 and r["run_tension_max_rel"] < 1e-9


def test_sway_alone_is_surge_turned_by_ninety_degrees():
    base = checks.pendulum_scene(ae=2e7, weight=2e4, mass=3000.0, cable_mass=True, drag=0.8,
                                 numerics=Numerics(duration=20.0, output_step=0.1, model="as-built", dimensions=3))
    term = (Sinusoid(amplitude=1.5, frequency=0.8),)
    surge = dataclasses.replace(base, top_motion=TopMotion(x=term, ramp_s=5.0))
    sway = dataclasses.replace(base, top_motion=TopMotion(z=term, ramp_s=5.0))
    assert sway.three_d and sway.three_d_fields() == ("top_motion.z", "body.mass_z")
    rs = simulate(surge, model=build_model(surge), rtol=1e-11, atol=1e-11)
    rw = simulate(sway, model=build_model(sway), rtol=1e-11, atol=1e-11)
    assert np.max(np.abs(rw["z_b"])) > 0.5
    # turning +x onto +z (90 degrees from x towards z): z_b(sway) = x_b(surge), x_b(sway) = 0
    assert np.max(np.abs(rw["z_b"] - rs["x_b"])) < 1e-8
    assert np.max(np.abs(rw["x_b"])) < 1e-8 and np.max(np.abs(rs["z_b"])) < 1e-12
    assert np.max(np.abs(rw["tension_top"] - rs["tension_top"])) < 1e-6 * np.max(rs["tension_top"])


def test_conical_pendulum_closed_form():
    r = checks.conical_pendulum(quick=True)
    case = r["cases"]["30"]
    assert case["rel_err_omega2"] < 1e-8                  # omega^2 = g / (L cos alpha)
    assert case["radius_rel_wander"] < 1e-8               # it stays on the cone
    assert abs(case["cone_angle_deg_mean"] - 30.0) < 1e-6
    assert case["tension_rel_err"] < 1e-8                 # T = W_b / cos(alpha) at both ends (3-D end forces)


def test_off_the_cone_rate_leaves_the_cone():
    # a 5 % faster start is no steady conical motion: the check sees it
    r = checks.conical_pendulum(quick=True, omega_factor=1.05)
    assert r["cases"]["30"]["radius_rel_wander"] > 1e-2


def test_energy_is_conserved_over_100_periods_without_drag_or_damping():
    r = checks.energy_drift(quick=True, n_periods=100)
    assert r["z_b_amplitude_m"] > 1.0                      # a real out-of-plane swing
    assert r["drift_rel"] < 1e-6


def test_out_of_plane_frequency_from_the_linearization_equals_the_in_plane_one():
    r = checks.out_of_plane_frequency()
    assert r["input_labels"][:3] == ["x_s", "y_s", "z_s"]
    assert r["rel_err"] < 1e-9
    assert r["rao_sway_vs_planar_surge_rel_err"] < 1e-9            # z_b / z_s is x_b / x_s of the planar model
    assert r["rao_tension_per_sway_over_per_heave"] < 1e-9         # sway does not change the tension at first order
    # a heavy body on a light cable: near the simple pendulum
    assert r["omega_out_of_plane_3d"] == pytest.approx(math.sqrt(2e4 / 3000.0 / 20.0), rel=0.05)   # sqrt(W_b / (M_b L))


@pytest.mark.parametrize("angles", ["per_section", "shared"])
def test_a_3d_chain_conserves_energy(angles):
    r = checks.energy_drift(quick=True, n_periods=5, scene=checks.chain_scene(angles))
    assert r["z_b_amplitude_m"] > 1.0 and r["drift_rel"] < 1e-6


def test_a_heavier_body_in_sway_shows_in_the_out_of_plane_frequency_and_rao():
    r = checks.out_of_plane_frequency(mass_z_factor=1.2)        # M_bvz 20 % above M_bvx: no longer symmetric
    assert r["omega_out_of_plane_3d"] < r["omega_in_plane_planar"] * 0.95
    assert r["rao_sway_vs_planar_surge_rel_err"] > 1e-2


def test_steady_state_in_a_current_at_a_heading_is_the_planar_one_turned():
    from cablesys.scene import Environment
    from cablesys.statics.steady import steady_state
    heading = 50.0
    planar = checks.pendulum_scene(ae=2e7, weight=2e4, mass=3000.0, cable_mass=True, drag=1.2,
                                   environment=Environment(current_depths=(0.0, 30.0), current_speeds=(1.5, 0.8)))
    planar = dataclasses.replace(planar, sections=(dataclasses.replace(
        planar.sections[0], body=dataclasses.replace(planar.body, mass_z=None)),))
    turned = planar.with_environment(current_headings_deg=(heading,))
    m2, m3 = build_model(planar), build_model(turned)
    s2, s3 = steady_state(m2, m2.parameters(planar)).outputs, steady_state(m3, m3.parameters(turned)).outputs
    assert abs(s2["x_b"]) > 0.5                                   # the current streams the body off
    x, _, z = checks.rotate(math.radians(heading), [s2["x_b"], 0.0, 0.0])
    assert s3["x_b"] == pytest.approx(x, abs=1e-9) and s3["z_b"] == pytest.approx(z, abs=1e-9)
    assert s3["y_b"] == pytest.approx(s2["y_b"], abs=1e-9)
    for name in ("tension_mid", "tension_top", "tension_bottom"):
        assert s3[name] == pytest.approx(s2[name], rel=1e-10)
