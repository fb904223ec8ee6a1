"""Several segments (Wang 1971 p. 33): one cable split into N identical straight sections.

The general segmented model of the report ("each segment has a different inclination and
stretch") is :mod:`cablesys.model.segmented`: N straight tension-only elements with lumped
node masses (``cable.segments = N``). As N grows the natural frequencies and the body response converge to the continuous
cable; N = 1 is Wang's 2-DOF model. For the Dale scene (light cable, W_c / W_b = 0.14)
and a long heavy cable (W_c / W_b = 4) we report the 2-DOF model's error relative to
the finest N.

Body response (N up to 16: its cost grows fast, and the quadrature of the expected Jacobian
gets noisier with the dimension, a few per cent at N = 8): the stochastically linearized significant amplitude of the lower body in
x and y for a JONSWAP sea entering through the top (a buoy following the surface orbit,
Wang 1971 eq. 26 at x = 0; :func:`cablesys.linear.stochastic.stochastic_response`).

Usage: python studies/segments_convergence.py --out DIR [--quick]
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import parse_args, setup_matplotlib, write_json

from cablesys import units as U
from cablesys.linear import modes as modes_of
from cablesys.linear.linearization import linearize
from cablesys.linear.spectra import jonswap
from cablesys.linear.stochastic import stochastic_response
from cablesys.model import build_model
from cablesys.scene import (
    Scene,
    dale_scene,
    heavy_wire_scene,
)

TOTAL_DRAG_SEGMENTS = 24      # drag points along the whole cable, shared among the sections


def heavy_cable_scene() -> Scene:
    """1000 m of 16 mm six-strand steel wire rope holding a 300 kg instrument sphere of 0.5 m
    (:func:`cablesys.scene.heavy_wire_scene`, its top at rest): the cable weighs about four times the body in
    water, the case where a single straight segment is expected to degrade."""
    return heavy_wire_scene(period=None).with_numerics(duration=60.0, output_step=0.05)


def segmented(scene: Scene, n: int) -> Scene:
    """``scene``'s single cable as ``n`` straight elements (:mod:`cablesys.model.segmented`), with
    about TOTAL_DRAG_SEGMENTS drag points along the whole cable."""
    drag = max(n, TOTAL_DRAG_SEGMENTS)
    return scene.replace_section(0, cable={"segments": n}).with_numerics(drag_segments=drag).replace(
        name=f"{scene.name}, {n} elements")


def _split_modes(md):
    """Undamped frequencies of swing modes and stretch modes (at phi = 0 they decouple)."""
    is_phi = np.array([lbl.startswith(("phi", "x[")) for lbl in md.q_labels])   # 2-DOF angle / node x
    swing, stretch = [], []
    for k, w in enumerate(md.omega_undamped):
        s = np.abs(md.shapes[:, k])
        (swing if np.linalg.norm(s[is_phi]) >= np.linalg.norm(s[~is_phi]) else stretch).append(float(w))
    return swing, stretch


def analyse(scene: Scene, ns, ns_response, sea: dict, n_log2: int) -> dict:
    """Modes for every N in ``ns``; the (costlier) stochastic body response for N in ``ns_response``."""
    rows = []
    for n in ns:
        t0 = time.perf_counter()
        sc = scene if n == 1 else segmented(scene, n)
        model = build_model(sc)
        p = model.parameters(sc)
        lin = linearize(model, p)
        swing, stretch = _split_modes(modes_of(lin))
        row = {"n": n, "swing_rad_s": swing[:3], "stretch_rad_s": stretch[:2]}
        if n in ns_response:
            sfx = ""
            w = np.linspace(sea["w_min"], sea["w_max"], sea["n"])
            st = stochastic_response(model, p, w, jonswap(w, sea["hs"], sea["tp"]), n_log2=n_log2)
            row.update({"x_b_sig_m": st.significant_amplitude(f"x_b{sfx}"),
                        "y_b_sig_m": st.significant_amplitude(f"y_b{sfx}"),
                        "tension_top_sig_N": st.significant_amplitude("tension_top"),
                        "stochastic_converged": st.converged})
        row["wall_s"] = time.perf_counter() - t0
        rows.append(row)
    ref = rows[-1]
    ref_r = [r for r in rows if r["n"] == max(ns_response)][0]
    rel = lambda a, b: abs(a - b) / abs(b)
    for r in rows:
        r["rel_err"] = {"swing_1": rel(r["swing_rad_s"][0], ref["swing_rad_s"][0]),
                        "stretch_1": rel(r["stretch_rad_s"][0], ref["stretch_rad_s"][0])}
        if len(r["swing_rad_s"]) > 1 and len(ref["swing_rad_s"]) > 1:
            r["rel_err"]["swing_2"] = rel(r["swing_rad_s"][1], ref["swing_rad_s"][1])
        if "x_b_sig_m" in r:
            r["rel_err"]["x_b_sig"] = rel(r["x_b_sig_m"], ref_r["x_b_sig_m"])
            r["rel_err"]["y_b_sig"] = rel(r["y_b_sig_m"], ref_r["y_b_sig_m"])
    return {"scene": scene.name, "cable_to_body_weight": scene.cable.total_weight / scene.body.weight, "sea": sea,
            "rows": rows, "two_dof_rel_err": rows[0]["rel_err"], "reference_n": ref["n"],
            "reference_n_response": ref_r["n"],
            "two_dof": {k: rows[0][k] for k in ("swing_rad_s", "stretch_rad_s", "x_b_sig_m", "y_b_sig_m")},
            "finest": {"swing_rad_s": ref["swing_rad_s"], "stretch_rad_s": ref["stretch_rad_s"],
                       "x_b_sig_m": ref_r["x_b_sig_m"], "y_b_sig_m": ref_r["y_b_sig_m"]}}


def plot(results: dict, out: Path) -> None:
    plt = setup_matplotlib()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.4))
    keys = (("swing_1", "first swing frequency", "o-"), ("swing_2", "second swing frequency", "s-"),
            ("stretch_1", "first stretch frequency", "^-"), ("x_b_sig", "body x sig. amplitude", "D--"),
            ("y_b_sig", "body y sig. amplitude", "v--"))
    for ax, (tag, res) in zip(axes, results.items()):
        for key, lab, sty in keys:
            pts = [(r["n"], r["rel_err"][key]) for r in res["rows"] if key in r["rel_err"]]
            ref = res["reference_n_response"] if key.endswith("sig") else res["reference_n"]
            pts = [(n, e) for n, e in pts if n != ref]
            if pts:
                n, e = np.array(pts).T
                ax.loglog(n, np.maximum(e, 1e-9), sty, label=f"{lab} (vs N = {ref})")
        from matplotlib.ticker import NullFormatter, ScalarFormatter
        ax.set_xticks([r["n"] for r in res["rows"] if r["n"] != res["reference_n"]])
        ax.xaxis.set_major_formatter(ScalarFormatter())
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.set_xlabel("number of segments N (N = 1: Wang's 2-DOF model)")
        ax.set_ylabel("relative difference from the finest N")
        ax.set_title(f"{res['scene']}\nW_c / W_b = {res['cable_to_body_weight']:.2f}", fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.text(0.5, 0.005, "dashed: stochastic-linearization significant amplitudes (JONSWAP through the top); their "
             "quadrature noise (Sobol, 3 n_q + 6 dimensions) is a few per cent at N = 8", ha="center", fontsize=7.5)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    fig.savefig(out / "segments_convergence.png", dpi=110)
    plt.close(fig)


def main(argv=None) -> int:
    args = parse_args(__doc__.splitlines()[0], argv)
    ns = (1, 2, 4, 8) if args.quick else (1, 2, 3, 4, 6, 8, 12, 16, 24)
    ns_response = (1, 2, 4) if args.quick else (1, 2, 4, 8, 16)
    n_log2 = 6 if args.quick else 7
    dale = dale_scene()
    w_d = 1.14
    heavy = heavy_cable_scene()
    cases = {"dale": (dale, dict(hs=2 * 2.5 * U.INCH, tp=2 * math.pi / w_d, w_min=0.2 * w_d, w_max=6 * w_d, n=120)),
             "heavy_cable": (heavy, dict(hs=3.0, tp=10.0, w_min=0.2, w_max=2.5, n=120))}
    results = {tag: analyse(sc, ns, ns_response, sea, n_log2) for tag, (sc, sea) in cases.items()}
    plot(results, args.out)
    write_json(args.out / "segments_convergence.json", {"quick": args.quick, "n_sections": list(ns),
                                                        "n_sections_response": list(ns_response), **results})
    return 0


if __name__ == "__main__":
    sys.exit(main())
