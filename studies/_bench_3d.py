"""bench_vs_moordyn's three-dimensional cases (issue 24, "Speed (benchmark)"): ``turn``, ``crane_rao``, ``current45``.

Same inputs in both codes (``_moordyn``: the top's x, y, z as MoorDyn's coupled point, set each call with
its secant velocity; a current with a heading as MoorDyn-C's ``Currents = 1`` profile), measured by the
main script's :func:`bench_vs_moordyn.bench_case` (MoorDyn at its largest stable RK4 step, cablesys's
segmented model at matched accuracy, Wang's model and ``auto``), passed in as for ``_bench_slack``.

- ``turn``: towing in a circle (Wang 1971 p. 32, "towing in a circle"), the 60 m wire and 3 kN body of
  ``_turning`` on an 80 m circle at 2 m/s (:class:`cablesys.scene.track.Track`). cablesys starts on its steady
  turn (:mod:`cablesys.statics.turning`, the run's own initial state); MoorDyn starts hanging at rest under the tow
  point (its own initial equilibrium) and settles within the first of two revolutions (the body's drag damps the
  swing in seconds): the statistics are over the second (the window rule of :func:`cablesys.statistics.window`). Checked against the steady turn's body
  radius, depth and top tension.
- ``crane_rao``: the 300 m / 2 t sphere line of ``heave_300m.toml`` hanging from a crane tip 20 m forward,
  15 m to starboard and 25 m above a vessel's RAO reference point; a regular wave of 1 m amplitude at T = 10 s
  travelling 150 deg from +x, the bow at 30 deg (relative heading 120 deg); the tip's x, y, z from the 6-DOF RAO
  (:class:`cablesys.scene.vessel.VesselRAO`). Checked against the rigid-body displacement
  s = eta_t + eta_r x r (Faltinsen 1990 ch. 3) computed here from the table (:func:`tip_closed_form`).
- ``current45``: the same line heaving 1 m at T = 10 s with its top 10 m deep, a uniform 0.5 m/s current at
  45 deg to x. MoorDyn's initial equilibrium is in still water: it drifts into the current, untimed, before its run
  (:func:`_moordyn.settle_in_current`), as cablesys starts from its statics in the current. Checked: the mean
  offset points along 45 deg in both codes (the line lies in the current's vertical
  plane by symmetry), and its size equals the planar run with the current along x (a rotation of the scene).

``planar_ratio``: the planar heave scene (``heave_300m.toml`` at T = 10 s, N = 20, the matched setting of
``heave_T10``) as the current code runs it (a planar scene builds the planar equations, 2 x 2 node blocks:
``SegmentedModel.dim == 2``) against the planar build asked for explicitly (``numerics.dimensions = 2``): both are
the one planar path the code keeps, so this ratio is ~1 by construction and says only that the dispatch adds
nothing; ``three_d_equations_ratio`` is the planar path against the 3-D equations run on the same planar scene
(``numerics.dimensions = 3``), what a planar scene would cost without its path, with the largest difference of
their body positions (m) and end tensions (N) at rtol 1e-10 (``planar_equivalence_max_abs``). Walls are the least of ``repeats`` alternating runs of simulators
built once (their time stepping and outputs), CPU times beside them.
"""

from __future__ import annotations

import dataclasses
import math
import os
import time
from pathlib import Path

import numpy as np
import tomllib

import cablesys
from cablesys.model import build_model
from cablesys.scene import load_scene, scene_from_dict
from cablesys.scene.harmonics import Sinusoid
from cablesys.scene.vessel import DOFS, HeadingRAO, VesselRAO

