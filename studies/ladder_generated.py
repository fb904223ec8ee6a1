"""The model ladder's stated error against the actual one, per reported quantity, on scenes generated within ranges.

    python studies/ladder_generated.py --out DIR [--quick] [--compiled | --vm] [--seed S] [--count K] [--only LABELS]

Issue 22's check: on scenes drawn with a seeded RNG within the issue's ranges, auto (``cablesys.simulate(scene)``,
as a user runs it) against the segmented node model at N_REF elements per section (one run of the node model,
:func:`cablesys.ladder.run_rung`, with REF_INTEGRATOR: BDF2 at rtol 1e-6; always in CasADi's VM: the same
equations, nothing to compile), every reported quantity (each body coordinate's amplitude
and mean, each tension extreme at every end and junction: :func:`cablesys.ladder.metrics.statistics`) has its
actual relative error (:func:`cablesys.ladder.metrics.quantity_errors`: floors: 1 cm or a tenth of the largest body amplitude, 1 % of the top tension)
within the tolerance (1 % body, 2 % tension), and its stated error (``model.estimated_error_per_quantity``) at
least half the actual one (``stated_at_least_half``; ``stated_honest`` also passes an actual error below
RESOLVED x the tolerance: :func:`_ladder_checks.quantity_rows`). A reference whose body amplitudes still change by
more than SETTLED_CHANGE between the halves of the window (:func:`cablesys.ladder.metrics.window_change`) is
marked ``reference_settled: false`` and listed in the totals: its "actual" errors partly measure a transient.

The ranges (:func:`generated_scene`): a steel wire rope (12-30 mm; metallic area 0.6 of the circle, density
7850 kg/m^3, E = 100 GPa on the metallic area: Feyrer, *Wire Ropes*, 2nd ed. 2015, ch. 1 and 3) and a sphere
(density 1500-3000 kg/m^3, added mass half the displaced water, C_D = 0.5 on its section); ``chain`` scenes hang
a second sphere 20-50 % of the length below an intermediate one (two sections, as ``dual_scene``). Cable/body
virtual-mass ratio (``scene_numbers().mass_ratio``, per section) 0.1-10, log-uniform. A current falling with
depth from 0-1.5 m/s at the surface (three knots: surface, 20-50 % of the length, twice the length). Surge
(0.2-1.5 m) and/or heave (0.2-1 m) of the top at 0.2-1.5 x the first transverse string mode
(``scene_numbers().omega_string``, log-uniform); heave is held below half the amplitude that would slacken the
lowest body quasi-statically (M_v a omega^2 <= W_b / 2), so the scenes stay taut (snap loads are outside the
issue's ranges). Duration: the statistics window (the last 5 periods) starts after the settling time
(ramp of 3 periods, the string travel time, and ln(100) x the slowest decay time below the forcing of Wang's cable
linearized in the current, the mean offset's drift: :func:`cablesys.ladder.estimate.settling_time`), checked
with :func:`cablesys.ladder.choice.settling_note`; output every period / 20 (quick) or / 40. ``--only`` runs
some of the drawn scenes (the others are still drawn, so the labels keep their scenes).

Writes ``ladder_generated.json`` (per scene: its parameters, auto's model, wall times and ``ladder_timing``, the a
posteriori check's integration part (:mod:`cablesys.ladder.checks`), one row per quantity; totals) and ``ladder_generated.png`` (stated against actual per quantity, log-log, y = x and y = x / 2).
"""

from __future__ import annotations

import dataclasses
import math
import os
import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import parse_args, setup_matplotlib, write_json  # noqa: E402
from _ladder_checks import QUANTITY_TOL, RESOLVED, quantity_rows  # noqa: E402

import cablesys  # noqa: E402
from cablesys.ladder import metrics, run_rung  # noqa: E402
from cablesys.ladder.choice import settling_note  # noqa: E402
from cablesys.ladder.estimate import settling_time  # noqa: E402
from cablesys.ladder.indicators import scene_numbers  # noqa: E402
from cablesys.scene import Body, Cable, Environment, Numerics, Scene, Section, Sinusoid, TopMotion  # noqa: E402

