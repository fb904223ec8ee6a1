"""Property-based tests of every CLI entry point: a result or a named error, never a traceback.

``cablesys scene | run | rao | design | slack | towed`` on generated files and options.
The allowed outcomes are exit 0 with finite outputs, exit 1 (a documented failure: an
integrator or NLP that did not converge, written and marked failed), exit 2 with a named
error (``CablesysError`` or an argparse usage error). Any other exception fails the test;
a NaN in a written JSON file or in printed numbers counts as a silent acceptance.
Runs are tiny (duration <= 0.2 s of simulated time) and example counts small.
"""

import contextlib
import io
import json
import math
import shutil
import tempfile
import time
import tomllib
from pathlib import Path

from fuzz_common import REPORT, dumps, encoded, fuzz_settings, mutated, tally
from hypothesis import given
from hypothesis import strategies as st
from test_fuzz_loaders import CHAIN, SLACK, csv_bytes

from cablesys.cli import main
from cablesys.scene import default_scene, dump_scene

TINY = {**tomllib.loads(dump_scene(default_scene())), "numerics": {"duration": 0.2, "output_step": 0.05}}
DESIGN = {"ae_bounds": [[1e6, 1e8], [1e5, 1e7]], "damping_bounds": [[10.0, 1e4], [10.0, 1e4]],
          "n_starts": 1, "outer_iterations": 1, "max_iter": 3, "n_omega": 8, "quadrature_log2": 4,
          "band": [0.5, 1.5], "hs": 2.0, "tp": 8.0}
NUMBER_TEXT = st.one_of(st.sampled_from(["nan", "inf", "-inf", "0", "-1", "1e-300", "1e300", "abc", "", "0.1", "2"]),
                        st.floats(allow_nan=True, allow_infinity=True).map(repr))


def _no_nan(text: str) -> None:
    """Raise if a JSON text holds NaN or Infinity (which json writes unless told not to)."""
    def bad(c):
        raise AssertionError(f"{c} in a JSON output reported as success")
    json.loads(text, parse_constant=bad)


def _cli(argv, out: Path | None = None, check=None) -> tuple[int, str, str]:
    """(exit code, stdout, stderr) of ``cablesys argv``; only named errors are allowed.

    ``check(stdout)`` runs after a success (exit 0) and asserts what a result must satisfy.
    """
    o, e = io.StringIO(), io.StringIO()
    entry, t0 = argv[0], time.perf_counter()
    try:
        with contextlib.redirect_stdout(o), contextlib.redirect_stderr(e):
            try:
                rc = main([str(a) for a in argv])
            except SystemExit as ex:                  # argparse: a usage error names the option
                rc = ex.code
                assert rc == 2, f"argparse exit {rc}"
        assert rc in (0, 1, 2), rc
        assert "Traceback" not in e.getvalue()
        if rc == 2:
            assert "error:" in e.getvalue(), e.getvalue()
        if rc == 0 and out is not None and out.exists():
            for f in out.glob("*.json"):
                _no_nan(f.read_text())
        if rc == 0 and check is not None:
            check(o.getvalue())
    except AssertionError as err:
        tally(entry, "silent acceptance or bad exit", time.perf_counter() - t0,
              f"{argv[1:]} {err!r} stderr: {e.getvalue()[-500:]}")
        if REPORT:
            return -1, o.getvalue(), e.getvalue()
        raise
    except Exception as err:
        tally(entry, f"raw {type(err).__name__}", time.perf_counter() - t0, f"{argv[1:]} {err!r}")
        if REPORT:
            return -1, o.getvalue(), e.getvalue()
        raise
    tally(entry, {0: "result", 1: "documented failure (exit 1)", 2: "named error"}[rc], time.perf_counter() - t0)
    return rc, o.getvalue(), e.getvalue()


@contextlib.contextmanager
def _files(**contents):
    """A temporary folder with the given files (bytes or text); yields (folder, paths)."""
    d = Path(tempfile.mkdtemp(prefix="cablesys_fuzz_"))
    try:
        paths = {}
        for name, data in contents.items():
            p = d / name.replace("_", ".")
            p.write_bytes(data if isinstance(data, bytes) else data.encode())
            paths[name] = p
        yield d, paths
    finally:
        shutil.rmtree(d, ignore_errors=True)


@fuzz_settings(25)
@given(data=st.sampled_from([TINY, tomllib.loads(CHAIN)]).flatmap(lambda b: mutated(b)).flatmap(
    lambda d: encoded(dumps(d))), units=st.sampled_from(["SI", "fps"]))
def test_scene_command(data, units):
    with _files(s_toml=data) as (d, f):
        def printed_scene_loads(out):     # what it prints is a scene again (in SI or fps)
            from cablesys.scene import load_scene
            (d / "back.toml").write_text(out)
            load_scene(d / "back.toml")
        _cli(["scene", f["s_toml"], "--units", units], check=printed_scene_loads)


@fuzz_settings(6)
@given(doc=mutated(TINY, n_max=2), duration=st.one_of(st.none(), NUMBER_TEXT.filter(lambda t: t != "1e300")),
       method=st.sampled_from([None, "cvodes", "idas", "rk", "nope"]))
