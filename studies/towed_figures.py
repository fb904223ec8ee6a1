"""Figures and checks of the Kennedy & Strahan (1981) towed-cable theory (Figs. 3-7, 11 analogues).

    python studies/towed_figures.py --out DIR [--quick]

Writes PNGs (cable-shape time histories, |H| and c* over space and frequency, the map of
where the real-order approximation fails, the interaction amplification) and
towed_figures.json (damping times, eigenfrequencies with the eq. 20b test, cross-checks).
Cable: the sea-trial coefficients with L = 1190 m, U = 5 m/s unless stated.
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

import numpy as np

from cablesys.towed.bessel import exact_solution, mpmath_solution, real_order_solution
from cablesys.towed.bvp import bvp_solution
from cablesys.towed.eigen import damping_time, exact_eigenfrequency, modes
from cablesys.towed.equation import REPORT_SEA_TRIAL, REPORT_TYPICAL, TowedCable
from cablesys.towed.mol import forced_response, slowest_mode
from cablesys.towed.interaction import (amplification, effective_amplification,
                                        effective_amplification_exact)
from cablesys.towed.transfer import c_star, transfer_grid, water_pulley_c_star
from cablesys.plots import save_figure  # noqa: E402


def shapes(plt, coef, out: Path):
    """Figs. 3-5 analogue: eta(xi, tau) = Re[H(xi) exp(i omega tau)] over one period."""
    fig, axes = plt.subplots(3, 1, figsize=(8, 9), sharex=True)
    xi = np.linspace(0.0, 1.0, 301)
    for ax, om in zip(axes, (5.0, 10.0, 20.0)):
        H = exact_solution(coef, xi, om)
        for k, tau in enumerate(np.linspace(0, 2 * math.pi / om, 8, endpoint=False)):
            ax.plot(xi, np.real(H * np.exp(1j * om * tau)), lw=1,
                    color=plt.cm.viridis(k / 8), label=f"tau = {tau:.2f}" if om == 5.0 else None)
        ax.plot(xi, np.abs(H), "k--", lw=1, label="envelope |H|" if om == 5.0 else None)
        ax.plot(xi, -np.abs(H), "k--", lw=1)
        ax.set_ylabel("eta / tow-point amplitude (-)")
        ax.set_title(f"omega = 2 pi f L / U = {om:g}")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7, ncol=3, loc="upper right")
    axes[-1].set_xlabel("xi = x / L (-), tow point at 0")
    fig.suptitle("Cable shape over one period (Kennedy & Strahan 1981 Figs. 3-5 analogue)")
    save_figure(fig, out / "towed_shapes.png", dpi=110)


def space_frequency(plt, coef, out: Path, n: int):
    """Figs. 6-7 analogue: |H| and c* over (xi, omega)."""
    xi = np.linspace(0.0, 1.0, n)
    om = np.linspace(0.05, 30.0, n)
    g = transfer_grid(coef, xi, om)
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    m = axes[0].pcolormesh(om, xi, np.abs(g.H), shading="auto", cmap="viridis")
    cs = axes[0].contour(om, xi, np.abs(g.H), levels=[0.05, 0.1, 0.25, 0.5, 0.75, 0.9], colors="w", linewidths=0.8)
    axes[0].clabel(cs, fontsize=7)
    fig.colorbar(m, ax=axes[0], label="|H(xi, omega)| (-)")
    axes[0].set_title("Transfer function magnitude (Fig. 6 analogue)")
    m = axes[1].pcolormesh(om, xi[1:], g.c_star[1:], shading="auto", cmap="magma")
    cs = axes[1].contour(om, xi[1:], g.c_star[1:], levels=[1.25, 1.5, 2, 2.5, 3], colors="w", linewidths=0.8)
    axes[1].clabel(cs, fontsize=7)
    fig.colorbar(m, ax=axes[1], label="c* = omega xi / psi (units of U)")
    axes[1].set_title(f"Phase velocity c* (Fig. 7 analogue); low-f limit 1+1/p = {water_pulley_c_star(coef):.3f}")
    for ax in axes:
        ax.set_xlabel("omega = 2 pi f L / U (-)")
        ax.set_ylabel("xi = x / L (-)")
    save_figure(fig, out / "towed_space_frequency.png", dpi=110)
    return g


def real_order_map(plt, out: Path, n: int):
    """Where the real-order form (eq. 16) departs from the exact complex order, vs L and omega."""
    lengths = np.geomspace(20.0, 3000.0, n)
    om = np.geomspace(0.1, 30.0, n)
    xi = np.linspace(0.0, 1.0, 21)[:, None]
    dH = np.empty((n, n))
    dHrel = np.empty((n, n))
    est = np.empty((n, n))
    ratio = np.empty((n, n))
    for i, L in enumerate(lengths):
        coef = TowedCable(length=L, speed=5.0, **REPORT_SEA_TRIAL).coefficients()
        ve = exact_solution(coef, xi, om[None, :])
        vr = real_order_solution(coef, xi, om[None, :])
        dH[i] = np.abs(ve - vr).max(axis=0)
        dHrel[i] = (np.abs(ve - vr) / np.abs(ve)).max(axis=0)
        ratio[i] = coef.order_ratio(om)
        # large-|x| estimate of the eq. 8b error: 0F1 ~ x^((1-2q)/4) exp(2 sqrt x), so dropping
        # Im q = 2 beta omega / b changes ln H by (beta omega / b) ln((a + b xi)/a) at xi = 1
        est[i] = coef.beta * om / coef.b * abs(math.log(abs((coef.a + coef.b) / coef.a)))
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.2))
    for ax, val, lab, lv in ((axes[0], dH, "log10 max_xi |H_real - H_exact| (-)", (1e-3, 1e-2)),
                             (axes[1], dHrel, "log10 max_xi |H_real - H_exact| / |H_exact| (-)", (1e-2, 1e-1))):
        m = ax.pcolormesh(om, lengths, np.log10(np.maximum(val, 1e-16)), shading="auto", cmap="cividis",
                          vmin=-6, vmax=0)
        fig.colorbar(m, ax=ax, label=lab)
        cs = ax.contour(om, lengths, ratio, levels=[0.01, 0.03, 0.1, 0.3], colors="r", linewidths=1)
        ax.clabel(cs, fmt="|Im nu|/p = %g", fontsize=7)
        cs2 = ax.contour(om, lengths, val, levels=list(lv), colors="w", linestyles="--", linewidths=1)
        ax.clabel(cs2, fmt="%g", fontsize=7)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("omega = 2 pi f L / U (-)")
        ax.set_ylabel("cable length L (m), d_c = 16 mm, sea-trial coefficients")
    axes[0].set_title("Real-order (eq. 16) minus exact: absolute\nred: eq. 8b measure |Im nu|/p = 2 beta omega/(b p)")
    cs3 = axes[1].contour(om, lengths, est, levels=[0.01, 0.1], colors="c", linewidths=1.2, linestyles=":")
    axes[1].clabel(cs3, fmt="(beta omega/b)|ln(1+b/a)| = %g", fontsize=7)
    axes[1].set_title("Real-order (eq. 16) minus exact: relative to |H|\n"
                      "(white dashed: 1 % and 10 %; cyan: asymptotic estimate)")
    save_figure(fig, out / "towed_real_order_map.png", dpi=110)
    # summary: worst |dH| inside bands of the eq. 8b ratio
    bands = {}
    for lo, hi in [(0, 0.01), (0.01, 0.03), (0.03, 0.1), (0.1, 0.3), (0.3, 10)]:
        sel = (ratio >= lo) & (ratio < hi)
        if np.any(sel):
            bands[f"{lo}-{hi}"] = {"max_abs_dH": float(dH[sel].max()),
                                   "max_rel_dH": float(dHrel[sel].max())}
    sel = dHrel > 1e-2
    return {"worst_real_order_error_by_eq8b_ratio": bands,
            "rel_error_over_estimate_median": float(np.median(dHrel[est > 1e-3] / est[est > 1e-3])),
            "min_omega_with_rel_error_gt_1pct": float(np.broadcast_to(om, dHrel.shape)[sel].min()) if sel.any() else None, "L_range_m": [20.0, 3000.0], "omega_range": [0.1, 30.0]}


def interaction(plt, out: Path):
    """Fig. 11 analogue: A(theta, phi) (eq. 38) and its Gaussian average (eq. B-5)."""
    from matplotlib.ticker import ScalarFormatter

    th = np.radians(np.linspace(1.0, 30.0, 200))
    sig = np.radians(np.linspace(0.5, 10.0, 40))
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6))
    for k, phd in enumerate((4, 6, 9)):
        col = f"C{k}"
        axes[0].plot(np.degrees(th), amplification(th, np.radians(phd)), col, label=f"phi = {phd} deg")
        axes[1].plot(np.degrees(sig), effective_amplification(sig, np.radians(phd)), col + "--",
                     label=f"eq. B-5 small angle, phi = {phd} deg")
        axes[1].plot(np.degrees(sig), [effective_amplification_exact(s, np.radians(phd)) for s in sig],
                     col, label=f"Gaussian average of eq. 36, phi = {phd} deg")
    for ax in axes:
        ax.axhline(0.16 / 0.07, color="k", lw=0.8, ls=":")
        ax.set_ylabel("amplification A = c_n* / c_n (-)")
        ax.set_yscale("log")
        ax.yaxis.set_major_formatter(ScalarFormatter())
        if ax is axes[0]:                          # narrow range: label the minor ticks too
            ax.yaxis.set_minor_formatter(ScalarFormatter())
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    axes[0].text(20, 0.16 / 0.07 * 1.08, "report: 0.16/0.07 = 2.29", fontsize=8)
    axes[0].set_xlabel("horizontal angle theta (deg)")
    axes[0].set_title("A(theta, phi), eq. 38 (Fig. 11 analogue)")
    axes[1].set_xlabel("rms horizontal angle sigma_theta (deg)")
    axes[1].set_title("Effective amplification, Appendix B")
    save_figure(fig, out / "towed_interaction.png", dpi=110)


def checks(coef) -> dict:
    """Numbers for the report: cross-checks, damping times, eigenfrequencies."""
    xi = np.linspace(0.0, 1.0, 11)[:, None]
    om = np.array([0.5, 2.0, 5.0, 10.0, 20.0, 40.0])[None, :]
    ve = exact_solution(coef, xi, om)
    vb = bvp_solution(coef, xi, om)
    vm = mpmath_solution(coef, xi[::5], om)
    low = float(c_star(coef, 1.0, 1e-3).c_star)
    mol_om = (2.0, 8.0)
    mol_err = [float(np.abs(forced_response(coef, w, [0.5, 1.0], n=200)
                            - exact_solution(coef, np.array([0.5, 1.0]), w)).max()) for w in mol_om]
    typ = TowedCable(**REPORT_TYPICAL)
    e = modes(typ.coefficients(), 5)
    return {
        "max_abs_exact_minus_shooting": float(np.abs(ve - vb).max()),
        "max_abs_exact_minus_mpmath": float(np.abs(ve[::5] - vm).max()),
        "max_abs_exact_minus_mol_casadi_n200": dict(zip([f"omega_{w:g}" for w in mol_om], mol_err)),
        "water_pulley": {"c_star_at_omega_1e-3": low, "1_plus_1_over_p": water_pulley_c_star(coef)},
        "typical_values": REPORT_TYPICAL,
        "t0_s": {"report_eq25_delta1_eq_p": damping_time(typ, zero="report"),
                 "first_zero_of_J_p": damping_time(typ, zero="bessel"),
                 "exact_complex_order": damping_time(typ, zero="exact"),
                 "mol_time_domain_operator_n200": typ.time_scale() / slowest_mode(typ.coefficients(), 200).imag},
        "eigen_typical": {
            "p": typ.coefficients().p, "D": typ.drag_term,
            "delta_n": e.delta.tolist(),
            "omega_slow": [[w.real, w.imag] for w in e.slow],
            "omega_fast": [[w.real, w.imag] for w in e.fast],
            "eq20b_ratio_slow": e.ratio_slow.tolist(), "eq20b_ratio_fast": e.ratio_fast.tolist(),
            "valid_slow": e.valid_slow.tolist(), "valid_fast": e.valid_fast.tolist(),
            "omega_1_exact_complex_order": [exact_eigenfrequency(typ.coefficients()).real,
                                            exact_eigenfrequency(typ.coefficients()).imag],
        },
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True, type=Path)
    ap.add_argument("--quick", action="store_true", help="coarser grids")
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cable = TowedCable(length=1190.0, speed=5.0, **REPORT_SEA_TRIAL)
    coef = cable.coefficients()
    shapes(plt, coef, args.out)
    space_frequency(plt, coef, args.out, 60 if args.quick else 200)
    rmap = real_order_map(plt, args.out, 12 if args.quick else 40)
    interaction(plt, args.out)
    result = {"cable": {"length_m": cable.length, "speed_mps": cable.speed, **REPORT_SEA_TRIAL},
              "p": coef.p, "xi_turn": coef.xi_turn, "real_order_map": rmap, **checks(coef)}
    (args.out / "towed_figures.json").write_text(json.dumps(result, indent=2))
    print(json.dumps(result, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
