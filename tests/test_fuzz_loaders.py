"""Property-based tests of every loader: generated files give a valid object or a named error.

Scene TOML (SI and ft/lb/slug, one section and a chain with waves and a sampled top
motion), slack-cable TOML, the ``[design]`` table and the towed-run CSV. No raw
exception, and nothing non-finite accepted as a valid input.
"""

import math
import tempfile
import time
import tomllib
from pathlib import Path

import pytest
from fuzz_common import (
    REPORT,
    dumps,
    encoded,
    fuzz_settings,
    mutated,
    nonfinite_fields,
    tally,
)
from hypothesis import given
from hypothesis import strategies as st

from cablesys.errors import CablesysError, ParameterError
from cablesys.scene import default_scene, dump_scene, load_scene
from cablesys.slack.scene import EXAMPLE_TOML
from cablesys.slack.scene import load_slack_scene as load_slack
from cablesys.towed.runs import read_runs

CHAIN = """
name = "chain"
units = "SI"
angles = "shared"
[[sections]]
[sections.cable]
length = 150.0
ae = 2e7
diameter = 0.02
mass_per_length = 1.0
weight_per_length = 8.0
[sections.body]
weight = 2000.0
mass_x = 400.0
mass_y = 400.0
drag_area_normal = 2.0
drag_area_tangential = 2.0
[[sections]]
[sections.cable]
length = 50.0
ae = 5e6
diameter = 0.02
mass_per_length = 1.0
weight_per_length = 8.0
[sections.body]
weight = 3000.0
mass_x = 300.0
mass_y = 300.0
[environment]
current_depths = [0.0, 100.0]
current_speeds = [0.5, 0.2]
[[environment.waves]]
amplitude = 1.0
length = 100.0
[[top_motion.y]]
amplitude = 1.0
frequency = 0.6
[top_motion.series]
times = [0.0, 1.0, 2.0, 3.0, 4.0]
x = [0.0, 0.1, 0.0, -0.1, 0.0]
y = [0.0, 0.0, 0.0, 0.0, 0.0]
[initial]
u_rate = 0.0
[numerics]
duration = 10.0
output_step = 0.5
"""

SCENES = [tomllib.loads(dump_scene(default_scene())), tomllib.loads(dump_scene(default_scene(), units="fps")),
          tomllib.loads(CHAIN)]
SLACK = tomllib.loads(EXAMPLE_TOML)
RUNS = ("run,L_m,a_over_lambda,U_mps,f_mHz,H,c_star\n1,1186.9,0.0097,3.10,0.97,0.8223,1.00\n"
        "5A,1193.8,0.01,5.10,0.37,0.9,1.1\n")


def _write(data: bytes, suffix: str) -> Path:
    f = tempfile.NamedTemporaryFile(suffix=suffix, delete=False)
    f.write(data)
    f.close()
    return Path(f.name)


def _load(loader, data: bytes, suffix: str):
    """loader(file) or None for a named error; any other exception fails the test."""
    path = _write(data, suffix)
    entry, t0 = f"load {loader.__module__}", time.perf_counter()
    try:
        out = loader(path)
        tally(entry, "result", time.perf_counter() - t0)
        return out
    except CablesysError as err:
        assert str(err), "a named error has a message"
        tally(entry, "named error", time.perf_counter() - t0)
        return None
    except Exception as err:
        tally(entry, f"raw {type(err).__name__}", time.perf_counter() - t0, f"{data[:300]!r} {err!r}")
        if REPORT:
            return None
        raise
    finally:
        path.unlink()


@st.composite
def scene_bytes(draw):
    base = draw(st.sampled_from(SCENES))
    return draw(encoded(dumps(draw(mutated(base)))))


@fuzz_settings(60)
@given(data=scene_bytes())
def test_scene_loader_gives_a_scene_or_a_named_error(data):
    scene = _load(load_scene, data, ".toml")
    if scene is not None:
        assert not nonfinite_fields(scene), nonfinite_fields(scene)


