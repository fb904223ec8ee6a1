"""A vessel's 6-DOF motion RAO carried to a crane tip: the rigid-body kinematics against exact
rotations, rotation invariance, the port-starboard mirror, heading interpolation, the plane as a
special case, TOML in and out, and field-named errors."""

import math

import numpy as np
import pytest
import tomllib

from cablesys.errors import ParameterError
from cablesys.scene import TopMotion, scene_from_dict
from cablesys.scene.sea import MotionRAO, SeaSpectrum, top_transfer
from cablesys.scene.toml_io import dump_scene
from cablesys.scene.vessel import DOFS, HeadingRAO, VesselRAO

OMEGA = (0.3, 0.5, 0.8, 1.2)


def _table(beta, rng):
    """A heading table with every DOF set (random amplitudes and phases)."""
    kw = {}
    for dof in DOFS:
        kw[f"{dof}_amplitude"] = tuple(rng.uniform(0.1, 2.0, len(OMEGA)))
        kw[f"{dof}_phase_deg"] = tuple(rng.uniform(-180.0, 180.0, len(OMEGA)))
    return HeadingRAO(heading_deg=beta, **kw)


def _rot(axis, a):
    c, s = math.cos(a), math.sin(a)
    return {"x": np.array([[1, 0, 0], [0, c, -s], [0, s, c]]),
            "y": np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]),
            "z": np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])}[axis]


def test_lever_arm_motion_is_the_small_rotation_limit_of_the_exact_rigid_body_motion():
    """Independent route: the tip's displacement eta + R(roll, pitch, yaw) r - r with the exact
    rotation matrix, for waves of amplitude eps -> 0, divided by eps, equals the RAO's transfer."""
    rng = np.random.default_rng(3)
    v = VesselRAO(omega=OMEGA, headings=(_table(150.0, rng),), lever_arm=(-20.0, 12.0, 18.0), vessel_heading_deg=35.0)
    w = 0.65
    m = v.motions([w], 185.0)                       # beta = 185 - 35 = 150: on the table
    X, Y, Z = v.transfer([w], 185.0)
    r = np.array(v.lever_arm)
    psi = math.radians(35.0)
    for t in (0.0, 1.7, 4.1):
        eps = 1e-5
        eta = {d: float(np.real(m[d][0] * np.exp(1j * w * t) * -1j)) * eps for d in DOFS}   # eta = sin(w t) per unit
        R = _rot("z", eta["yaw"]) @ _rot("y", eta["pitch"]) @ _rot("x", eta["roll"])
        s = np.array([eta["surge"], eta["sway"], eta["heave"]]) + R @ r - r            # vessel axes (x fwd, y port, z up)
        east = math.cos(psi) * s[0] - math.sin(psi) * s[1]
        north = math.sin(psi) * s[0] + math.cos(psi) * s[1]
        expected = np.array([east, -s[2], north]) / eps                                 # cablesys x, y (down), z
        got = np.array([np.real(T[0] * np.exp(1j * w * t) * -1j) for T in (X, Y, Z)])
        np.testing.assert_allclose(got, expected, atol=1e-3 * np.abs(expected).max())


def test_turning_vessel_and_sea_together_turns_the_tip_motion_in_the_horizontal_plane():
    rng = np.random.default_rng(5)
    kw = dict(omega=OMEGA, headings=(_table(120.0, rng),), lever_arm=(30.0, -8.0, 25.0))
    w = np.array(OMEGA)
    X0, Y0, Z0 = VesselRAO(vessel_heading_deg=10.0, **kw).transfer(w, 130.0)
    for turn in (47.0, 200.0):
        X1, Y1, Z1 = VesselRAO(vessel_heading_deg=10.0 + turn, **kw).transfer(w, 130.0 + turn)
        c, s = math.cos(math.radians(turn)), math.sin(math.radians(turn))
        np.testing.assert_allclose(X1, c * X0 - s * Z0, atol=1e-12)
        np.testing.assert_allclose(Z1, s * X0 + c * Z0, atol=1e-12)
        np.testing.assert_allclose(Y1, Y0, atol=1e-12)


def test_a_table_over_0_to_180_serves_the_other_side_by_port_starboard_symmetry():
    rng = np.random.default_rng(7)
    tab = _table(60.0, rng)
    v = VesselRAO(omega=OMEGA, headings=(_table(0.0, rng), tab, _table(180.0, rng)))
    m, mm = v.motions(OMEGA, 60.0), v.motions(OMEGA, 300.0)
    for dof in DOFS:
        sign = -1.0 if dof in ("sway", "roll", "yaw") else 1.0
        np.testing.assert_allclose(mm[dof], sign * m[dof], atol=1e-14)
    # a tip on the centreline, waves from starboard vs from port: its sway reverses, its heave does not
    arm = VesselRAO(omega=OMEGA, headings=v.headings, lever_arm=(15.0, 0.0, 20.0))
    (X, Y, Z), (Xm, Ym, Zm) = arm.transfer(OMEGA, 60.0), arm.transfer(OMEGA, 300.0)
    np.testing.assert_allclose(Zm, -Z, atol=1e-12)
    np.testing.assert_allclose(Ym, Y, atol=1e-12)


