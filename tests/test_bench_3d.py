"""bench_vs_moordyn's 3-D cases (issue 24: turn, crane_rao, current45) in --quick mode, and their MoorDyn inputs.

No timing is asserted: the checks are physical. The crane tip moves as the rigid-body displacement of the
vessel's RAO says (Faltinsen 1990 ch. 3) in both codes; a uniform current at 45 deg pushes the line along 45 deg
in both codes and as far as the same current along x pushes the planar line; both codes' steady turn has the
steady-turn statics' radius, depth and tension.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "studies"))


def test_crane_tip_closed_form_by_hand():
    """The tip's motion from the RAO at its table point, written out for one axis: with the vessel heading psi,
    cablesys' y (down) is -s_3 = -(eta_3 + y eta_4 - x eta_5), independent of psi; the table route
    (VesselRAO.transfer through the scene's sinusoids) gives the same complex amplitudes."""
    import _bench_3d as B
    c = {d: a * (math.pi / 180 if d in ("roll", "pitch", "yaw") else 1.0) * np.exp(1j * math.radians(p))
         for d, (a, p) in B.RAO_120.items()}
    x, y, _ = B.LEVER_ARM
    heave_down = -(c["heave"] + y * c["roll"] - x * c["pitch"]) * B.WAVE_AMPLITUDE
    closed = B.tip_closed_form()
    assert closed[1] == pytest.approx(heave_down, rel=1e-12)
    # horizontal size is the vessel-axes size whatever the heading
    s1 = c["surge"] + B.LEVER_ARM[2] * c["pitch"] - y * c["yaw"]
    s2 = c["sway"] - B.LEVER_ARM[2] * c["roll"] + x * c["yaw"]
    assert abs(closed[0]) ** 2 + abs(closed[2]) ** 2 == pytest.approx(abs(s1) ** 2 + abs(s2) ** 2, rel=1e-12)
    sc = B.crane_scene(20.0)
    for axis, v in zip("xyz", closed):
        (s,) = getattr(sc.top_motion, axis)
        assert s.amplitude == pytest.approx(abs(v), rel=1e-9)
        assert math.sin(s.phase) == pytest.approx(math.sin(np.angle(v)), abs=1e-9)
        assert math.cos(s.phase) == pytest.approx(math.cos(np.angle(v)), abs=1e-9)


def test_moordyn_current_profile_along_its_heading():
    """cablesys' current (depth below the surface, heading from +x towards +z) becomes MoorDyn's profile in its
    axes (z up, Y = cablesys z): ux = c cos h, uy = c sin h, ascending z, and the Currents option is set."""
    import _bench_3d as B
    from _moordyn import current_option, current_profile_text, moordyn_axes
    sc = B.current_scene(20.0)
    rows = [[float(v) for v in line.split()] for line in current_profile_text(sc).splitlines()[3:]]
    assert [r[0] for r in rows] == sorted(r[0] for r in rows) and rows[-1][0] == 0.0
    for r in rows:
        assert r[1:] == pytest.approx([B.CURRENT_SPEED / math.sqrt(2), B.CURRENT_SPEED / math.sqrt(2), 0.0], rel=1e-9)
    assert current_option(sc).split()[1] == "Currents"
    # (x, y down, z) -> (X, Y, Z up) is a rotation: right-handed both
    R = moordyn_axes(np.eye(3))
    assert np.linalg.det(R) == pytest.approx(1.0)
    assert np.allclose(moordyn_axes([1.0, 2.0, 3.0]), [1.0, 3.0, -2.0])


@pytest.mark.slow
def test_quick_3d_cases_agree_with_closed_forms_and_moordyn(tmp_path):
    pytest.importorskip("moordyn", reason="the 'bench' extra (MoorDyn v2 wheel)")
    import bench_vs_moordyn
    bench_vs_moordyn.main(["--out", str(tmp_path), "--quick", "--case", "turn", "--case", "crane_rao",
                           "--case", "current45"])
    check_quick_rows(json.loads((tmp_path / "bench_vs_moordyn.json").read_text()))


def check_quick_rows(data):
    """The assertions of the quick 3-D benchmark on its JSON."""
    rows = {r["case"]: r for r in data["cases"]}
    assert set(rows) == {"turn", "crane_rao", "current45"}
    for r in rows.values():
        (e,) = r["by_n"]
        assert e["moordyn_stable"] and "z_b_amplitude" in e["cablesys_stats"] and "z_b_amplitude" in e["moordyn_stats"]
        err = e["cablesys_settings"]["error_vs_own_tight"]
        assert err["body"] <= 0.005 and err["tension"] <= 0.01      # matched accuracy was reached
        assert e["speedup"] > 0 and r["planar_ratio"] > 0
    # the planar scene runs the planar equations; the 3-D equations on it give the same answer
    planar = rows["turn"]["planar"]
    assert planar["model_dim"] == {"dispatched": 2, "planar_path": 2, "three_d_equations": 3}
    assert planar["planar_equivalence_max_abs"] < 1e-2     # m and N (tensions ~8 kN) at rtol 1e-10
    # crane tip: both codes move the top as the rigid-body displacement of the RAO says
    c = rows["crane_rao"]["checks"]
    # both from samples of the last period (401 and 201): the peak between samples, (pi / 200)^2 / 2 ~ 1e-4
    assert c["cablesys_vs_closed_form_max_rel"] < 3e-4
    assert c["moordyn_vs_closed_form_max_rel"] < 3e-4
    # current at 45 deg: the offset points along it in both codes, as far as the planar line's along x
    k = rows["current45"]["checks"]
    assert k["cablesys"]["offset_heading_deg"] == pytest.approx(45.0, abs=1e-6)
    assert k["moordyn"]["offset_heading_deg"] == pytest.approx(45.0, abs=1e-3)
    assert k["offset_vs_planar_rel"] < 1e-6 and k["depth_vs_planar_rel"] < 1e-6
    assert k["moordyn"]["offset_m"] == pytest.approx(k["cablesys"]["offset_m"], rel=0.02)
    # steady turn: radius, depth and top tension of both codes against the steady-turn statics
    t = rows["turn"]["checks"]
    assert t["cablesys"]["radius_rel_err"] < 1e-4 and t["cablesys"]["tension_top_rel_err"] < 1e-4
    for q in ("radius_rel_err", "depth_rel_err", "tension_top_rel_err"):
        assert t["moordyn"][q] < 0.02, q
