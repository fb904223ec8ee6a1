"""Sweeps of the slack and towed analyses: the table equals the direct analyses, bad labels are refused before any
case runs, and the verdict judges the static tensions against the scene's [limits]."""

import re
import tomllib
from pathlib import Path

import numpy as np
import pytest

import cablesys
from cablesys import slack, towed
from cablesys.cli import main
from cablesys.errors import ParameterError
from cablesys.scene import dale_scene
from cablesys.scene.limits import Limits
from cablesys.slack import scene as slack_scene_module
from cablesys.sweeps import analyses
from cablesys.sweeps.api import sweep as sweep_function
from cablesys.towed import scene as towed_scene_module
from cablesys.verdict import judge, passed

ROOT = Path(__file__).resolve().parents[1]
SPANS = [22.0, 22.5, 22.9]                 # m; chord < L (1 + max_strain) = 24.3 m
SPEEDS = [3.0, 5.0, 7.0]                   # m/s


def slack_scene(**kw):
    """The Griffin & Rosenthal example span (two 4.5 kg masses), coarse: 24 elements, 4 modes."""
    doc = tomllib.loads(slack_scene_module.EXAMPLE_TOML)
    return slack_scene_module.scene_from_dict(doc).replace(n_elements=24, n_modes=4, **kw)


def towed_scene():
    return towed_scene_module.towed_scene_from_dict(tomllib.loads(towed_scene_module.EXAMPLE_TOML))


def close(a, b, rtol=1e-12):
    return abs(a - b) <= rtol * max(abs(a), abs(b), 1e-300)


def test_a_slack_sweep_equals_three_direct_analyses():
    ds = cablesys.sweep(slack_scene(), {"span": SPANS}, analysis="slack", workers=1, progress=False)
    assert list(ds["status"].values) == ["ok"] * 3
    assert ds["span"].attrs["units"] == "m" and ds["omega_n_0_rad_s"].attrs["units"] == "rad/s"
    assert ds["max_tension_N"].attrs["units"] == "N"
    for i, span in enumerate(SPANS):
        r = slack.analyze(slack_scene().replace(span=span))
        eq = r.equilibrium
        for k, w in enumerate(r.modes.omega):
            assert close(float(ds[f"omega_n_{k}_rad_s"][i]), float(w))
            assert str(ds[f"mode_type_{k}"].values[i]) == r.modes.mode_type[k]
        assert close(float(ds["lambda2"][i]), eq.lambda2)
        assert close(float(ds["max_tension_N"][i]), float(np.max(eq.tension)))
        assert close(float(ds["min_tension_N"][i]), float(np.min(eq.tension)))
        assert close(float(ds["horizontal_tension_N"][i]), eq.horizontal_tension)
        assert close(float(ds["sag_m"][i]), eq.sag)
    # a shorter span hangs slacker: a lower tension and a lower first frequency (Irvine 1981, the taut-string limit)
    assert np.all(np.diff(ds["max_tension_N"].values) > 0) and np.all(np.diff(ds["omega_n_0_rad_s"].values) > 0)


def test_a_towed_sweep_equals_three_direct_analyses():
    ds = cablesys.sweep(towed_scene(), {"speed": SPEEDS}, analysis="towed", workers=1, progress=False)
    assert list(ds["status"].values) == ["ok"] * 3
    assert ds["tension_top_N"].attrs["units"] == "N" and ds["far_end_c_star_m_s_1"].attrs["units"] == "m/s"
    for i, speed in enumerate(SPEEDS):
        r = towed.analyze(towed_scene_module.TowedScene(**{**towed_scene().__dict__, "speed": speed}))
        k = int(np.argmax(r.xi))
        assert close(float(ds["tension_top_N"][i]), r.tension_top)
        assert close(float(ds["tension_bottom_N"][i]), r.tension_bottom)
        assert close(float(ds["damping_time_s"][i]), r.damping_time_s)
        assert close(float(ds["far_end_H_abs_0"][i]), float(abs(r.H[k, 0])))
        assert close(float(ds["far_end_c_star_m_s_1"][i]), float(r.c_star_m_s[k, -1]))
    # steady tensions are drags, 2 M U^2 (...) (eq. 1-3): they scale with U^2
    top = ds["tension_top_N"].values
    assert np.allclose(top / top[0], (np.array(SPEEDS) / SPEEDS[0]) ** 2, rtol=1e-12)


@pytest.mark.parametrize("scene, analysis, label", [(slack_scene, "slack", "spam"),
                                                    (slack_scene, "slack", "cable.aee"),
                                                    (slack_scene, "slack", "masses[5].mass"),
                                                    (towed_scene, "towed", "spead"),
                                                    (towed_scene, "towed", "cable.cd_nrmal")])
def test_an_unknown_field_is_refused_by_name_before_any_case(monkeypatch, scene, analysis, label):
    def boom(*a):
        raise AssertionError("a case ran")
    monkeypatch.setitem(analyses.ANALYSIS, analysis, boom)
    with pytest.raises(ParameterError) as err:
        cablesys.sweep(scene(), {label: [1.0, 2.0]}, analysis=analysis, workers=1, progress=False)
    assert err.value.field == "vary" and err.value.value == label
    assert "names no scene field" in err.value.allowed or "out of range" in err.value.allowed


