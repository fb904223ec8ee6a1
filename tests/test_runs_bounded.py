"""Runs that end: the model's size is predicted before it is built, and a plan past the limit is not built.

The Dale cable in a 2.5 m/s current (1 s of motion) needs N = 82 for the tolerance; the quasi-static segmented
cable at that N is about 5 M generated operations (over 14 GB to build and compile). The ladder predicts that
size (:func:`cablesys.ladder.choice.model_operations`), runs the node model there and says why; a user who forces
the quasi-static rung at that N gets a named refusal before anything is built.
"""

import json
import os
import re
import resource
import subprocess
import sys

import pytest

from cablesys.errors import NumericalWarning, ParameterError
from cablesys.ladder import choice as C
from cablesys.ladder.auto import decide
from cablesys.ladder.rungs import RungCache, rung_scene
from cablesys.model.quasistatic import _build_quasistatic, default_iterations
from cablesys.scene.toml_io import load_scene

HANG_GUARD_S = 300               # only against a hang: the bounded run ends in seconds
MEMORY_CAP_BYTES = 4 * 2 ** 30   # address space of the run; the unbounded plan needed > 14 GB
CURRENT = 2.5                    # m/s, the reported scene


def _scene_file(tmp_path):
    """The reported scene as a user makes it: the example, a 2.5 m/s current, 1 s of motion."""
    text = subprocess.run([sys.executable, "-m", "cablesys.cli", "scene", "--example"], capture_output=True,
                          text=True, check=True, timeout=HANG_GUARD_S).stdout
    text, k1 = re.subn(r"(?m)^current_speeds = \[0\.0\]", f"current_speeds = [{CURRENT}]", text)
    text, k2 = re.subn(r"(?m)^duration = [0-9.]+", "duration = 1.0", text)
    assert (k1, k2) == (1, 1), "the example scene no longer has the fields this test edits"
    f = tmp_path / "dale_current.toml"
    f.write_text(text)
    return f


@pytest.fixture(scope="module")
def scene_file(tmp_path_factory):
    return _scene_file(tmp_path_factory.mktemp("strong_current"))


def _capped():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_CAP_BYTES, MEMORY_CAP_BYTES))


def test_strong_current_dale_run_ends_within_memory_and_says_why(scene_file, tmp_path):
    """`cablesys run` on the reported scene, under a 4 GB address-space cap and a hang guard: it finishes, runs
    the node model at the N the estimates ask for, its a posteriori check within the tolerance, and the reason
    names the quasi-static plan it did not build (its N and predicted size)."""
    scene, out = scene_file, tmp_path / "out"
    proc = subprocess.run([sys.executable, "-m", "cablesys.cli", "run", str(scene), "--out", str(out)],
                          capture_output=True, text=True, timeout=HANG_GUARD_S, preexec_fn=_capped,
                          env=dict(os.environ, MPLBACKEND="Agg"))
    assert proc.returncode == 0, proc.stderr[-3000:]
    summary = json.loads((out / "summary.json").read_text())
    assert summary["status"] == "success" and summary["success"]
    model = summary["model"]
    assert model["name"] == "segmented"
    assert C.model_operations(load_scene(scene), "segmented", model["segments"]) <= C.MAX_MODEL_OPERATIONS
    assert model["estimated_error"]["body"] <= 0.01 and model["estimated_error"]["tension"] <= 0.02
    assert "the quasi-static segmented cable would need N = " in model["reason"]
    assert "the node model runs instead" in model["reason"]


def test_predicted_size_matches_the_built_quasistatic_cable(scene_file):
    """The prediction against the operation count of the built functions (ODE plus outputs) at N = 16 and 24,
    within 25 %; and it grows faster than N^2 (the reason the cap is on operations, not elements)."""
    sc = load_scene(scene_file)
    counts = {}
    for n in (16, 24):
        s = rung_scene(sc, "quasi-static", n)
        m = _build_quasistatic(s, None, default_iterations(s))
        counts[n] = m.ode.n_instructions() + m.outputs.n_instructions()
        predicted = C.model_operations(sc, "quasi-static", n)
        assert abs(predicted / counts[n] - 1.0) < 0.25, (n, predicted, counts[n])
    assert counts[24] / counts[16] > (24 / 16) ** 2


def test_auto_never_plans_a_quasistatic_cable_past_the_limit(scene_file):
    """Auto's plan on the reported scene stays within MAX_MODEL_OPERATIONS; without the cap it would be the
    quasi-static cable at the N the reason names, whose predicted size is past the limit."""
    sc = load_scene(scene_file)
    choice, tol, auto = decide(sc, None, None, None, RungCache())
    assert auto
    assert C.model_operations(sc, choice.name, choice.segments) <= C.MAX_MODEL_OPERATIONS
    need = int(re.search(r"would need N = (\d+)", choice.reason).group(1))
    assert need > C.quasistatic_max_segments(sc)
    assert C.model_operations(sc, "quasi-static", need) > C.MAX_MODEL_OPERATIONS
    assert C.model_operations(sc, "quasi-static", C.quasistatic_max_segments(sc)) <= C.MAX_MODEL_OPERATIONS
    assert C.model_operations(sc, "quasi-static", C.quasistatic_max_segments(sc) + 1) > C.MAX_MODEL_OPERATIONS


def test_forced_quasistatic_past_the_limit_is_refused_before_building(scene_file):
    """`--model quasi-static` with N = 82 is a ParameterError naming the field, the value, the largest N built
    and what to run instead; the cache holds no quasi-static model afterwards (nothing was built)."""
    sc = load_scene(scene_file)
    cache = RungCache()
    with pytest.raises(ParameterError) as err:
        decide(sc, "quasi-static", None, 82, cache)
    e = err.value
    assert (e.field, e.value) == ("cable.segments", 82)
    assert f"up to N = {C.quasistatic_max_segments(sc)}" in str(e)
    assert "--model segmented" in str(e) and "--model wang" in str(e) and "model_tolerance" in str(e)
    assert not any(key[0] == "quasi-static" for key in cache._models)
    with pytest.warns(NumericalWarning, match="OUTSIDE its validity"):     # built, with its stated error
        ok, _, _ = decide(sc, "quasi-static", None, C.quasistatic_max_segments(sc), RungCache())
    assert ok.segments == C.quasistatic_max_segments(sc)
