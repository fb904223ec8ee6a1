"""The other-ends rows of ``bench_vs_moordyn`` (issue 25): a mooring line on the seabed and a lowering by a winch.

``mooring``: a studless chain (the one of ``ends_checks``: 300 m = 3 x the 100 m water depth below the fairlead,
w = 1300 N/m, EA = 50 MN, d = 0.1 m, 150 kg/m) from an anchor on a flat seabed to a fairlead 10 m below the
surface, half its length on the bed at rest; the bed is MoorDyn's default (k = 3 MPa/m, c = 0.3 MPa s/m per unit
contact area) with Coulomb friction mu = 0.5 (regularised over v_s = 0.01 m/s). The fairlead moves on a regular
ellipse: surge x = 2 m sin(w t), heave y = 1 m cos(w t) (y down), T = 10 s, both codes behind the same smooth start
(3 periods). Built with cablesys's anchor and seabed (:class:`cablesys.scene.Anchor`, :class:`cablesys.scene.Seabed`,
:mod:`cablesys.model.segmented_seabed`); MoorDyn's line is the same cable (``_moordyn.moordyn_input``) between a
fixed point and the coupled fairlead, with its seabed options mapped by ``_moordyn.seabed_options`` (where the laws
differ is said there). Friction makes the state history-dependent: MoorDyn's stationary solver starts the line
without friction (its friction is zero at rest), cablesys's statics lay it down by pulling the fairlead away (the
anchor tension relieved by mu w per metre on the bed, :func:`cablesys.statics.closed_forms.seabed_catenary`). So that
both codes start from the same state, every cablesys run compared with MoorDyn starts from the frictionless statics
(``start``); the laid-down start is run beside it (``laid_start_vs_frictionless_start``) and is what ``auto`` (as a
user runs it) starts from, so auto's error is against a reference started the same way.

``lowering``: a 2 kN package (400 kg, C_D A = 1 m^2) on a 30 mm wire (w = 25 N/m, EA = 20 MN, 3 kg/m) hanging from a
fixed sheave, paid out by the ``[winch]`` (:class:`cablesys.scene.Winch`, :mod:`cablesys.model.segmented_winch`) from
20 m to 80 m at 1 m/s (3 s smoothstep ramps). MoorDyn pays out with its own length rate (``SetLineUnstretchedLength``
and ``SetLineUnstretchedLengthVel`` before every coupling call, ``_moordyn.winch_hook``): its nodes stay at fixed
fractions of L as ours do, mass, weight and buoyancy follow L. What MoorDyn does not have, and is therefore switched
off on both sides: the material strain rate (MoorDyn's Voigt damping acts on the segment's rate of stretch, which a
steady payout makes BA w / L of compression damping: internal damping 0 here) and the tangential drag of the cable
sliding through the water (MoorDyn's drag sees the node velocities, (1 - c) w at a node a fraction c of L above the
package, half the material's on average: C_t = 0 here). So the closed form in the constant-speed part is
T = W_b + w L - 1/2 rho C_D A v^2 (the weight in water of package and paid-out wire less the package's drag; Wang
1971 eq. 12, 32), for cablesys's tension on the sheave and, less the half segment w L / (2 N) lumped on MoorDyn's
coupled point, for MoorDyn's top segment.

Per case and N (both cases N = 20; ``--quick`` N = 10 and 6, short runs, no reference and no auto): MoorDyn at its
largest stable step (RK4, halving from 4x the axial estimate, then one geometric bisection round:
``_moordyn.largest_stable_dt``; a step is accepted when its run agrees with the half step's on the body and on *both*
end tensions, :func:`_agree`), cablesys's segmented
model at matched accuracy (the loosest CVODES BDF(<= 2) rtol whose body amplitudes are within 0.5 % and tension
extremes within 1 % of its own tight run, rtol 1e-7: ``bench_vs_moordyn._matched``), both timed in the same run as
wall and process CPU time of the second run of a simulator built once (MoorDyn: its steps and outputs; its CPU is
of the whole call, input and stationary solver included), with the 1-minute load; ``auto``: the ladder's default
(``_bench_auto.auto_row``) against MoorDyn at N.
"""