DATA = Path(cablesys.__file__).resolve().parent / "data"
CASES_3D = ("turn", "crane_rao", "current45")
HEAVE_PERIOD = 10.0                  # s: the taut heave of heave_300m.toml
WAVE_AMPLITUDE, WAVE_HEADING_DEG = 1.0, 150.0     # crane_rao's regular wave
VESSEL_HEADING_DEG = 30.0
LEVER_ARM = (20.0, -15.0, 25.0)      # m: crane tip in vessel axes (x forward, y to port, z up)
# the vessel's RAO at T = 10 s (omega = 0.628 rad/s, the middle table frequency) and relative heading 120 deg
# (the middle table heading): illustrative numbers of a ~90 m vessel in quartering-to-beam seas; per DOF
# (amplitude per m of wave amplitude (m/m, deg/m), phase lead over the wave elevation in deg)
RAO_120 = {"surge": (0.35, 95.0), "sway": (0.55, -80.0), "heave": (0.9, -10.0),
           "roll": (2.0, -75.0), "pitch": (0.9, 105.0), "yaw": (0.25, 15.0)}
CURRENT_SPEED, CURRENT_HEADING_DEG, CURRENT_TOP_DEPTH = 0.5, 45.0, 10.0


def _heave_base(period: float = HEAVE_PERIOD):
    """heave_300m.toml at ``period`` with the sphere's sway virtual mass (the scene made 3-D by its body)."""
    sc = load_scene(DATA / "heave_300m.toml")
    sine = dataclasses.replace(sc.top_motion.y[0], frequency=2 * math.pi / period)
    sc = dataclasses.replace(sc, top_motion=dataclasses.replace(sc.top_motion, y=(sine,)))
    return sc.replace_section(0, body={"mass_z": sc.sections[0].body.mass_x})


def vessel_rao() -> VesselRAO:
    """The crane vessel's table: three frequencies around 2 pi / 10 s and headings 60, 120, 180 deg; the values at
    (omega = 2 pi / 10, 120 deg) are ``RAO_120``, the others scaled (0.7, 1.3 in frequency; 0.8, 1.1 in heading) so
    an interpolation error would show."""
    w0 = 2 * math.pi / HEAVE_PERIOD
    omega = (0.8 * w0, w0, 1.25 * w0)

    def table(beta, k):
        cols = {}
        for dof, (amp, ph) in RAO_120.items():
            cols[f"{dof}_amplitude"] = tuple(k * amp * f for f in (0.7, 1.0, 1.3))
            cols[f"{dof}_phase_deg"] = tuple(ph + d for d in (-20.0, 0.0, 20.0))
        return HeadingRAO(heading_deg=beta, **cols)
    return VesselRAO(omega=omega, headings=(table(60.0, 0.8), table(120.0, 1.0), table(180.0, 1.1)),
                     lever_arm=LEVER_ARM, vessel_heading_deg=VESSEL_HEADING_DEG)


def tip_closed_form() -> np.ndarray:
    """Complex amplitudes (x, y, z in cablesys axes, m) of the crane tip in the regular wave, from ``RAO_120`` by the
    rigid-body displacement of a point r of the vessel, s = (eta_1, eta_2, eta_3) + (eta_4, eta_5, eta_6) x r
    (Faltinsen 1990 ch. 3), rotated by the vessel heading psi about the vertical (x = cos psi s_1 - sin psi s_2,
    z = sin psi s_1 + cos psi s_2, y = -s_3: cablesys' y is down)."""
    c = {d: WAVE_AMPLITUDE * a * (math.pi / 180 if d in ("roll", "pitch", "yaw") else 1.0) * np.exp(1j * math.radians(p))
         for d, (a, p) in RAO_120.items()}
    s = np.array([c["surge"], c["sway"], c["heave"]]) + np.cross(np.array([c["roll"], c["pitch"], c["yaw"]]),
                                                                  np.array(LEVER_ARM, complex))
    psi = math.radians(VESSEL_HEADING_DEG)
    return np.array([math.cos(psi) * s[0] - math.sin(psi) * s[1], -s[2], math.sin(psi) * s[0] + math.cos(psi) * s[1]])


