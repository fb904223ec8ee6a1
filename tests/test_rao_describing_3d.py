"""The describing-function RAO in 3-D (``cablesys rao``, :mod:`cablesys.linear.equivalent`): one harmonic balance per
direction of the top's motion, the node model's balance in its element coordinates (phi_k, phi_z_k, u_k).

- against the time domain: a 60 m wire with a 6 kN sphere in a 0.5 m/s current at 30 deg, swayed at its top: the
  first harmonics of the body's x, y, z and of the top tension agree with the nonlinear run's;
- against the plane: a planar scene's describing functions per surge and heave are those of the same scene run by
  the 3-D equations, and without a current the sway's is the surge's turned by 90 deg;
- ``cablesys rao`` writes the sway's describing-function table and says where it holds.
"""

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest

from cablesys.linear.equivalent import harmonic_model, harmonic_response
from cablesys.model import build_model
from cablesys.scene import Body, Cable, Environment, Numerics, Sinusoid, TopMotion, dump_scene, single_section_scene
from cablesys.time_domain import simulate


def _scene(n=3, current=0.5, heading=30.0, top=None):
    """A 60 m steel wire (24 mm, AE 4e7 N) with a 6 kN sphere, N elements, in a current at ``heading`` (None: along x,
    a planar scene)."""
    cable = Cable(length=60.0, ae=4.0e7, diameter=0.024, mass_per_length=2.4, weight_per_length=18.0, cd_normal=1.5,
                  ct_tangential=0.01, internal_damping=1e4, segments=n)
    body = Body(weight=6000.0, mass_x=900.0, mass_y=900.0, mass_z=900.0 if heading is not None else None,
                drag_area_normal=1.5, drag_area_tangential=1.5, axis_angle_deg=999.0)
    env = Environment(current_depths=(0.0,), current_speeds=(current,),
                      current_headings_deg=(heading,) if heading is not None else ())
    return single_section_scene(cable=cable, body=body, environment=env, top_motion=top or TopMotion(ramp_s=10.0),
                                numerics=Numerics(duration=60.0, output_step=0.1), name="sway")


def _first_harmonic(result, label, omega, periods=5):
    """|a_1| of the least-squares fit a_0 + Re(a_1 e^{i omega t}) over the last ``periods`` periods."""
    t = np.asarray(result.time)
    w = t >= t[-1] - periods * 2 * math.pi / omega - 1e-9
    B = np.column_stack([np.ones(w.sum()), np.cos(omega * t[w]), np.sin(omega * t[w])])
    c = np.linalg.lstsq(B, np.asarray(result[label])[w], rcond=None)[0]
    return float(np.hypot(c[1], c[2]))


def test_the_3d_describing_function_is_the_first_harmonic_of_the_time_domain():
    """0.4 m of sway at 0.6 rad/s across a 0.5 m/s current at 30 deg (the body sways 10 cm): the balance in element
    coordinates gives the run's first harmonics of x_b, y_b, z_b and the top tension within 0.5 %; in node coordinates
    it overstates the sway by several per cent (the arc a node swings on: equivalent.harmonic_model)."""
    omega, a = 0.6, 0.4
    sc = _scene(top=TopMotion(z=(Sinusoid(amplitude=a, frequency=omega),), ramp_s=10.0))
    node = build_model(sc)
    p = node.parameters(sc)
    ec = harmonic_model(sc, node)
    assert ec.q_labels[:3] == ("phi[0]", "phi_z[0]", "u[0]")
    Z = np.array([0.0, 0.0, a], complex)
    h = harmonic_response(ec, p, [omega], Z, n_theta=32)
    h_node = harmonic_response(node, p, [omega], Z, n_theta=32)
    assert h.converged and not h.slack[0] and h.input_labels[:3] == ("x_s", "y_s", "z_s")
    run = simulate(sc, model=node, times=np.arange(0.0, 40 * 2 * math.pi / omega, 0.05))
    td = {k: _first_harmonic(run, k, omega) for k in ("x_b", "y_b", "z_b", "tension_top")}
    assert td["z_b"] > 0.05 and td["x_b"] > 0.01                # across the current the sway moves x and z
    for k, v in td.items():
        assert h.amplitude(k)[0] == pytest.approx(v, rel=5e-3), k
    assert h_node.amplitude("z_b")[0] > 1.03 * td["z_b"]