from __future__ import annotations

import math
import os
import time

import numpy as np
from _common import BDF_RTOLS
from _moordyn import largest_stable_dt, moordyn_input, moordyn_static, run_moordyn, seabed_options, volume_diameter

from cablesys.ladder import metrics as M
from cablesys.model import build_model
from cablesys.scene import Anchor, Body, Cable, Numerics, Seabed, Winch, single_section_scene
from cablesys.scene.components import Environment, TopMotion
from cablesys.scene.harmonics import Sinusoid
from cablesys.statics.closed_forms import seabed_catenary
from cablesys.time_domain.initial import initial_state
from cablesys.time_domain.integrators import COMPILE_MAX_ELEMENTS, IntegratorSettings
from cablesys.time_domain.run import Simulator

ENDS_CASES = ("mooring", "lowering")
RTOLS = BDF_RTOLS                            # BDF(<= 2) candidates, loosest first (as the taut rows)
TIGHT = (1e-7, 1e-10)                        # cablesys's own tight run (rtol, atol)

# the mooring line: the chain of ends_checks, the fairlead TOP_DEPTH below the surface, half the chain on the bed
TOP_DEPTH, DEPTH = 10.0, 100.0
PERIOD, SURGE, HEAVE = 10.0, 2.0, 1.0        # s, m, m: x = SURGE sin(w t), y = HEAVE cos(w t) (y down)
FRICTION = 0.5
# the lowering: 30 mm wire, 2 kN package, 20 m -> 80 m at 1 m/s
L0, PAY_OUT, SPEED, RAMP = 20.0, 60.0, 1.0, 3.0


def mooring_scene(n: int, quick: bool = False, friction: float = FRICTION):
    """The mooring case at N = ``n`` (module docstring): 80 s (quick 30 s with a one-period start), outputs every 0.1 s."""
    from ends_checks import catenary_case, chain
    span, _ = catenary_case(0.0)                       # L_B = L / 2 on the bed, without friction
    w = 2 * math.pi / PERIOD
    ramp, dur = (PERIOD, 3 * PERIOD) if quick else (3 * PERIOD, 8 * PERIOD)
    return single_section_scene(
        name=f"mooring: 300 m chain, anchor {span:.1f} m away, fairlead surge {SURGE:g} m / heave {HEAVE:g} m, "
             f"T = {PERIOD:g} s, mu = {friction:g}",
        cable=chain(n), body=Body(weight=0.0, mass_x=1.0, mass_y=1.0), anchor=Anchor(x=span, y=DEPTH),
        environment=Environment(top_depth=TOP_DEPTH),
        seabed=Seabed(depth=DEPTH + TOP_DEPTH, friction_axial=friction),
        top_motion=TopMotion(x=(Sinusoid(amplitude=SURGE, frequency=w),),
                             y=(Sinusoid(amplitude=HEAVE, frequency=w, phase=math.pi / 2),), ramp_s=ramp),
        numerics=Numerics(duration=dur, output_step=0.1, model="as-built"))


def lowering_scene(n: int, quick: bool = False):
    """The lowering case at N = ``n`` (module docstring); quick: 10 m paid out with 2 s ramps."""
    pay, ramp = (10.0, 2.0) if quick else (PAY_OUT, RAMP)
    cable = Cable(length=L0, ae=2e7, diameter=0.03, mass_per_length=3.0, weight_per_length=25.0, cd_normal=1.5,
                  ct_tangential=0.0, internal_damping=0.0, segments=n)
    body = Body(weight=2000.0, mass_x=400.0, mass_y=400.0, drag_area_normal=1.0, drag_area_tangential=1.0)
    duration = pay / SPEED + ramp
    return single_section_scene(
        name=f"lowering: 2 kN package paid out {L0:g} m -> {L0 + pay:g} m at {SPEED:g} m/s", cable=cable, body=body,
        numerics=Numerics(duration=duration, output_step=0.1, model="as-built"),
        winch=Winch(speed=SPEED, duration=duration, ramp=ramp, max_length=L0 + pay + 5.0))