def crane_scene(duration: float, ramp_periods: int = 3):
    """``crane_rao``: the tip's sinusoids from the vessel's table (:meth:`VesselRAO.transfer`) for the regular
    wave eta = a sin(omega t) (phase of a sinusoid = arg of its complex amplitude, as :func:`.sea.sea_sinusoids`)."""
    w = 2 * math.pi / HEAVE_PERIOD
    X = [WAVE_AMPLITUDE * complex(np.ravel(v)[0]) for v in vessel_rao().transfer([w], WAVE_HEADING_DEG)]
    sines = [(Sinusoid(amplitude=abs(v), frequency=w, phase=float(np.angle(v) % (2 * math.pi))),) for v in X]
    sc = _heave_base()
    top = dataclasses.replace(sc.top_motion, x=sines[0], y=sines[1], z=sines[2], ramp_s=ramp_periods * HEAVE_PERIOD)
    return dataclasses.replace(sc, name="300 m wire, 2 t sphere, crane tip on a vessel RAO (regular wave 1 m, "
                               "T = 10 s, relative heading 120 deg, lever arm 20 / -15 / 25 m)",
                               top_motion=top).with_numerics(duration=duration)


def current_scene(duration: float, heading_deg: float | None = CURRENT_HEADING_DEG, ramp_periods: int = 3):
    """``current45``: 1 m heave at T = 10 s, top 10 m deep, 0.5 m/s current at ``heading_deg`` (None: along +x, the
    planar scene of the rotation check)."""
    sc = _heave_base()
    if heading_deg is None:
        sc = sc.replace_section(0, body={"mass_z": None})
    top = dataclasses.replace(sc.top_motion, ramp_s=ramp_periods * HEAVE_PERIOD)
    sc = dataclasses.replace(sc, name=f"300 m wire, 2 t sphere, 1 m heave at T = 10 s, 0.5 m/s current at "
                             f"{heading_deg or 0:g} deg", top_motion=top)
    return sc.with_environment(top_depth=CURRENT_TOP_DEPTH, current_depths=(0.0,), current_speeds=(CURRENT_SPEED,),
                               current_headings_deg=(heading_deg,) if heading_deg is not None else ()
                               ).with_numerics(duration=duration)


def turn_scene(revolutions: float, segments: int = 6):
    """``turn``: ``_turning``'s tow on its circle for ``revolutions`` turns, sampled every 0.5 s."""
    from _turning import TOW
    sc = scene_from_dict(tomllib.loads(TOW.replace("segments = 6", f"segments = {segments}")))
    period = 2 * math.pi / abs(sc.top_motion.track.turn_rate)
    return sc.with_numerics(duration=revolutions * period, output_step=0.5), period


def cases_3d(quick: bool):
    """(name, scene, period, element counts, taut?) of the 3-D cases, as :func:`bench_vs_moordyn.cases`."""
    turn, t_turn = turn_scene(2.0)         # the statistics window is the second revolution
    dur, ramp = (20.0, 1) if quick else (60.0, 3)  # the smooth start: 3 periods as the planar cases (quick: 1)
    return [("turn", turn, t_turn, (6,) if quick else (10, 20), True),
            ("crane_rao", crane_scene(dur, ramp), HEAVE_PERIOD, (6,) if quick else (20,), True),
            ("current45", current_scene(dur, ramp_periods=ramp), HEAVE_PERIOD, (6,) if quick else (20,), True)]


# -- per-case checks against closed forms and independent routes -------------------------------------------


def _tight(sc):
    return cablesys.simulate(sc, model="segmented", method="cvodes", rtol=1e-8, atol=1e-10)


def turn_checks(scene, row) -> dict:
    """The steady turn (:func:`cablesys.statics.turning.turning_initial_state`) at the case's first N: body radius
    from the circle's centre, depth, top tension; against both codes' window means (cablesys's tight run, MoorDyn's
    run in the row) and the radius against the body's x amplitude (a steady turn's x_b is R_b sin)."""
    from cablesys.statics.turning import turning_initial_state
    e0 = row["by_n"][0]
    sc = scene.replace_section(0, cable={"segments": e0["segments"]})
    model = build_model(sc)
    p = model.parameters(sc)
    x0 = turning_initial_state(sc, model, p)
    y = dict(zip(model.output_labels, np.array(model.outputs(x0, model.top(0.0, p), p)).ravel()))
    steady = {"radius_m": float(math.hypot(y["x_b"], y["z_b"])), "depth_m": float(y["y_b"]),
              "tension_top_N": float(y["tension_top"])}
    out = {"steady_turn": steady}
    for who in ("cablesys", "moordyn"):
        st = e0[f"{who}_stats"]
        r = 0.5 * (st["x_b_amplitude"] + st["z_b_amplitude"])
        out[who] = {"radius_m": r, "depth_m": st["y_b_mean"], "tension_top_max_N": st["tension_top_max"],
                    "radius_rel_err": abs(r - steady["radius_m"]) / steady["radius_m"],
                    "depth_rel_err": abs(st["y_b_mean"] - steady["depth_m"]) / steady["depth_m"],
                    "tension_top_rel_err": abs(st["tension_top_max"] - steady["tension_top_N"]) / steady["tension_top_N"]}
    return out


