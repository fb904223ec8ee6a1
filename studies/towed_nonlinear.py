"""The towed cable as the 3-D node model against Kennedy & Strahan (1981): linearized, and nonlinear at sea.

    python studies/towed_nonlinear.py --out DIR [--quick]

1. :func:`linear_vs_theory`: the node model (:mod:`cablesys.towed.nodes`) linearized about the straight
   tow, with the theory's equivalent linear normal drag (eq. 38-39), solved per frequency, against
   ``towed/``'s exact solution of eq. 3 (0F1 series) with the coefficients of the node model's physics
   (:func:`cablesys.towed.nodes.node_coefficients`): |H(1)| and c*(1) at omega L/U = 1, 3, 8 (the report's
   sea-trial cable, L = 1190 m, U = 5 m/s), at N = 20, 40 (, 80) elements over L, with the observed order;
   and the difference of that theory from the report's own coefficients (friction along the stream,
   convected fluid inertia), a difference of the models, not of the discretization.
2. :func:`sea_trials`: the nonlinear node model (quadratic cross-flow normal drag, Wang eq. 42, with the
   report's C_n = 0.16) in the time domain for the runs of Table A-2: the tow point swayed at the run's
   frequency f with amplitude a = (a/lambda) U / f (lambda = U / f, the tow point's track in the water),
   speed U and length L of the run; |H| and c* at the far pinger from the harmonic at f over the last two
   periods; against the measured values, beside the linear theory's (``towed.runs.model_runs``) and the
   linearized node model's; and against the same quadratic drag by harmonic equivalent linearization
   (:func:`cablesys.towed.nodes.describing_function_response`), a route independent of the time domain.
   Quick mode: three runs, N = 16.

Writes towed_nonlinear.json and towed_nonlinear.png.
"""

from __future__ import annotations

import dataclasses
import math
import sys
from importlib import resources
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import parse_args, setup_matplotlib, write_json  # noqa: E402

from cablesys.model import build_model  # noqa: E402
from cablesys.scene import Sinusoid, TopMotion  # noqa: E402
from cablesys.time_domain.run import simulate  # noqa: E402
from cablesys.towed.equation import REPORT_SEA_TRIAL, Coefficients, TowedCable  # noqa: E402
from cablesys.towed.nodes import (  # noqa: E402
    describing_function_response,
    describing_function_scan,
    frequency_response,
    harmonic,
    node_coefficients,
    phase_lag_along,
    straight_tow,
    tow_scene,
)
from cablesys.towed.runs import model_runs, read_runs  # noqa: E402
from cablesys.towed.transfer import c_star, transfer_function  # noqa: E402

OMEGA_CHECK = (1.0, 3.0, 8.0)        # omega L / U of the linear check
QUICK_RUNS = ("1", "6", "20")


def linear_vs_theory(quick: bool) -> dict:
    """Linearized node model vs ``towed/``'s exact H and c* at xi = 1 (see the module docstring)."""
    cab = TowedCable(length=1190.0, speed=5.0, **REPORT_SEA_TRIAL)
    w = np.array(OMEGA_CHECK)
    ref = node_coefficients(cab)
    H_th, c_th = np.abs(transfer_function(ref, 1.0, w).H), c_star(ref, 1.0, w).c_star
    H_rep, c_rep = np.abs(transfer_function(cab.coefficients(), 1.0, w).H), c_star(cab.coefficients(), 1.0, w).c_star
    # which of the two model-form terms makes the difference: each alone in the report's eq. 3
    r0 = cab.coefficients()
    terms = {"friction_along_element_only": Coefficients(a=r0.a, b=r0.b, c=r0.d, d=r0.d, beta=r0.beta),
             "no_convective_inertia_only": dataclasses.replace(ref, c=r0.c)}
    term_diff = {k: float(max(np.max(np.abs(np.abs(transfer_function(c, 1.0, w).H) / H_rep - 1)),
                              np.max(np.abs(c_star(c, 1.0, w).c_star / c_rep - 1)))) for k, c in terms.items()}
    rows = []
    for n in ((20, 40) if quick else (20, 40, 80)):
        rs = frequency_response(cab, w, segments=n)
        H = np.array([abs(r.H1) for r in rs])
        cs = np.array([r.c_star1 for r in rs])
        rows.append({"elements": n, "H": H.tolist(), "c_star": cs.tolist(),
                     "H_rel_err": (np.abs(H / H_th - 1)).tolist(), "c_star_rel_err": (np.abs(cs / c_th - 1)).tolist()})
    err = lambda r: np.maximum(r["H_rel_err"], r["c_star_rel_err"])
    order = [np.log2(err(a) / err(b)).tolist() for a, b in zip(rows[:-1], rows[1:])]
    return {"omega_nd": list(OMEGA_CHECK), "cable": {"length": 1190.0, "speed": 5.0, **REPORT_SEA_TRIAL},
            "theory_node_coefficients": vars(ref) | {"H": H_th.tolist(), "c_star": c_th.tolist()},
            "by_elements": rows, "observed_order": order, "max_rel_err": float(np.max(err(rows[-1]))),
            "theory_report_coefficients": {"H": H_rep.tolist(), "c_star": c_rep.tolist()},
            "model_form_vs_report_coefficients_max_rel": float(max(np.max(np.abs(H_th / H_rep - 1)),
                                                                   np.max(np.abs(c_th / c_rep - 1)))),
            "model_form_terms_max_rel": term_diff,
            "model_form_note": "the node model's friction acts along the element (its cross-track part cancels "
                               "-T' y_x: c = d, the report's c = b + d) and its added mass on the node's own "
                               "acceleration (no 2 beta eta_xt, no beta in a): towed/ with those coefficients is "
                               "the reference; the report's eq. 3 differs from it by this much"}


