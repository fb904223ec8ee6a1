"""Reproduce Griffin & Rosenthal (1985) Tables 1-5 and the frequency/sag figures.

    python studies/slack_tables.py --out DIR [--quick]

Writes DIR/slack_tables.json (keys table1, table2, table3_two_masses,
table4_five_masses, table5_bare: lists of {"mode_type", "omega_rad_s"} ascending,
Richardson-extrapolated from 3 element counts) plus a "report" block with
comparisons, and PNG figures. --quick uses coarser grids and fewer sweep points.
The tables come from the shared cable (``converge``: the node model's span, cablesys.slack.shared);
the sweeps and figures from the lumped chain (``solve_equilibrium`` and ``modes``), the same
discrete equations by the energy route.
"""

from __future__ import annotations

import argparse
import itertools
import json
import logging
import math
import time
from pathlib import Path

import numpy as np
import scipy.optimize

from cablesys.slack import irvine
from cablesys.slack.vibration import converge, modes
from cablesys.slack.plots import COLORS
from cablesys.slack.scene import SlackCable, PointMass, SlackScene
from cablesys.slack.statics import solve_equilibrium, solve_equilibrium_shooting

log = logging.getLogger("slack_tables")
# the published tables, copied into the package with their source headers (Griffin & Rosenthal 1985)
REF = Path(__file__).resolve().parents[1] / "cablesys" / "data"

# Griffin & Rosenthal (1985) section 6: l = 22.9 m, m = 1.14 kg/m, EA = 8.9e5 N
SPAN6, M6, EA6 = 22.9, 1.14, 8.9e5
LIGHT, HEAVY = 2.0, 4.5
# Table 1 (Triantafyllou 1984b): L = 330 m, EA = 7.07e-4 * 15e10 N, m = 5.56 kg/m,
# w = 47.6 N/m in water, added mass 0.128 m, depth 130 m, H = 76300 N
T1 = dict(L=330.0, EA=7.07e-4 * 15e10, m=5.56, w=47.6, ca=0.128, depth=130.0, H=76300.0)


def cable6(l_over_L: float) -> SlackCable:
    return SlackCable(length=SPAN6 / l_over_L, mass_per_length=M6, ae=EA6)


def scene6(l_over_L: float, masses=()) -> SlackScene:
    return SlackScene(cable=cable6(l_over_L), span=SPAN6, masses=tuple(masses))


def read_reference():
    import csv
    rows = {}
    with open(REF / "griffin_slack_frequencies.csv") as f:
        for r in csv.DictReader(line for line in f if not line.startswith("#")):
            rows.setdefault(r["table"] + "_" + r["case"], []).append(r)
    with open(REF / "griffin_table1_inclined.csv") as f:
        t1 = {r["source"]: [float(r[f"omega_{k}"]) for k in range(1, 6)]
              for r in csv.DictReader(line for line in f if not line.startswith("#"))}
    return rows, t1


# --- Table 1 ----------------------------------------------------------------

def table1_scene(n_elements=120) -> SlackScene:
    """Inclined cable in water; span found so that H = 76300 N with the depth 130 m."""
    cab = SlackCable(length=T1["L"], mass_per_length=T1["m"], ae=T1["EA"],
                weight_per_length=T1["w"], added_mass_per_length=T1["ca"] * T1["m"],
                specific_gravity=1.0 / (1.0 - T1["w"] / (T1["m"] * 9.80665)))

    def sc(span):
        return SlackScene(cable=cab, span=span, rise=T1["depth"], medium="water", n_elements=n_elements)

    span = scipy.optimize.brentq(
        lambda sp: solve_equilibrium_shooting(sc(sp)).horizontal_tension - T1["H"], 280.0, 309.0, xtol=1e-9)
    return sc(span)


def do_table1(levels, ref1):
    sc = table1_scene()
    eq = solve_equilibrium(sc)
    conv = converge(sc, 12, levels=levels)
    rows = [r for r in conv.table() if r["mode_type"] != "O"][:5]
    om = np.array([r["omega_rad_s"] for r in rows])
    rep = {"span_m": sc.span, "chord_angle_deg": math.degrees(sc.inclination),
           "top_tension_N": float(eq.tension[-1]), "top_tension_printed_N": 86660.0,
           "lambda2": eq.lambda2, "sag_to_length": eq.sag_to_length,
           "note": "in-plane modes only, as in the printed table; depth 130 m and H = 76300 N fix the geometry"}
    for src, vals in ref1.items():
        rep[f"rel_err_vs_{src}"] = (om / np.array(vals) - 1).tolist()
    return rows, rep