def case(name: str, quick: bool):
    """(scene builder n -> scene, forcing period or None, element counts, start scene builder or None)."""
    if name == "mooring":
        return (lambda n: mooring_scene(n, quick), PERIOD, (10,) if quick else (20,),
                lambda n: mooring_scene(n, quick, friction=0.0))
    return (lambda n: lowering_scene(n, quick)), None, (6,) if quick else (20,), None


STEP_TOL, STEP_REFINE = 0.02, 1


def _agree(a: dict, b: dict, tol: float = STEP_TOL) -> bool:
    """MoorDyn's step test (``_moordyn.largest_stable_dt``): a run at a step and at half of it agree sample by sample
    within ``tol`` on the body's (package's) position (of the larger of its ranges and 1 m) and on *both* end
    tensions (each of its own largest value). The bottom end matters on the mooring line: at N = 20 its laid nodes'
    friction slope mu w l / (m v_s) = 430 1/s puts RK4's limit near 6.5 ms, and at 12.5 ms (where the top tension
    still agrees within 0.1 %) the friction chatters and the anchor tension swings 77-86 kN instead of 81.4-81.6 kN."""
    span = max(np.ptp(b["x_b"]), np.ptp(b["y_b"]), 1.0)
    body = max(np.max(np.abs(a["x_b"] - b["x_b"])), np.max(np.abs(a["y_b"] - b["y_b"]))) / span
    tens = max(np.max(np.abs(a[k] - b[k])) / max(np.max(np.abs(b[k])), 1e-300) for k in ("tension_top", "tension_bottom"))
    return bool(body <= tol and tens <= tol)


# -- cablesys runs from a given start ---------------------------------------------------------------------------------

def _prepared(sc, method, rtol, atol, start=None):
    """(simulator, p, x0, setup wall): the segmented model of ``sc``, its integrators, and x0 from the statics of
    ``start`` (the same model structure; default ``sc`` itself)."""
    t0 = time.perf_counter()
    model = build_model(sc)
    sim = Simulator(model, sc.output_times, IntegratorSettings(method=method, rtol=rtol, atol=atol,
                                                               steps_per_output=sc.numerics.steps_per_output))
    p = model.parameters(sc)
    x0 = initial_state(start or sc, model, model.parameters(start) if start is not None else p)
    return sim, p, x0, time.perf_counter() - t0


def _timed_run(sc, method, rtol, atol, start=None):
    """(result, wall, first-call wall, setup wall, CPU) of the stepping and outputs: a second run of a simulator built
    once (setup apart, as MoorDyn's input and stationary solver)."""
    sim, p, x0, setup = _prepared(sc, method, rtol, atol, start)
    t0 = time.perf_counter()
    sim.run(p, x0)
    first = setup + time.perf_counter() - t0
    t0, c0 = time.perf_counter(), time.process_time()
    r = sim.run(p, x0)
    return r, time.perf_counter() - t0, first, setup, time.process_time() - c0


def _run_once(sc, method, rtol, atol, start=None):
    """One run of ``sc`` from the statics of ``start`` (untimed)."""
    sim, p, x0, _ = _prepared(sc, method, rtol, atol, start)
    return sim.run(p, x0)


def _moordyn_timed(sc, n, dt):
    """MoorDyn's run at step ``dt``, its second call timed: (run, CPU of the whole second call)."""
    run_moordyn(sc, n, dt)
    c0 = time.process_time()
    r = run_moordyn(sc, n, dt)
    return r, time.process_time() - c0


