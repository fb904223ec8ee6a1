"""A span between two supports in the time domain (studies/span_dynamics.py --quick, run once here):
free decays against the node model's linear modes, Irvine & Caughey's closed form and its lambda^2
crossover, energy conservation, the second-order amplitude shift, a decay in water, and the forced
motion of a support against the periodic orbit, the describing function and the linear response."""

import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies"))
import span_dynamics as SD  # noqa: E402

from cablesys.slack.irvine import LAMBDA2_CROSSOVER  # noqa: E402


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    out = tmp_path_factory.mktemp("span_dynamics")
    SD.main(["--out", str(out), "--quick"])
    return out, json.loads((out / "span_dynamics.json").read_text())


def rows(res, **match):
    return [r for r in res["decay"] if all(r[k] == v for k, v in match.items())]


def test_quick_study_writes_json_and_figure(study):
    out, res = study
    assert (out / "span_dynamics.png").stat().st_size > 50_000
    assert res["quick"] and res["N"] == [10, 20] and len(res["decay"]) == 8
    assert all(r["success"] for r in res["decay"] + res["water_decay"] + res["forced"])


def test_free_decay_frequency_is_the_linear_mode(study):
    """From q* + 1e-3 sag phi, the frequency fitted to the series equals the node model's linear mode
    (K phi = omega^2 M phi of the same equations) to 1e-5 at every N, lambda^2 and mode type: what is
    left is the nonlinear shift, about (1e-3 / 2.5e-3)^2 of the sweep's smallest."""
    _, res = study
    assert res["decay_vs_modes_max_rel_err"] < 1e-5
    shift = abs(res["amplitude"]["shift"][0]) * (SD.DECAY_AMPLITUDE / res["amplitude"]["amplitude_over_sag"][0]) ** 2
    assert shift < 3e-6


def test_energy_is_conserved_without_drag_or_damping(study):
    """max |E(t) - E(0)| over the oscillation's energy E(0) - E* (CVODES at rtol 1e-9 in --quick: the drift is
    the tolerance's, 1e-7 at rtol 1e-10 in the full run)."""
    _, res = study
    assert res["decay_rtol"] == 1e-9 and res["energy_drift_rel_max"] < 1e-5


def test_time_domain_crosses_where_irvine_says(study):
    """lambda^2 = 35 < 4 pi^2: S1 below A1; lambda^2 = 81 > 4 pi^2: S1 above A1 (Irvine & Caughey 1974),
    both read from the time series at N = 10 and 20."""
    _, res = study
    lo, hi = SD.SLACKS
    assert res["lambda2"][f"slack={lo:g}"] < LAMBDA2_CROSSOVER < res["lambda2"][f"slack={hi:g}"]
    for n in (10, 20):
        (s_lo,), (a_lo,) = rows(res, slack=lo, n=n, mode="S"), rows(res, slack=lo, n=n, mode="A")
        (s_hi,), (a_hi,) = rows(res, slack=hi, n=n, mode="S"), rows(res, slack=hi, n=n, mode="A")
        assert s_lo["omega_td"] < a_lo["omega_td"] and s_hi["omega_td"] > a_hi["omega_td"]


def test_decay_frequencies_converge_to_irvine_at_second_order(study):
    """S1: the error to Irvine's eq. 6 falls 4x from N = 10 to 20 (second order, 3.5 to 4.8 allowed) and the
    Richardson value of the two is within 5e-4 of it. A1: within 1 % after Richardson; Irvine's
    A1 = 2 pi / l sqrt(H / m) drops the (d / l)^2 terms of the sag (the node model's limit at N = 160
    is 0.3 % and 0.6 % below it at d / l = 0.027 and 0.036)."""
    _, res = study
    for s in SD.SLACKS:
        for typ in "SA":
            (c,), (f,) = rows(res, slack=s, n=10, mode=typ), rows(res, slack=s, n=20, mode=typ)
            rich = f["omega_td"] + (f["omega_td"] - c["omega_td"]) / 3
            err = rich / f["omega_irvine"] - 1
            if typ == "S":
                assert 3.5 < c["td_vs_irvine"] / f["td_vs_irvine"] < 4.8, s
                assert abs(err) < 5e-4, s
            else:
                assert abs(f["td_vs_irvine"]) < abs(c["td_vs_irvine"]) and abs(err) < 0.01, s