G, RHO, STEEL = 9.81, 1025.0, 7850.0
FILL, E_ROPE = 0.6, 1.0e11          # wire rope: metallic area / circle, modulus on the metallic area (Pa)
RAMP_PERIODS = 3                    # TopMotion's default smooth start
WINDOW_PERIODS = 5                  # metrics.window
N_REF = {"quick": 64, "full": 128}
KINDS = ("wire", "chain")
REF_INTEGRATOR = {"method": "cvodes-bdf2", "rtol": 1e-6, "atol": 1e-7}
#                                     the reference's integrator (atol on scaled states): one run, no check; on
#                                     chain-22-7 at N = 48 rtol 1e-6 and 1e-5 differ by 0.011 % on the smallest amplitude
SETTLED_CHANGE = 0.01               # a reference whose body amplitudes change more between the window's halves
#                                     (metrics.window_change) has not settled: its errors are marked, not trusted


@dataclasses.dataclass(frozen=True)
class Ranges:
    """The generator's ranges (SI)."""

    length: tuple = (50.0, 300.0)           # total cable length (m), log-uniform
    diameter: tuple = (0.012, 0.030)        # m
    mass_ratio: tuple = (0.1, 10.0)         # cable / body virtual mass, per section, log-uniform
    body_density: tuple = (1500.0, 3000.0)  # kg/m^3
    surface_current: tuple = (0.0, 1.5)     # m/s
    string_ratio: tuple = (0.2, 1.5)        # forcing / first string mode, log-uniform
    surge: tuple = (0.2, 1.5)               # m
    heave: tuple = (0.2, 1.0)               # m
    samples_per_period: int = 40


QUICK = Ranges(length=(20.0, 40.0), samples_per_period=20)


def rope(length: float, d: float, tension: float) -> Cable:
    """A steel wire rope of diameter ``d`` (m) at its mean tension ``tension`` (N) (module docstring)."""
    a = FILL * math.pi * d * d / 4
    return Cable(length=length, tension_ref=tension, ae=E_ROPE * a, diameter=d, mass_per_length=STEEL * a,
                 weight_per_length=(STEEL - RHO) * G * a, cd_normal=1.2, ct_tangential=0.01, tension_floor=0.0)


def sphere(virtual_mass: float, density: float) -> Body:
    """A sphere of ``density`` whose virtual mass (dry mass plus half the displaced water) is ``virtual_mass`` (kg)."""
    dry = virtual_mass / (1.0 + 0.5 * RHO / density)
    r = (3 * dry / (4 * math.pi * density)) ** (1 / 3)
    area = 0.5 * math.pi * r * r                            # C_D A, C_D = 0.5
    return Body(weight=dry * G * (1 - RHO / density), mass_x=virtual_mass, mass_y=virtual_mass,
                drag_area_normal=area, drag_area_tangential=area)


def _virtual_mass_per_length(d: float) -> float:
    return STEEL * FILL * math.pi * d * d / 4 + RHO * math.pi * d * d / 4     # added mass factor 1 (eq. 23)


def _log_uniform(rng, lo_hi) -> float:
    return float(10 ** rng.uniform(math.log10(lo_hi[0]), math.log10(lo_hi[1])))


