"""studies/three_d_checks.py in quick mode: the keys it computes, the ones it does not, and its figure."""

import json


def test_three_d_checks_study(run_study):
    out = run_study("three_d_checks", "--quick")
    r = json.loads((out / "three_d_checks.json").read_text())
    assert r["planar_equivalence_max_abs"] < 1e-10 and r["planar_equivalence_max_rel"] < 1e-10
    assert r["rotation_invariance_max_abs"] < 1e-10 and r["rotation_invariance_scalars_max_rel"] < 1e-9
    assert r["conical_pendulum_rel_err"] < 1e-8
    assert r["energy_drift_rel"] < 1e-6
    assert r["out_of_plane_frequency_rel_err"] < 1e-9 and r["out_of_plane_rao_rel_err"] < 1e-9
    # what this first step does not build is null and named, never a number
    # the node model's cases are in the keys above; the chain's out-of-plane modes are its in-plane ones (the
    # eigensolver's rounding on the stiff chain), converging to the Bessel-J0 frequencies at second order
    assert r["chain_out_of_plane_mode_rel_err"] < 1e-8
    chain = r["details"]["node_model"]["chain_modes"]
    assert chain["observed_order"][-1][0] > 1.8 and r["chain_out_of_plane_vs_bessel_rel_err"] < 0.06
    node = r["details"]["node_model"]
    assert node["planar_equivalence"]["run_max_abs"] < 1e-10 and node["rotation_invariance"]["run_position_max_abs_m"] < 1e-10
    assert node["energy"]["drift_rel"] < 1e-7 and node["energy"]["z_b_amplitude_m"] > 1.0
    assert r["not_built"] == []
    # a free rigid body tumbling about its intermediate axis (with added mass) conserves impulse and energy
    assert r["rigid_body_momentum_drift_rel"] < 1e-8 and r["details"]["rigid_body"]["cases"]
    assert all(c["flipped"] for c in r["details"]["rigid_body"]["cases"].values())
    # a span's sway modes on the node model: Irvine's string frequencies (sag 2.6 % of the span), second order in N
    span = r["details"]["span_out_of_plane"]
    assert r["span_out_of_plane_vs_irvine_rel_err"] < 1e-3 and span["sag_to_span"] > 0.02
    assert all(abs(p - 2.0) < 0.05 for p in span["observed_order"])
    # towing in a circle: a run started at rest under the tow point reaches the steady turn (35 m off at the start)
    turn = r["details"]["turning_tow"]
    assert turn["start_distance_m"] > 30.0 and r["turning_tow_steady_vs_time_domain_rel_err"] < 1e-4
    assert (out / "three_d_turning_tow.png").stat().st_size > 20000
    # the towed cable: linearized node model vs towed/'s exact H and c* (2 %), the sea trials' four means
    assert r["towed_linear_vs_theory_max_rel_err"] < 0.02
    sea = r["towed_sea_trials"]
    assert set(sea) == {"mean_abs_dH_nonlinear", "mean_abs_dH_linear_theory", "mean_abs_dcstar_nonlinear",
                        "mean_abs_dcstar_linear_theory"} and all(v > 0 for v in sea.values())
    assert (out / "three_d_towed_nonlinear.png").stat().st_size > 20000
    assert all(r[k] is None for k in r["not_built"])
    assert (out / "three_d_conical_pendulum.png").stat().st_size > 20000
    # the pitching rigid body is a case of the planar equivalence: its equations (random states) to rounding, its
    # run (theta against the quaternion, each on its own steps at rtol 1e-12) to the integration's error
    r_pl = r["details"]["rigid_body_planar_equivalence"]
    assert r_pl["equations_max_abs"] <= r["planar_equivalence_max_abs"] and r_pl["run_pitch_range_rad"] > 0.3
    assert r["planar_equivalence_rigid_run_max_rel"] < 1e-8
    # manoeuvres: a straight track is the ship-frame tow seen from the ground (no added mass: rounding on the same
    # RK4 steps), the added mass's Munk couples are the frames' difference, a turn settles on the steady turn, a
    # zig-zag turned about the vertical gives the turned answer (in rotation_invariance_*)
    tr = r["details"]["tracks"]
    assert r["straight_track_vs_system_speed_max_rel"] < 1e-9 and tr["galilean"]["body_swing_m"] > 10.0
    assert r["straight_track_munk_couple_rel_err"] < 1e-12 and tr["galilean_with_added_mass"]["max_rel"] > 1e-5
    assert r["turn_settles_on_steady_turn_rel_err"] < 1e-4 and tr["turn"]["start_distance_m"] > 10.0
    assert tr["zigzag_rotation"]["position_max_abs_m"] <= r["rotation_invariance_max_abs"] < 1e-10
    assert (out / "three_d_tracks.png").stat().st_size > 20000
