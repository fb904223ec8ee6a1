"""The seabed in space (cablesys.model.segmented_seabed on the 3-D node model): its scene fields and errors, the 3-D
statics of a turned mooring against the closed form, the lateral friction holding or sliding a line laid across a slope
(closed form of the regularised law), a line resting on a bed sloping across it, and the energy of a line bouncing on
the bed (studies/_seabed_3d.py). The planar seabed forced through the 3-D equations and the turned mooring's run are
checked by studies/ends_checks.py's quick run (tests/test_ends_study.py)."""

import math
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies"))
import _seabed_3d as S  # noqa: E402

import cablesys  # noqa: E402
from cablesys.errors import ParameterError  # noqa: E402
from cablesys.model import build_model  # noqa: E402
from cablesys.model.params import parameter_items, structure_of  # noqa: E402
from cablesys.scene import Anchor, Numerics, Seabed, dump_scene, scene_from_dict, single_section_scene  # noqa: E402
from cablesys.statics.catenary import anchored_line_forces, segmented_steady  # noqa: E402
from cablesys.statics.closed_forms import seabed_catenary, seabed_catenary_span  # noqa: E402

pytestmark = pytest.mark.filterwarnings("ignore")


def test_anchor_z_and_bed_heading_make_a_3d_scene_and_a_planar_one_keeps_its_parameters():
    """``anchor.z`` or ``seabed.heading_deg`` set runs the 3-D equations (and adds their parameters); unset, the planar
    scene's parameters and structure are as before; the bed's depth under (x, z) follows the slope's heading."""
    planar = S.mooring(8, dimensions=None)
    assert not planar.three_d and not [lb for lb, _ in parameter_items(planar) if lb in ("anchor.z", "seabed.heading_deg")]
    for scene in (planar.replace(anchor=Anchor(x=250.0, y=100.0, z=0.0)),
                  planar.replace(seabed=Seabed(depth=100.0, heading_deg=0.0))):
        assert scene.three_d and structure_of(scene)[:len(structure_of(planar))] == structure_of(planar)
        labels = [lb for lb, _ in parameter_items(scene)]
        assert "anchor.z" in labels and "seabed.heading_deg" in labels
    bed = Seabed(depth=100.0, slope_deg=10.0, heading_deg=30.0)
    x, z = 40.0, -25.0
    assert bed.bed_y(x, 5.0, z) == pytest.approx(95.0 + math.tan(math.radians(10.0)) * (x * math.cos(math.radians(30.0))
                                                                                     + z * math.sin(math.radians(30.0))))
    with pytest.raises(ParameterError, match="numerics.dimensions"):
        planar.replace(anchor=Anchor(x=250.0, y=100.0, z=10.0), numerics=Numerics(dimensions=2))


def test_3d_ends_round_trip_and_bad_input_is_named_before_any_work():
    """TOML (SI and fps) keeps anchor.z and seabed.heading_deg; an anchor under a bed sloping towards its heading names
    seabed.depth and the anchor's z; a line shorter than the 3-D chord names cable.length; a NaN heading is named."""
    sc = S.mooring(8, bearing_deg=35.0, slope_deg=2.0)
    for units in ("SI", "fps"):
        back = scene_from_dict(tomllib.loads(dump_scene(sc, units=units)))
        assert back.anchor.z == pytest.approx(sc.anchor.z, rel=1e-12) and back.seabed.heading_deg == 35.0
    # the bed deepens towards +z: an anchor at z = +200 m lies 200 tan(5 deg) = 17.5 m deeper than the bed at z = 0 allows
    with pytest.raises(ParameterError, match=r"^seabed\.depth.*anchor\.z = 200 m"):
        single_section_scene(cable=S.chain(8), body=S.BODY, anchor=Anchor(x=0.0, y=100.0, z=200.0),
                             seabed=Seabed(depth=100.0, slope_deg=-5.0, heading_deg=90.0))
    with pytest.raises(ParameterError) as err:
        single_section_scene(cable=S.chain(8), body=S.BODY, anchor=Anchor(x=200.0, y=100.0, z=250.0))
    assert err.value.field == "cable.length" and "335.41 m" in str(err.value)
    with pytest.raises(ParameterError, match=r"^seabed\.heading_deg"):
        Seabed(depth=100.0, heading_deg=math.nan)


