"""studies/bench_control.py --quick: every key the benchmark promises, and the numbers that are checks."""

import json

KEYS = ("ocp_wall_s", "ocp_iterations", "ocp_status", "ocp_heave_reduction_db", "mpc_heave_reduction_db",
        "pi_heave_reduction_db", "mpc_step_ms", "mpc_realtime_factor", "design_gradient_cost_ratio",
        "lq_rel_err", "gradient_fd_rel_err", "resimulated_constraint_violation_rel",
        "mpc_no_preview_heave_reduction_db", "mpc_ipopt_heave_reduction_db", "mpc_speedup_vs_ipopt")


def test_bench_control_quick(run_study):
    out = run_study("bench_control", "--quick")
    doc = json.loads((out / "bench_control.json").read_text())
    for key in KEYS:
        assert key in doc, key
    assert doc["ocp_status"] == "Solve_Succeeded"
    assert doc["lq_rel_err"] < 1e-6
    assert doc["gradient_fd_rel_err"] < 1e-5
    assert doc["resimulated_constraint_violation_rel"] < 0.01
    # compensation reduces the heave (1 m/s winch against a 2.5 m sea's crane tip): optimum and MPC by > 20 dB
    assert doc["ocp_heave_reduction_db"] < -20 and doc["mpc_heave_reduction_db"] < -20
    assert doc["pi_heave_reduction_db"] < -3
    assert doc["mpc_step_ms"] > 0 and doc["mpc_realtime_factor"] > 0
    # the real-time iteration (one Gauss-Newton QP per step) against IPOPT to convergence on the same
    # closed loop: the same heave reduction to 1 dB; without preview still > 20 dB
    assert abs(doc["mpc_heave_db_vs_ipopt"]) < 1.0
    assert doc["mpc_no_preview_heave_reduction_db"] < -20