def _series(tight, md, every: int = 2) -> dict:
    """Every ``every``-th output of both codes' end tensions (N) for the figure: cablesys's forces on the end points and
    its end elements' tensions, MoorDyn's end segments'."""
    T = np.asarray(tight.profiles["element_tension"])
    return {"time": np.asarray(tight.time)[::every].tolist(),
            "cablesys_tension_top": np.asarray(tight["tension_top"])[::every].tolist(),
            "cablesys_tension_bottom": np.asarray(tight["tension_bottom"])[::every].tolist(),
            "cablesys_top_element_tension": T[::every, 0].tolist(),
            "cablesys_bottom_element_tension": T[::every, -1].tolist(),
            "moordyn_time": md["time"][::every].tolist(), "moordyn_tension_top": md["tension_top"][::every].tolist(),
            "moordyn_tension_bottom": md["tension_bottom"][::every].tolist()}


def _each(a: dict, b: dict) -> dict:
    """Each tension extreme's relative difference of a against b (statistics of ``bench_vs_moordyn._stats``)."""
    return {k: (a[k] - b[k]) / abs(b[k]) if abs(b[k]) > 1e-9 else a[k] - b[k]
            for k in b if k.startswith("tension") and k.endswith(("_max", "_min")) and k in a}


# -- the static and closed-form checks (the quick test's physics) -----------------------------------------------------

def mooring_static(n: int) -> dict:
    """Static fairlead force of both codes at N = ``n`` against the elastic catenary with seabed contact (frictionless,
    rigid-bed limit: :func:`cablesys.statics.closed_forms.seabed_catenary`): cablesys's top tension at t = 0 (the force
    on the fairlead) and MoorDyn's force on its coupled point (``_moordyn.moordyn_static``), relative errors."""
    from ends_checks import DIAMETER, EA, LENGTH, W, catenary_case
    sc = mooring_scene(n, True, friction=0.0)
    span, _ = catenary_case(0.0)
    cf = seabed_catenary(length=LENGTH, weight_per_length=W, ea=EA, span=span, height=DEPTH)
    exact = math.hypot(cf["H"], cf["V_F"])
    sim, p, x0, _ = _prepared(sc.with_numerics(duration=1.0), "cvodes", 1e-8, 1e-10)
    cs = float(sim.run(p, x0)["tension_top"][0])
    md = moordyn_static(sc, n)["top_force"]
    # the bed's compliance sinks the laid chain by w / (k d_0) = 4.3 mm (the closed form's bed is rigid)
    return {"N": n, "closed_form_N": exact, "cablesys_N": cs, "moordyn_N": md, "cablesys_rel_err": cs / exact - 1,
            "moordyn_rel_err": md / exact - 1, "bed_sink_m": W / (sc.seabed.stiffness * DIAMETER)}


def lowering_closed_form(result, scene, segment: bool = False) -> dict:
    """Top tension over the constant-speed part (1 s after the ramp to the start of the ramp down) against
    W_b + w L - 1/2 rho C_D A v^2 (module docstring), L the zero-tension length paid out (the winch profile);
    ``segment``: MoorDyn's top segment, less w L / (2 N). Returns the largest relative error and the drag's share."""
    wn, b, c = scene.winch, scene.sections[0].body, scene.sections[0].cable
    t = np.asarray(result["time"] if isinstance(result, dict) else result.time)
    L = L0 + np.array([wn.profile(ti)[0] for ti in t])
    drag = 0.5 * scene.environment.density * b.drag_area_tangential * SPEED**2
    closed = b.weight + c.weight_per_length * c.length / L0 * L - drag
    if segment:
        closed = closed - c.weight_per_length * c.length / L0 * L / (2 * c.segments)
    steady = (t > wn.start + wn.ramp + 1.0) & (t < wn.start + wn.duration - wn.ramp)
    T = np.asarray(result["tension_top"])
    return {"max_rel_err": float(np.max(np.abs(T[steady] / closed[steady] - 1))),
            "drag_share": float(drag / np.min(closed[steady]))}


# -- the row -----------------------------------------------------------------------------------------------------------