def test_between_table_headings_amplitude_and_phase_are_linear_in_heading():
    a = HeadingRAO(heading_deg=90.0, heave_amplitude=(1.0,) * 4, heave_phase_deg=(170.0,) * 4)
    b = HeadingRAO(heading_deg=180.0, heave_amplitude=(0.4,) * 4, heave_phase_deg=(-170.0,) * 4)
    v = VesselRAO(omega=OMEGA, headings=(a, b))
    h = v.motions([0.5], 150.0)["heave"][0]                 # 2/3 of the way; the phase goes through 180, not 0
    assert abs(h) == pytest.approx(1.0 + 2 / 3 * (0.4 - 1.0), rel=1e-12)
    assert math.degrees(np.angle(h)) % 360.0 == pytest.approx(170.0 + 2 / 3 * 20.0, abs=1e-9)


def test_heave_only_at_the_reference_point_is_the_planar_motion_rao():
    heave = dict(heave_amplitude=(1.0, 0.9, 0.5, 0.1), heave_phase_deg=(0.0, -5.0, -40.0, -120.0))
    surge = dict(surge_amplitude=(0.8, 0.5, 0.2, 0.0), surge_phase_deg=(90.0, 80.0, 50.0, 0.0))
    sea = SeaSpectrum(hs=3.0, tp=9.0, n_components=25, seed=4)
    vessel = TopMotion(spectrum=sea, vessel=VesselRAO(omega=OMEGA, headings=(HeadingRAO(heading_deg=0.0, **heave, **surge),)))
    planar = TopMotion(spectrum=sea, rao=MotionRAO(omega=OMEGA, **heave, **surge))
    assert vessel.z == () and len(vessel.y) == len(planar.y) == 25
    for axis in ("x", "y"):
        for p, q in zip(getattr(vessel, axis), getattr(planar, axis)):
            assert (p.amplitude, p.frequency) == pytest.approx((q.amplitude, q.frequency), rel=1e-14)
            assert p.phase == pytest.approx(q.phase, abs=1e-12)
    X, Y, Z = top_transfer(vessel.vessel, OMEGA, 0.0)
    assert not np.any(Z)


SCENE = """
name = "crane tip 15 m to port, beam sea"
[cable]
length = 80.0
ae = 4.0e7
diameter = 0.024
mass_per_length = 2.4
weight_per_length = 18.0
[body]
weight = 6000.0
mass_x = 900.0
mass_y = 1100.0
[top_motion.spectrum]
hs = 2.0
tp = 8.0
n_components = 12
heading_deg = 90.0
[top_motion.vessel]
omega = [0.4, 0.8, 1.2]
lever_arm = [5.0, 15.0, 12.0]
vessel_heading_deg = 0.0
[[top_motion.vessel.headings]]
heading_deg = 90.0
heave_amplitude = [1.0, 0.7, 0.2]
heave_phase_deg = [0.0, -20.0, -60.0]
roll_amplitude = [1.0, 4.0, 0.5]
roll_phase_deg = [90.0, 60.0, 20.0]
"""


def test_a_beam_sea_on_a_rolling_vessel_makes_a_3d_scene_that_writes_and_reads_back():
    sc = scene_from_dict(tomllib.loads(SCENE))
    assert sc.three_d and sc.three_d_fields()[0].startswith("top_motion.vessel")
    top = sc.top_motion
    assert len(top.y) == len(top.z) == 12 and top.x == ()       # no surge, sway, pitch or yaw: no x motion
    # the tip's sway is -z_arm * roll and its heave gains y_arm * roll (Faltinsen 1990 ch. 3)
    X, Y, Z = top_transfer(top.vessel, [0.8], 90.0)
    roll = math.radians(4.0) * np.exp(1j * math.radians(60.0))
    assert Z[0] == pytest.approx(-12.0 * roll, rel=1e-12)
    assert Y[0] == pytest.approx(-(0.7 * np.exp(-1j * math.radians(20.0)) + 15.0 * roll), rel=1e-12)
    for units in ("SI", "fps"):
        again = scene_from_dict(tomllib.loads(dump_scene(sc, units=units)))
        assert len(again.top_motion.z) == 12 and len(again.top_motion.y) == 12      # realised once, not twice
        assert again.top_motion.vessel.lever_arm == pytest.approx((5.0, 15.0, 12.0), rel=1e-12)
        assert again.top_motion.vessel.headings[0].roll_amplitude == pytest.approx((1.0, 4.0, 0.5), rel=1e-12)


