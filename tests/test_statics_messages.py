"""CasADi's KINSOL warnings stay off stderr in the statics (issue 29: warnings as one clean line each).

CasADi 3.8 prints a rootfinder's failed return flag (``KIN_LINESEARCH_NONCONV``) through its own
warning stream whatever ``print_level`` or ``disable_internal_warnings`` say; the statics try
several guesses and a stalled line search on one of them is expected, so they collect these
blocks (:func:`cablesys.messages.casadi_warnings_captured`) and name the flags only in the error
of a failed solve.
"""

import dataclasses
import sys

import numpy as np
import pytest

from cablesys.messages import casadi_warnings_captured, kinsol_flags
from cablesys.model import build_model
from cablesys.scene import load_scene
from cablesys.statics import steady_state
from cablesys.statics import catenary as C
from cablesys.statics.problem import static_parameters, static_residual

ROV = "cablesys/data/rov_lift.toml"


@pytest.fixture(scope="module")
def rov_segmented():
    """The ROV lift as the ladder runs it (segmented, N = 14): model and parameters."""
    from pathlib import Path
    sc = load_scene(Path(__file__).resolve().parents[1] / ROV)
    sc = dataclasses.replace(sc, sections=tuple(dataclasses.replace(s, cable=dataclasses.replace(s.cable, segments=14))
                                                for s in sc.sections))
    m = build_model(sc)
    return m, m.parameters(sc)


def test_rov_statics_print_no_raw_kinsol_line(rov_segmented, capfd):
    m, p = rov_segmented
    pp = static_parameters(m, p)
    polar, _ = C._rootfinders(m)
    # the same rootfinder called bare from the statics' first guess stalls and CasADi prints it: the capture sees it
    polar(C.to_polar(C.hanging_guess(m, pp)), pp)
    sys.stderr.flush()
    assert "KIN_LINESEARCH_NONCONV" in capfd.readouterr().err
    st = steady_state(m, p)
    sys.stderr.flush()
    err = capfd.readouterr().err
    assert "KIN" not in err and "CasADi" not in err
    # and the equilibrium is found: the residual forces vanish against the weight (statics' own scale)
    assert float(np.max(np.abs(np.array(static_residual(m)(st.q, pp))))) < 1e-9


def test_capture_keeps_other_lines_and_names_the_flags(capsys):
    block = ('CasADi - 2026-01-01 00:00:00 WARNING("Module "KINSol" returned flag "KIN_MAXITER_REACHED".\n'
             'The description of this flag is: \n"The maximum number of nonlinear iterations has been reached."\n'
             'Consult KINSOL documentation for more information.") [.../kinsol_interface.cpp:707]\n')
    with casadi_warnings_captured() as got:
        sys.stderr.write("a line of the user's\n")
        sys.stderr.write(block)
        sys.stderr.write(block.replace("KIN_MAXITER_REACHED", "KIN_LINESEARCH_NONCONV"))
    err = capsys.readouterr().err
    assert err == "a line of the user's\n"
    assert len(got) == 2 and kinsol_flags(got + got) == ["KIN_MAXITER_REACHED", "KIN_LINESEARCH_NONCONV"]


def test_a_failed_statics_names_the_flags_once_in_its_error(dale, capfd):
    """Every guess fails (a residual (q - 100)^2 + 1 with no root, stalling far from any equilibrium): the SolverError names KINSOL's flags; stderr stays clean."""
    import casadi as ca

    from cablesys.errors import SolverError
    _, m, p = dale
    q, pp = ca.SX.sym("q", m.nq), ca.SX.sym("p", len(m.layout))
    no_root = ca.rootfinder("no_root", "kinsol", ca.Function("r", [q, pp], [(q - 100) ** 2 + 1]),
                            {"strategy": "linesearch", "error_on_fail": False, "print_level": 0,
                             "disable_internal_warnings": True, "max_iter": 20})
    with pytest.raises(SolverError, match=r"steady state not found.*\(KINSOL: KIN_[A-Z_]+"):
        steady_state(m, p, solver=no_root)
    sys.stderr.flush()
    assert "KIN" not in capfd.readouterr().err
