"""The verdict against [limits] (cablesys/verdict.py): each criterion flips at its limit; the CLI's --strict."""

import dataclasses
import math

import numpy as np
import pytest

from cablesys import verdict as vd
from cablesys.errors import ParameterError
from cablesys.scene.limits import Limits


@dataclasses.dataclass
class _Run:
    """A stand-in for a TimeResult: a known tension and body motion."""
    time: np.ndarray
    data: dict
    events: tuple = ()
    snaps: tuple = ()
    initially_slack: tuple = ()

    @property
    def labels(self):
        return tuple(self.data)

    def __getitem__(self, k):
        return self.data[k]

    def time_slack(self):
        return 0.0


def _run():
    t = np.linspace(0, 100, 10001)
    w = 2 * np.pi / 10
    return _Run(t, {"x_b": 2.0 + 0.5 * np.sin(w * t), "y_b": 100 + 1.5 * np.sin(w * t),
                    "tension_top": 1000 + 400 * np.sin(w * t), "tension_bottom": 600 + 300 * np.sin(w * t)})


def _verdict(**limits):
    lim = Limits(statistics_start=0.0, **limits)
    r = _run()
    return vd.evaluate(lim, vd.run_statistics(r, lim))


@pytest.mark.parametrize("limits, criterion, at", [
    ({"safe_working_load": None}, "peak_tension", 1400.0),                  # max of tension_top
    ({"least_tension": None}, "least_tension", 300.0),                      # min of tension_bottom
    ({"slack_fraction": None}, "slack", 0.5),                               # 300 / 600
    ({"max_daf": None}, "daf", 1.5),                                        # 900 / 600 and 1400 / 1000
    ({"max_excursion": None}, "excursion", 1.5),                            # heave of the body
])
def test_each_criterion_flips_at_its_limit(limits, criterion, at):
    name = next(iter(limits))
    upper = criterion in ("peak_tension", "daf", "excursion")
    for factor, ok in ((1.01, upper), (0.99, not upper)):
        v = _verdict(**{name: at * factor})[criterion]
        assert v["value"] == pytest.approx(at, rel=1e-4)
        assert v["pass"] is ok
        assert (v["margin"] >= 0) is ok


def test_mbl_and_safety_factor_give_the_working_load():
    v = _verdict(minimum_breaking_load=7000.0, safety_factor=5.0)["peak_tension"]
    assert v["limit"] == pytest.approx(1400.0) and v["margin"] == pytest.approx(0.0, abs=1e-4)
    with pytest.raises(ParameterError, match="limits.safety_factor"):
        Limits(safety_factor=3.0)


def test_exposure_uses_the_most_probable_extreme_when_larger():
    """A long exposure raises the peak to the Rayleigh most probable maximum."""
    short = _verdict(safe_working_load=2000.0)["peak_tension"]["value"]
    long = _verdict(safe_working_load=2000.0, exposure=3 * 3600.0)["peak_tension"]["value"]
    sigma = 400 / np.sqrt(2)
    assert long == pytest.approx(1000 + sigma * np.sqrt(2 * np.log(3 * 3600 / 10.0)), rel=1e-3)
    assert long > short


def test_no_limits_no_verdict_and_table_text():
    assert vd.evaluate(None, {}) == {}
    lines = vd.format_table(_verdict(safe_working_load=1000.0))
    assert "FAIL" in lines[1] and lines[-1] == "verdict: FAIL"


@pytest.mark.slow
def test_run_strict_exits_nonzero_on_a_failed_criterion(tmp_path, capsys):
    """The shipped ROV lift (shortened) passes; with a working load below its peak tension,
    --strict exits 3 and the console prints FAIL."""
    from cablesys.cli import main
    from cablesys.examples import example_text
    text = example_text("rov-lift").replace("duration = 600.0", "duration = 120.0")
    ok = tmp_path / "ok.toml"
    ok.write_text(text)
    assert main(["run", str(ok), "--out", str(tmp_path / "a"), "--strict"]) == 0
    assert "verdict: PASS" in capsys.readouterr().out
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace("safety_factor = 5.0", "safety_factor = 30.0"))
    assert main(["run", str(bad), "--out", str(tmp_path / "b"), "--strict"]) == 3
    out = capsys.readouterr().out
    assert "peak_tension" in out and "FAIL" in out
    assert main(["run", str(bad), "--out", str(tmp_path / "c")]) == 0