def generated_scene(rng: np.random.Generator, kind: str, ranges: Ranges = Ranges()) -> tuple[Scene, dict]:
    """A scene of ``kind`` ("wire": one section; "chain": two, an intermediate body) drawn within ``ranges``
    (module docstring), and the drawn parameters."""
    total = _log_uniform(rng, ranges.length)
    d = float(rng.uniform(*ranges.diameter))
    fractions = (1.0,) if kind == "wire" else (1.0 - float(rng.uniform(0.2, 0.5)),)
    lengths = [total * f for f in fractions] + ([] if kind == "wire" else [total * (1 - fractions[0])])
    ratios = [_log_uniform(rng, ranges.mass_ratio) for _ in lengths]
    bodies = [sphere(_virtual_mass_per_length(d) * le / r, float(rng.uniform(*ranges.body_density)))
              for le, r in zip(lengths, ratios)]
    below, secs = 0.0, []
    for le, b in reversed(list(zip(lengths, bodies))):
        c = rope(le, d, 1.0)
        tension = below + b.weight + 0.5 * c.total_weight           # the mean hanging tension (dual_scene)
        secs.insert(0, Section(cable=dataclasses.replace(c, tension_ref=tension), body=b))
        below = tension + 0.5 * c.total_weight
    u0 = float(rng.uniform(*ranges.surface_current))
    knee = float(rng.uniform(0.2, 0.5)) * total
    speeds = (u0, u0 * float(rng.uniform(0.3, 0.8)), u0 * float(rng.uniform(0.0, 0.3)))
    env = Environment(density=RHO, gravity=G, current_depths=(0.0, knee, 2 * total), current_speeds=speeds)
    still = Scene(name="draft", sections=tuple(secs), environment=env, angles="per_section",
                  top_motion=TopMotion(y=(Sinusoid(amplitude=0.1, frequency=1.0),)))
    w_string = scene_numbers(still).omega_string
    string_ratio = _log_uniform(rng, ranges.string_ratio)
    omega = string_ratio * w_string
    motion = str(rng.choice(["surge", "heave", "both"]))
    low = bodies[-1]
    heave_cap = 0.5 * low.weight / (low.mass_y * omega**2)      # quasi-static slack margin of the lowest body
    a_x = float(rng.uniform(*ranges.surge)) if motion != "heave" else 0.0
    a_y = min(float(rng.uniform(*ranges.heave)), heave_cap) if motion != "surge" else 0.0
    top = TopMotion(x=(Sinusoid(amplitude=a_x, frequency=omega, phase=math.pi / 2),) if a_x else (),
                    y=(Sinusoid(amplitude=a_y, frequency=omega),) if a_y else ())
    period = 2 * math.pi / omega
    draft = dataclasses.replace(still, top_motion=top)
    settle = settling_time(draft)
    duration = 1.02 * max(settle + WINDOW_PERIODS * period, 2 * WINDOW_PERIODS * period)
    name = (f"{kind} {total:.0f} m, d {1e3 * d:.0f} mm, mass ratio {'/'.join(f'{r:.2g}' for r in ratios)}, "
            f"U0 {u0:.2f} m/s, {motion} {a_x:.2f}/{a_y:.2f} m at {string_ratio:.2f} w_string")
    scene = dataclasses.replace(draft, name=name, numerics=Numerics(
        duration=duration, output_step=period / ranges.samples_per_period))
    params = {"kind": kind, "length_m": total, "section_lengths_m": lengths, "diameter_m": d, "mass_ratios": ratios,
              "mass_ratio_scene": scene_numbers(scene).mass_ratio, "surface_current_m_s": u0,
              "current_depths_m": env.current_depths, "current_speeds_m_s": speeds, "motion": motion,
              "surge_m": a_x, "heave_m": a_y, "heave_cap_m": heave_cap, "omega_rad_s": omega,
              "omega_string_rad_s": w_string, "string_ratio": string_ratio, "duration_s": duration,
              "settling_time_s": settle, "output_step_s": period / ranges.samples_per_period}
    return scene, params


def _compile(on: bool):
    """Set CABLESYS_COMPILE for the runs that follow (read at each build: cablesys.compiled)."""
    os.environ["CABLESYS_COMPILE"] = "1" if on else "0"