def test_frequency_shift_is_second_order_in_the_amplitude(study):
    """S1 at lambda^2 = 81: omega(a) / omega_linear - 1 ~ -c a^2 (softening), fitted power 2 +- 0.1."""
    _, res = study
    sw = res["amplitude"]
    assert all(v < 0 for v in sw["shift"])
    assert abs(sw["order"] - 2.0) < 0.1


def test_decay_in_water_keeps_the_linear_frequencies(study):
    """In water with the node model's drag, 1e-2 sag: the fitted frequencies within 1e-3 of the linear
    modes (added mass included; the drag's effect on the frequency is second order in its damping),
    and the drag takes energy out."""
    _, res = study
    assert res["span_decay_vs_modes_max_rel_err"] < 1e-3
    assert all(0 < r["energy_drift_rel"] < 1 and r["damping_ratio_mean"] > 0 for r in res["water_decay"])


def test_forced_support_settles_on_the_frequency_responses(study):
    """Top moved vertically 10 mm, span in water with drag. Away (0.5 x the first in-plane mode): the
    settled amplitude equals the exact linear response to 1e-3 and the periodic orbit to 1e-4. At the
    mode: the drag holds it (the undamped linear response is unbounded), the periodic orbit agrees to
    1e-3 and the one-harmonic describing function to 3 %; the run has settled (two windows of 10
    periods agree to 1e-5) and stays in the plane."""
    _, res = study
    away, near = sorted(res["forced"], key=lambda r: r["fraction"])
    assert away["fraction"] == 0.5 and near["fraction"] == 1.0
    assert abs(away["linear_vs_td"]) < 1e-3 and abs(away["periodic_vs_td"]) < 1e-4
    assert abs(away["describing_vs_td"]) < 1e-3
    assert abs(near["periodic_vs_td"]) < 1e-3 and abs(near["describing_vs_td"]) < 0.03
    assert abs(near["phase_td"] - near["phase_periodic"]) < 1e-3
    assert near["amplitude_td_m"] > 2 * away["amplitude_td_m"] and near["amplitude_linear_m"] > 1e3 * near["amplitude_td_m"]
    for r in (away, near):
        assert r["settled_rel"] < 1e-5 and r["max_out_of_plane_m"] < 1e-12
        assert r["periodic_success"] and r["describing_success"]


def test_fit_frequency_reads_a_known_sinusoid():
    """The estimator on y = 0.3 + cos(w t + 0.4) + 0.05 sin(2 w t) over 5 periods, 40 samples each, started 1 %
    off: w to 1e-9."""
    w = 7.3
    t = np.linspace(0, 5 * 2 * math.pi / w, 201)
    y = 0.3 + np.cos(w * t + 0.4) + 0.05 * np.sin(2 * w * t)
    assert SD.fit_frequency(t, y, 1.01 * w) == pytest.approx(w, rel=1e-9)


def test_starting_guesses_of_a_span_are_its_node_positions():
    """The periodic solve's first start on a node model (statics.steady.starting_guesses): the anchored line's
    guess, one position per free node, running from the top towards the anchor in the plane."""
    from cablesys.slack import shared
    from cablesys.statics.steady import starting_guesses
    sc = SD.span_scene(SD.SLACKS[1], 10)
    _, q, p = shared.equilibrium(sc).node_state
    model = shared.span_model(shared.to_scene(sc))
    (g,) = list(starting_guesses(model, p))
    r = g.reshape(-1, 3)
    assert g.shape == q.shape and np.all(np.isfinite(g)) and np.all(r[:, 2] == 0.0)
    assert np.all(np.diff(r[:, 0]) > 0) and 0.0 < r[0, 0] and r[-1, 0] < SD.SPAN
