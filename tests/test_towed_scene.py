"""`cablesys towed SCENE.toml`: the cable in the Wang scene's terms, converted once, written with units."""

import csv
import json
import math
import re
import tomllib

import numpy as np
import pytest

from cablesys.cli import main
from cablesys.errors import ParameterError
from cablesys.towed import (
    TowedCable,
    analyze,
    c_star,
    load_towed_scene,
    transfer_function,
)
from cablesys.towed.scene import EXAMPLE_TOML, towed_scene_from_dict


def _scene_file(tmp_path, **towed):
    doc = EXAMPLE_TOML
    for key, value in towed.items():
        doc = re.sub(rf"^{key} = .*$", "", doc, flags=re.M).replace("[towed]\n", f"[towed]\n{key} = {value}\n", 1)
    path = tmp_path / "towed.toml"
    path.write_text(doc)
    return path


def _scripted(doc: dict):
    """The conversion a user would script from Kennedy & Strahan (1981), written out here by hand."""
    cab, tow = doc["cable"], doc["towed"]
    rho = doc["environment"]["density"]
    d = cab["diameter"]
    M = rho * math.pi * d**2 / 4                             # displaced fluid mass per length (eq. 1-2)
    cable = TowedCable(length=cab["length"], speed=tow["speed"], diameter=d,
                       c_t=cab["ct_tangential"] / math.pi,      # F_t: (rho/2) pi d c_t U^2 = (rho/2) C_t d U^2
                       c_n=tow["amplification"] * cab["cd_normal"],          # c_n* = A c_n (eq. 39)
                       c_t_drogue=tow["drogue_drag_area"] / (math.pi * d**2),  # (rho/2) C_D A U^2 = 2 c_t' M U^2
                       beta=M / (M + cab["mass_per_length"]))
    return cable


