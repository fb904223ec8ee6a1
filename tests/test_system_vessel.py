"""A vessel's 6-DOF motion RAO moving several prescribed points of a system, each by its own lever arm.

The first prescribed point is at ``top_motion.vessel.lever_arm``; a further one at that plus its mean position
offset turned into the vessel's axes (scene/vessel.py: r_k = r_0 + R^T Delta_k), and it moves by
s_0 + theta x Delta_k in the node frame (Faltinsen 1990 ch. 3, the rigid-body displacement eta_t + eta_r x r)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import cablesys
from cablesys.errors import ParameterError
from cablesys.linear.frequency_response import rao
from cablesys.linear.linearization import linearize
from cablesys.model import build_model
from cablesys.scene import Body, Cable, Scene, TopMotion
from cablesys.scene.components import Numerics
from cablesys.scene.sea import SeaSpectrum, interpolate_rao
from cablesys.scene.system import Line, Point, System
from cablesys.scene.vessel import DOFS, HeadingRAO, VesselRAO

OMEGA = (0.3, 0.6, 0.9, 1.2)


def wire(n, **kw):
    return Cable(**{**dict(length=30.0, ae=2e6, diameter=0.02, mass_per_length=1.5, weight_per_length=12.0,
                           cd_normal=1.2, internal_damping=400.0, segments=n), **kw})


def only(dof: str, amplitude=(2.0, 1.5, 1.0, 0.5), phase=(10.0, 20.0, 40.0, 80.0), beta=90.0) -> HeadingRAO:
    """A table at relative heading ``beta`` with one motion (deg/m for a rotation, m/m for a translation)."""
    return HeadingRAO(heading_deg=beta, **{f"{dof}_amplitude": amplitude, f"{dof}_phase_deg": phase})


def lift(b_at, space: bool) -> System:
    """Two prescribed points of one vessel, ``a`` (the origin, at the lever arm) and ``b`` at ``b_at``, lifting a
    package on two wires of two elements."""
    pkg = Body(weight=3000.0, mass_x=400.0, mass_y=450.0, mass_z=420.0 if space else None, drag_area_normal=0.8,
               drag_area_tangential=0.8)
    return System(point=(Point(name="a", kind="prescribed"), Point(name="b", kind="prescribed", x=b_at[0], y=b_at[1],
                                                                   z=b_at[2] or None),
                         Point(name="pkg", kind="body", body=pkg, x=0.5 * b_at[0], y=28.0)),
                  line=(Line(name="la", start="a", end="pkg", section=(wire(2),)),
                        Line(name="lb", start="b", end="pkg", section=(wire(2),))))


def test_lever_arm_of_a_further_point_turns_its_offset_into_the_vessels_axes():
    """r_k = r_0 + R^T Delta (scene/vessel.py): at psi = 0 forward is node x, port node z, up -node y; at psi = 90 deg
    (bow along +z) port is -x. Independent route: the vessel's own Faltinsen transfer at r_k (VesselRAO.transfer, a
    VesselRAO made with that lever arm) equals s_0 + theta x Delta, the model's linear map (theta =
    rotation_transfer), for a table with all six motions and a heading off the axes, to 1e-12."""
    at0 = VesselRAO(omega=OMEGA, headings=(only("roll"),), lever_arm=(1.0, 2.0, 3.0))
    assert at0.arm_of((10.0, 0.0, 0.0)) == (11.0, 2.0, 3.0)      # forward
    assert at0.arm_of((0.0, -4.0, 0.0)) == (1.0, 2.0, 7.0)       # up
    assert at0.arm_of((0.0, 0.0, 5.0)) == (1.0, 7.0, 3.0)        # to port
    at90 = VesselRAO(omega=OMEGA, headings=(only("roll"),), lever_arm=(1.0, 2.0, 3.0), vessel_heading_deg=90.0)
    assert at90.arm_of((5.0, 0.0, 0.0)) == pytest.approx((1.0, -3.0, 3.0), abs=1e-12)   # +x is starboard
    assert at90.arm_of((0.0, 0.0, 5.0)) == pytest.approx((6.0, 2.0, 3.0), abs=1e-12)    # +z is forward

    rng = np.random.default_rng(3)
    table = HeadingRAO(heading_deg=150.0, **{f"{d}_{p}": tuple(rng.uniform(0.1, 2.0, 4) if p == "amplitude" else
                                                                 rng.uniform(-180, 180, 4))
                                              for d in DOFS for p in ("amplitude", "phase_deg")})
    kw = dict(omega=OMEGA, headings=(table,), vessel_heading_deg=35.0)
    v0 = VesselRAO(lever_arm=(-20.0, 12.0, 18.0), **kw)
    w = np.linspace(0.25, 1.3, 9)
    s0, th = np.array(v0.transfer(w, 185.0)), np.array(v0.rotation_transfer(w, 185.0))
    for delta in ((10.0, -3.0, 7.0), (-25.0, 8.0, -4.0)):
        vk = VesselRAO(lever_arm=v0.arm_of(delta), **kw)
        sk = np.array(vk.transfer(w, 185.0))
        mapped = s0 + np.cross(th.T, np.asarray(delta)).T
        np.testing.assert_allclose(sk, mapped, rtol=0, atol=1e-12 * np.max(np.abs(sk)))


@pytest.mark.parametrize("dof, psi, b_at", [("yaw", 30.0, (10.0, 2.0, 4.0)), ("roll", 0.0, (6.0, -1.0, 8.0))])
def test_each_point_moves_by_the_vessels_rotation_at_its_own_lever_arm(dof, psi, b_at):
    """Pure yaw (vessel heading 30 deg) or pure roll: point ``a`` at the lever arm r_0 and point ``b`` at r_0 + R^T
    Delta move by eta_r x r_k (Faltinsen 1990 ch. 3), written here in the vessel's axes from the sea's components and
    the RAO table and turned into the node frame by hand (x = c s_1 - s s_2, y = -s_3, z = s s_1 + c s_2); the run's
    outputs point.a.*, point.b.* (their mean positions removed) agree to 1e-9 of the largest displacement (measured
    ~1e-14). An abrupt
    start (ramp_s = 0): the statics place b where the rotation puts it at t = 0."""
    sea = SeaSpectrum(hs=2.0, tp=8.0, n_components=3, seed=5, heading_deg=psi + 90.0)
    r0 = (4.0, -3.0, 12.0)
    vessel = VesselRAO(omega=OMEGA, headings=(only(dof),), lever_arm=r0, vessel_heading_deg=psi)
    sc = Scene(system=lift(b_at, True), top_motion=TopMotion(spectrum=sea, vessel=vessel, ramp_s=0.0),
               numerics=Numerics(duration=1.0, output_step=0.25))
    assert sc.three_d and sc.vessel_rotation_axes == ("x", "y", "z")
    r = cablesys.simulate(sc, model="as-built")
    assert r.success
    t = np.asarray(r.time)
    # the vessel's rotation (rad) from the components: |R| a sin(w t + eps + theta_R)
    w, amp, eps = sea.components()
    mag, ph = interpolate_rao(OMEGA, np.radians(only(dof).__getattribute__(f"{dof}_amplitude")),
                              np.radians(only(dof).__getattribute__(f"{dof}_phase_deg")), w)
    angle = np.sum((mag * amp)[:, None] * np.sin(w[:, None] * t[None, :] + (eps + ph)[:, None]), axis=0)
    eta_r = np.zeros((3, t.size))
    eta_r[{"roll": 0, "pitch": 1, "yaw": 2}[dof]] = angle
    c, s = math.cos(math.radians(psi)), math.sin(math.radians(psi))
    rb = np.array(r0) + np.array([c * b_at[0] + s * b_at[2], -s * b_at[0] + c * b_at[2], -b_at[1]])
    worst = 0.0
    for name, arm, mean in (("a", np.array(r0), np.zeros(3)), ("b", rb, np.array(b_at))):
        s1, s2, s3 = np.cross(eta_r.T, arm).T                     # vessel axes
        expected = np.array([c * s1 - s * s2, -s3, s * s1 + c * s2])
        got = np.array([r[f"point.{name}.{axis}"] for axis in "xyz"]) - mean[:, None]
        scale = np.max(np.abs(expected))
        assert scale > 1e-3                                       # the point does move (m)
        worst = max(worst, float(np.max(np.abs(got - expected)) / scale))
    assert worst < 1e-9
    th = np.array([r[f"rot_{a}_s"] for a in "xyz"])
    np.testing.assert_allclose(th, np.array([c * eta_r[0] - s * eta_r[1], -eta_r[2], s * eta_r[0] + c * eta_r[1]]),
                               atol=1e-12)


def test_translation_only_vessel_equals_the_translated_points():
    """A vessel RAO with surge, sway and heave only (its rotation zero) moves both points by the same translation: the
    run equals the system's run under that translation given as top_motion.x, y, z sinusoids (main's translated
    points, no vessel) output for output to 1e-12 of each output's scale (measured: bitwise equal); a single
    prescribed point keeps the one
    lever arm's motion (no rotation input)."""
    table = HeadingRAO(heading_deg=60.0, surge_amplitude=(0.3, 0.5, 0.4, 0.2), surge_phase_deg=(0, 30, 60, 90),
                       sway_amplitude=(0.2, 0.4, 0.3, 0.1), sway_phase_deg=(10, 20, 30, 40),
                       heave_amplitude=(1.0, 0.9, 0.6, 0.3), heave_phase_deg=(0, -10, -40, -90))
    sea = SeaSpectrum(hs=2.0, tp=8.0, n_components=3, seed=2, heading_deg=60.0)
    top = TopMotion(spectrum=sea, vessel=VesselRAO(omega=OMEGA, headings=(table,), lever_arm=(5.0, 1.0, 10.0)),
                    ramp_s=1.0)
    assert all(not terms for terms in top.vessel_rotation.values()) and top.z
    num = Numerics(duration=3.0, output_step=0.25)
    with_vessel = Scene(system=lift((10.0, 2.0, 3.0), True), top_motion=top, numerics=num)
    translated = Scene(system=lift((10.0, 2.0, 3.0), True), numerics=num,
                       top_motion=TopMotion(x=top.x, y=top.y, z=top.z, ramp_s=top.effective_ramp_s))
    assert with_vessel.vessel_rotation_axes and not translated.vessel_rotation_axes
    a, b = cablesys.simulate(with_vessel, model="as-built"), cablesys.simulate(translated, model="as-built")
    assert a.success and b.success
    labels = [k for k in b.labels if k in a.labels]
    assert "point.b.y" in labels and len(labels) == len(b.labels)
    for k in labels:
        scale = max(1.0, float(np.max(np.abs(b[k]))))
        np.testing.assert_allclose(a[k], b[k], rtol=0, atol=1e-12 * scale, err_msg=k)
    assert np.ptp(a["point.b.y"]) > 0.1
    one = Scene(system=System(point=(Point(name="a", kind="prescribed"), Point(name="pin", kind="fixed", x=5, y=29.0)),
                              line=(Line(name="la", start="a", end="pin", section=(wire(2),)),
                                    Line(name="lb", start="pin", end="a", section=(wire(2),)))), top_motion=top)
    assert one.system is not None and one.vessel_rotation_axes == ()