def test_3d_statics_of_a_turned_mooring_are_the_closed_form_catenary_with_friction():
    """Turned by 120 degrees, with axial friction 0.1 (laid-down), the 3-D statics give the fairlead and anchor forces
    and the length on the bed of the planar closed form (seabed_catenary) at the node model's second order: within
    the same errors as the planar statics at N = 40."""
    mu, n = 0.1, 40
    span = seabed_catenary_span(length=S.LENGTH, weight_per_length=S.W, ea=S.EA, height=S.DEPTH, seabed_length=150.0,
                                friction=mu)
    cf = seabed_catenary(length=S.LENGTH, weight_per_length=S.W, ea=S.EA, span=span, height=S.DEPTH, friction=mu)
    errs = {}
    for bearing, dims in ((0.0, None), (120.0, 3)):
        sc = S.mooring(n, bearing_deg=bearing, span=span, friction_axial=mu, dimensions=dims).replace(
            seabed=Seabed(depth=S.DEPTH, heading_deg=None if dims is None else bearing, stiffness=1e11, damping=0.0,
                          friction_axial=mu, friction_lateral=0.6))
        model = build_model(sc)
        p = model.parameters(sc)
        f = anchored_line_forces(model, segmented_steady(model, p), p)
        errs[bearing] = np.array([f[k] / cf[k] - 1 for k in ("H", "V_F", "H_A", "L_B")])
    assert np.max(np.abs(errs[120.0])) < 3e-3
    np.testing.assert_allclose(errs[120.0], errs[0.0], atol=1e-9)


@pytest.mark.parametrize("mu", [0.6, 0.2])
def test_lateral_friction_holds_a_laid_line_until_the_slope_exceeds_it(mu):
    """A line laid along the contour of a bed sloping 20 degrees (tan = 0.364), dropped: with lateral friction 0.6 the
    friction holds it but for the regularisation's creep, its speed settling at v_s atanh(tan a / mu) (7.0 mm/s); with 0.2
    it slides down, accelerating at g_w (sin a - mu cos a) (1.27 m/s^2); both as the closed form of one node's
    m_e v' = w sin a - mu w cos a tanh(v / v_s), to 1e-8 and 1e-6 m/s (sliding: for 0.5 s, until the tension of the
    held ends reaches the middle)."""
    r = S.lateral_slide(mu, duration=4.0 if mu > 0.3 else 0.5)
    assert r["success"]
    if mu > r["tan_slope"]:
        assert r["speed_end_m_s"] == pytest.approx(r["creep_speed_m_s"], rel=1e-6) and r["creep_speed_m_s"] < 0.01
        assert r["speed_max_abs_err_m_s"] < 1e-8
    else:
        assert r["speed_end_m_s"] > 0.6 and r["speed_max_abs_err_m_s"] < 1e-6
        assert r["speed_end_m_s"] / 0.5 == pytest.approx(r["acceleration_m_s2"], rel=0.02)


def test_a_line_resting_across_a_sloped_bed_stays_at_rest():
    """The turned mooring on a bed sloping 3 degrees towards 60 degrees off the line (its laid part bowed 3.9 m across by
    the slope and held by its tension: the statics have no lateral friction), no axial friction, lateral 0.6: left
    from its static state for 1000 s it moves less than 1e-9 m."""
    r = S.resting(1000.0)
    assert r["success"] and r["static_offset_across_m"] > 1.0
    assert r["drift_max_m"] < 1e-9


def test_contact_in_space_creates_no_energy():
    """A rope bowed sideways and lifted, dropped on a flat bed at 35 degrees bearing, no drag, no friction, no contact
    damping: its energy to 1e-5 of the drop over four contacts, while it also swings across."""
    r = S.bouncing(4.0, n=6, rtol=1e-8)
    assert r["success"] and r["contacts"] >= 4 and r["sway_range_m"] > 0.5
    assert r["energy_drift_rel"] < 1e-5


def test_the_ladder_runs_a_3d_seabed_scene_on_the_node_model():
    """``cablesys.simulate`` runs a 3-D mooring on the node model (asked by name, unchecked, to stay short) and says
    why; its sway series and the lateral friction profile are in the result; Wang's straight cable is refused."""
    sc = S.mooring(8, bearing_deg=35.0, duration=4.0)
    for model in ("segmented", "wang"):
        scene = sc.replace(numerics=Numerics(duration=4.0, output_step=0.5, dimensions=3, model=model))
        if model == "wang":
            with pytest.raises(ParameterError, match="numerics.model.*anchor"):
                cablesys.simulate(scene)
            continue
        run = cablesys.simulate(scene)
        assert run.success and run.stats["model"]["name"] == "segmented"
        assert "anchored line or a seabed" in run.stats["model"]["reason"]
        assert "z_b" in run.data and "seabed_friction_lateral" in run.profiles
