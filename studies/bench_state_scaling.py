"""State scaling: steps and error with and without per-state tolerances (issue 13).

    python studies/bench_state_scaling.py --out DIR [--quick]

CVODES/IDAS take one scalar atol, so the integrators integrate x~ = x / S(p) with S the states'
natural scales (:mod:`cablesys.model.scales`) and atol acts per state as atol x S_i
(``IntegratorSettings.scaled``). For each scene this runs the same rtol unscaled (atol in SI,
the former ladder default atol = rtol / 1000) and scaled (atol = rtol, rtol / 10: the ladder's
default), and reports the integrator steps and the error of every series against a tight run as
a fraction of that series' range (max |x - x_ref| / ptp(x_ref)): the dynamic tension is a small
part of the tension (5 % on Dale), so an error relative to its value says nothing.

Scenes: Dale (Wang 1971 Table 1, Wang's 2-DOF model) with its abrupt start (the undamped stretch
mode rings at 254 rad/s throughout) and with a one-period smooth start; without ``--quick`` also
the segmented Dale (N = 10) and the 300 m / 2 t sphere with 1 m heave at T = 10 s (N = 20) of
``bench_vs_moordyn.py``. Writes ``bench_state_scaling.json`` and ``.png``.
"""

from __future__ import annotations

import dataclasses
import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import parse_args, setup_matplotlib, write_json

import cablesys
from cablesys.model import build_model
from cablesys.scene import TopMotion, dale_scene, load_scene
from cablesys.time_domain import IntegratorSettings, Simulator, initial_state

DATA = Path(cablesys.__file__).resolve().parent / "data"
KEYS = ("tension_mid", "tension_top", "tension_bottom", "x_b", "y_b", "u_rate")


def scenes(quick: bool) -> list:
    """(name, scene, elements or None for Wang's model)."""
    base = dale_scene(duration=4.0 if quick else 20.0, output_step=0.1)
    tm = base.top_motion
    period = 2 * math.pi / tm.x[0].frequency
    ramped = base.replace(top_motion=TopMotion(x=tm.x, y=tm.y, ramp_s=period))
    out = [("dale_wang_ramped", ramped, None)]
    if quick:
        return out
    out.append(("dale_wang_abrupt", base.with_numerics(duration=8.0), None))
    out.append(("dale_segmented_N10", ramped.replace_section(0, cable={"segments": 10}), 10))
    heave = load_scene(DATA / "heave_300m.toml")
    sine = dataclasses.replace(heave.top_motion.y[0], frequency=2 * math.pi / 10.0)
    heave = dataclasses.replace(heave, top_motion=dataclasses.replace(heave.top_motion, y=(sine,), ramp_s=30.0))
    out.append(("heave_T10_N20", heave.with_numerics(duration=30.0).replace_section(0, cable={"segments": 20}), 20))
    return out


def variants() -> list:
    """(label, settings) at the ladder's rtol 1e-4 (BDF <= 2), and the library default rtol."""
    bdf2 = [("bdf2 unscaled atol=rtol/1000 (former ladder)", IntegratorSettings("cvodes-bdf2", 1e-4, 1e-7, scaled=False)),
            ("bdf2 scaled atol=rtol/10 (ladder)", IntegratorSettings("cvodes-bdf2", 1e-4, 1e-5)),
            ("bdf2 scaled atol=rtol", IntegratorSettings("cvodes-bdf2", 1e-4, 1e-4))]
    default = [("cvodes rtol 1e-7 unscaled atol=1e-9", IntegratorSettings("cvodes", 1e-7, 1e-9, scaled=False)),
               ("cvodes rtol 1e-7 scaled atol=1e-9", IntegratorSettings("cvodes", 1e-7, 1e-9)),
               ("cvodes rtol 1e-7 scaled atol=rtol", IntegratorSettings("cvodes", 1e-7, 1e-7))]
    return bdf2 + default