# --- Tables 2-5 ---------------------------------------------------------------

def masses_two(L):
    return [PointMass(position=L * k / 3, mass=HEAVY, name=f"heavy-{k}") for k in (1, 2)]


def masses_five(L, pattern="HLHLH"):
    return [PointMass(position=L * (k + 1) / 6, mass=HEAVY if c == "H" else LIGHT, name=f"{c}{k + 1}")
            for k, c in enumerate(pattern)]


def static_summary(sc):
    eq = solve_equilibrium(sc.replace(n_elements=192))
    W = M6 * 9.80665 * SPAN6
    return {"sag_to_length": eq.sag_to_length, "H_over_mgl": eq.horizontal_tension / W,
            "lambda2": eq.lambda2}


def compare_slack(rows, ref_rows):
    out = []
    for r, ref in zip(rows, ref_rows):
        d = {"mode_type": r["mode_type"], "ref_type": ref["mode_type"], "omega_rad_s": r["omega_rad_s"]}
        for code in ("SLACK1", "SLACK2"):
            v = ref[f"omega_{code}"]
            if v:
                d[code] = float(v)
                d[f"rel_diff_{code}"] = r["omega_rad_s"] / float(v) - 1
        out.append(d)
    verdict = {}
    for code in ("SLACK1", "SLACK2"):
        diffs = [abs(d[f"rel_diff_{code}"]) for d in out if f"rel_diff_{code}" in d]
        if diffs:
            verdict[f"mean_abs_rel_diff_{code}"] = float(np.mean(diffs))
            verdict[f"max_abs_rel_diff_{code}"] = float(np.max(diffs))
    return {"rows": out, **verdict}


def five_mass_sensitivity(L, levels):
    """All 10 placements of 2 light + 3 heavy masses at the sixth points."""
    res = {}
    for light in itertools.combinations(range(5), 2):
        pat = "".join("L" if k in light else "H" for k in range(5))
        c = converge(scene6(0.962, masses_five(L, pat)), 9, levels=levels)
        res[pat] = c.table()
    om = np.array([[r["omega_rad_s"] for r in v] for v in res.values()])
    return {"patterns": res, "min": om.min(0).tolist(), "max": om.max(0).tolist(),
            "spread_rel": ((om.max(0) - om.min(0)) / om.mean(0)).tolist()}


# --- sweeps and figures -----------------------------------------------------

def air_cable_T1() -> SlackCable:
    """The Table 1 cable in air (Figs. 6-8: 'cable properties as in Table 1')."""
    return SlackCable(length=T1["L"], mass_per_length=T1["m"], ae=T1["EA"])


def sweep(theta_deg, n_points, n_modes=18, n_el=90):
    cab = air_cable_T1()
    # chord/L from 1.012 (stretched taut cable, s/L ~ 0.002) down to 0.08 (doubled up)
    n1 = n_points // 3
    c_over_L = np.concatenate([1 + np.logspace(math.log10(0.012), -4, n1),
                               1 - np.logspace(-5, math.log10(0.92), n_points - n1)])
    out = []
    for col in c_over_L:
        sc = SlackScene.from_chord(cable=cab, chord=cab.length * col, theta_deg=theta_deg, n_elements=n_el)
        eq = static(sc)
        ms = modes(eq, n_modes, solver="dense")
        out.append((eq.sag_to_length, ms))
    return out