def test_vessel_rao_from_a_csv_in_long_format(tmp_path):
    f = tmp_path / "vessel.csv"
    rows = ["heading_deg,omega,heave_amplitude,heave_phase_deg,roll_amplitude,roll_phase_deg"]
    for beta in (90.0, 180.0):
        for w, a in zip(OMEGA, (1.0, 0.9, 0.5, 0.1)):
            rows.append(f"{beta},{w},{a},{-10 * w},{2 * a if beta == 90 else 0},{45}")
    f.write_text("\n".join(rows) + "\n")
    v = VesselRAO(file=str(f), lever_arm=(0.0, 10.0, 0.0))
    assert v.omega == OMEGA and [h.heading_deg for h in v.headings] == [90.0, 180.0] and v.file == ""
    assert v.motions([0.5], 90.0)["roll"][0] == pytest.approx(math.radians(1.8) * np.exp(1j * math.radians(45.0)))


@pytest.mark.parametrize("kw, field", [
    (dict(omega=(0.5, 0.4), headings=(HeadingRAO(heading_deg=0.0),)), "top_motion.vessel.omega"),
    (dict(omega=OMEGA), "top_motion.vessel.headings"),
    (dict(omega=OMEGA, headings=(HeadingRAO(heading_deg=0.0, heave_amplitude=(1.0,)),)),
     "top_motion.vessel.headings[0].heave_amplitude"),
    (dict(omega=OMEGA, headings=(HeadingRAO(heading_deg=0.0),), lever_arm=(1.0, 2.0)), "top_motion.vessel.lever_arm"),
    (dict(omega=OMEGA, headings=(HeadingRAO(heading_deg=90.0), HeadingRAO(heading_deg=45.0))),
     "top_motion.vessel.headings[1].heading_deg"),
])
def test_bad_vessel_tables_name_the_field(kw, field):
    with pytest.raises(ParameterError) as err:
        VesselRAO(**kw)
    assert err.value.field == field


def test_a_heading_the_table_does_not_cover_and_two_raos_are_named_errors():
    v = VesselRAO(omega=OMEGA, headings=(HeadingRAO(heading_deg=150.0, heave_amplitude=(1.0,) * 4),
                                         HeadingRAO(heading_deg=180.0, heave_amplitude=(1.0,) * 4)))
    with pytest.raises(ParameterError) as err:
        v.transfer(OMEGA, 90.0)                 # beta = 90 (or its mirror 270): not in 150..180
    assert err.value.field == "top_motion.vessel.headings" and "90" in str(err.value)
    sea = SeaSpectrum(hs=1.0, tp=8.0, heading_deg=180.0)
    with pytest.raises(ParameterError) as err:
        TopMotion(spectrum=sea, vessel=v, rao=MotionRAO(omega=OMEGA))
    assert err.value.field == "top_motion.vessel"
    with pytest.raises(ParameterError) as err:
        TopMotion(vessel=v)
    assert err.value.field == "top_motion.vessel"


def test_realised_tip_motion_has_the_variance_of_the_rao_times_the_spectrum():
    """Two routes to the tip's heave and sway variance: the realised sinusoids (sum a_k^2 |T(w_k)|^2 / 2)
    and the spectral integral of |T|^2 S over the band converge to each other as components are added."""
    text = SCENE.replace("n_components = 12", "n_components = 400")
    sc = scene_from_dict(tomllib.loads(text))
    sea, top = sc.top_motion.spectrum, sc.top_motion
    lo, hi = sea.band()
    w = np.linspace(lo, hi, 4001)
    for axis, T in zip("xyz", top_transfer(top.vessel, w, sea.heading_deg)):
        spectral = float(np.trapezoid(np.abs(T) ** 2 * sea.density(w), w))
        realised = sum(s.amplitude ** 2 / 2 for s in getattr(top, axis))
        assert realised == pytest.approx(spectral, rel=0.01, abs=1e-12)


def test_the_run_of_a_rolling_vessel_reports_the_body_sway_beside_heave():
    """A 3-D run's summary and statistics carry z_b: the sway the lever arm gives is not dropped."""
    import cablesys
    from cablesys.verdict import run_statistics
    text = SCENE + "\n[numerics]\nduration = 30.0\noutput_step = 0.25\n"
    res = cablesys.simulate(scene_from_dict(tomllib.loads(text)), model="wang")
    body = res.summary()["body"]
    assert body["z_amplitude_m"] > 0.05 and body["y_amplitude_m"] > 0.1
    assert {"x_b", "y_b", "z_b"} <= set(run_statistics(res))
    no_roll = text.replace("roll_amplitude = [1.0, 4.0, 0.5]", "roll_amplitude = [0.0, 0.0, 0.0]")
    planar = cablesys.simulate(scene_from_dict(tomllib.loads(no_roll)), model="wang")      # heave only: planar
    assert "z_amplitude_m" not in planar.summary()["body"] and "z_b" not in run_statistics(planar)
