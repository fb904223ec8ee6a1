"""`cablesys towed RUNS.csv [--json]`, run-table reading errors, and the sea-trial study."""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from cablesys.cli import main
from cablesys.errors import ParameterError
from cablesys.towed.equation import REPORT_SEA_TRIAL, TowedCable
from cablesys.towed.runs import model_runs, read_runs
from cablesys.towed.transfer import transfer_function

ROOT = Path(__file__).resolve().parents[1]
TABLE = ROOT / "cablesys" / "data" / "kennedy_tableA2.csv"   # Table A-2 with its source header


def _shooting_H(length, speed, f_hz, **coefficients):
    """|H(xi = 1)| by shooting (towed/bvp.py) at omega = 2 pi f L / U (Kennedy & Strahan eq. 2)."""
    cable = TowedCable(length=length, speed=speed, **{**REPORT_SEA_TRIAL, **coefficients})
    omega = 2 * np.pi * f_hz * length / speed
    return float(abs(transfer_function(cable.coefficients(), 1.0, omega, method="bvp").H))


@pytest.fixture
def small_csv(tmp_path):
    p = tmp_path / "runs.csv"
    p.write_text("# two runs of Table A-2 and a made-up one\nrun,L_m,U_mps,f_mHz,note\n"
                 "5,1193.8,5.10,0.37,slow\n21,596.9,5.15,4.39,short\nX,1000,4,1e-6,tiny f\n")
    return p


def test_cli_text_output(small_csv, capsys):
    assert main(["towed", str(small_csv)]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    assert lines[0].split() == ["run", "L_m", "U_mps", "f_mHz", "H", "c_star"]
    rows = {ln.split()[0]: ln.split() for ln in lines[1:]}
    # run 5: omega = 2 pi f L / U (eq. 2) = 0.544, |H(1)| from the shooting solution of the
    # boundary-value problem (solve_ivp; the CLI uses the exact 0F1 series), printed to 4 decimals
    assert float(rows["5"][4]) == pytest.approx(_shooting_H(1193.8, 5.10, 0.37e-3), abs=6e-5)
    # vanishing frequency: |H| -> 1 and c* -> 1 + 1/p = 1 + pi c_t / c_n
    assert float(rows["X"][4]) == pytest.approx(1.0, abs=1e-4)
    assert float(rows["X"][5]) == pytest.approx(1 + np.pi * 0.0101 / 0.16, abs=2e-3)


def test_cli_json_and_overrides(small_csv, capsys):
    assert main(["towed", str(small_csv), "--json"]) == 0
    default = json.loads(capsys.readouterr().out)
    assert [r["run"] for r in default] == [5, 21, "X"]
    assert default[1]["note"] == "short" and default[1]["L_m"] == 596.9
    assert set(default[0]) >= {"L_m", "U_mps", "f_mHz", "H", "c_star"}
    # |H(1)| of every run against an independent route (shooting, not the 0F1 series)
    assert [r["H"] for r in default] == pytest.approx(
        [_shooting_H(1193.8, 5.10, 0.37e-3), _shooting_H(596.9, 5.15, 4.39e-3), _shooting_H(1000.0, 4.0, 1e-9)],
        rel=1e-7)
    assert main(["towed", str(small_csv), "--json", "--c-n", "1.0"]) == 0
    stiff = json.loads(capsys.readouterr().out)
    # larger c_n: stronger water pulley, c* closer to 1 (eq. 14)
    assert stiff[2]["c_star"] == pytest.approx(1 + np.pi * 0.0101 / 1.0, abs=2e-3)
    assert stiff[1]["c_star"] < default[1]["c_star"]


@pytest.mark.parametrize("body,needle", [
    ("L_m,U_mps\n1000,5\n", "missing column(s) f_mHz"),
    ("L_m,U_mps,f_mHz\n1000,5,1\n1000,-5,1\n", "row 2 (line 3), column U_mps"),
    ("L_m,U_mps,f_mHz\n0,5,1\n", "row 1 (line 2), column L_m"),
    ("L_m,U_mps,f_mHz\n1000,5,zero\n", "column f_mHz = 'zero': must be a number"),
    ("L_m,U_mps,f_mHz\n", "no data rows"),
])
def test_bad_csv_names_row_and_column(tmp_path, capsys, body, needle):
    p = tmp_path / "bad.csv"
    p.write_text(body)
    with pytest.raises(ParameterError) as err:
        read_runs(p)
    assert needle in str(err.value)
    assert main(["towed", str(p)]) == 2
    assert needle in capsys.readouterr().err


def test_bad_option_is_a_clear_error(small_csv, capsys):
    assert main(["towed", str(small_csv), "--c-t", "-0.01"]) == 2
    assert "--c-t = -0.01: must be a finite number in [0.0001, 1]" in capsys.readouterr().err


def test_report_coefficients_against_table_A2():
    """The report: theory agrees with the amplitude data to roughly 25 %."""
    runs = read_runs(TABLE)
    H_data = np.array([float(r.columns["H"]) for r in runs])
    res = model_runs(runs)
    H, om = res.H_abs, res.omega
    assert len(runs) == 17 and om.min() > 0.5 and om.max() < 18
    assert np.sqrt(np.mean((H - H_data) ** 2)) < 0.07
    assert np.median(np.abs(H - H_data) / H_data) < 0.25


def test_sea_trial_study_quick(tmp_path):
    out = tmp_path / "trials"
    env = dict(os.environ, MPLBACKEND="Agg")
    proc = subprocess.run([sys.executable, str(ROOT / "studies" / "towed_sea_trials.py"), "--quick",
                           "--out", str(out)], capture_output=True, text=True, env=env)
    assert proc.returncode == 0, proc.stderr[-3000:]
    res = json.loads((out / "towed_sea_trials.json").read_text())
    assert len(res["runs"]) == 17
    fits = res["fits"]
    # the report's finding: the phase wants a much larger c_n than the amplitude; no c_n fits both
    assert fits["phase"]["c_n"] > 2 * fits["amplitude"]["c_n"]
    assert res["no_single_cn_fits_both"]["holds"] is True
    assert fits["amplitude"]["rms_H"] < res["stats_report_coefficients"]["H"]["rms"]
    assert fits["phase"]["rms_c_star"] < res["stats_report_coefficients"]["c_star"]["rms"]
    for name in ("towed_trials_H.png", "towed_trials_cstar.png", "towed_trials_cn.png"):
        assert (out / name).stat().st_size > 10_000


def test_model_runs_is_a_labelled_result(small_csv):
    """model_runs returns the protocol's result on dimension ``run``; the old tuple unpacking warns."""
    runs = read_runs(small_csv)
    res = model_runs(runs)
    assert res.success and res.labels == ("5", "21", "X")
    # omega = 2 pi f L / U (eq. 2) of run 5
    assert res.omega[0] == pytest.approx(2 * np.pi * 0.37e-3 * 1193.8 / 5.10, rel=1e-14)
    ds = res.to_xarray()
    assert list(ds["run"].values) == ["5", "21", "X"] and ds["H_abs"].values[0] == res.H_abs[0]
    assert "omega L/U" in ds["omega"].attrs["long_name"] and ds["c_star"].attrs["units"] == "1"
    assert json.loads(json.dumps(res.summary()))["runs"][2]["H_abs"] == pytest.approx(1.0, abs=1e-4)
    with pytest.warns(DeprecationWarning, match="unpacking model_runs"):
        H, cs, om = res
    assert H is res.H_abs and om is res.omega