def test_slack_and_snap_warnings_count_what_the_verdict_reads():
    """A run slack over [3.0, 3.2] s with a 5000 N snap load at 3.3 s (before the window) and a 2500 N one at
    80 s (in it): the warnings give the slack time and split the snap loads at the window; the verdict's peak
    tension is the in-window snap load, above the sampled maxima (1400 N), and not the earlier one."""
    from cablesys.results import SlackEvent, SnapLoad, TimeResult
    r = _run()
    r = TimeResult(time=r.time, data=r.data, events=(SlackEvent(time=3.0, section=0, kind="slack", rate=-5.0),
                                                     SlackEvent(time=3.2, section=0, kind="taut", rate=4.0)),
                   snaps=(SnapLoad(time=3.3, section=0, tension=5000.0), SnapLoad(time=80.0, section=0, tension=2500.0)))
    lim = Limits(statistics_start=50.0, safe_working_load=3000.0)
    rep = vd.report(type("S", (), {"limits": lim})(), r)
    w = rep["warnings"]
    assert "went slack 1 times" in w[0] and "0.2 s" in w[0]
    assert "1 snap loads in the statistics window; largest 2500 N" in w[1]
    assert "1 snap loads before the statistics window" in w[2] and "5000 N" in w[2]
    peak = rep["verdict"]["peak_tension"]
    assert peak["value"] == 2500.0 and "snap load at t = 80 s" in peak["text"]


def test_gaussian_minimum_below_zero_is_no_negative_tension_in_the_verdict():
    """Frequency-domain statistics of a tension whose most probable minimum is below -400 N: the least-tension and
    slack criteria read 0 N (and fail a positive limit), the grouped statistics show 0 with the slack
    probability."""
    from cablesys import statistics as st
    w = np.linspace(0.5, 1.5, 101)
    fd = st.frequency_domain(w, np.full(w.size, 300.0**2), duration=3 * 3600.0, mean=600.0)
    assert fd["most_probable_min"] < -400.0                          # the injected case
    stats = {"tension_top": fd}
    v = vd.evaluate(Limits(least_tension=10.0, slack_fraction=0.1, exposure=3 * 3600.0), stats)
    assert v["least_tension"]["value"] == 0.0 and not v["least_tension"]["pass"]
    assert v["slack"]["value"] == 0.0 and not v["slack"]["pass"]
    g = vd.group_by_quantity(stats)["force_N"]["tension_top"]
    assert g["most_probable_min"] == 0.0 and g["slack_probability"] == pytest.approx(0.5 * math.erfc(2 / math.sqrt(2)))


def test_design_failed_starts_are_named_with_the_reason():
    from types import SimpleNamespace

    from cablesys.isolation.cli import failed_starts
    runs = ({"outer": 0, "status": "Maximum_Iterations_Exceeded", "iterations": 100, "objective": 1.0, "max_violation": 0.0},
            {"outer": 0, "status": "Solve_Succeeded", "iterations": 12, "objective": 0.9, "max_violation": 0.0},
            {"outer": 0, "status": "Infeasible_Problem_Detected", "iterations": 30, "objective": 2.0, "max_violation": 0.5})
    f = failed_starts(SimpleNamespace(runs=runs))
    assert [x["solve"] for x in f] == [1, 3]
    assert "iteration limit" in f[0]["why"] and "constraints" in f[1]["why"]


def test_body_labels_pick_the_lowest_body_position_not_a_rate():
    """Multi-section outputs end in _k: the lowest body is the highest k, and never x_b_rate_k."""
    from cablesys.verdict import body_labels
    assert body_labels(["x_b", "x_b_rate", "y_b", "y_b_rate"]) == ("x_b", "y_b")
    labels = [f"{n}_{k}" for k in (1, 2, 10) for n in ("x_b", "x_b_rate", "y_b", "y_b_rate")]
    assert body_labels(labels) == ("x_b_10", "y_b_10")
