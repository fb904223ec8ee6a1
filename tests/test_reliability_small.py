"""Regression tests of the smaller reliability items: bounded sizes, solver failures as failures, RFC 4180 CSV.

Each test drives the ``cablesys`` command through ``main([...])`` and asserts its exit code
(0 a result, 1 a failed computation, 2 bad input) and the message that names the cause.
"""

import contextlib
import io
import json
import math
import tomllib

import pytest
from fuzz_common import dumps

from cablesys.cli import main
from cablesys.errors import SolverError
from cablesys.scene import default_scene, dump_scene
from cablesys.towed.runs import read_runs

SCENE = tomllib.loads(dump_scene(default_scene()))


def cablesys(*argv):
    """(exit code, stdout, stderr) of ``cablesys argv``."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = main([str(a) for a in argv])
    return rc, out.getvalue(), err.getvalue()


@pytest.mark.parametrize("axis, key, value, message", [
    ("x", "amplitude", 5.6e16, "s.toml, line 7: top_motion.x[0].amplitude = 5.6e+16: must be in [-10000.0, 10000.0] m"),
    ("y", "frequency", 1e300, "top_motion.y[0].frequency = 1e+300: must be in (0.0, 10000.0] rad/s"),
])
def test_huge_top_motion_is_bad_input(tmp_path, axis, key, value, message):
    """The values that overflowed the ladder are refused by the reader (exit 2), naming field, value, range;
    ``run`` refuses before it writes anything."""
    doc = json.loads(json.dumps(SCENE))
    doc["top_motion"][axis][0][key] = value
    f = tmp_path / "s.toml"
    f.write_text(dumps(doc))
    rc, _, err = cablesys("scene", f)
    assert rc == 2 and message in err
    rc, _, err = cablesys("run", f, "--out", tmp_path / "out")
    assert rc == 2 and message in err
    assert not (tmp_path / "out" / "timeseries.csv").exists()


@pytest.mark.parametrize("sea, message", [
    ({"hs": 1e6, "tp": 10.0}, "top_motion.spectrum.hs = 1000000.0: must be in (0.0, 100.0] m"),
    ({"hs": 2.0, "tp": 1e-5}, "top_motion.spectrum.tp = 1e-05: must be in [0.1, 1000.0] s"),
])
def test_sea_outside_its_range_names_the_sea_field(tmp_path, sea, message):
    """A sea whose realised sinusoids would exceed the bounds names the sea's own field, not a
    derived top_motion.amplitude or frequency."""
    doc = json.loads(json.dumps(SCENE))
    doc["top_motion"]["spectrum"] = sea
    f = tmp_path / "s.toml"
    f.write_text(dumps(doc))
    rc, _, err = cablesys("scene", f)
    assert rc == 2 and message in err, err


@pytest.mark.parametrize("wave, message", [
    ({"amplitude": 1e20, "length": 100.0}, "waves[0].amplitude = 1e+20: must be in [0.0, 10000.0] m"),
    ({"amplitude": 1.0, "length": 1e-300}, "waves[0].length = 1e-300: must be in [0.01, 1000000.0] m"),
])
def test_wave_outside_its_range_is_bad_input(tmp_path, wave, message):
    """A surface wave's amplitude and length (which sets sigma = sqrt(g 2 pi / lambda)) are bounded."""
    doc = json.loads(json.dumps(SCENE))
    doc["environment"]["waves"] = [wave]
    f = tmp_path / "s.toml"
    f.write_text(dumps(doc))
    rc, _, err = cablesys("scene", f)
    assert rc == 2 and message in err, err


def test_top_motion_velocity_is_bounded(tmp_path):
    """Amplitude and frequency each within range but |a| omega = 1e8 m/s (the values that overflowed the
    ladder's linearised drag) is refused naming the product, its value and the 100 m/s limit."""
    doc = json.loads(json.dumps(SCENE))
    doc["top_motion"]["x"][0].update(amplitude=1e4, frequency=1e4)
    f = tmp_path / "s.toml"
    f.write_text(dumps(doc))
    rc, _, err = cablesys("scene", f)
    assert rc == 2 and "top_motion.x[0].amplitude * frequency = 100000000.0: must be <= 100 m/s" in err, err