def bench_ends_case(name: str, quick: bool, *, matched, stats, diff, segment_stats, moordyn_stats, compiled_ctx,
                    auto_row=None, auto_bound=None) -> dict:
    """One other-ends row (module docstring). The helpers are ``bench_vs_moordyn``'s (``_matched``, ``_stats``,
    ``_diff``, ``_segment_stats``, ``_moordyn_stats``, ``_compiled``) and ``_bench_auto.auto_row`` (None: no auto)."""
    make, period, ns, make_start = case(name, quick)
    scene = make(max(ns))
    dur = scene.numerics.duration
    row = {"case": name, "scene": scene.name, "duration_s": dur, "period_s": period, "quick": quick, "by_n": [],
           "timing": "wall and process CPU seconds of a second run (setup apart) under the stated 1-minute load of a "
                     "shared 2-core machine: compare the ratios, measured in one run"}
    if name == "mooring":
        row["static"] = mooring_static(max(ns))
        row["moordyn_seabed"] = seabed_options(scene, max(ns), volume_diameter(moordyn_input(scene, max(ns), 1e-3)))
        row["top_motion"] = (f"regular: surge x = {SURGE:g} m sin(2 pi t / {PERIOD:g} s), heave y = {HEAVE:g} m "
                             f"cos(2 pi t / {PERIOD:g} s) (y down): an ellipse, ramped over {scene.top_motion.ramp_s:g} s")
    md_at = None
    for n in ns:
        sc, start = make(n), (make_start(n) if make_start else None)
        compiled = n <= COMPILE_MAX_ELEMENTS and not quick
        dt = largest_stable_dt(sc, n, probe_s=min(dur, 2 * (period or 5.0)), agree=_agree, refine=STEP_REFINE)
        load = os.getloadavg()[0]
        md, md_cpu = _moordyn_timed(sc, n, dt)
        md_stats = moordyn_stats(md, period)
        with compiled_ctx(compiled):
            tight = _run_once(sc, "cvodes", *TIGHT, start)
            tight_stats = stats(tight, period)
            cpus = {}

            def timed(meth, rtol, sc=sc, start=start):
                out = _timed_run(sc, meth, rtol, rtol * 1e-3, start)
                cpus[(meth, rtol)] = out[4]
                return out
            m = matched(None, tight_stats, period, timed=timed, methods=("cvodes-bdf2",),
                        rtols=(1e-4,) if quick else RTOLS)
            laid = stats(_run_once(sc, "cvodes", *TIGHT), period) if start is not None else None
        entry = {"segments": n, "cablesys_compiled": compiled, "moordyn_dt_s": dt, "largest_stable_dt": dt,
                 "moordyn_s_per_s": md["wall_s"] / dur, "moordyn_wall_s": md["wall_s"], "moordyn_cpu_s": md_cpu,
                 "moordyn_stable": md["stable"], "moordyn_steps": int(round(dur / dt)), "load_1min": load,
                 "moordyn_stats": md_stats, "cablesys_stats": tight_stats,
                 "cablesys_vs_moordyn": diff(tight_stats, md_stats),
                 "cablesys_vs_moordyn_segments": diff(segment_stats(tight, period), md_stats),
                 "cablesys_vs_moordyn_each": _each(tight_stats, md_stats),
                 "cablesys_vs_moordyn_segments_each": _each(segment_stats(tight, period), md_stats),
                 "series": _series(tight, md)}
        if laid is not None:
            entry["laid_start_stats"] = laid
            entry["laid_start_vs_frictionless_start"] = _each(laid, tight_stats)
        if name == "lowering":
            entry["closed_form"] = {"cablesys": lowering_closed_form(tight, sc),
                                    "moordyn": lowering_closed_form(md, sc, segment=True)}
        if m:
            res, wall, first, how = m
            cpu = cpus[(how["method"], how["rtol"])]
            entry.update(cablesys_s_per_s=wall / dur, cablesys_wall_s=wall, cablesys_cpu_s=cpu, cablesys_settings=how,
                         cablesys_build_s=first - wall, cablesys_steps=res.stats.get("nsteps"),
                         speedup=md["wall_s"] / wall, speedup_cpu=md_cpu / cpu)
        else:
            entry.update(cablesys_s_per_s=None, speedup=None, note="no setting met matched accuracy")
        row["by_n"].append(entry)
        md_at = (n, md["wall_s"])
    if quick or auto_row is None:
        row["auto"] = {"skipped": "--quick: no converged reference and no auto (its compile alone takes longer)"}
        return row
    # the converged reference: 2 x N, from the start auto also uses (the scene's own statics)
    with compiled_ctx(False):
        ref = _run_once(make(2 * max(ns)), "cvodes", *TIGHT)
    ref_stats = stats(ref, period)
    row["reference"] = {"segments": 2 * max(ns), "start": "the scene's own statics", "stats": ref_stats,
                        "success": bool(ref.success)}
    for e in row["by_n"]:          # the run started as the reference was (MoorDyn's tensions are its segments': no error)
        e["cablesys_error_vs_converged"] = diff(e.get("laid_start_stats", e["cablesys_stats"]), ref_stats)
    row["auto"] = auto_row(scene, period, ref_stats, md_at, stats=stats, diff=diff)
    if auto_bound is not None:    # the most any auto keeping its tolerance could reach here (choice and checks free)
        row["auto_bound"] = auto_bound(make, M.statistics(ref, period), 2 * max(ns), period, md_at,
                                       timed_run=_timed_run,
                                       compiled_ctx=compiled_ctx, compiled_max=COMPILE_MAX_ELEMENTS,
                                       moordyn_stats=row["by_n"][-1]["moordyn_stats"],
                                       moordyn_reference=segment_stats(ref, period))
    row["auto_speedup"] = row["auto"].get("speedup")
    row["auto_speedup_run_only"] = row["auto"].get("speedup_run_only")
    row["auto_error"] = row["auto"].get("error")
    return row


