"""The steady rung (cablesys/ladder/rung/steady.py, cablesys/ladder/steady_tow.py): a towing ship's steady turn or
straight tow answered by the node model's steady state carried with the tow, against the node model stepped in time
(an independent route), its stability against a perturbed run (the rotating-frame linearization A = J - Omega_hat),
where it must decline, the honesty of its a posteriori error, and the CLI's words."""

import json
import sys
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg
import tomllib

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies"))
import _tracks  # noqa: E402
from _turning import TOW  # noqa: E402

import cablesys  # noqa: E402
from cablesys.cli import main  # noqa: E402
from cablesys.ladder import RungCache, metrics, steady_tow  # noqa: E402
from cablesys.ladder.auto import decide, run_rung  # noqa: E402
from cablesys.ladder.rung.steady import RUNG as STEADY  # noqa: E402
from cablesys.ladder.rungs import rung_scene  # noqa: E402
from cablesys.scene import scene_from_dict  # noqa: E402
from cablesys.scene.toml_io import dump_scene  # noqa: E402
from cablesys.time_domain import IntegratorSettings, Simulator  # noqa: E402
from cablesys.time_domain import simulate as step  # noqa: E402
from cablesys.time_domain.initial import initial_state  # noqa: E402

STRAIGHT = '[top_motion.track]\nkind = "straight"\nspeed = 2.0\nheading_deg = 30.0\n'


def _turn(duration=30.0, **body):
    """studies/_turning.py's tow: 60 m of wire and a 3 kN body on a circle of 80 m at 2 m/s (0.025 rad/s)."""
    text = TOW
    for k, v in body.items():
        text = text.replace("[body]\n", f"[body]\n{k} = {v}\n") if k not in text else text.replace(
            next(line for line in text.splitlines() if line.startswith(f"{k} =")), f"{k} = {v}")
    return scene_from_dict(tomllib.loads(text)).with_numerics(duration=duration, output_step=0.5)


def _stepped(sc, n, rtol=1e-8):
    """The node model at N stepped by CVODES at ``rtol`` (CasADi's virtual machine: no compile), from the scene's own
    start (the steady state the statics find)."""
    model = RungCache().model(sc, "segmented", n)
    run = rung_scene(sc, "segmented", n)
    sim = Simulator(model, run.output_times, IntegratorSettings(method="cvodes", rtol=rtol, atol=1e-2 * rtol,
                                                                compiled=False))
    r = step(run, model=model, simulator=sim)
    assert r.success, r.message
    return r


def _stats(sc, r):
    return metrics.statistics(r, metrics.forcing_period(sc), sc.top_motion.effective_ramp_s)


@pytest.mark.parametrize("kind", ["turn", "straight"])
def test_auto_answers_a_steady_tow_by_its_steady_state_as_the_stepped_node_model_does(kind):
    """Auto picks the steady rung for a steady turn and for a straight tow (on a heading: 3-D); its statistics (body
    radius and depth through the x, z amplitudes and means, top tension extremes, ...) are those of the node model at the
    same N stepped in time at rtol 1e-8, each within 1e-5 of its own value (floors of metrics.quantity_errors: 1 cm is
    the floor of a length, so 1e-5 of it is 0.1 mm); the series carry the node model's labels and states."""
    n = 8 if kind == "turn" else 6
    sc = _turn() if kind == "turn" else _tracks.scene(STRAIGHT, n=n, duration=30.0, output_step=0.5)
    r = cablesys.simulate(sc, segments=n)
    info = r.model_info
    assert (info["name"], info["segments"]) == ("steady", n)
    assert ("steady turn" if kind == "turn" else "steady straight tow") in info["reason"]
    assert "least damped" in info["reason"] and "a posteriori (N = " in info["reason"]
    assert r.stats["ladder_timing"]["runs"][0]["steps"] == 0 and r.stats["steady"]["stable"]
    # the carried state solves the ODE: f(y, 0) = Omega_hat y (turn) or (V, 0) (tow), m/s and m/s^2; a wrong sign of
    # Omega_hat would leave the tow point's speed, 2 m/s
    assert r.stats["steady"]["residual"] < 1e-6
    stepped = _stepped(sc, n)
    assert set(stepped.labels) <= set(r.labels) and r.states.shape == stepped.states.shape
    got, ref = _stats(sc, r), _stats(sc, stepped)
    err = metrics.quantity_errors(ref, got)
    assert set(err) == set(metrics.quantity_errors(ref, ref)) and max(err.values()) < 1e-5, err
    if kind == "turn":      # the body goes round a circle about the centre: its radius is constant on the steady turn
        radius = np.hypot(r["x_b"], r["z_b"])
        assert np.ptp(radius) < 1e-9 * radius[0] and np.ptp(r["y_b"]) < 1e-9 * r["y_b"][0]
        assert np.max(np.abs(np.hypot(stepped["x_b"], stepped["z_b"]) - radius)) < 1e-5 * radius[0]