def case(label: str, scene: Scene, params: dict, n_ref: int, compiled: bool) -> dict:
    """Auto (compiled or in the VM) and the reference (segmented, ``n_ref`` elements per section, VM) on ``scene``."""
    period = metrics.forcing_period(scene)
    note = settling_note(scene)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        _compile(compiled)
        t0 = time.perf_counter()
        auto = cablesys.simulate(scene)
        wall_auto = time.perf_counter() - t0
        _compile(False)
        t0 = time.perf_counter()
        ref = run_rung(scene, "segmented", n_ref, **REF_INTEGRATOR)
        wall_ref = time.perf_counter() - t0
    m = auto.stats["model"]
    ramp = scene.top_motion.effective_ramp_s          # run_rung's record carries no smooth start: the scene's
    actual = metrics.quantity_errors(metrics.statistics(auto, period, ramp), metrics.statistics(ref, period, ramp))
    stated = m.get("estimated_error_per_quantity") or {}
    rows = quantity_rows(actual, stated)
    change = metrics.window_change(ref, period, ramp)
    return {"case": label, "scene": scene.name, "params": params, "settling_note": note,
            "reference_window_change": change, "reference_settled": change <= SETTLED_CHANGE,
            "model": {k: m.get(k) for k in ("name", "segments", "checked", "reason", "estimated_error")},
            "reference": {"model": "segmented", "segments": n_ref, "compiled": False, **REF_INTEGRATOR},
            "integration_check": m.get("integration_check"),
            "auto_compiled": compiled, "auto_wall_s": wall_auto, "reference_wall_s": wall_ref,
            "auto_timing": auto.stats.get("ladder_timing"), "rows": rows,
            "all_within_tolerance": all(r["within_tolerance"] for r in rows),
            "all_stated_at_least_half": all(r["stated_at_least_half"] is True for r in rows),
            "all_stated_honest": all(r["stated_honest"] is True for r in rows)}


def scenes(seed: int, count: int, ranges: Ranges) -> list:
    """``count`` (label, scene, params), kinds alternating, from one RNG seeded with ``seed``."""
    rng = np.random.default_rng(seed)
    out = []
    for i in range(count):
        kind = KINDS[i % len(KINDS)]
        scene, params = generated_scene(rng, kind, ranges)
        out.append((f"{kind}-{seed}-{i}", scene, params))
    return out


def totals(cases: list) -> dict:
    rows = [r for c in cases for r in c["rows"]]
    worst = sorted(rows, key=lambda r: -r["actual"] / r["tolerance"])[:5]
    low = sorted((r for r in rows if r["stated"] is not None), key=lambda r: r["stated"] / max(r["actual"], 1e-300))[:5]
    where = {id(r): c["case"] for c in cases for r in c["rows"]}
    brief = lambda r: {"case": where[id(r)], "quantity": r["quantity"], "actual": r["actual"], "stated": r["stated"],  # noqa: E731
                       "tolerance": r["tolerance"]}
    return {"scenes": len(cases), "quantities": len(rows),
            "within_tolerance": sum(r["within_tolerance"] for r in rows),
            "stated_at_least_half": sum(r["stated_at_least_half"] is True for r in rows),
            "stated_honest": sum(r["stated_honest"] is True for r in rows),
            "not_stated": sum(r["stated"] is None for r in rows),
            "unsettled_references": [c["case"] for c in cases if not c["reference_settled"]],
            "worst_actual_over_tolerance": [brief(r) for r in worst],
            "lowest_stated_over_actual": [brief(r) for r in low]}


def plot(cases: list, path: Path) -> None:
    plt = setup_matplotlib()
    fig, ax = plt.subplots(figsize=(8.0, 6.5))
    colours = {"wire": "tab:blue", "chain": "tab:orange"}
    markers = {"body": "o", "tension": "s"}
    lo = 1e-6
    for kind in KINDS:
        for grp in ("body", "tension"):
            pts = [(r["actual"], r["stated"]) for c in cases if c["params"]["kind"] == kind for r in c["rows"]
                   if r["stated"] is not None and metrics.group(r["quantity"]) == grp]
            if pts:
                a, s = np.maximum(np.array(pts), lo).T
                ax.loglog(a, s, markers[grp], color=colours[kind], mfc="none" if grp == "tension" else colours[kind],
                          alpha=0.75, ms=6, label=f"{kind}: {grp} quantities ({len(pts)})")
        unstated = [r["actual"] for c in cases if c["params"]["kind"] == kind for r in c["rows"] if r["stated"] is None]
        if unstated:
            ax.loglog(np.maximum(unstated, lo), np.full(len(unstated), 1.3 * lo), "x", color=colours[kind], ms=7,
                      label=f"{kind}: no stated error ({len(unstated)}; drawn on the bottom axis)")
    lim = (lo, 1.0)
    ax.plot(lim, lim, "k-", lw=0.9, label="stated = actual")
    ax.plot(lim, (0.5 * lim[0], 0.5 * lim[1]), "k--", lw=0.9, label="stated = actual / 2 (below: dishonest)")
    for grp, ls in (("body", ":"), ("tension", "-.")):
        ax.axvline(QUANTITY_TOL[grp], color="tab:red", lw=0.9, ls=ls, label=f"{grp} tolerance {100 * QUANTITY_TOL[grp]:g} %")
        ax.axvline(RESOLVED * QUANTITY_TOL[grp], color="grey", lw=0.7, ls=ls,
                   label=f"{grp}: {RESOLVED:g} x tolerance (resolution asked)")
    n_sc = len(cases)
    comp = "compiled" if cases and cases[0]["auto_compiled"] else "CasADi VM"
    ref = cases[0]["reference"]["segments"] if cases else "?"
    ax.set(xlim=lim, ylim=(lo, 1.0), xlabel=f"actual relative error against the segmented cable, N = {ref} per section",
           ylabel="stated relative error (model.estimated_error_per_quantity)",
           title=f"Model ladder on {n_sc} generated scenes (auto {comp}): stated vs actual, every quantity")
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=7.5, loc="upper left", framealpha=0.9)
    from cablesys.plots import save_figure
    save_figure(fig, path)