def plot(rows, path):
    """Per case (a column) the top tension (upper row) and the bottom-end tension (lower: the anchor or the package)
    of both codes against time (cablesys: the force on the end point and the end element's tension; MoorDyn: its end
    segment's), and the speed bars (s per simulated s, log) on the right."""
    from _common import setup_matplotlib, speed_bars

    from cablesys.plots import save_figure
    plt = setup_matplotlib()
    fig = plt.figure(figsize=(5.0 * (len(rows) + 1), 7.6))
    grid = fig.add_gridspec(2, len(rows) + 1)
    ends = (("top", "top tension (kN)", "force on the top"), ("bottom", "bottom-end tension (kN)", "force on the end"))
    for col, r in enumerate(rows):
        e = r["by_n"][-1]
        s = e["series"]
        bottom = "anchor" if r["case"] == "mooring" else "package"
        for row, (end, ylabel, point) in enumerate(ends):
            ax = fig.add_subplot(grid[row, col])
            ax.plot(s["time"], np.array(s[f"cablesys_tension_{end}"]) / 1e3, "-", lw=1.2, label=f"cablesys: {point}")
            ax.plot(s["time"], np.array(s[f"cablesys_{end}_element_tension"]) / 1e3, "-", lw=1.0,
                    label=f"cablesys: {end} element")
            ax.plot(s["moordyn_time"], np.array(s[f"moordyn_tension_{end}"]) / 1e3, "--", lw=1.0,
                    label=f"MoorDyn: {end} segment")
            where = ("fairlead" if bottom == "anchor" else "top") if end == "top" else bottom
            ax.set_title(f"{r['case']}, N = {e['segments']}: {where}", fontsize=10)
            ax.set_ylabel(ylabel)
            ax.grid(alpha=0.3)
            ax.legend(fontsize=7)
            if row == 1:
                ax.set_xlabel("time (s)")
    speed_bars(fig.add_subplot(grid[:, -1]), rows, ("auto",), fontsize=7,
               cablesys_label="cablesys (segmented: matched accuracy;\nauto: as a user runs it)",
               title="speed, both codes in the same run (speedup over the bars)")
    save_figure(fig, path)