def test_the_rotating_frame_linearization_predicts_a_perturbed_run():
    """A = J - Omega_hat (cablesys/ladder/steady_tow.py): the turn at N = 4 started off its steady state along the
    least-damped slow eigenvector (1 mm) and stepped at rtol 1e-10; turned back by -Omega t, its departure from the
    steady turn is exp(A t) of the first one to 1e-3 (the quadratic terms at 1 mm), where exp(J t) alone (the earth
    frame's Jacobian, no -Omega_hat) is 10 % off by 5 s. Every eigenvalue of A has a negative real part."""
    sc = _turn(duration=10.0).with_numerics(output_step=1.0)
    n, w = 4, sc.top_motion.track.turn_rate
    model = RungCache().model(sc, "segmented", n)
    run = rung_scene(sc, "segmented", n)
    p = model.parameters(run)
    y = initial_state(run, model, p)
    A, J = steady_tow.frame_matrix(model, y, p, w), steady_tow.frame_matrix(model, y, p, 0.0)
    lam, vec = np.linalg.eig(A)
    assert np.all(lam.real < 0)
    assert steady_tow.stability(model, y, p, w)["stable"]
    slow = max((k for k in range(lam.size) if abs(lam[k]) < 1.0), key=lambda k: lam[k].real)
    d0 = np.real(vec[:, slow])
    d0 *= 1e-3 / np.max(np.abs(d0[:model.nq]))
    sim = Simulator(model, run.output_times, IntegratorSettings(method="cvodes", rtol=1e-10, atol=1e-12, compiled=False))
    r = step(run, model=model, simulator=sim, x0=y + d0)
    for k in (5, 10):
        t = r.time[k]
        d = steady_tow._rotated(r.states[:, k], np.array([-w * t]))[:, 0] - y
        good, bad = scipy.linalg.expm(A * t) @ d0, scipy.linalg.expm(J * t) @ d0
        assert np.linalg.norm(d - good) < 1e-3 * np.linalg.norm(good)
        assert np.linalg.norm(d - bad) > 0.1 * np.linalg.norm(bad)


def test_the_rung_declines_what_is_not_a_steady_tow_and_says_why():
    """A zig-zag, a body whose virtual masses differ in x and z on a circle (statics/turning.heading_dependent_bodies),
    a rigid body on a straight tow: valid() says why in a sentence, auto steps the node model, and naming the rung is an
    error with that reason."""
    zigzag = _tracks.scene(_tracks.ZIGZAG.format(heading=0.0), n=4)
    uneven = _turn(mass_z=550.0)
    rigid = _tracks.scene(STRAIGHT, n=4).replace_section(0, body={"pitch_inertia": 50.0})
    for sc, words in ((zigzag, "'zig-zag' track changes the tow's heading"), (uneven, "body.mass_z = 550"),
                      (rigid, "a rigid body")):
        why = STEADY.valid(sc)
        assert words in why, why
        choice, _, _ = decide(sc, "auto", None, None)
        assert choice.name == "segmented"
        with pytest.raises(cablesys.ParameterError, match="numerics.model = 'steady'"):
            decide(sc, "steady", None, None)
    assert STEADY.valid(_turn()) == "" and "no towing ship's track" in STEADY.valid(cablesys.dale_scene())
    named = _turn().with_numerics(model="steady")            # numerics.model names it as any rung
    assert decide(named, None, None, None)[0].name == "steady"
    with pytest.raises(cablesys.ParameterError, match="x0"):  # a start off the steady state is not its question
        cablesys.simulate(named, x0=np.zeros(6))


def test_an_unstable_verdict_sends_auto_to_the_stepped_run(monkeypatch):
    """With a margin no eigenvalue can meet (Re lambda < -10 max |lambda|) the steady turn counts as not stable: auto
    runs the node model in time at the same N, its reason naming the least-damped eigenvalue."""
    monkeypatch.setattr(steady_tow, "STABILITY_MARGIN", 10.0)
    sc = _turn(duration=4.0)
    r = cablesys.simulate(sc, segments=4)
    info = r.model_info
    assert (info["name"], info["segments"]) == ("segmented", 4)
    assert "NOT stable: its least-damped eigenvalue" in info["reason"] and "time-domain run with N = 4 instead" in \
        info["reason"]
    assert r.stats["ladder_timing"]["runs"][-1]["steps"] > 0


def test_the_stated_error_of_steady_states_is_honest():
    """Auto's stated error per quantity (N = 8 against 4 and 2, Richardson) is at least the actual error against
    the steady turn at N = 32, and both are within the 1 % tolerance."""
    sc = _turn(duration=40.0)
    cache = RungCache()
    r = cablesys.simulate(sc, segments=8, cache=cache)
    info = r.model_info
    assert (info["name"], info["segments"]) == ("steady", 8) and "N = 2 too" in info["reason"]
    actual = metrics.quantity_errors(_stats(sc, run_rung(sc, "steady", 32, cache=cache)), _stats(sc, r))
    stated = info["estimated_error_per_quantity"]
    assert set(actual) == set(stated)
    assert all(stated[k] >= actual[k] for k in stated), {k: (stated[k], actual[k]) for k in stated}
    assert max(stated.values()) < 0.01 and max(info["estimated_error"].values()) < 0.01


def test_cablesys_run_on_a_tow_says_the_steady_rung_ran(tmp_path, capsys):
    f = tmp_path / "tow.toml"
    f.write_text(dump_scene(_turn(duration=20.0).replace_section(0, cable={"segments": 4})))
    assert main(["run", str(f), "--out", str(tmp_path / "out")]) == 0
    text = capsys.readouterr().out
    assert "model steady, N = 16" in text and "steady turn" in text and "least damped" in text
    assert "not stepped (steady state" in text and "integrator" not in text     # no integrator to name
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["model"]["name"] == "steady" and summary["success"]