def _options(ap) -> None:
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--compiled", dest="compiled", action="store_true", default=None, help="auto compiled to C")
    g.add_argument("--vm", dest="compiled", action="store_false", help="auto in CasADi's VM (default)")
    ap.add_argument("--seed", type=int, default=22, help="RNG seed of the generator")
    ap.add_argument("--count", type=int, default=None, help="number of scenes (default: 2 quick, 12 full)")
    ap.add_argument("--only", default=None, help="comma-separated case labels to run of the drawn ones (e.g. "
                    "chain-22-3,chain-22-7); the others are drawn (the RNG's sequence) but not run")


def main(argv=None) -> int:
    args = parse_args(__doc__.splitlines()[0], argv, extra=_options)
    compiled = bool(args.compiled)
    count = args.count if args.count is not None else (2 if args.quick else 12)
    if count < 1:
        from cablesys.errors import ParameterError
        raise ParameterError("--count", count, "at least 1")
    n_ref = N_REF["quick" if args.quick else "full"]
    ranges = QUICK if args.quick else Ranges()
    drawn = scenes(args.seed, count, ranges)
    if args.only is not None:
        want = [w.strip() for w in args.only.split(",") if w.strip()]
        missing = sorted(set(want) - {label for label, _, _ in drawn})
        if missing or not want:
            from cablesys.errors import ParameterError
            raise ParameterError("--only", args.only, f"labels among {[label for label, _, _ in drawn]}")
        drawn = [d for d in drawn if d[0] in want]
    cases = []
    for label, scene, params in drawn:
        c = case(label, scene, params, n_ref, compiled)
        cases.append(c)
        worst = max(c["rows"], key=lambda r: r["actual"] / r["tolerance"])
        print(f"{label:10s} {c['model']['name']} N = {c['model']['segments']} (auto {c['auto_wall_s']:.1f} s, ref "
              f"{c['reference_wall_s']:.1f} s): worst {worst['quantity']} actual {worst['actual']:.2g} stated "
              f"{worst['stated']}; within tolerance {c['all_within_tolerance']}, stated >= actual/2 "
              f"{c['all_stated_at_least_half']}; reference window change {c['reference_window_change']:.2g}"
              + ("" if c["reference_settled"] else " (NOT SETTLED: its actual errors measure a transient)"), flush=True)
        write_json(args.out / "ladder_generated.json", {"quick": args.quick, "seed": args.seed, "compiled": compiled,
                                                         "tolerance": QUANTITY_TOL, "resolved_fraction": RESOLVED,
                                                         "ranges": dataclasses.asdict(ranges), "cases": cases,
                                                         "totals": totals(cases)})
    plot(cases, args.out / "ladder_generated.png")
    t = totals(cases)
    print(f"{t['quantities']} quantities on {t['scenes']} scenes: {t['within_tolerance']} within tolerance, "
          f"{t['stated_at_least_half']} stated >= actual/2, {t['stated_honest']} honest (with resolution)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