NOTES = {
    "mooring_step": "MoorDyn's largest stable step on the mooring line is set by the laid chain's friction, not by its "
                    "axial modes: the friction slope at rest mu w l / v_s over the node mass, 0.5 x 19.5 kN / 0.01 m/s / "
                    "2250 kg = 430 1/s at N = 20, puts RK4's limit near 2.78 / 430 = 6.5 ms (the bed's damping c d_0 l "
                    "/ m: 190 1/s, 14.6 ms; the axial mode 2 sqrt(k / m): 77 rad/s, 36 ms). Above it the friction "
                    "chatters and the anchor tension is wrong while the fairlead's is not: at 12.5 ms (accepted by a "
                    "test on the top tension alone, the taut rows' test) the anchor segment swings 77.1-85.8 kN, at "
                    "6.25, 5, 3.1, 1.6, 0.8 ms 81.39-81.56 kN; the fairlead segment 194.5-208.5 kN at every step. So "
                    "the step test here (_agree) also holds the bottom tension to 2 % of itself; with one geometric "
                    "bisection round it accepts 8.84 ms, where the anchor segment is 80.1-80.5 kN (1.3 % below its "
                    "small-step level, noisy: the bottom-left panel of the figure). A user who needs the anchor "
                    "tension within 1 % runs MoorDyn at <= 6.25 ms (0.76 s for the 80 s run against 0.43 s at 12.5 ms "
                    "in a separate run under load 4: about 1.4 x the wall of the accepted step).",
    "mooring_agreement": "Converged case (N = 20, both codes converged in time; cablesys from the frictionless statics, "
                         "as MoorDyn's stationary solver starts): fairlead, the same quantity (cablesys's top element "
                         "against MoorDyn's top segment) max 0.10 %, min -0.05 %; as the forces on the fairlead 4.7 % / "
                         "4.2 %, which is the half segment w h / 2 = 1300 N/m x 7.5 m = 9.75 kN (4.6 %) that cablesys "
                         "lumps on the fairlead and MoorDyn's segment tension leaves out (a definition, see the "
                         "tension_gap note of bench_vs_moordyn). Anchor (window 30-80 s): cablesys's bottom element "
                         "81.42-81.65 kN against MoorDyn's bottom segment 81.39-81.56 kN at its small steps (<= 6.25 ms: "
                         "within 0.1 %), "
                         "80.1-80.5 kN at its accepted 8.84 ms step (1.4 / 1.7 %: its friction at the edge of RK4's "
                         "stability, mooring_step). Statics at N = 20: both codes' fairlead force 0.33 % below the "
                         "elastic catenary with seabed contact (the lumped line's O(h^2) error: MoorDyn -1.4, -0.33, "
                         "-0.08 % at N = 10, 20, 40), 4e-5 apart. No disagreement above 3 % on the fairlead in the "
                         "converged case once the quantities are the same; none from the seabed law (the normal force's "
                         "clipping and the friction's knee differ, seabed_options: their effect is below the 0.1 % seen "
                         "at the anchor).",
    "mooring_friction_history": "Friction makes the state depend on history: cablesys's own statics lay the chain "
                                "down by pulling the fairlead away (the anchor relieved by mu w per metre on the bed, "
                                "here fully: H - mu w L_B < 0), MoorDyn's start without friction. Started laid down, "
                                "cablesys's fairlead extremes change by 1e-4 and its anchor extremes by -0.1 / -2.4 % "
                                "(laid_start_vs_frictionless_start: over 80 s the regularised friction lets the laid "
                                "chain creep back towards the frictionless state, ends_checks' laid_line_creep_m). "
                                "The benchmark's cablesys runs start as MoorDyn's; auto runs as a user runs it (laid "
                                "down), and its reference (N = 40, rtol 1e-7) starts the same way.",
    "mooring_speed": "Run of 2026-12-05 12:16-12:19 UTC (this JSON), load 0.9 on 2 cores (nothing else running): "
                     "MoorDyn N = 20 at 8.84 ms, 9051 steps, 0.199 s wall, 0.224 s CPU (the whole call, its stationary "
                     "solver included); cablesys segmented N = 20, BDF(<= 2) at rtol 1e-2, the loosest of "
                     "_common.BDF_RTOLS within matched accuracy, 545 steps, 0.015 s: speedup 13.0 (target >= 5: met). "
                     "Auto (N = 20 from the scene's cable, checked a posteriori against N = 10 and against rtol 1e-5; "
                     "the node model is the only rung for an anchored line): choose 0.1 ms + run 0.027 s + checks "
                     "0.082 s = 0.109 s: auto_speedup 1.83 (target >= 20: missed); speedup_run_only 4.9 (the reported "
                     "run, N = 20 at rtol 1e-5, 0.041 s); its error against the reference 0.30 %. The bound "
                     "(auto_bound): the least N keeping auto's tolerance on every quantity against the N = 40 "
                     "reference is 10 (tension_top_min 1.1 %; N = 8: 2.6 %), its fastest run 7.6 ms (rtol 1e-2, 590 "
                     "steps): 26x with no choice and no check. A check of N = 10 costs a second run: N = 5 takes 7.3 ms "
                     "at rtol 1e-2 (603 steps: the step count, not N, sets the cost here), so N = 10 checked costs at "
                     "least 14.9 ms, 13x, and auto's check (Richardson, order 2) cannot accept N = 10 from N = 5 "
                     "(tension_bottom_min 5.6 % apart: it climbs to N = 24, 0.32 s). MoorDyn's N = 20 run misses auto's "
                     "tolerance itself (tension_top_max 2.7 % from the converged reference, like for like).",
    "lowering_law": "MoorDyn pays out as cablesys does (nodes at fixed fractions of L, mass, weight and buoyancy from "
                    "L). Left out on both sides because MoorDyn lacks them: the material strain rate (its Voigt damping "
                    "sees the rate of stretch of a segment, BA w / L of compression damping in a steady payout: C_I "
                    "= 0) and the tangential drag of the wire sliding through the water (its drag sees node "
                    "velocities: C_t = 0). Same-quantity agreement (end element vs end segment) over the run: package "
                    "end 1e-5, top minimum 4e-6, top maximum 1.2 %: the maximum is in the final 3 s ramp down, where "
                    "cablesys decelerates the paid-out wire's material at alpha (m_r L alpha, its material "
                    "acceleration, segmented_winch) and MoorDyn its nodes at (1 - c) alpha, half of it on average: "
                    "at the ramp's peak deceleration 1.5 w / ramp = 0.5 m/s^2, 3 kg/m x 80 m x 0.5 m/s^2 / 2 = 60 N, "
                    "1.4 % of the 4.15 kN maximum (1.2 % seen). Both within 0.09 % of the closed form "
                    "W_b + w L - 1/2 rho C_D A v^2 (drag 25 % of the load) over the constant-speed part.",
    "lowering_speed": "Same run: MoorDyn N = 20 at 0.427 ms (the 1 m elements of the 20 m start set RK4's axial "
                      "limit), 2.51 s wall, 2.63 s CPU; cablesys segmented N = 20, BDF(<= 2) rtol 1e-4 (tension 0.55 % "
                      "from its tight run; the looser ones of _common.BDF_RTOLS miss matched accuracy), 478 steps, "
                      "0.014 s: speedup 178 (target >= 5: met); auto N = 20 checked against 10 and rtol 1e-5, 0.051 s: "
                      "auto_speedup 50 (target >= 20: met; the run it reports alone 152x), error 0.17 % (stated 0.23 %).",
    "moordyn_wheel": "The moordyn 2.7.2 wheel's SetLineUnstretchedLength and SetLineUnstretchedLengthVel drop a reference "
                     "to None per call (CPython aborts with 'deallocating None' after ~6000 calls); _moordyn.winch_hook "
                     "gives the references back (ctypes Py_IncRef).",
}
