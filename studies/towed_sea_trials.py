"""Sea trials of Kennedy & Strahan (1981), Table A-2: theory vs data and fits of c_n (Figs. 12-13 analogues).

    python studies/towed_sea_trials.py --out DIR [--quick] [--table CSV]

1. |H| (eq. 26) and c* (eq. 27b) at the far pinger (xi = 1) for every run with the report's
   coefficients (c_n* = 0.16, c_t = 0.0101, beta = 0.5, d_c = 16 mm, c_t' = 228), error statistics.
2. c_n fitted (scipy.optimize) to the amplitude alone, the phase alone and both; the report's
   finding is that no single c_n fits both.
Writes towed_sea_trials.json and PNGs (towed_trials_H.png, towed_trials_cstar.png, towed_trials_cn.png).
"""

from __future__ import annotations

import argparse
import json
import math
from importlib import resources
from pathlib import Path

import numpy as np

from cablesys.towed.equation import REPORT_SEA_TRIAL, TowedCable
from cablesys.towed.interaction import rms_angle_for
from cablesys.towed.runs import fit_normal_drag, model_runs, read_runs
from cablesys.towed.transfer import transfer_grid
from cablesys.plots import save_figure  # noqa: E402

RISPIN_CN = 0.070          # Rispin's shallow-angle coefficient (report p. 31)


def stats(model, data) -> dict:
    err = np.asarray(model) - np.asarray(data)
    return {"rms": float(np.sqrt(np.mean(err**2))), "mean": float(np.mean(err)),
            "max_abs": float(np.max(np.abs(err))),
            "mean_abs_rel": float(np.mean(np.abs(err) / np.abs(data))),
            "fraction_within_25pct": float(np.mean(np.abs(err) <= 0.25 * np.abs(data)))}


def curves(lengths, omega, c_n):
    """|H(1, omega)| and c*(1, omega) for a cable of each length (U enters only through omega)."""
    out = {}
    for L in lengths:
        coef = TowedCable(length=L, speed=5.0, **{**REPORT_SEA_TRIAL, "c_n": c_n}).coefficients()
        xi = np.linspace(0.0, 1.0, max(65, int(8 * omega.max()) + 1))
        g = transfer_grid(coef, xi, omega)
        out[L] = (np.abs(g.H[-1]), g.c_star[-1])
    return out


def plot(plt, out: Path, om, H_data, c_data, lengths_run, fits, n_curve):
    omega = np.linspace(0.1, 20.0, n_curve)
    groups = sorted({round(L, -2) for L in lengths_run}, reverse=True)   # longest (most runs) first
    cases = [("report c_n* = 0.16", 0.16, "k", "-"),
             (f"best amplitude fit c_n = {fits['amplitude'].c_n:.3f}", fits["amplitude"].c_n, "C0", "--"),
             (f"best phase fit c_n = {fits['phase'].c_n:.3f}", fits["phase"].c_n, "C3", "-."),
             (f"Rispin c_n = {RISPIN_CN}", RISPIN_CN, "0.6", ":")]
    curve = {c: curves(groups, omega, c) for _, c, _, _ in cases}
    for k, (name, ylabel, data, fname) in enumerate((
            ("Transfer function magnitude at the far pinger (Fig. 12 analogue)", "|H(xi=1, omega)| (-)",
             H_data, "towed_trials_H.png"),
            ("Phase velocity between the pingers (Fig. 13 analogue)", "c* = phase velocity / U (-)",
             c_data, "towed_trials_cstar.png"))):
        fig, ax = plt.subplots(figsize=(8.5, 5.5))
        for label, c, col, ls in cases:
            for j, L in enumerate(groups):
                ax.plot(omega, curve[c][L][k], color=col, ls=ls, lw=1.4 if j == 0 else 0.9,
                        alpha=1.0 if j == 0 else 0.6,
                        label=f"theory, {label}" if j == 0 else None)
        for j, L in enumerate(groups):
            sel = np.array([round(x, -2) == L for x in lengths_run])
            ax.plot(om[sel], data[sel], "o" if j == 0 else "s", ms=7, mfc="C1" if j == 0 else "C2",
                    mec="k", ls="none", label=f"sea trial, L ~ {L:.0f} m ({sel.sum()} runs)")
        ax.set_xlabel("omega = 2 pi f L / U (-)")
        ax.set_ylabel(ylabel)
        thin = ", ".join(f"{L:.0f}" for L in groups[1:])
        ax.set_title(name + (f"\nthick lines: L = {groups[0]:.0f} m; thin lines: L = {thin} m" if thin else ""))
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        if k == 1:
            ax.set_ylim(0.6, 3.0)
        save_figure(fig, out / fname, dpi=110)