def crane_checks(scene, row) -> dict:
    """The tip's amplitudes per axis: the closed form (:func:`tip_closed_form`), cablesys's prescribed top
    (``model.top`` over the last period) and MoorDyn's coupled node over the last period (a run at the row's step)."""
    from _moordyn import run_moordyn
    e0 = row["by_n"][0]
    sc = scene.replace_section(0, cable={"segments": e0["segments"]})
    model = build_model(sc)
    p = model.parameters(sc)
    t1 = sc.numerics.duration
    ts = np.linspace(t1 - HEAVE_PERIOD, t1, 401)
    e = np.array([np.array(model.top(t, p)).ravel() for t in ts])
    cs = 0.5 * np.ptp(e[:, 1:4], axis=0)
    md = run_moordyn(sc, e0["segments"], e0["moordyn_dt_s"])
    tm = np.asarray(md["time"])
    w = tm >= t1 - HEAVE_PERIOD - 1e-9
    top = md["top_moordyn_axes"][w]
    md_amp = 0.5 * np.array([np.ptp(top[:, 0]), np.ptp(top[:, 2]), np.ptp(top[:, 1])])   # X, -Z, Y = x, y, z
    closed = np.abs(tip_closed_form())
    return {"tip_amplitude_closed_form_m": closed.tolist(), "tip_amplitude_cablesys_m": cs.tolist(),
            "tip_amplitude_moordyn_m": md_amp.tolist(),
            "cablesys_vs_closed_form_max_rel": float(np.max(np.abs(cs - closed)) / closed.max()),
            "moordyn_vs_closed_form_max_rel": float(np.max(np.abs(md_amp - closed)) / closed.max())}


def current_checks(scene, row) -> dict:
    """The mean offset's heading atan2(z_b, x_b) (deg; 45 by symmetry) and size in both codes, and cablesys's
    size against the planar scene with the current along +x (the same scene turned by -45 deg), tight runs at the
    case's first N."""
    e0 = row["by_n"][0]
    n = e0["segments"]
    out = {}
    for who in ("cablesys", "moordyn"):
        st = e0[f"{who}_stats"]
        out[who] = {"offset_heading_deg": math.degrees(math.atan2(st["z_b_mean"], st["x_b_mean"])),
                    "offset_m": math.hypot(st["x_b_mean"], st["z_b_mean"]), "depth_m": st["y_b_mean"]}
    from cablesys.ladder import metrics as M
    ramp = scene.top_motion.ramp_s / HEAVE_PERIOD
    planar = current_scene(scene.numerics.duration, None, round(ramp)).replace_section(0, cable={"segments": n})
    res = _tight(planar)
    stp = M.statistics(res, HEAVE_PERIOD)
    out["planar_current_along_x"] = {"offset_m": stp["x_b_mean"], "depth_m": stp["y_b_mean"]}
    out["offset_vs_planar_rel"] = abs(out["cablesys"]["offset_m"] - stp["x_b_mean"]) / abs(stp["x_b_mean"])
    out["depth_vs_planar_rel"] = abs(out["cablesys"]["depth_m"] - stp["y_b_mean"]) / abs(stp["y_b_mean"])
    return out


CHECKS = {"turn": turn_checks, "crane_rao": crane_checks, "current45": current_checks}


