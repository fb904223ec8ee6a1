"""The winch with the line's other ends (cablesys.model.segmented_winch): a mooring line hauled in at its fairlead against
the catenary of its current length (closed form and the node model's statics), the mass of an anchored line in the
water, and a rigid body lowered by the winch (studies/_winch_ends.py). The laid part's friction while hauled and the
winch in space against the planar one are checked by studies/ends_checks.py's quick run (tests/test_ends_study.py)."""

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies"))
import _winch_ends as WE  # noqa: E402

from cablesys.scene import Body, Cable, Environment, Numerics, Winch, single_section_scene  # noqa: E402
from cablesys.time_domain import simulate  # noqa: E402

pytestmark = pytest.mark.filterwarnings("ignore")


def test_hauling_in_a_mooring_line_follows_the_catenary_of_its_length():
    """10 m of the 300 m chain hauled in at the fairlead (anchor fixed, 150 m on the bed at the start): the fairlead
    tension as L passes each length is the node model's static tension of that length to 7e-4 at 0.1 m/s, and that
    difference (the haul's dynamics) falls about as the square of the speed (0.2 -> 0.1 m/s: more than 3x less); the
    statics against the closed-form catenary with seabed contact (seabed_catenary) is the discretisation, 1.8 % at
    N = 10 (second order in 1/N: tests/test_ends.py; studies/ends_checks.py runs the haul at N = 20 and 40)."""
    fast, slow = WE.haulin(10, 0.2), WE.haulin(10, 0.1)
    for r in (fast, slow):
        assert r["success"] and r["length_end_m"] == pytest.approx(290.0, abs=1e-9)
    assert slow["vs_statics_max_rel"] < 1e-3 and slow["vs_statics_max_rel"] < fast["vs_statics_max_rel"] / 3
    assert slow["statics_vs_closed_form_max_rel"] < 0.02 and slow["vs_closed_form_max_rel"] < 0.02


def test_an_anchored_line_in_the_water_has_the_mass_of_its_length():
    """Hauled in, held and paid back out: the free nodes carry m_r L (1 - 1 / N), the halves at the sheave and at the
    anchor being fixed, at every L(t)."""
    assert WE.anchored_mass() < 1e-12


def test_a_rigid_body_lowered_by_the_winch_keeps_its_hanging_pitch():
    """A rigid body hung off its centre of gravity (attachment 0.5 m forward and 0.8 m above) paid out with a smoothstep
    acceleration to 2 m/s: it pitches to hang its CG under the attachment, tan(theta) = 0.5 / -0.8, and keeps that pitch
    while the line accelerates (the apparent gravity changes its size, not its direction); the top tension is that of
    the point body, W_b + w L - (M_b + m_r L) alpha, within the elastic response (1.6 N of 564 N of inertia)."""
    m_r, w_r, w_b, m_b = 10.0, 8.0, 500.0, 100.0
    cable = Cable(length=50.0, ae=1e7, diameter=0.02, mass_per_length=m_r, weight_per_length=w_r, added_mass_factor=0.0,
                  cd_normal=0.0, ct_tangential=0.0, internal_damping=5e5, segments=4)
    body = Body(weight=w_b, mass_x=m_b, mass_y=m_b, drag_area_normal=0.0, drag_area_tangential=0.0, pitch_inertia=30.0,
                attachment_x=0.5, attachment_y=-0.8)
    sc = single_section_scene(cable=cable, body=body, environment=Environment(gravity=9.80665),
                              numerics=Numerics(duration=12.0, output_step=0.25),
                              winch=Winch(speed=2.0, start=0.0, duration=12.0, ramp=4.0, max_length=100.0))
    run = simulate(sc)
    t, L, a = np.asarray(run.time), run["winch_length"], run["winch_acceleration"]
    assert L[-1] == pytest.approx(66.0, abs=1e-9)
    np.testing.assert_allclose(run["theta_b"], np.arctan(0.5 / -0.8), atol=1e-8)
    np.testing.assert_allclose(run["x_cg"], run["x_b"], atol=1e-8)
    inertia = (m_b + m_r * L) * a
    sel = (t > 1.0) & (t < 11.0)
    assert np.max(np.abs(run["tension_top"] - (w_b + w_r * L - inertia))[sel]) < 2.0 and np.max(np.abs(inertia)) > 500