def nonlinear_run(run, segments: int, model_cache: dict, n_settle: float = 4.0) -> dict:
    """|H| and c* at the far pinger of the nonlinear node model for one Table A-2 run."""
    cab = TowedCable(length=run.length, speed=run.speed, **REPORT_SEA_TRIAL)
    w, T = 2 * math.pi * run.frequency, 1.0 / run.frequency
    a = float(run.columns["a_over_lambda"]) * run.speed / run.frequency
    Lstar = run.length + cab.diameter * cab.c_t_drogue / cab.c_t
    settle = n_settle * Lstar / run.speed + T                 # transit times of the lengthened cable, one ramp
    dur = settle + 2 * T
    sc = tow_scene(cab, segments=segments, duration=dur, output_step=T / 40, rtol=1e-6, atol=1e-6)
    sc = dataclasses.replace(sc, top_motion=TopMotion(z=(Sinusoid(amplitude=a, frequency=w),), ramp_s=T))
    key = tuple(s.cable.segments for s in sc.sections)
    if key not in model_cache:
        model_cache[key] = build_model(sc)
    m = model_cache[key]
    p = m.parameters(sc)
    q0 = straight_tow(m, p, sc)
    r = simulate(sc, model=m, x0=np.r_[q0, np.zeros(q0.size)])
    t, Z = np.asarray(r.time), np.asarray(r.profiles["node_z"])
    xi = np.r_[0.0, q0[0::3][:segments]] / run.length
    out = {}
    for name, lo, hi in (("last", dur - 2 * T, dur + 1), ("before", dur - 3 * T, dur - T)):
        sel = (t >= lo - 1e-9) & (t <= hi)
        amp = np.array([harmonic(t[sel], Z[sel, j], w) for j in range(segments + 1)])
        out[name] = phase_lag_along(xi, amp / amp[0], w * run.length / run.speed, segments)
    last, before = out["last"], out["before"]
    return {"run": run.label, "omega_nd": last.omega_nd, "amplitude_m": a, "H": abs(last.H1), "c_star": last.c_star1,
            "periodic_change_H": abs(abs(last.H1) / abs(before.H1) - 1), "duration_s": dur,
            "max_sway_slope": float(np.max(np.abs(np.diff(Z[t >= dur - 2 * T][:, :segments + 1], axis=1))
                                           / np.diff(xi * run.length))),
            "_xi": last.xi, "_H": last.H}