def agreement(row, limit: float = 0.02) -> list:
    """The N at which cablesys's tight run and MoorDyn differ by more than ``limit`` (body or tension), with the
    like-for-like figure (end element vs MoorDyn's end segment, ``cablesys_vs_moordyn_segments``) beside it."""
    out = []
    for e in row["by_n"]:
        d, s = e["cablesys_vs_moordyn"], e["cablesys_vs_moordyn_segments"]
        if max(d["body"], d["tension"]) > limit:
            out.append({"segments": e["segments"], "vs_moordyn": d, "vs_moordyn_segments": s})
    return out


# -- planar_ratio ----------------------------------------------------------------------------------------------


def _cpu() -> float:
    t = os.times()
    return t.user + t.system


def planar_ratio(prepared, n: int = 20, method: str = "cvodes-bdf2", rtol: float = 1e-4, repeats: int = 3,
                 duration: float = 60.0) -> dict:
    """The planar heave scene (T = 10 s, ``n`` elements) three ways, simulators built once (``prepared(sc, method,
    rtol, atol) -> (sim, p, x0, setup)`` of the main script), each run ``repeats`` times alternately, least wall
    (and its CPU) of each: as dispatched (``numerics.dimensions`` unset), the planar path asked for
    (``dimensions = 2``) and the 3-D equations (``dimensions = 3``). See the module docstring."""
    base = load_scene(DATA / "heave_300m.toml")
    sine = dataclasses.replace(base.top_motion.y[0], frequency=2 * math.pi / HEAVE_PERIOD)
    base = dataclasses.replace(base, top_motion=dataclasses.replace(base.top_motion, y=(sine, ), ramp_s=3 * HEAVE_PERIOD))
    base = dataclasses.replace(base.replace_section(0, cable={"segments": n}).with_numerics(duration=duration),
                               name=f"300 m steel wire, 2 t sphere, 1 m heave at T = {HEAVE_PERIOD:g} s (planar)")
    variants = {"dispatched": base, "planar_path": base.with_numerics(dimensions=2),
                "three_d_equations": base.with_numerics(dimensions=3)}
    built = {k: prepared(sc, method, rtol, rtol * 1e-3) for k, sc in variants.items()}
    best = {k: (math.inf, math.inf) for k in variants}
    for i in range(repeats + 1):                    # the first round warms every simulator up
        for k, (sim, p, x0, _) in built.items():
            t0, c0 = time.perf_counter(), _cpu()
            sim.run(p, x0)
            wall, cpu = time.perf_counter() - t0, _cpu() - c0
            if i:
                best[k] = min(best[k], (wall, cpu))
    # the same answer: both paths at a tight tolerance (the timed runs' rtol leaves ~1e-3 of integration error)
    a, b = (prepared(variants[k], "cvodes", 1e-10, 1e-12) for k in ("planar_path", "three_d_equations"))
    a, b = a[0].run(a[1], a[2]), b[0].run(b[1], b[2])
    diff = max(float(np.max(np.abs(np.asarray(a[k]) - np.asarray(b[k])))) for k in ("x_b", "y_b", "tension_top", "tension_bottom"))
    dims = {k: int(v[0].model.dim) for k, v in built.items()}
    return {"scene": base.name, "segments": n, "method": method, "rtol": rtol, "repeats": repeats, "duration_s": duration,
            "model_dim": dims, "wall_s": {k: v[0] for k, v in best.items()}, "cpu_s": {k: v[1] for k, v in best.items()},
            "planar_ratio": best["planar_path"][0] / best["dispatched"][0],
            "planar_ratio_cpu": best["planar_path"][1] / max(best["dispatched"][1], 1e-9),
            "three_d_equations_ratio": best["planar_path"][0] / best["three_d_equations"][0],
            "planar_equivalence_max_abs": diff, "load_1min": os.getloadavg()[0],
            "compares": "the planar scene as the current code runs it (dim 2) against the planar path asked for "
                        "(dimensions = 2, dim 2): the same path, so ~1; three_d_equations_ratio: the planar path "
                        "against the 3-D equations (dim 3) on the same scene"}
