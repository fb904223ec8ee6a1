"""The towed cable as the 3-D node model (cablesys.towed.nodes): linearized against towed/'s exact eq. 3."""

import math

import numpy as np
import pytest

from cablesys.errors import ParameterError
from cablesys.model import build_model
from cablesys.towed.equation import REPORT_SEA_TRIAL, TowedCable, added_fluid_mass
from cablesys.towed.nodes import frequency_response, node_coefficients, straight_tow, tow_scene
from cablesys.towed.transfer import c_star, transfer_function

CABLE = TowedCable(length=1190.0, speed=5.0, **REPORT_SEA_TRIAL)
OMEGA = np.array([1.0, 3.0, 8.0])          # omega L / U: quasi-steady, |H| ~ 0.5, |H| ~ 0.09


def test_linearized_node_model_reproduces_eq3_and_converges():
    ref = node_coefficients(CABLE)
    H_ex, c_ex = np.abs(transfer_function(ref, 1.0, OMEGA).H), c_star(ref, 1.0, OMEGA).c_star
    errs = []
    for n in (20, 40):
        rs = frequency_response(CABLE, OMEGA, segments=n)
        eH = np.abs(np.array([abs(r.H1) for r in rs]) / H_ex - 1)
        ec = np.abs(np.array([r.c_star1 for r in rs]) / c_ex - 1)
        errs.append(np.maximum(eH, ec))
    assert np.all(errs[1] < 0.02)
    # second-order elements: halving h cuts the worst error (omega L/U = 8) by at least 3
    assert errs[1][-1] < errs[0][-1] / 3


def test_straight_tow_tension_is_friction_plus_drogue():
    """Tension at the tow point: T(0) = 2 M U^2 (c_t L / d + c_t') (Kennedy & Strahan eq. 1-3), the
    lengthened cable's friction carrying the drogue's drag; the pinger node's tension 2 c_t' M U^2."""
    sc = tow_scene(CABLE, segments=20)
    m = build_model(sc)
    p = m.parameters(sc)
    q = straight_tow(m, p, sc)
    y = np.array(m.outputs(np.r_[q, 0 * q], np.zeros(m.top.size1_out(0)), p)).ravel()
    lab = m.output_labels
    M = added_fluid_mass(1025.0, CABLE.diameter)
    T0 = 2 * M * CABLE.speed**2 * (CABLE.c_t * CABLE.length / CABLE.diameter + CABLE.c_t_drogue)
    Td = 2 * M * CABLE.speed**2 * CABLE.c_t_drogue
    # element tensions at mid-elements: the first element is h/2 below the tow point
    h = CABLE.length / 20
    f_t = 0.5 * 1025.0 * CABLE.ct_tangential * CABLE.diameter * CABLE.speed**2
    assert y[lab.index("element_tension[0]")] == pytest.approx(T0 - f_t * h / 2, rel=1e-3)
    assert y[lab.index("element_tension[19]")] == pytest.approx(Td + f_t * h / 2, rel=2e-3)
    acc = np.array(m.accel(q, 0 * q, np.zeros(m.top.size1_out(0)), p)).ravel()
    assert np.max(np.abs(acc)) < 1e-6                          # at rest on the straight line (m/s^2)


def test_bad_input_is_named():
    with pytest.raises(ParameterError, match="segments"):
        tow_scene(CABLE, segments=1)
    with pytest.raises(ParameterError, match="omega"):
        tow_scene(CABLE, segments=10, amplitude=1.0)
    with pytest.raises(ParameterError, match="omega_nd"):
        frequency_response(CABLE, [0.0], segments=10)


def test_nonlinear_time_domain_matches_describing_function():
    """Sea-trial run 6 (L = 1193.9 m, U = 5.18 m/s, f = 2.2 mHz, a = 30.6 m), quadratic drag C_n = 0.16:
    the time-domain run's |H| and c* at the far pinger against the harmonic equivalent linearization of the
    same drag (8/(3 pi) |V| per element, Caughey 1963), two independent routes; the drag is then far below
    the theory's linear c_n* (the cable's small sway angles), so the response is nearly undamped."""
    import sys
    from pathlib import Path
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies"))
    from towed_nonlinear import nonlinear_run
    from cablesys.towed.nodes import describing_function_response
    from cablesys.towed.runs import Run

    run = Run(label="6", length=1193.9, speed=5.18, frequency=2.2e-3, columns={"a_over_lambda": "0.0130"})
    td = nonlinear_run(run, 16, {})
    cab = TowedCable(length=run.length, speed=run.speed, **REPORT_SEA_TRIAL)
    df, info = describing_function_response(cab, cab.omega(run.frequency), td["amplitude_m"], segments=16)
    assert td["periodic_change_H"] < 3e-3
    assert td["H"] == pytest.approx(abs(df.H1), rel=0.01)
    assert td["c_star"] == pytest.approx(df.c_star1, rel=0.01)
    assert info["c_n_star_range"][1] < 0.1 * CABLE.c_n