def tethers(d=6.0, numerics=None, port=None) -> Scene:
    """Two taut vertical tethers (30 m at 6 kN: l_0 = 29.91 m, AE = 2 MN) from two deck points of a vessel 2 d apart,
    the first ``port`` (default d: symmetric about the centreline) to port, to anchors 30 m below, in beam seas; the
    bow along +z (vessel_heading_deg = 90) puts the vessel's transverse plane in cablesys' x-y plane: a planar scene.
    The roll RAO is 2 deg/m at every frequency."""
    vessel = VesselRAO(omega=OMEGA, headings=(only("roll", amplitude=(2.0,) * 4, phase=(0.0,) * 4),),
                       lever_arm=(0.0, d if port is None else port, 0.0), vessel_heading_deg=90.0)
    sea = SeaSpectrum(hs=2.0, tp=10.0, n_components=4, seed=7, heading_deg=180.0)   # beta = 90: beam seas
    taut = wire(3, length=30.0, tension_ref=6000.0)
    return Scene(system=System(point=(Point(name="a", kind="prescribed"), Point(name="b", kind="prescribed", x=2 * d,
                                                                                y=0.0),
                                      Point(name="anchor_a", kind="fixed", x=0.0, y=30.0),
                                      Point(name="anchor_b", kind="fixed", x=2 * d, y=30.0)),
                               line=(Line(name="la", start="a", end="anchor_a", section=(taut,)),
                                     Line(name="lb", start="b", end="anchor_b", section=(taut,)))),
                 top_motion=TopMotion(spectrum=sea, vessel=vessel), numerics=numerics or Numerics())