def test_bounds_are_inclusive_at_the_physical_limits(tmp_path):
    """The limits themselves are accepted: 1e4 m at 0.01 rad/s and 0.01 m at 1e4 rad/s (100 m/s each)."""
    doc = json.loads(json.dumps(SCENE))
    doc["top_motion"]["x"][0].update(amplitude=1e4, frequency=0.01)
    doc["top_motion"]["y"][0].update(amplitude=0.01, frequency=1e4)
    f = tmp_path / "s.toml"
    f.write_text(dumps(doc))
    rc, out, err = cablesys("scene", f)
    assert rc == 0, err
    back = tomllib.loads(out)["top_motion"]
    assert (back["x"][0]["amplitude"], back["x"][0]["frequency"]) == (1e4, 0.01)
    assert (back["y"][0]["amplitude"], back["y"][0]["frequency"]) == (0.01, 1e4)


def test_towed_run_length_is_bounded_before_any_allocation(tmp_path):
    """L_m = 1e12 (a 250 GiB phase grid) is bad input naming the row, column, value and limit."""
    f = tmp_path / "r.csv"
    f.write_text("L_m,U_mps,f_mHz\n1190,2.5,5\n1e12,2.5,5\n")
    rc, _, err = cablesys("towed", f)
    assert rc == 2
    assert "r.csv row 2 (line 3), column L_m = '1e12': must be <= 100000 (m)" in err


def test_towed_run_frequency_beyond_the_grid_is_named(tmp_path):
    """A legal length with omega L/U = 2 pi f L / U above 1.25e5 is refused with its value."""
    f = tmp_path / "r.csv"
    f.write_text("L_m,U_mps,f_mHz\n1e5,0.01,10\n")      # omega L/U = 2 pi 0.01 1e5 / 0.01 = 6.28e5
    rc, _, err = cablesys("towed", f)
    assert rc == 2
    w = 2 * math.pi * 0.01 * 1e5 / 0.01
    assert f"r.csv row 1 (line 2): omega L/U = 2 pi f L / U = {w!r}: must be <= 125000" in err


def test_towed_scene_omega_max_is_bounded(tmp_path):
    """A towed scene whose omega_max needs more than 1e6 grid points is bad input naming towed.omega_max."""
    rc, example, _ = cablesys("towed", "--example")
    assert rc == 0
    doc = tomllib.loads(example)
    L, U = doc["cable"]["length"], doc["towed"]["speed"]
    doc["towed"]["omega_max"] = 2e5 * U / L                # omega L/U = 2e5 > 1.25e5
    f = tmp_path / "t.toml"
    f.write_text(dumps(doc))
    rc, _, err = cablesys("towed", f, "--out", tmp_path / "out")
    assert rc == 2 and "towed.omega_max = " in err and "omega L/U <= 125000" in err


def test_towed_csv_is_rfc4180(tmp_path):
    """Quoted fields with commas, doubled quotes and newlines are one field; comments and blank lines
    between records are skipped, and a later row's error names the line it starts on."""
    text = ('# sea trial\nrun,L_m,U_mps,f_mHz,note\n"a,1",1190,2.5,5,"two\nlines, ""quoted"""\n\n'
            'b,1190,2.5,10,plain\nc,1190,x,10,bad\n')
    f = tmp_path / "r.csv"
    f.write_text(text)
    rc, _, err = cablesys("towed", f)
    assert rc == 2 and "r.csv row 3 (line 7), column U_mps = 'x': must be a number (m/s)" in err
    f.write_text(text.rsplit("c,", 1)[0])
    runs = read_runs(f)
    assert [r.label for r in runs] == ["a,1", "b"]
    assert runs[0].columns["note"] == 'two\nlines, "quoted"'
    assert runs[1].frequency == pytest.approx(0.01)
    rc, out, err = cablesys("towed", f, "--json")
    assert rc == 0, err
    # the same runs, one per line, give the same numbers: the quoting changed nothing but the text
    g = tmp_path / "plain.csv"
    g.write_text("run,L_m,U_mps,f_mHz\na1,1190,2.5,5\nb,1190,2.5,10\n")
    rc2, out2, _ = cablesys("towed", g, "--json")
    assert rc2 == 0
    quoted, plain = json.loads(out), json.loads(out2)
    assert [r["H"] for r in quoted] == [r["H"] for r in plain] and len(quoted) == 2
    assert quoted[0]["note"] == 'two\nlines, "quoted"'          # the input column is kept whole