def run(model, scene, settings):
    p = model.parameters(scene)
    x0 = initial_state(scene, model, p)
    sim = Simulator(model, scene.output_times, settings)
    t0 = time.perf_counter()
    rec = sim.run(p, x0)
    return rec, time.perf_counter() - t0


def measure(name, scene, elements) -> dict:
    model = build_model(scene)
    # the tight reference: variable-order BDF for Wang's model, BDF <= 2 for the segmented cable
    # (orders 3-5 follow its undamped element modes at any tolerance)
    tight = IntegratorSettings("cvodes-bdf2" if elements else "cvodes", 1e-9 if elements else 1e-11,
                               1e-12 if elements else 1e-13, scaled=False, max_num_steps=10**7)
    ref, _ = run(model, scene, tight)
    # series that move (a heave leaves x_b at round-off: its "range" would make any error look huge)
    keys = [k for k in KEYS if k in ref.data and np.ptp(ref.data[k]) > 1e-9 * (np.max(np.abs(ref.data[k])) + 1e-300)]
    rows = []
    for label, st in variants():
        if elements and st.method == "cvodes":
            continue           # variable-order BDF on the segmented cable: orders 3-5 ring (see integrators.py)
        rec, wall = run(model, scene, st)
        err = {k: float(np.max(np.abs(rec.data[k] - ref.data[k])) / np.ptp(ref.data[k])) for k in keys} if rec.success else {}
        rows.append({"variant": label, "method": st.method, "rtol": st.rtol, "atol": st.atol, "scaled": st.scaled,
                     "success": rec.success, "steps": int(rec.stats.get("nsteps", -1)), "wall_s": wall,
                     "error_over_range": err})
    return {"scene": name, "elements": elements or 1, "model": model.kind, "reference_steps": int(ref.stats["nsteps"]),
            "ranges": {k: float(np.ptp(ref.data[k])) for k in keys}, "rows": rows}


def plot(path, results):
    plt = setup_matplotlib()
    n = len(results)
    fig, axes = plt.subplots(1, n, figsize=(max(5.6 * n, 7.0), 5.0), squeeze=False)
    for ax, res in zip(axes[0], results):
        key = "tension_mid" if "tension_mid" in res["ranges"] else "tension_top"
        for r in res["rows"]:
            if not r["success"]:
                continue
            marker = "o" if r["scaled"] else "s"
            color = "C0" if r["method"] == "cvodes-bdf2" else "C1"
            ax.loglog(r["steps"], max(r["error_over_range"][key], 1e-12), marker, color=color,
                      mfc=color if r["scaled"] else "none", ms=8)
            ax.annotate(r["variant"].replace(" (", "\n("), (r["steps"], r["error_over_range"][key]),
                        fontsize=6, xytext=(4, 2), textcoords="offset points")
        ax.set_title(f"{res['scene']} ({res['model']})", fontsize=9)
        ax.set_xlabel("integrator steps")
        ax.set_ylabel(f"max |{key} error| / range of {key}")
        ax.grid(True, which="both", alpha=0.3)
        x0, x1 = ax.get_xlim()
        ax.set_xlim(x0, x1 * 4)          # room for the labels
    fig.suptitle("State scaling: filled = scaled states (atol x natural scale), open = one SI atol\n"
                 "blue: BDF <= 2 at rtol 1e-4, orange: variable-order BDF at rtol 1e-7", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv=None):
    args = parse_args(__doc__.splitlines()[0], argv)
    results = [measure(*case) for case in scenes(args.quick)]
    write_json(args.out / "bench_state_scaling.json", {"quick": args.quick, "results": results})
    plot(args.out / "bench_state_scaling.png", results)
    for res in results:
        print(res["scene"])
        for r in res["rows"]:
            e = " ".join(f"{k}={v:.2g}" for k, v in r["error_over_range"].items())
            print(f"  {r['variant']:48s} steps {r['steps']:7d}  {e}")


if __name__ == "__main__":
    main()