def fig_sweep(path, theta_deg, data):
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 5.5), constrained_layout=True)
    sl = np.array([d[0] for d in data])
    for t, lab in (("O", "out-of-plane"), ("S", "in-plane symmetric"), ("A", "in-plane antisymmetric"),
                   ("H", "in-plane hybrid")):
        xs, ys = [], []
        for s, ms in data:
            for tt, w in zip(ms.mode_type, ms.omega):
                if tt == t:
                    xs.append(s)
                    ys.append(w)
        ax.scatter(xs, ys, s=7 if t != "O" else 4, color=COLORS[t], label=lab,
                   marker="o" if t != "O" else "x", zorder=3 if t != "O" else 2)
    # in-plane branches joined by index (solid), out-of-plane dashed
    ninp = min(len([t for t in ms.mode_type if t != "O"]) for _, ms in data)
    for k in range(ninp):
        ax.plot(sl, [ms.omega[[i for i, t in enumerate(ms.mode_type) if t != "O"][k]] for _, ms in data],
                "-", color="k", lw=0.5, alpha=0.5)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("sag-to-length ratio s/L (-)")
    ax.set_ylabel(r"natural frequency $\omega$ (rad/s)")
    ax.set_title(f"Table 1 cable in air, chord inclination {theta_deg:g} deg (cf. Griffin & Rosenthal Fig. "
                 f"{ {0: 6, 30: 7, 60: 8}[theta_deg] })", fontsize=10)
    ax.legend(loc="upper right", fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def veering_gap(data):
    """Smallest relative gap between the 1st and 2nd in-plane frequencies along the sweep."""
    gaps = []
    for s, ms in data:
        w = ms.of_type("A", "S", "H")
        gaps.append((w[1] - w[0]) / w[0])
    i = int(np.argmin(gaps))
    return {"min_rel_gap": float(gaps[i]), "at_sag_to_length": float(data[i][0])}


def static(sc):
    """Shooting (fast, exact for the chain), the CasADi NLP if it fails."""
    try:
        return solve_equilibrium_shooting(sc)
    except Exception:  # noqa: BLE001
        return solve_equilibrium(sc)


def min_gap(theta_deg, n_el=90):
    """Refined smallest relative gap of the two lowest in-plane modes (crossover: ~0; veering: > 0)."""
    cab = air_cable_T1()

    def gap(c_over_L):
        sc = SlackScene.from_chord(cable=cab, chord=cab.length * c_over_L, theta_deg=theta_deg, n_elements=n_el)
        eq = static(sc)
        w = modes(eq, 6, solver="dense").of_type("A", "S", "H")
        return (w[1] - w[0]) / w[0]
    r = scipy.optimize.minimize_scalar(gap, bounds=(0.99, 1.012), method="bounded", options={"xatol": 1e-7})
    sc = SlackScene.from_chord(cable=cab, chord=cab.length * r.x, theta_deg=theta_deg, n_elements=n_el)
    eq = static(sc)
    return {"min_rel_gap": float(r.fun), "chord_over_length": float(r.x), "sag_to_length": eq.sag_to_length,
            "lambda2": eq.lambda2}


def fig_transition(path, n_el=120):
    """Fig. 5 analogue: first two in-plane modes of the 60 deg cable across the veering."""
    import matplotlib.pyplot as plt
    cab = air_cable_T1()
    # locate the veering: smallest gap between the two lowest in-plane frequencies
    def gap(c_over_L):
        sc = SlackScene.from_chord(cable=cab, chord=cab.length * c_over_L, theta_deg=60, n_elements=n_el)
        eq = static(sc)
        w = modes(eq, 6, solver="dense").of_type("A", "S", "H")
        return (w[1] - w[0]) / w[0]
    r = scipy.optimize.minimize_scalar(gap, bounds=(0.995, 1.012), method="bounded", options={"xatol": 1e-6})
    centres = r.x + np.array([0.004, 0.0015, 0.0, -0.0015, -0.004])
    fig, axes = plt.subplots(2, len(centres), figsize=(13, 5), sharex=True, constrained_layout=True)
    for j, col in enumerate(centres):
        sc = SlackScene.from_chord(cable=cab, chord=cab.length * col, theta_deg=60, n_elements=n_el)
        eq = static(sc)
        ms = modes(eq, 8, solver="dense")
        idx = [i for i, t in enumerate(ms.mode_type) if t != "O"][:2]
        for row, i in enumerate(idx):
            sh = ms.shapes[i]
            un = -sh[:, 0] * math.sin(math.radians(60)) + sh[:, 2] * math.cos(math.radians(60))
            ax = axes[row, j]
            ax.plot(ms.s / cab.length, un, color=COLORS[ms.mode_type[i]])
            ax.axhline(0, color="k", lw=0.5)
            ax.set_title(f"s/L={eq.sag_to_length:.2e}\nmode {row + 1}: {ms.mode_type[i]}, "
                         f"{ms.omega[i]:.3f} rad/s", fontsize=8)
            if j == 0:
                ax.set_ylabel(r"normal displacement $\psi_n/\psi_R$ (kg$^{-1/2}$)", fontsize=8)
            if row == 1:
                ax.set_xlabel("arc length s/L (-)")
    fig.suptitle("First two in-plane modes through the veering, theta = 60 deg (cf. Fig. 5); "
                 "S symmetric, A antisymmetric, H hybrid", fontsize=10)
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return {"veering_chord_over_length": float(r.x), "min_rel_gap": float(r.fun)}


def irvine_check(levels, n_points):
    """Numerical (Richardson) vs eq. 6 / string for the Table-2 cable at small sag."""
    rows = []
    for sl in np.linspace(0.0004, 0.0025, n_points):     # 1 - l/L: sag/span <= ~3 %
        sc = scene6(1 - sl)
        eq = solve_equilibrium(sc.replace(n_elements=levels[-1]))
        c = converge(sc, 6, levels=levels)
        lam2, H, l = eq.lambda2, eq.horizontal_tension, SPAN6
        ref = irvine.irvine_modes(8, lambda2=lam2, span=l, H=H, m=M6)
        errs = []
        for t in ("O", "A", "S"):
            num = sorted(w for tt, w in zip(c.mode_type, c.richardson) if tt == t)
            th = [m.omega for m in ref if m.mode_type == t][:len(num)]
            errs += [(t, float(a / b - 1)) for a, b in zip(num, th)]
        rows.append({"one_minus_l_over_L": float(sl), "sag_to_span": eq.sag / l, "lambda2": lam2,
                     "errors": errs, "max_abs_err": max(abs(e) for _, e in errs)})
    return rows


def fig_irvine(path, rows):
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.5), constrained_layout=True)
    for t in ("O", "A", "S"):
        xs = [r["lambda2"] for r in rows for tt, e in r["errors"] if tt == t]
        ys = [100 * e for r in rows for tt, e in r["errors"] if tt == t]
        ax.scatter(xs, ys, color=COLORS[t], s=12, label={"O": "out-of-plane", "A": "antisymmetric",
                                                         "S": "symmetric"}[t])
    ax.axvline(irvine.LAMBDA2_CROSSOVER, color="k", ls=":", label=r"crossover $\lambda^2=4\pi^2$")
    ax.axhspan(-1, 1, color="g", alpha=0.08, label="+/- 1 %")
    ax.set_xlabel(r"Irvine parameter $\lambda^2$ (-)")
    ax.set_ylabel("numerical / Irvine-Caughey - 1 (%)")
    ax.set_title("Converged lumped-mass frequencies vs eq. 6 (Table 2 cable, sag/span < 3 %)", fontsize=10)
    ax.legend(fontsize=8)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def convergence_study(n_modes, levels):
    c = converge(scene6(0.987), n_modes, levels=levels)
    return c