def test_run_command(doc, duration, method):
    with _files(s_toml=dumps(doc)) as (d, f):
        argv = ["run", f["s_toml"], "--out", d / "out"]
        if duration is not None:
            argv += ["--duration", duration]
            try:
                if float(duration) > 0.2:  # keep CI fast: a valid but long run is not the point here
                    argv[-1] = "0.2"
            except ValueError:
                pass
        if method:
            argv += ["--method", method]
        _cli(argv, d / "out")


@fuzz_settings(6)
@given(doc=mutated(TINY, n_max=2), n=st.sampled_from([None, 1, 2, 5, -3, 10**8]),
       omega_max=st.one_of(st.none(), NUMBER_TEXT))
def test_rao_command(doc, n, omega_max):
    with _files(s_toml=dumps(doc)) as (d, f):
        argv = ["rao", f["s_toml"], "--out", d / "out", "--n", 12 if n is None else n]
        if omega_max is not None:
            argv += ["--omega-max", omega_max]
        def finite_tables(_):
            for csv in (d / "out").glob("*.csv"):
                assert "nan" not in csv.read_text().lower(), csv.name
        _cli(argv, d / "out", check=finite_tables)


def test_rao_accepts_the_documented_cable_mass_switch(tmp_path):
    doc = {**TINY, "cable": {**TINY["cable"], "cable_mass_switch": -1.0}}
    (tmp_path / "s.toml").write_text(dumps(doc))
    assert _cli(["rao", tmp_path / "s.toml", "--out", tmp_path / "o", "--n", 12], tmp_path / "o")[0] == 0


@fuzz_settings(3)
@given(table=mutated(DESIGN, n_max=2, extra_keys=("foo", "tol")))
def test_design_command(table):
    doc = {**tomllib.loads(CHAIN), "design": table}
    doc.pop("top_motion")
    with _files(s_toml=dumps(doc)) as (d, f):
        _cli(["design", f["s_toml"], "--out", d / "out"], d / "out")


@fuzz_settings(8)
@given(doc=mutated({**SLACK, "scene": {**SLACK["scene"], "n_elements": 16, "n_modes": 4}}, n_max=2,
                   extra_keys=("foo", "n_modes", "gravity", "n_elements")))
def test_slack_command(doc):
    with _files(s_toml=dumps(doc)) as (d, f):
        _cli(["slack", f["s_toml"], "--out", d / "out"], d / "out")


OPTION = st.sampled_from(["--c-n", "--c-t", "--c-t-drogue", "--beta", "--diameter"])


@fuzz_settings(15)
@given(data=csv_bytes(), options=st.lists(st.tuples(OPTION, NUMBER_TEXT), max_size=2), as_json=st.booleans())
def test_towed_command(data, options, as_json):
    with _files(r_csv=data) as (d, f):
        argv = ["towed", f["r_csv"], *[x for opt in options for x in opt]] + (["--json"] if as_json else [])
        def finite(out):
            if as_json:
                _no_nan(out)
                return
            for line in out.splitlines()[1:]:
                assert all(math.isfinite(float(x)) for x in line.split()[-2:]), line
        _cli(argv, check=finite)


def test_casadi_warnings_are_quiet_unless_verbose(capsys):
    import casadi as ca

    from cablesys.messages import casadi_messages_to_log
    x = ca.SX.sym("x")
    rf = ca.rootfinder("rf", "kinsol", ca.Function("f", [x], [x**2 + 1]),
                       {"error_on_fail": False, "print_level": 0, "disable_internal_warnings": True})
    import sys
    with casadi_messages_to_log(verbose=False):
        rf(0.5)
        print("kept", file=sys.stderr)
    err = capsys.readouterr().err
    assert "KINSol" not in err and "kept" in err
    with casadi_messages_to_log(verbose=True):
        rf(0.5)
    assert "KINSol" in capsys.readouterr().err


def test_rao_grid_size_and_band_are_checked_before_any_work(tmp_path):
    (tmp_path / "s.toml").write_text(dumps(TINY))
    for opts, msg in ((["--n", "100000000"], "--n = 100000000: must be an integer in [2, 10000]"),
                      (["--omega-max", "nan"], "--omega-max = nan: must be a finite number in (0, 1e+06]"),
                      (["--omega-max", "-1"], "--omega-max = -1.0: must be")):
        rc, _, err = _cli(["rao", tmp_path / "s.toml", "--out", tmp_path / "o", *opts])
        assert rc == 2 and msg in err
        assert not (tmp_path / "o").exists()


def test_slack_load_beyond_the_allowed_strain_is_refused(tmp_path):
    # a 1e6 kg point mass on the 23.8 m example cable (EA 8.9e5 N) hung at 500 % strain, reported
    # as success, and its mode-shape plot exhausted memory
    doc = {**SLACK, "scene": {**SLACK["scene"], "n_elements": 16, "n_modes": 4},
           "masses": [SLACK["masses"][0], {**SLACK["masses"][1], "mass": 1e6}]}
    (tmp_path / "s.toml").write_text(dumps(doc))
    rc, _, err = _cli(["slack", tmp_path / "s.toml", "--out", tmp_path / "o"])
    assert rc == 2 and "cable.max_strain = 0.02: the equilibrium stretches the cable by" in err