def sea_trials(quick: bool, table=None) -> dict:
    """Nonlinear node model, linear theory and linearized node model against Table A-2 (module docstring)."""
    table = table or Path(str(resources.files("cablesys") / "data" / "kennedy_tableA2.csv"))
    runs = read_runs(table)
    if quick:
        runs = [r for r in runs if r.label in QUICK_RUNS]
    n = 16 if quick else 40
    H_d = np.array([float(r.columns["H"]) for r in runs])
    c_d = np.array([float(r.columns["c_star"]) for r in runs])
    lin = model_runs(runs)
    cache: dict = {}
    nl = [nonlinear_run(r, n if r.length > 900 else max(8, n // 2), cache) for r in runs]
    lin_nodes, df = [], []
    for r, x in zip(runs, nl):
        cab = TowedCable(length=r.length, speed=r.speed, **REPORT_SEA_TRIAL)
        n_r = n if r.length > 900 else max(8, n // 2)
        lin_nodes.append(frequency_response(cab, cab.omega(r.frequency), segments=n_r)[0])
        df.append(describing_function_response(cab, cab.omega(r.frequency), x["amplitude_m"], segments=n_r))
    H_nl, c_nl = np.array([x["H"] for x in nl]), np.array([x["c_star"] for x in nl])
    H_ln, c_ln = np.array([abs(x.H1) for x in lin_nodes]), np.array([x.c_star1 for x in lin_nodes])
    H_df, c_df = np.array([abs(x.H1) for x, _ in df]), np.array([x.c_star1 for x, _ in df])
    mad = lambda a, b: float(np.mean(np.abs(a - b)))
    # which quadratic C_n would the nonlinear model need (the describing-function route, full mode)
    scan = None
    if not quick:
        cns = np.geomspace(0.16, 16.0, 9)
        per_run = []
        for r, x in zip(runs, nl):
            cab = TowedCable(length=r.length, speed=r.speed, **REPORT_SEA_TRIAL)
            per_run.append(describing_function_scan(cab, cab.omega(r.frequency), x["amplitude_m"], cns,
                                                    segments=n if r.length > 900 else max(8, n // 2)))
        dH = [mad(np.array([abs(pr[k].H1) for pr in per_run]), H_d) for k in range(cns.size)]
        dc = [mad(np.array([pr[k].c_star1 for pr in per_run]), c_d) for k in range(cns.size)]
        scan = {"cd_normal": cns.tolist(), "mean_abs_dH": dH, "mean_abs_dcstar": dc,
                "best_cd_normal_H": float(cns[int(np.argmin(dH))]), "best_cd_normal_cstar": float(cns[int(np.argmin(dc))]),
                "best_at_scan_upper_end": bool(np.argmin(dH) == cns.size - 1 and np.argmin(dc) == cns.size - 1)}
    # the discretization: the first run again with twice the elements (full mode)
    conv = None
    if not quick:
        fine = nonlinear_run(runs[0], 2 * n, cache)
        conv = {"run": runs[0].label, "elements": [n, 2 * n], "H": [nl[0]["H"], fine["H"]],
                "c_star": [nl[0]["c_star"], fine["c_star"]],
                "rel_change": max(abs(fine["H"] / nl[0]["H"] - 1), abs(fine["c_star"] / nl[0]["c_star"] - 1))}
    summary = {"mean_abs_dH_nonlinear": mad(H_nl, H_d), "mean_abs_dH_linear_theory": mad(lin.H_abs, H_d),
               "mean_abs_dcstar_nonlinear": mad(c_nl, c_d), "mean_abs_dcstar_linear_theory": mad(lin.c_star, c_d)}
    return {**summary,
            "mean_abs_dH_linearized_nodes": mad(H_ln, H_d), "mean_abs_dcstar_linearized_nodes": mad(c_ln, c_d),
            # the time-domain runs against the harmonic equivalent linearization of the same quadratic drag
            "nonlinear_vs_describing_function_max_rel": float(max(np.max(np.abs(H_nl / H_df - 1)),
                                                                  np.max(np.abs(c_nl / c_df - 1)))),
            "nonlinear_convergence": conv,
            "quadratic_cd_normal_scan_describing_function": scan,
            "periodic_change_H_max": float(max(x["periodic_change_H"] for x in nl)),
            "runs": [{**{k: v for k, v in x.items() if not k.startswith("_")}, "H_data": float(hd), "c_star_data": float(cd),
                      "H_linear_theory": float(hl), "c_star_linear_theory": float(cl),
                      "H_linearized_nodes": float(hn), "c_star_linearized_nodes": float(cn),
                      "H_describing_function": float(hf), "c_star_describing_function": float(cf),
                      "describing_function_c_n_star_range": info["c_n_star_range"]}
                     for x, hd, cd, hl, cl, hn, cn, hf, cf, (_, info)
                     in zip(nl, H_d, c_d, lin.H_abs, lin.c_star, H_ln, c_ln, H_df, c_df, df)],
            "elements_over_L": n, "quadratic_cd_normal": REPORT_SEA_TRIAL["c_n"], "quick_subset": list(QUICK_RUNS) if quick else None,
            "nonlinear_fits_better": {"H": summary["mean_abs_dH_nonlinear"] < summary["mean_abs_dH_linear_theory"],
                                      "c_star": summary["mean_abs_dcstar_nonlinear"] < summary["mean_abs_dcstar_linear_theory"]},
            "_profiles": [(x["run"], x["_xi"], x["_H"]) for x in nl]}


def figure(lin: dict, sea: dict, path: Path) -> Path:
    """|H| and c* at the far pinger per run: data, linear theory, linearized and nonlinear node model; and the
    linear check's |H| along the element counts."""
    plt = setup_matplotlib()
    fig, axes = plt.subplots(1, 3, figsize=(16, 6.4))
    runs = sea["runs"]
    om = np.array([r["omega_nd"] for r in runs])
    order = np.argsort(om)
    for ax, q, lab in ((axes[0], "H", "|H(xi = 1)|"), (axes[1], "c_star", "c*(xi = 1) / U")):
        ax.plot(om[order], np.array([r[f"{q}_data"] for r in runs])[order], "ko", ms=7, label="sea trial (Table A-2)")
        ax.plot(om[order], np.array([r[f"{q}_linear_theory"] for r in runs])[order], "s", color="C0", mfc="none", ls="none",
                label="linear theory, report's eq. 3 (c_n* = 0.16)")
        ax.plot(om[order], np.array([r[f"{q}_linearized_nodes"] for r in runs])[order], "^", color="C2", mfc="none", ls="none",
                label="3-D node model linearized (equivalent linear drag c_n* = 0.16)")
        ax.plot(om[order], np.array([r[q] for r in runs])[order], "D", color="C3", ls="none",
                label="3-D node model nonlinear, time domain (quadratic drag C_n = 0.16)")
        ax.plot(om[order], np.array([r[f"{q}_describing_function"] for r in runs])[order], "k+", ms=9,
                label="same quadratic drag, describing function (independent route)")
        ax.set(xlabel="omega L / U (-) (each point one run: its own L, U, f)", ylabel=lab)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), frameon=False)
    axes[0].set_title(f"Far-pinger amplitude ratio: mean |dH| nonlinear {sea['mean_abs_dH_nonlinear']:.3f}, "
                      f"linear theory {sea['mean_abs_dH_linear_theory']:.3f}", fontsize=9)
    axes[1].set_title(f"Phase velocity: mean |dc*| nonlinear {sea['mean_abs_dcstar_nonlinear']:.2f}, "
                      f"linear theory {sea['mean_abs_dcstar_linear_theory']:.2f}", fontsize=9)
    ax = axes[2]
    w = lin["omega_nd"]
    Hth = lin["theory_node_coefficients"]["H"]
    for k, row in enumerate(lin["by_elements"]):
        ax.plot(w, row["H_rel_err"], "o-", color=f"C{k}", label=f"|H| error, N = {row['elements']}")
        ax.plot(w, row["c_star_rel_err"], "x--", color=f"C{k}", label=f"c* error, N = {row['elements']}")
    ax.axhline(0.02, color="k", lw=0.8, ls=":", label="2 %")
    ax.set(xscale="log", yscale="log", xlabel="omega L / U (-)", ylabel="relative error vs towed/ exact (-)",
           title="Linearized node model vs towed/'s eq. 3 (node physics)\n|H(1)| = "
                 f"{', '.join(f'{h:.3f}' for h in Hth)} at omega L/U = {', '.join(f'{x:g}' for x in w)}")
    ax.title.set_fontsize(9)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), frameon=False, ncol=2)
    fig.suptitle("Towed cable (Kennedy & Strahan 1981) as the 3-D segmented node model", fontsize=11)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def main(argv=None) -> dict:
    args = parse_args("Towed cable: the 3-D node model against Kennedy & Strahan (1981)", argv)
    lin = linear_vs_theory(args.quick)
    sea = sea_trials(args.quick)
    sea.pop("_profiles")
    fig = figure(lin, sea, args.out / "towed_nonlinear.png")
    doc = {"linear_vs_theory": lin, "sea_trials": sea, "quick": args.quick, "figure": fig.name}
    write_json(args.out / "towed_nonlinear.json", doc)
    return doc


if __name__ == "__main__":
    main()