def test_a_rolling_vessels_two_tethers_heave_and_pull_in_antiphase():
    """Pure roll about the centreline: the port point rises by d roll while the starboard one sinks by d roll
    (antiphase, equal: correlation -1 to 1e-9), and each taut tether's tension follows its own point, quasi-statically
    dT = -(AE / l_0) dy (the wires' first axial mode is far above the sea): regressed on its point's heave the slope is
    AE / l_0 within 2 %, and the two tensions' fluctuations correlate below -0.99 (in antiphase to first order; the
    translated-points model would move both alike). The linearization takes the rotation as an input (rot_z_s): the
    starboard tether's tension per unit rotation at low frequency is -(AE / l_0) 2 d, the port one's ~0."""
    sc = tethers(numerics=Numerics(duration=12.0, output_step=0.1, model="as-built"))
    assert not sc.three_d and sc.vessel_rotation_axes == ("z",)
    r = cablesys.simulate(sc)
    assert r.success
    ya, yb = r["point.a.y"], r["point.b.y"]
    assert np.ptp(ya) > 0.05 and np.corrcoef(ya, yb)[0, 1] < -1 + 1e-9
    np.testing.assert_allclose(ya, -yb, atol=1e-12)
    k = 2e6 / (30.0 * (1.0 - 6000.0 / 2e6))
    for y, T in ((ya, r["line.la.tension_from"]), (yb, r["line.lb.tension_from"])):
        slope = np.polyfit(-y, T, 1)[0]
        assert slope == pytest.approx(k, rel=0.02)
    Ta, Tb = r["line.la.tension_from"], r["line.lb.tension_from"]
    assert np.corrcoef(Ta - Ta.mean(), Tb - Tb.mean())[0, 1] < -0.99

    model = build_model(sc)
    lin = linearize(model, model.parameters(sc))
    assert lin.input_labels[:3] == ("x_s", "y_s", "rot_z_s")
    h = rao(lin, np.array([0.05]))
    assert h("line.lb.tension_from", "rot_z_s")[0].real == pytest.approx(-k * 12.0, rel=0.02)
    assert abs(h("line.la.tension_from", "rot_z_s")[0]) < 1e-6 * k * 12.0