def test_cli_scene_equals_the_scripted_conversion(tmp_path, capsys):
    path = _scene_file(tmp_path, omega_max=0.3, n_omega=40)
    out = tmp_path / "out"
    assert main(["towed", str(path), "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    doc = json.loads((out / "towed.json").read_text())
    cable = _scripted(tomllib.loads(path.read_text()))
    coef = cable.coefficients()
    r = doc["response"]
    xi, omega = np.array(r["xi"]), np.array(r["omega_rad_s"])
    # the grid: log-spaced from the default 0.1 U/L to the given 0.3 rad/s
    assert omega[0] == pytest.approx(0.1 * cable.speed / cable.length, rel=1e-14) and omega[-1] == pytest.approx(0.3)
    om_nd = omega * cable.length / cable.speed                 # eq. 2: tau = U t / L
    assert np.array(r["omega_nd"]) == pytest.approx(om_nd, rel=1e-14)
    H = transfer_function(coef, xi[:, None], om_nd[None, :]).H
    cs = c_star(coef, xi[:, None], om_nd[None, :]).c_star
    H_cli = np.array(r["H_real"]) + 1j * np.array(r["H_imag"])
    assert np.max(np.abs(H_cli - H)) <= 1e-12
    assert np.max(np.abs(np.array(r["c_star"]) - cs) / cs) <= 1e-12
    assert np.array(r["c_star_m_s"]) == pytest.approx(cs * cable.speed, rel=1e-14)
    for key in ("c_t", "c_n", "c_t_drogue", "beta"):
        assert doc["coefficients"][key] == pytest.approx(getattr(cable, key), rel=1e-14)
    assert doc["units"]["omega_rad_s"] == "rad/s" and doc["units"]["c_star_m_s"] == "m/s"
    # the CSV holds the same numbers, one row per (xi, omega)
    rows = list(csv.DictReader((out / "towed.csv").open()))
    assert len(rows) == xi.size * omega.size
    last = rows[-1]
    assert float(last["H_abs"]) == abs(H_cli[-1, -1]) and float(last["omega_rad_s"]) == omega[-1]
    assert (out / "towed.png").stat().st_size > 10_000
    # printed to significant digits: the far end's smallest |H| reads back to 6 digits, not 0.0000
    tail = [ln.split() for ln in printed.splitlines() if ln.startswith("  ")][-1]
    assert float(tail[2]) == pytest.approx(abs(H_cli[-1, -1]), rel=1e-5) and abs(H_cli[-1, -1]) < 1e-3


def test_analysis_result_keeps_units_and_the_report_values():
    scene = towed_scene_from_dict(tomllib.loads(EXAMPLE_TOML))
    res = analyze(scene)
    assert res.success and res.message == ""
    # the example is the report's sea-trial cable (p. 31): c_t = 0.0101, c_n* = 0.16, c_t' = 228, beta = 0.5
    assert res.coefficients["c_t"] == pytest.approx(0.0101, rel=2e-3)
    assert res.coefficients["c_t_drogue"] == pytest.approx(228.0, rel=1e-3)
    assert res.coefficients["beta"] == pytest.approx(0.5, rel=1e-3)
    # low-frequency limit: c* -> (1 + 1/p) U with p = c_n / (pi c_t) (eq. 8c, 14)
    p = res.coefficients["c_n"] / (math.pi * res.coefficients["c_t"])
    assert res.c_star_m_s[:, 0] == pytest.approx((1 + 1 / p) * scene.speed, rel=2e-3)
    ds = res.to_xarray()
    assert ds["omega"].attrs["units"] == "rad/s" and ds["omega_nd"].attrs["units"] == "1"
    assert ds["c_star_m_s"].attrs["units"] == "m/s" and ds["frequency"].attrs["units"] == "Hz"
    assert ds["H_abs"].dims == ("xi", "omega")
    # the report's damping time (eq. 25) from the converted coefficients, written out
    D = 2 * res.coefficients["c_t"] * scene.cable.length / scene.cable.diameter + 2 * res.coefficients["c_t_drogue"]
    assert res.damping_time_report_s == pytest.approx(
        2 * math.pi * (D - 1) * scene.cable.diameter / (res.coefficients["c_n"] * scene.speed), rel=1e-12)
    # steady tensions: the drogue end carries the drogue's drag, the tow point adds the friction of L (Wang eq. 44)
    from cablesys.model.fluid import quadratic_drag
    drogue = float(quadratic_drag(scene.density, scene.drogue_drag_area, scene.speed))
    friction = float(quadratic_drag(scene.density, scene.cable.ct_tangential * scene.cable.diameter, scene.speed))
    assert res.tension_bottom == pytest.approx(drogue, rel=1e-12)
    assert res.tension_top == pytest.approx(drogue + friction * scene.cable.length, rel=1e-12)
    assert json.loads(json.dumps(res.summary()))["tension_top_N"] == res.tension_top


def test_runs_table_prints_significant_digits(tmp_path, capsys):
    """A run whose |H(1)| is below 1e-8 prints to significant digits (never as 0.0000)."""
    p = tmp_path / "runs.csv"
    p.write_text("run,L_m,U_mps,f_mHz\nfast,1190,5,100\n")
    assert main(["towed", str(p), "--json"]) == 0
    exact = json.loads(capsys.readouterr().out)[0]["H"]
    assert 0 < exact < 1e-8
    assert main(["towed", str(p)]) == 0
    row = capsys.readouterr().out.strip().splitlines()[1].split()
    assert float(row[4]) == pytest.approx(exact, rel=1e-5)


@pytest.mark.parametrize("edit,needle", [
    (("cd_normal = 0.16", "cd_normal = -0.16"), "cable.cd_normal"),
    (("ct_tangential = 0.0317", "ct_tangential = 0.0317\nc_t = 0.01"), "cable.c_t"),
    (("speed = 5.0", "speed = 0.0"), "towed.speed"),
    (("xi = [0.5, 1.0]", "xi = [0.5, 1.5]"), "towed.xi"),
    (("n_omega = 120", "n_omega = 120\nomega_min = 1.0\nomega_max = 0.5"), "towed.omega_min"),
])
def test_bad_scene_names_the_field(tmp_path, capsys, edit, needle):
    path = tmp_path / "bad.toml"
    path.write_text(EXAMPLE_TOML.replace(*edit))
    with pytest.raises(ParameterError, match=needle.replace(".", r"\.")):
        load_towed_scene(path)
    assert main(["towed", str(path), "--out", str(tmp_path / "o")]) == 2
    assert needle in capsys.readouterr().err
    assert not (tmp_path / "o" / "towed.json").exists()


def test_theory_options_with_a_scene_are_refused(tmp_path, capsys):
    """--c-n would be silently ignored by a scene (it gives cd_normal): a clear error instead."""
    path = _scene_file(tmp_path)
    assert main(["towed", str(path), "--c-n", "0.2", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "--c-n = 0.2" in err and "RUNS.csv only" in err
    assert main(["towed", "--example"]) == 0
    assert towed_scene_from_dict(tomllib.loads(capsys.readouterr().out)) == towed_scene_from_dict(
        tomllib.loads(EXAMPLE_TOML))