def fig_convergence(path, c):
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.5), constrained_layout=True)
    h = 1.0 / np.array(c.levels)
    for k in range(len(c.richardson)):
        err = np.abs(c.omega[:, k] / c.richardson[k] - 1)
        ax.loglog(c.levels, err, "-", color=COLORS[c.mode_type[k]], alpha=0.6, lw=0.8)
    ax.loglog(c.levels, 0.5 * (h / h[0]) ** 2 * np.max(np.abs(c.omega[0] / c.richardson - 1)), "k--",
              lw=2, label="slope -2")
    for t, lab in (("O", "out-of-plane"), ("A", "antisymmetric"), ("S", "symmetric")):
        ax.plot([], [], color=COLORS[t], label=lab)
    ax.set_xlabel("number of elements N (-)")
    ax.set_ylabel("|omega_N / omega_Richardson - 1| (-)")
    ax.set_title(f"Convergence of the {len(c.richardson)} lowest modes, Table 2 cable", fontsize=10)
    ax.legend(fontsize=8)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True)
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    levels = (24, 48, 96) if args.quick else (48, 96, 192)
    refrows, ref1 = read_reference()
    doc, rep = {}, {}

    doc["table1"], rep["table1"] = do_table1((30, 60, 120) if args.quick else (60, 120, 240), ref1)
    log.info("table 1 done %.1fs", time.perf_counter() - t0)

    c2 = converge(scene6(0.987), 9, levels=levels)
    doc["table2"] = c2.table()
    rep["table2"] = compare_slack(doc["table2"], refrows["T2_bare"])
    rep["table2"]["statics"] = static_summary(scene6(0.987))
    rep["table2"]["observed_order"] = c2.order.tolist()

    L962 = SPAN6 / 0.962
    c5 = converge(scene6(0.962), 8, levels=levels)
    doc["table5_bare"] = [r for r in c5.table() if r["mode_type"] != "O"][:4]
    rep["table5_bare"] = compare_slack(doc["table5_bare"], refrows["T5_bare"])
    rep["table5_bare"]["statics"] = static_summary(scene6(0.962))

    c3 = converge(scene6(0.962, masses_two(L962)), 9, levels=levels)
    doc["table3_two_masses"] = c3.table()
    rep["table3_two_masses"] = {"assumption": "two 4.5 kg point masses at the third points of the "
                                "unstretched arc length", "statics": static_summary(scene6(0.962, masses_two(L962)))}
    # sensitivity: masses at the third points of the span (x = l/3, 2l/3) instead
    pos = L962 / 3
    for _ in range(6):
        eq = solve_equilibrium_shooting(scene6(0.962, [PointMass(position=pos, mass=HEAVY),
                                                          PointMass(position=L962 - pos, mass=HEAVY)]))
        pos += SPAN6 / 3 - np.interp(pos, eq.s, eq.x)
    c3b = converge(scene6(0.962, [PointMass(position=pos, mass=HEAVY), PointMass(position=L962 - pos, mass=HEAVY)]),
                   9, levels=levels)
    rep["table3_two_masses"]["span_third_points_variant"] = {"arc_position_m": pos, "table": c3b.table()}
    log.info("tables 2, 3, 5 done %.1fs", time.perf_counter() - t0)

    c4 = converge(scene6(0.962, masses_five(L962)), 9, levels=levels)
    doc["table4_five_masses"] = c4.table()
    rep["table4_five_masses"] = compare_slack(doc["table4_five_masses"], refrows["T4_five_masses"])
    rep["table4_five_masses"]["assumption"] = ("masses at the sixth points of the unstretched arc length, "
                                               "pattern heavy-light-heavy-light-heavy (HLHLH)")
    rep["table4_five_masses"]["statics"] = static_summary(scene6(0.962, masses_five(L962)))
    rep["table4_five_masses"]["sensitivity"] = five_mass_sensitivity(L962, (12, 24, 48) if args.quick else levels)
    log.info("table 4 done %.1fs", time.perf_counter() - t0)

    # Table 5: first four in-plane modes of the three configurations
    rep["table5"] = {name: [r for r in tab if r["mode_type"] != "O"][:4] for name, tab in
                     (("bare", doc["table5_bare"]), ("two_masses", doc["table3_two_masses"]),
                      ("five_masses", doc["table4_five_masses"]))}

    irv = irvine_check((24, 48, 96), 5 if args.quick else 12)
    rep["irvine"] = {"max_abs_rel_err": max(r["max_abs_err"] for r in irv), "rows": irv}
    fig_irvine(out / "irvine_agreement.png", irv)

    cc = convergence_study(30 if args.quick else 40, (50, 100, 200) if args.quick else (100, 200, 400))
    rep["convergence"] = {"levels": cc.levels, "mode_type": cc.mode_type, "observed_order": cc.order.tolist(),
                          "richardson": cc.richardson.tolist(),
                          "finest_rel_err": cc.relative_error_finest.tolist()}
    fig_convergence(out / "convergence.png", cc)
    log.info("irvine + convergence done %.1fs", time.perf_counter() - t0)

    rep["sweeps"] = {}
    for th in (0, 30, 60):
        data = sweep(th, 14 if args.quick else 45)
        fig_sweep(out / f"freq_vs_sag_theta{th}.png", th, data)
        rep["sweeps"][f"theta{th}"] = {"sampled": veering_gap(data), "refined": min_gap(th)}
    rep["transition"] = fig_transition(out / "mode_transition_theta60.png", n_el=60 if args.quick else 120)
    log.info("figures done %.1fs", time.perf_counter() - t0)

    doc["report"] = rep
    doc["meta"] = {"levels": levels, "quick": args.quick, "seconds": time.perf_counter() - t0,
                   "route": "tables (converge): the shared cable, the node model's span (cablesys.slack.shared); "
                            "sweeps and figures: the lumped chain (NLP statics, energy Hessian)",
                   "omega_rad_s": "Richardson-extrapolated natural angular frequency, rad/s"}
    (out / "slack_tables.json").write_text(json.dumps(doc, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