def _df(scene, inputs, omegas, amplitude=0.3):
    """{input: |output| per metre} of the describing function (element coordinates) per input direction alone."""
    node = build_model(scene)
    p, ec = node.parameters(scene), harmonic_model(scene, node)
    out = {}
    for inp in inputs:
        Z = np.zeros(3 if scene.three_d else 2, complex)
        Z[("x_s", "y_s", "z_s").index(inp)] = amplitude
        h = harmonic_response(ec, p, omegas, Z, n_theta=32, linear_models=False)
        assert h.converged
        out[inp] = {k: h.amplitude(k) / amplitude for k in h.output_labels if k in ("x_b", "y_b", "z_b", "tension_top")}
    return out


def test_the_plane_is_the_special_case_of_the_3d_describing_function():
    """A planar scene (a current along x) and the same scene run by the 3-D equations: the same describing functions
    per surge and per heave (1e-8); without a current, sway is surge turned by 90 deg: z_b per unit z_s is x_b per
    unit x_s of the planar scene, and the top tensions are equal (1e-8)."""
    omegas = [0.4, 1.0, 2.0]
    planar = _scene(current=0.4, heading=None)
    a, b = _df(planar, ("x_s", "y_s"), omegas), _df(planar.with_numerics(dimensions=3), ("x_s", "y_s"), omegas)
    for inp in ("x_s", "y_s"):
        for k in ("x_b", "y_b", "tension_top"):
            assert np.allclose(b[inp][k], a[inp][k], rtol=1e-8, atol=1e-12), (inp, k)
        assert np.max(b[inp]["z_b"]) < 1e-12
    still = _scene(current=0.0, heading=None)
    surge = _df(still, ("x_s",), omegas)["x_s"]
    sway = _df(dataclasses.replace(still.replace_section(0, body={"mass_z": 900.0}), name="sway"), ("z_s",), omegas)["z_s"]
    assert np.allclose(sway["z_b"], surge["x_b"], rtol=1e-8) and np.allclose(sway["tension_top"], surge["tension_top"],
                                                                                rtol=1e-8)
    assert np.max(sway["x_b"]) < 1e-12


def test_cablesys_rao_gives_the_sway_its_describing_function(tmp_path, monkeypatch):
    """The command on a 3-D scene swayed at its top: the sway's describing-function table and record (the node model's
    balance in its element coordinates), its figures asked for (drawn as empty files here: tests/test_figures.py
    draws the command's figures; 18 Bode plots in 3-D are most of this command's time)."""
    from cablesys.cli import main
    from cablesys.linear import plots
    drawn = []

    def stub(*args, **kw):
        drawn.append(args[2] if len(args) > 2 else None)
        Path(args[4] if len(args) > 4 else args[2]).write_bytes(b"")
    monkeypatch.setattr(plots, "plot_rao_bode", stub)
    monkeypatch.setattr(plots, "plot_modes", lambda md, lin, path, **kw: Path(path).write_bytes(b""))
    sc = _scene(top=TopMotion(z=(Sinusoid(amplitude=0.5, frequency=0.6),), ramp_s=10.0))
    f = tmp_path / "sway.toml"
    f.write_text(dump_scene(sc))
    assert main(["rao", str(f), "--out", str(tmp_path / "rao"), "--n", "24"]) == 0
    out = tmp_path / "rao"
    assert (out / "rao_describing_z_s.csv").is_file() and (out / "rao_z_b_z_s.png").is_file() and "z_s" in drawn
    doc = json.loads((out / "rao_summary.json").read_text())
    df = doc["linearizations"]["describing function z_s"]
    assert df["amplitude_m"] == 0.5 and df["valid"] > 0 and "phi_z[0]" in df["coordinates"]
    assert set(df["exact_vs_describing_max_rel"]) == {"z_b", "tension_top"}
    head = (out / "rao_describing_z_s.csv").read_text().splitlines()[0]
    assert "z_b" in head