def test_wrong_values_scenes_and_options_are_refused_before_any_case(monkeypatch):
    monkeypatch.setitem(analyses.ANALYSIS, "slack", lambda *a: pytest.fail("a case ran"))
    with pytest.raises(ParameterError, match=r"vary\['n_elements'\].*integer"):
        cablesys.sweep(slack_scene(), {"n_elements": [24, 24.5]}, analysis="slack", progress=False)
    with pytest.raises(ParameterError, match=r"vary\['span'\].*number"):
        cablesys.sweep(slack_scene(), {"span": ["wide"]}, analysis="slack", progress=False)
    with pytest.raises(ParameterError, match="the slack analysis takes a slack scene"):
        cablesys.sweep(dale_scene(), {"cable.ae": [1.0]}, analysis="slack", progress=False)
    with pytest.raises(ParameterError, match="the towed analysis takes a towed scene"):
        cablesys.sweep(slack_scene(), {"span": [22.0]}, analysis="towed", progress=False)
    with pytest.raises(ParameterError, match="not an option of the slack analysis"):
        cablesys.sweep(slack_scene(), {"slack.solvr": ["dense"]}, analysis="slack", progress=False)


def test_the_verdict_fails_a_working_load_the_span_exceeds_and_passes_one_it_meets():
    eq = slack.analyze(slack_scene()).equilibrium
    t_max, t_min = float(np.max(eq.tension)), float(np.min(eq.tension))
    over = judge(slack.analyze(slack_scene(limits=Limits(safe_working_load=0.99 * t_max))))
    met = judge(slack.analyze(slack_scene(limits=Limits(safe_working_load=1.01 * t_max, least_tension=0.9 * t_min))))
    assert not passed(over) and over["peak_tension"]["value"] == t_max
    assert close(over["peak_tension"]["margin"], (0.99 - 1.0) / 0.99)
    assert passed(met) and close(met["least_tension"]["margin"], (1.0 - 0.9) / 0.9)
    low = judge(slack.analyze(slack_scene(limits=Limits(least_tension=1.01 * t_min))))
    assert not passed(low) and low["least_tension"]["value"] == t_min
    # the same through a sweep of the limit: the verdict columns say which one the span meets
    ds = cablesys.sweep(slack_scene(limits=Limits(safe_working_load=t_max)),
                        {"limits.safe_working_load": [0.99 * t_max, 1.01 * t_max]}, analysis="slack",
                        workers=1, progress=False)
    assert list(ds["verdict_pass"].values) == [0, 1]
    assert ds["limits.safe_working_load"].attrs["units"] == "N"


def test_a_towed_verdict_reads_both_steady_tensions():
    r = towed.analyze(towed_scene())
    scene = towed_scene_module.TowedScene(**{**towed_scene().__dict__,
                                             "limits": Limits(least_tension=1.01 * r.tension_bottom)})
    v = judge(towed.analyze(scene))
    assert not passed(v) and v["least_tension"]["value"] == r.tension_bottom


def test_limits_a_static_analysis_cannot_judge_are_refused_by_name():
    for name, value in (("max_daf", 2.0), ("slack_fraction", 0.1), ("max_excursion", 1.0), ("exposure", 3600.0)):
        with pytest.raises(ParameterError) as err:
            slack_scene(limits=Limits(**{name: value}))
        assert err.value.field == f"limits.{name}" and "needs a time run" in str(err.value)
    doc = tomllib.loads(towed_scene_module.EXAMPLE_TOML)
    doc["limits"] = {"max_daf": 2.0}
    with pytest.raises(ParameterError, match=r"limits\.max_daf"):
        towed_scene_module.towed_scene_from_dict(doc)
    with pytest.raises(ParameterError, match="static_tensions"):
        judge(slack.analyze(slack_scene()).modes)          # modes alone carry no tensions


def test_the_readme_and_the_docstring_list_the_registry_of_analyses():
    readme = (ROOT / "README.md").read_text()
    block = re.search(r"<!-- sweep-analyses:begin -->\n(.*?)\n<!-- sweep-analyses:end -->", readme, re.S)
    assert block and block.group(1) == analyses.analyses_markdown(), analyses.analyses_markdown()
    for name in analyses.ANALYSES:
        assert f"``{name}``" in sweep_function.__doc__


def test_the_command_sweeps_a_slack_scene_file(tmp_path, capsys):
    path = tmp_path / "span.toml"
    path.write_text(slack_scene_module.EXAMPLE_TOML.replace("n_elements = 120", "n_elements = 24")
                    .replace("n_modes = 12", "n_modes = 4") + "\n[limits]\nsafe_working_load = 1e6\n")
    out = tmp_path / "out"
    assert main(["sweep", str(path), "--analysis", "slack", "--vary", "span=22,22.9", "--out", str(out),
                 "--workers", "1", "--no-plots"]) == 0
    header = (out / "sweep.csv").read_text().splitlines()[0]
    assert "omega_n_0_rad_s [rad/s]" in header and "verdict_pass" in header
    capsys.readouterr()
    assert main(["sweep", str(path), "--analysis", "slack", "--vary", "span=22", "--duration", "3",
                 "--out", str(tmp_path / "other")]) == 2
    assert "--duration" in capsys.readouterr().err and not (tmp_path / "other").exists()