def test_the_sea_response_carries_the_rotation_to_a_point_off_the_centreline():
    """The linear sea response (cablesys rao's) of the tethers with the first point on the centreline (it does not
    heave under roll) and the second 12 m to starboard: sigma of the second tether's tension is the quasi-static
    k 2 d sigma_roll = (AE / l_0) 12 m x 2 deg/m x H_s / 4 within 2 % (it comes only through the rotation input), the
    first's below 1 % of it."""
    from cablesys.linear.sea_response import sea_response
    sc = tethers(port=0.0)
    model = build_model(sc)
    lin = linearize(model, model.parameters(sc))
    resp = sea_response(sc, lin, outputs=["line.la.tension_from", "line.lb.tension_from"])
    k = 2e6 / (30.0 * (1.0 - 6000.0 / 2e6))
    expected = k * 12.0 * math.radians(2.0) * 2.0 / 4.0
    assert resp.statistics["line.lb.tension_from"]["std"] == pytest.approx(expected, rel=0.02)
    assert resp.statistics["line.la.tension_from"]["std"] < 0.01 * expected


def test_a_point_swayed_by_roll_needs_the_3d_equations():
    """Roll swings a point below or above the first one sideways (z_k = z_0 + theta_x dy): the planar equations are
    refused by name before any work (numerics.dimensions = 2, the field naming top_motion.vessel and the point)."""
    sea = SeaSpectrum(hs=2.0, tp=8.0, n_components=3, seed=5, heading_deg=90.0)
    top = TopMotion(spectrum=sea, vessel=VesselRAO(omega=OMEGA, headings=(only("roll"),)))
    assert Scene(system=lift((10.0, 2.0, 0.0), False), top_motion=top).three_d
    with pytest.raises(ParameterError) as err:
        Scene(system=lift((10.0, 2.0, 0.0), False), top_motion=top, numerics=Numerics(dimensions=2))
    assert err.value.field == "numerics.dimensions" and "top_motion.vessel" in str(err.value) and "point[1]" in str(err.value)


def test_cablesys_rao_tabulates_the_response_per_rad_of_the_vessels_rotation(tmp_path):
    """``cablesys rao`` on the tethers (the first point on the centreline, the second 12 m to starboard): a table and
    figures per unit rotation (rot_z_s, per rad) beside those per metre; at the band's lowest frequency the second
    tether's tension per rad is the quasi-static (AE / l_0) 12 m within 2 %, the first's is not drawn (zero)."""
    import json
    from cablesys.cli import main
    from cablesys.scene import dump_scene
    f = tmp_path / "tethers.toml"
    f.write_text(dump_scene(tethers(port=0.0)))
    out = tmp_path / "rao"
    assert main(["rao", str(f), "--out", str(out)]) == 0
    rows = (out / "rao_exact_rot_z_s.csv").read_text().splitlines()
    head, first = rows[0].split(","), np.array(rows[1].split(","), float)
    k = 2e6 / (30.0 * (1.0 - 6000.0 / 2e6))
    assert first[head.index("line.lb.tension_from_amp [N/rad]")] == pytest.approx(k * 12.0, rel=0.02)
    assert (out / "rao_line.lb.tension_from_rot_z_s.png").exists()
    assert "line.la.tension_from per unit rot_z_s" in json.loads((out / "rao_summary.json").read_text())["zero_responses"]