@fuzz_settings(40)
@given(data=st.builds(lambda d: d, st.just(None)).flatmap(
    lambda _: mutated(SLACK, extra_keys=("foo", "n_modes", "gravity"))).flatmap(lambda d: encoded(dumps(d))))
def test_slack_loader_gives_a_scene_or_a_named_error(data):
    out = _load(load_slack, data, ".toml")
    if out is not None:
        scene = out
        assert not nonfinite_fields(scene) and 1 <= scene.n_modes
        assert 4 <= scene.n_elements <= 5000


DESIGN = {"ae_bounds": [[1e6, 1e8], [1e5, 1e7]], "damping_bounds": [[10.0, 1e4], [10.0, 1e4]],
          "hs": 2.0, "tp": 8.0, "n_omega": 20, "band": [0.5, 1.5], "objective": "significant"}


@fuzz_settings(40)
@given(table=mutated(DESIGN, extra_keys=("foo", "n_starts", "tol")))
def test_design_settings_give_settings_or_a_named_error(table):
    from cablesys.isolation import settings_from_dict
    try:
        s = settings_from_dict(table)
    except ParameterError:
        return
    assert not nonfinite_fields(s)


def test_design_loader_reads_a_scene_file_with_a_design_table(tmp_path):
    from cablesys.isolation.cli import load
    f = tmp_path / "d.toml"
    f.write_text(CHAIN + "\n[design]\nae_bounds = [[1e6, 1e8], [1e5, 1e7]]\n"
                 "damping_bounds = [[10.0, 1e4], [10.0, 1e4]]\nhs = \"2\"\n")
    with pytest.raises(ParameterError, match=r"d\.toml, line \d+: design\.hs = '2': must be a number"):
        load(f)


# ------------------------------------------------------------------------- towed CSV
CELLS = st.one_of(st.sampled_from(["1", "0", "-3", "nan", "inf", "1e308", "1e-320", "", " 4 ", "x", '"1,2"', "1_0"]),
                  st.floats(allow_nan=True, allow_infinity=True).map(repr),
                  st.text(alphabet=st.characters(codec="utf-8", exclude_categories=("Cs",)), max_size=5))


@st.composite
def csv_bytes(draw):
    lines = RUNS.splitlines()
    header = lines[0].split(",")
    if draw(st.booleans()):
        header = draw(st.permutations(header))
    rows = [header]
    for _ in range(draw(st.integers(0, 4))):
        n = len(header) + draw(st.sampled_from([0, 0, 0, -1, 1, -3]))
        rows.append([draw(CELLS) for _ in range(max(n, 0))])
    if draw(st.booleans()):
        rows += [ln.split(",") for ln in lines[1:]]
    text = "".join(",".join(r) + "\n" for r in rows)
    if draw(st.booleans()):
        text = "# comment\n" + text
    return draw(encoded(text))


@fuzz_settings(80)
@given(data=csv_bytes())
def test_towed_csv_gives_runs_or_a_named_error(data):
    runs = _load(read_runs, data, ".csv")
    if runs is not None:
        assert runs and all(math.isfinite(v) and v > 0 for r in runs for v in (r.length, r.speed, r.frequency))


def test_reader_names_the_byte_that_is_not_utf8(tmp_path):
    f = tmp_path / "s.toml"
    f.write_bytes(b'name = "a"\nunits = "SI"\n# caf\xe9\n')
    with pytest.raises(ParameterError, match=r"not UTF-8 text: byte 29 \(0xe9\) at line 3, column 6"):
        load_scene(f)


def test_byte_order_mark_is_accepted(tmp_path):
    f = tmp_path / "s.toml"
    f.write_bytes(b"\xef\xbb\xbf" + dump_scene(default_scene()).encode())
    assert load_scene(f) == default_scene()
    c = tmp_path / "r.csv"
    c.write_bytes(b"\xef\xbb\xbf" + RUNS.encode())
    assert [r.label for r in read_runs(c)] == ["1", "5A"]