def plot_cn(plt, out: Path, runs, H_data, c_data, fits, n):
    cn = np.geomspace(0.02, 3.0, n)
    eH, ec = [], []
    for c in cn:
        res = model_runs(runs, c_n=c)
        H, cs = res.H_abs, res.c_star
        eH.append(np.sqrt(np.mean((H - H_data) ** 2)))
        ec.append(np.sqrt(np.mean((cs - c_data) ** 2)))
    fig, ax = plt.subplots(figsize=(8, 5))
    ax.plot(cn, eH, "C0", label="rms error of |H| (-)")
    ax.plot(cn, ec, "C3", label="rms error of c* (units of U)")
    for t, col in (("amplitude", "C0"), ("phase", "C3"), ("both", "k")):
        ax.axvline(fits[t].c_n, color=col, ls="--", lw=1, label=f"best c_n for {t}: {fits[t].c_n:.3f}")
    ax.axvline(0.16, color="0.5", ls=":", label="report c_n* = 0.16")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("effective normal drag coefficient c_n* (-)")
    ax.set_ylabel("rms error over the 17 runs")
    ax.set_title("No single c_n fits both amplitude and phase (Table A-2)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    save_figure(fig, out / "towed_trials_cn.png", dpi=110)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True, type=Path)
    ap.add_argument("--quick", action="store_true", help="coarser c_n scan and curves")
    ap.add_argument("--table", type=Path, default=None,
                    help="run table (default: the packaged Table A-2)")
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    table = args.table or Path(str(resources.files("cablesys") / "data" / "kennedy_tableA2.csv"))
    runs = read_runs(table)
    H_data = np.array([float(r.columns["H"]) for r in runs])
    c_data = np.array([float(r.columns["c_star"]) for r in runs])

    res = model_runs(runs)
    H, cs, om = res.H_abs, res.c_star, res.omega
    fits = fit_normal_drag(runs, H_data, c_data, n_scan=9 if args.quick else 25,
                           xatol=1e-3 if args.quick else 1e-5)
    fa, fp, fb = fits["amplitude"], fits["phase"], fits["both"]
    # "no single c_n fits both": at the joint optimum each error is well above its own minimum
    excess_H = fb.rms_H / fa.rms_H
    excess_c = fb.rms_c_star / fp.rms_c_star
    A = 0.16 / RISPIN_CN
    result = {
        "table": str(table),
        "coefficients": REPORT_SEA_TRIAL,
        "runs": [{"run": r.label, "L_m": r.length, "U_mps": r.speed, "f_mHz": r.frequency * 1e3,
                  "omega": float(w), "H_data": float(hd), "H_model": float(h),
                  "c_star_data": float(cd), "c_star_model": float(c)}
                 for r, w, hd, h, cd, c in zip(runs, om, H_data, H, c_data, cs)],
        "stats_report_coefficients": {"H": stats(H, H_data), "c_star": stats(cs, c_data)},
        "fits": {k: vars(v) for k, v in fits.items()},
        "fit_cost_note": "amplitude: mean squared |H| error; phase: mean squared c* error; both: "
                         "each mean squared error divided by the variance of its data, summed",
        "no_single_cn_fits_both": {
            "c_n_phase_over_c_n_amplitude": fp.c_n / fa.c_n,
            "rms_H_at_joint_fit_over_best": excess_H,
            "rms_c_star_at_joint_fit_over_best": excess_c,
            "holds": bool(max(excess_H, excess_c) > 1.5 and fp.c_n / fa.c_n > 1.5),
        },
        "interaction": {
            "A_report": A, "rispin_c_n": RISPIN_CN,
            "rms_theta_deg_for_A_by_eq_B5": {f"phi_{d}_deg": math.degrees(rms_angle_for(A, math.radians(d)))
                                             for d in (4, 6, 9)},
        },
        "quick": bool(args.quick),
    }
    plot(plt, args.out, om, H_data, c_data, [r.length for r in runs], fits, 60 if args.quick else 200)
    plot_cn(plt, args.out, runs, H_data, c_data, fits, 10 if args.quick else 40)
    (args.out / "towed_sea_trials.json").write_text(json.dumps(result, indent=2))
    print(json.dumps({k: result[k] for k in ("stats_report_coefficients", "fits", "no_single_cn_fits_both")},
                     indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
