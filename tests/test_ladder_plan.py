"""How auto divides the cable (issue 12: "never a rung that a cheaper rung beats"): the cheapest of the node
model and the quasi-static segmented cable, with N sure (its estimate within half the tolerance) or checked a
posteriori against N / 2 (within the tolerance), and the note when a run ends before its response settles.

The scene is the model-ladder study's long heavy cable (1000 m steel wire, 300 kg sphere, 1 m surge and heave at
T = 10 s: forced at 2.7x its first string mode, omega/omega_ax = 0.152). Its settled errors against the converged
cable (model_ladder study, 120 s, vs N = 40): quasi-static segmented N = 5 / 6 / 8 0.94 / 0.49 / 1.13 %, the node
model N = 9 / 10 0.96 / 0.77 %.
"""

import math
import shutil
import warnings

import numpy as np
import pytest
from ladder_pricing import both, priced, said
from test_ladder_random import random_scene

from cablesys.errors import NumericalWarning
from cablesys.ladder import choice as ch
from cablesys.ladder import estimate as est
from cablesys.ladder import metrics, run_rung, simulate
from cablesys.ladder.auto import explicit_or_node, node_model
from cablesys.ladder.indicators import scene_numbers
from cablesys.ladder.rungs import RungCache
from cablesys.scene import heavy_wire_scene

needs_cc = pytest.mark.skipif(shutil.which("cc") is None, reason="no C compiler")
TOL = (0.01, 0.02)


@pytest.fixture(scope="module")
def heavy():
    """(scene, its choice in CasADi's VM) of the 1000 m wire, 120 s (choosing only: no run); the choice compiled
    code gets is :func:`heavy_compiled`'s."""
    scene = heavy_wire_scene(duration=120.0)
    with priced(False):
        c = ch.choose(scene)
    return scene, c


@pytest.fixture(scope="module")
def heavy_compiled(heavy):
    """The 1000 m wire's choice priced as compiled code runs (as users run)."""
    with priced(True):
        return ch.choose(heavy[0])


def test_estimates_of_the_heavy_wire_have_no_straight_cable_floor(heavy):
    """Above the first string mode the segmented estimate is the continuum's and the element-by-element
    drag's, not the straight cable's error x N^-2 (46.7 % x N^-2 would state 1.30 % at N = 6): at N = 6
    the local-drag table, 0.84 % (settled 0.59 %), at N = 9 0.46 % (settled 0.71 %), within 2x."""
    _, c = heavy
    errs = c.numbers["estimates"]
    assert errs["segmented_1"]["floor"] == 0.0                     # no current: no static bow
    e6, e9 = (est.segmented_error(errs, n)["body"] for n in (6, 9))
    assert e6 == pytest.approx(0.0084, rel=0.05) and e9 == pytest.approx(0.0046, rel=0.05)
    for n, settled in ((6, 0.0059), (9, 0.0071)):
        assert 0.5 <= est.segmented_error(errs, n)["body"] / settled <= 2.0
    # the quasi-static segmented cable adds the stretch's part, r^2 / |1 - r^2| of the dynamic stretch
    stretch = errs["quasi-static"]["stretch"]["body"]
    assert est.quasistatic_segmented_error(errs, 6)["body"] == pytest.approx(e6 + stretch)
    assert 0.0005 < stretch < 0.002


def test_uncompiled_the_node_model_runs_its_sure_n(heavy, heavy_compiled):
    """In CasADi's VM (the explicit pair needs compiled code) the quasi-static segmented cable does not
    compete (omega/omega_ax = 0.152 > 1/30); the node model's sure N = 9 (0.46 %, cost 9) ties with its
    checked N = 6 (0.84 %, cost 1.5 x 6) and the sure one wins the tie. The reason names what compiled code
    runs instead (the quasi-static segmented cable at N = 6: the next test)."""
    scene, c = heavy
    said(heavy_compiled, c)
    assert c.reason.endswith("with it the ladder would run quasi-static N = 6")
    assert c.name == "segmented" and c.segments == 9
    assert c.numbers["plan"] == {"name": "segmented", "segments": 9, "checked": False, "explicit_only": False,
                                 "cost": 9.0, "fallback": None}
    assert c.estimated_error["body"] <= ch.SAFETY * TOL[0]
    assert "the least N with its estimate within 0.5 x the tolerance" in c.reason


