"""A package lowered onto the seabed (studies/_landing.py): the body's footprint on the bed (body.bed_area) makes the
landed state the same at every N but for the half element the bed takes with it (first order, exactly w h / 2), and
the model ladder judges those tensions at that order (cablesys.ladder.landed) instead of doubling N to its cap (checked
with auto's stated errors against a fine reference by studies/ends_checks.py's quick run, tests/test_ends_study.py)."""

import sys
import tomllib
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies"))
import _landing as LG  # noqa: E402

from cablesys.errors import ParameterError  # noqa: E402
from cablesys.model.params import parameter_items  # noqa: E402
from cablesys.scene import Body, dump_scene, scene_from_dict  # noqa: E402

pytestmark = pytest.mark.filterwarnings("ignore")


def test_bed_area_is_a_body_field_read_only_with_a_seabed():
    """Written and read back; negative named; a parameter of every section's body only when the scene has a seabed."""
    sc = LG.scene(4, bed_area=0.8)
    back = scene_from_dict(tomllib.loads(dump_scene(sc)))
    assert back.body.bed_area == 0.8 and ("body.bed_area", 0.8) in parameter_items(sc)
    assert "body.bed_area" not in [lb for lb, _ in parameter_items(sc.replace(seabed=None))]
    with pytest.raises(ParameterError, match=r"^body\.bed_area"):
        Body(weight=1.0, mass_x=1.0, mass_y=1.0, bed_area=-1.0)


def test_a_package_with_a_footprint_lands_alike_at_every_n():
    """Landed with a 1 m^2 footprint, the package carries its weight and the half element above it, which the bed takes:
    the top tension is w (L - h / 2) and the line's pull on it w h / 2 (h = L / N, first order: the continuum's are w L
    and 0), its depth the bed's plus (W_b + w h / 2) / (k (A_b + d h / 2)). A point body (no footprint) rests on its
    cable's half element alone, whose contact area d h / 2 falls with N: at N = 32 it has sunk until the line carries
    104 N of its 500 N, a landed state that does not converge in N."""
    for n in (8, 16):
        r = LG.landed_state(n, 1.0)
        h = LG.DEPTH / n
        assert r["success"]
        assert r["tension_top_N"] == pytest.approx(LG.W_R * (LG.DEPTH - h / 2), rel=1e-9)
        assert r["tension_bottom_N"] == pytest.approx(LG.W_R * h / 2, rel=1e-7)
        sink = (LG.W_B + LG.W_R * h / 2) / (LG.K_BED * (1.0 + LG.D * h / 2))
        assert r["depth_m"] == pytest.approx(LG.DEPTH + sink, rel=1e-9)
    point = LG.landed_state(32, None)
    assert point["tension_top_N"] > LG.W_R * LG.DEPTH + 50.0 and point["tension_bottom_N"] > 50.0
