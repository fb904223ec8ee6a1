"""The other-ends rows of studies/bench_vs_moordyn.py (issue 25: mooring, lowering) in --quick mode, and their mapping.

No timing is asserted (the machine may be shared). The checks are physical: the MoorDyn seabed options give the same
normal force and friction slope as cablesys's seabed; both codes' static fairlead force approaches the elastic
catenary with seabed contact (closed form) the same way; both codes' lowering tension follows the closed form
W_b + w L - 1/2 rho C_D A v^2; and the same quantities (end element against end segment) agree between the codes.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "studies"))

pytest.importorskip("moordyn", reason="the 'bench' extra (MoorDyn v2 wheel) is installed by the README's test command")


def test_moordyn_seabed_options_give_our_contact_force_and_friction_slope():
    """kBot d_v = k d_0 and cBot d_v = c d_0 (the force per unit length of bed contact, MoorDyn's B_z = (kBot delta -
    cBot delta') d_v l against ours (k delta + c delta') d_0 l); mu FricDamp = mu w l / v_s, the slope at rest of our
    mu F_n tanh(v / v_s) for a node under its own weight in water; the anchor is a fixed point on the bed."""
    from _bench_ends import mooring_scene
    from _moordyn import ends_input, volume_diameter

    n = 20
    sc = mooring_scene(n)
    text = ends_input(sc, n, 1e-3)
    opts = {line.split()[1]: float(line.split()[0]) for line in text.splitlines()
            if len(line.split()) == 2 and line.split()[1] in ("WtrDpth", "kBot", "cBot", "FrictionCoefficient",
                                                              "FricDamp", "StatDynFricScale")}
    d_v, bed, c = volume_diameter(text), sc.seabed, sc.sections[0].cable
    assert d_v > c.diameter                    # the chain's displacement is not its hydrodynamic diameter's
    assert opts["kBot"] * d_v == pytest.approx(bed.stiffness * c.diameter, rel=1e-9)
    assert opts["cBot"] * d_v == pytest.approx(bed.damping * c.diameter, rel=1e-9)
    assert opts["FrictionCoefficient"] == bed.friction_axial and opts["StatDynFricScale"] == 1.0
    node_weight = c.weight_per_length * c.length / n
    assert opts["FrictionCoefficient"] * opts["FricDamp"] == pytest.approx(
        bed.friction_axial * node_weight / bed.friction_speed, rel=1e-9)
    assert opts["WtrDpth"] == sc.environment.top_depth + sc.anchor.y == bed.depth
    anchor = next(line.split() for line in text.splitlines() if line.startswith("2 "))
    assert anchor[1] == "Fixed" and float(anchor[2]) == pytest.approx(sc.anchor.x) and float(anchor[4]) == -bed.depth


@pytest.mark.filterwarnings("ignore")
def test_quick_ends_cases_agree_with_closed_forms_and_each_other(tmp_path):
    import bench_vs_moordyn as B
    B.main(["--out", str(tmp_path), "--quick", "--case", "mooring", "--case", "lowering"])
    data = json.loads((tmp_path / "bench_vs_moordyn_ends.json").read_text())
    assert (tmp_path / "bench_vs_moordyn_ends.png").stat().st_size > 10_000
    rows = {r["case"]: r for r in data["cases"]}
    assert set(rows) == {"mooring", "lowering"}

    # the mooring line at rest, N = 10, against the elastic catenary with seabed contact (frictionless, rigid bed):
    # the lumped line's O(h^2) error is -1.4 % at N = 10 (MoorDyn: -1.4, -0.33, -0.08 % at N = 10, 20, 40) and the
    # two codes lump the same way, so they agree with each other to far less than with the closed form
    st = rows["mooring"]["static"]
    assert st["N"] == 10 and st["bed_sink_m"] < 0.01
    for code in ("cablesys", "moordyn"):
        assert -0.02 < st[f"{code}_rel_err"] < 0.0, code
    assert st["cablesys_N"] == pytest.approx(st["moordyn_N"], rel=1e-3)

    for name, row in rows.items():
        (e,) = row["by_n"]
        assert e["moordyn_stable"] and e["largest_stable_dt"] > 0 and e["speedup"] > 0, name
        err = e["cablesys_settings"]["error_vs_own_tight"]
        assert err["body"] <= 0.005 and err["tension"] <= 0.01, name          # matched accuracy
        seg = e["cablesys_vs_moordyn_segments_each"]
        # the top: the same quantity (end element against end segment) within 1 % in both cases
        assert abs(seg["tension_top_max"]) < 0.01 and abs(seg["tension_top_min"]) < 0.01, (name, seg)

    # the lowering: both codes' top tension over the constant-speed part within 0.5 % of the closed form (the issue's
    # tolerance), where the package's drag is a quarter of the load; the package end agrees to 1e-3
    low = rows["lowering"]["by_n"][0]
    for code in ("cablesys", "moordyn"):
        cf = low["closed_form"][code]
        assert cf["max_rel_err"] < 0.005 and 0.2 < cf["drag_share"] < 0.3, code
    seg = low["cablesys_vs_moordyn_segments_each"]
    assert abs(seg["tension_bottom_max"]) < 1e-3 and abs(seg["tension_bottom_min"]) < 1e-3
    # the package is lowered by the paid-out length on both sides (half the range of y over the window)
    assert low["cablesys_stats"]["y_b_amplitude"] == pytest.approx(low["moordyn_stats"]["y_b_amplitude"], rel=1e-4)
    assert math.isfinite(low["moordyn_cpu_s"]) and low["cablesys_cpu_s"] > 0