def test_compiled_the_quasi_static_segmented_cable_checked_at_n_6_is_cheapest(heavy, heavy_compiled):
    """Compiled, the quasi-static segmented cable stepped by rk23 costs 0.7 of the node model per element:
    N = 6 checked (estimate 0.95 %, within 1 % but not 0.5 %) costs 0.7 x 1.5 x 6 = 6.3 against the node
    model's 9; no N <= 8 of it is sure (N = 8: 0.91 %)."""
    scene, c = heavy
    numbers = scene_numbers(scene)
    plan = ch.element_plan(scene, numbers, c.numbers["estimates"], TOL, compiled=True)
    assert (plan.name, plan.segments, plan.checked, plan.explicit_only) == ("quasi-static", 6, True, True)
    assert plan.cost == pytest.approx(ch.EXPLICIT_COST * ch.CHECK_COST * 6)
    e = est.rung_error(c.numbers["estimates"], "quasi-static", 6)
    assert ch.SAFETY * TOL[0] < e["body"] <= TOL[0]
    assert all(est.rung_error(c.numbers["estimates"], "quasi-static", n)["body"] > ch.SAFETY * TOL[0]
               for n in range(2, ch.EXPLICIT_MAX_ELEMENTS + 1))
    chosen = heavy_compiled
    assert (chosen.name, chosen.segments) == ("quasi-static", 6)
    assert chosen.numbers["plan"] == plan.as_dict()
    # the check's fallback is the cheapest sure option, the node model's sure N = 9 (the VM's choice)
    assert plan.fallback == {"name": "segmented", "segments": 9, "explicit_only": False}
    assert "checked a posteriori against N = 3" in chosen.reason


def test_the_explicit_only_plan_falls_back_to_the_node_model(heavy_compiled, heavy, monkeypatch):
    """A quasi-static segmented choice made for the explicit pair's sake (the compiled choice) becomes the node
    model at the same N, with the node model's estimate, when the pair will not step it (here: CasADi's VM, where
    the guard does not run the explicit pair; also a method named by the caller). Compiled, the pair steps it
    (test_compiled_auto_on_the_heavy_wire_within_tolerance)."""
    scene, c = heavy[0], heavy_compiled
    monkeypatch.setenv("CABLESYS_COMPILE", "0")     # the guard's VM, whatever the module's fixtures set
    cache = RungCache()
    for kw in ({}, {"method": "cvodes"}):
        got = explicit_or_node(scene, c, TOL, cache, kw)
        assert (got.name, got.segments) == ("segmented", 6)
        assert got.estimated_error["body"] == pytest.approx(est.segmented_error(c.numbers["estimates"], 6)["body"])
        assert "the node model with N = 6 instead" in got.reason
    # a plan that was not made for the pair is left alone
    plain = node_model(c, "test")
    assert explicit_or_node(scene, plain, TOL, cache) is plain


def test_dale_keeps_its_sure_n():
    """Dale at omega_n and 2 omega_n: N = 4 and 3 are sure (0.40 % and 0.37 % estimated), and a checked N >= 4
    would cost more (1.5 x 4): the plan does not change them."""
    from cablesys.scene import dale_scene
    for ratio, n in ((1.0, 4), (2.0, 3)):
        for c in both(dale_scene(omega_ratio=ratio, duration=60.0)):      # compiled and in the VM alike
            assert c.segments == n and c.numbers["plan"]["checked"] is False, c.reason


def test_a_window_before_the_response_settles_is_noted():
    """Random heavy-6 over 7 periods (the run whose start-up transient the straight-cable floor had covered):
    its statistics window starts at 15.5 s, before the surge has travelled down the wire and the body's mean
    offset in the 0.066 m/s current has crept to its mean (settling time 16.2 periods: ramp, string travel and
    ln(100) x tau_slow, tau_slow 12 s), and the reason says so with the run length that would do; 25 periods
    carry no note."""
    scene = random_scene(np.random.default_rng(6), "heavy")
    period = metrics.forcing_period(scene)
    settle = est.settling_time(scene)
    assert 3.5 * period < settle < 25 * period - 5 * period
    note = ch.settling_note(scene)
    assert "before the forced response settles" in note and f"{settle:.4g} s" in note
    for c in both(scene):
        assert note in c.reason
    long = scene.with_numerics(duration=25 * period)
    assert ch.settling_note(long) == ""
    # the length it asks for is enough: a window of min(5 periods, half the run) then starts at the settling time
    need = float(note.rsplit("run at least ", 1)[1].split(" s")[0])
    assert ch.settling_note(scene.with_numerics(duration=need * 1.001)) == ""