def _edited(units="SI", **tables) -> str:
    doc = tomllib.loads(dump_scene(default_scene(), units=units))
    for name, table in tables.items():
        doc[name] = table if not isinstance(table, dict) else {**doc.get(name, {}), **table}
    return dumps(doc)


def test_a_string_never_skips_unit_conversion(tmp_path):
    f = tmp_path / "s.toml"
    f.write_text(_edited("fps", cable={"length": "9"}))
    with pytest.raises(ParameterError, match=r"cable\.length = '9': must be a number, not a string"):
        load_scene(f)
    f.write_text(_edited("fps", cable={"length": 9}))
    assert load_scene(f).cable.length == pytest.approx(9 * 0.3048)


@pytest.mark.parametrize("tables, match", [
    ({"initial": {"u": math.nan}}, r"initial\.u = nan: must be finite"),
    ({"initial": {"phi": 4.0}}, r"initial\.phi = 4\.0: must be in \[-3\.14"),
    ({"initial": {"u": -1000.0}}, r"initial\.u = -1000\.0: must be > -2\.7"),
    ({"initial": {"phi_rate": math.inf}}, r"initial\.phi_rate = inf: must be finite"),
    ({"initial": [{"u": 0.0}]}, r"initial = '1 tables': must be one table \[initial\]"),
    ({"numerics": {"duration": True}}, r"numerics\.duration = True: must be a number, not a boolean"),
    ({"numerics": {"drag_segments": 2.5}}, r"numerics\.drag_segments = 2\.5: must be an integer"),
])
def test_initial_and_types_are_checked(tmp_path, tables, match):
    f = tmp_path / "s.toml"
    f.write_text(_edited(**tables))
    with pytest.raises(ParameterError, match=match):
        load_scene(f)


def test_errors_name_file_and_line(tmp_path):
    f = tmp_path / "s.toml"
    f.write_text(dump_scene(default_scene()).replace("[body]\n", "[body]\nmass_q = 1.0\n", 1))
    line = f.read_text().splitlines().index("mass_q = 1.0") + 1
    with pytest.raises(ParameterError, match=rf"s\.toml, line {line}: body\.mass_q = 1\.0: unknown key"):
        load_scene(f)


def test_one_table_where_an_array_of_tables_belongs(tmp_path):
    f = tmp_path / "s.toml"
    f.write_text(dump_scene(default_scene()).replace("[[top_motion.x]]", "[top_motion.x]", 1))
    with pytest.raises(ParameterError, match=r"top_motion\.x = 'one table': must be an array of tables"):
        load_scene(f)


def test_towed_rows_with_extra_or_missing_fields_are_named(tmp_path):
    c = tmp_path / "r.csv"
    c.write_text("run,L_m,U_mps,f_mHz\n1,1000,4,1\n2,1000,4,1,oops\n")
    with pytest.raises(ParameterError, match=r"r\.csv row 2 \(line 3\).*has 5 fields; the header has 4"):
        read_runs(c)
    c.write_text("run,L_m,U_mps,f_mHz\n1,1000,4\n")
    with pytest.raises(ParameterError, match=r"row 1 \(line 2\).*has 3 fields"):
        read_runs(c)


def test_requested_size_limits_are_named(tmp_path, monkeypatch):
    import cablesys.reader as reader
    f = tmp_path / "s.toml"
    f.write_text(dumps({**SLACK, "scene": {**SLACK["scene"], "n_elements": 1e6}}))
    with pytest.raises(ParameterError, match=r"scene\.n_elements = 1000000: must be an integer in \[4, 5000\]"):
        load_slack(f)
    monkeypatch.setattr(reader, "MAX_INPUT_BYTES", 100)
    f.write_text(EXAMPLE_TOML)
    with pytest.raises(ParameterError, match=r"is \d+ bytes; the limit for an input file is 100"):
        load_slack(f)