def test_towed_csv_unterminated_quote_is_named(tmp_path):
    """A quote never closed is bad input naming the file and the line the record starts on."""
    f = tmp_path / "r.csv"
    f.write_text('L_m,U_mps,f_mHz\n1190,2.5,"5\n')
    rc, _, err = cablesys("towed", f)
    assert rc == 2 and "r.csv, line 2 = 'not CSV': cannot be parsed as RFC 4180 CSV" in err


SLACK = """[scene]
span = {span}
rise = {rise}
medium = "{medium}"
n_elements = 120
n_modes = 4
[cable]
length = 23.80
mass_per_length = 1.14
ae = 8.9e5
{extra}
"""


@pytest.mark.parametrize("span, rise, medium, extra, reason", [
    (1e-4, 0.0, "air", "", "statics NLP did not converge"),                     # nearly coincident supports
    (1e-3, 23.7, "air", "", "statics (nlp-ipopt): element 0 is in compression"),  # near-vertical chord
])
def test_slack_solver_failure_on_valid_input_exits_1(tmp_path, monkeypatch, span, rise, medium, extra, reason):
    """A valid slack geometry whose statics fail is a failed computation (exit 1, status failed, the
    reason printed), not bad input (exit 2)."""
    monkeypatch.setenv("CABLESYS_COMPILE", "0")
    f = tmp_path / "s.toml"
    f.write_text(SLACK.format(span=span, rise=rise, medium=medium, extra=extra))
    rc, _, err = cablesys("slack", f, "--out", tmp_path / "out")
    assert rc == 1, err
    assert reason in err and "bad input" not in err
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["status"] == "failed"


def test_a_nearly_neutral_span_in_water_solves_on_the_shared_cable(tmp_path, monkeypatch):
    """Specific gravity 1.0001 (the chain's energy NLP stalls there): the node-model statics, started by
    shooting, find the shallow span, whose horizontal tension is the parabola's w s^2 / (8 d) to the
    catenary's order (d / s)^2."""
    monkeypatch.setenv("CABLESYS_COMPILE", "0")
    f = tmp_path / "s.toml"
    f.write_text(SLACK.format(span=22.9, rise=0.0, medium="water", extra="specific_gravity = 1.0001"))
    rc, _, err = cablesys("slack", f, "--out", tmp_path / "out")
    assert rc == 0, err
    eq = json.loads((tmp_path / "out" / "slack_result.json").read_text())["equilibrium"]
    w = 1.14 * 9.80665 * (1 - 1 / 1.0001)
    assert eq["horizontal_tension_N"] == pytest.approx(w * 22.9**2 / (8 * eq["sag_m"]), rel=0.03)


def test_solver_error_carries_exit_1_and_parameter_error_2(tmp_path):
    """The CLI maps a SolverError to exit 1 through its exit_code, and keeps 2 for bad input."""
    assert SolverError("x").exit_code == 1
    rc, _, err = cablesys("slack", tmp_path / "missing.toml")
    assert rc == 2 and "missing.toml" in err


@pytest.mark.parametrize("span, rise", [(1e-4, 0.0), (1e-3, 23.7)])
def test_slack_shooting_failure_is_a_solver_error(tmp_path, span, rise):
    """The shooting route's start (the elastic parabola) has no root for these chords: a SolverError
    naming the geometry, not a raw ValueError or OverflowError."""
    from cablesys.slack.scene import load_slack_scene
    from cablesys.slack.statics import solve_equilibrium_shooting
    f = tmp_path / "s.toml"
    f.write_text(SLACK.format(span=span, rise=rise, medium="air", extra=""))
    with pytest.raises(SolverError, match=rf"statics shooting.* span = {span:g} m, rise = {rise:g} m"):
        solve_equilibrium_shooting(load_slack_scene(f))