@pytest.mark.slow
@needs_cc
def test_compiled_auto_on_the_heavy_wire_within_tolerance(compiling):
    """Auto compiled on the heavy wire (120 s) held to the body and tension groups only (``quantities=()``: the body
    amplitudes over the largest, the tension extremes over the top tension): quasi-static segmented N = 6 with
    rk23, checked against N = 3; against the node model at N = 40 (CVODES rtol 1e-7; 0.17 % from N = 20 in the
    study) its body error is within the tolerance and its stated estimate (Richardson 0.31 % + the stretch's
    0.11 %) within 2x of it; the tension's actual error (0.11 %, below a tenth of its 2 % tolerance) is stated
    within the tolerance. The same check per quantity flags the body's surge amplitude, a few centimetres under
    1 m of heave, as outside the tolerance, and it is (against N = 40): the default, every quantity held to the
    tolerance, runs far more elements on this wire."""
    scene = heavy_wire_scene(duration=120.0)
    period = metrics.forcing_period(scene)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NumericalWarning)
        got = simulate(scene, quantities=())
    m = got.stats["model"]
    assert (m["name"], m["segments"]) == ("quasi-static", 6), m["reason"]
    assert "a posteriori (N = 6 vs 3" in m["reason"]
    ref = metrics.statistics(run_rung(scene, "segmented", 40), period)
    actual = metrics.errors(metrics.statistics(got, period), ref)
    stated = m["estimated_error"]
    assert actual["body"] <= TOL[0] and actual["tension"] <= TOL[1]
    assert 0.5 <= stated["body"] / actual["body"] <= 2.0
    assert stated["tension"] <= TOL[1] and math.isfinite(stated["tension"])
    surge = metrics.quantity_errors(metrics.statistics(got, period), ref)["x_b_amplitude"]
    assert m["estimated_error_per_quantity"]["x_b_amplitude"] > TOL[0] and surge > TOL[0]


def test_a_run_still_building_up_says_so():
    """Random heavy-6 (forced at 1.55x its first string mode, 4.4 s period): over 7 periods the body amplitude
    changes by ~0.2 between the halves of the statistics window, far above the stated error, and auto's reason
    says the run has not settled; over 20 periods it changes by < 1e-3 and nothing is said."""
    scene = random_scene(np.random.default_rng(6), "heavy")
    period = metrics.forcing_period(scene)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NumericalWarning)
        short = simulate(scene)
        long = simulate(scene.with_numerics(duration=20 * period))
    assert metrics.window_change(short, period) > 0.1
    assert "the run has not settled" in short.stats["model"]["reason"]
    assert metrics.window_change(long, period) < 1e-3
    assert "has not settled" not in long.stats["model"]["reason"]


def test_a_checked_n_that_misses_its_check_runs_the_sure_n():
    """Random heavy-9 (forced at its first string mode): the node model checked at N = 6 (estimate 0.82 %,
    cost 9) beats the sure N = 10 (0.48 %) a priori; its check against N = 3 states more than CHECK_ACCEPT x the
    tolerance (the 7-period run is still building up), so auto runs the sure N = 10 and says why; N = 10 is checked
    in turn, against N = 5 with one drag point per element as N = 10 has (choice.check_scene), and grows as that
    check asks: no run of N >= 4 is left with its a priori estimate alone."""
    scene = random_scene(np.random.default_rng(9), "heavy")
    c, vm = both(scene)           # compiled, the quasi-static segmented cable does not beat it: the same plan
    assert vm.numbers["plan"] == c.numbers["plan"]
    plan = c.numbers["plan"]
    assert (plan["name"], plan["segments"], plan["checked"]) == ("segmented", 6, True)
    assert plan["fallback"] == {"name": "segmented", "segments": 10, "explicit_only": False}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NumericalWarning)
        got = simulate(scene, quantities=())      # the body and tension groups: the plan's own measure
    m = got.stats["model"]
    assert f"not within {ch.CHECK_ACCEPT:g} x the tolerance: segmented with N = 10" in m["reason"]
    assert "a posteriori (N = 10 vs 5, one drag point per element in both" in m["reason"]
    n = m["segments"]
    assert m["name"] == "segmented" and m["checked"] == f"a posteriori: N = {n} against N = {n // 2}"
    # stated: the check's estimate, never below the a priori one at that N
    assert m["estimated_error"]["body"] >= est.segmented_error(c.numbers["estimates"], n)["body"]
    assert m["estimated_error"]["body"] <= ch.CHECK_ACCEPT * TOL[0] or n == ch.MAX_SEGMENTS


def test_a_checked_n_and_its_half_share_the_drag_rule(heavy):
    """With 10 drag points per section an element has two or more up to N = 6 and one from N = 7, where the
    segmented error changes sign: N = 7..13 and their halves (3..6) lie across the switch, N = 4..6 and 14.. do
    not. The check of N = 7..13 runs N / 2 with one drag point per element, as N has (ch.check_scene); the others
    run the scene's own rule."""
    from cablesys.model.segmented import drag_points
    scene, _ = heavy
    assert [n for n in range(4, 16) if not ch.checkable(scene, n)] == list(range(7, 14))
    for n in range(4, 40):
        coarse = ch.check_scene(scene, n)
        assert (drag_points(coarse, n // 2) > 1) == (drag_points(scene, n) > 1), n
        assert (coarse is scene) == ch.checkable(scene, n)
