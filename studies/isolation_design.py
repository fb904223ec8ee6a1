"""Isolation design (Wang 1971 p. 33, "dual isolation system"): baseline single rope vs optimized dual system.

A 300 kg instrument package hangs 200 m below a ship in a JONSWAP sea (Hs 2.5 m, Tp 9 s):
baseline, one polyester rope; designed, 150 m rope - heave-damper plate - 50 m rope with AE and
C_I of both ropes chosen by the NLP of :mod:`cablesys.isolation` (example values and bounds with
their reasons in :mod:`cablesys.isolation.example`). Outputs:

* RAO of the package's heave per unit sea amplitude, before/after, over the sea spectrum;
* the parameter table (Markdown), ``isolation_design.json`` and the problem as a scene TOML with a
  ``[design]`` table (``dual_isolation_design.toml``, for ``cablesys design``);
* the check with the nonlinear time-domain model in one irregular-sea realization (random-phase
  sum of spectral components, the top following the surface orbit as in the linear model): the
  reduction of the package's heave standard deviation must be within 10 % of the linear
  prediction (ratio of reduction factors), and no rope may go slack.

Usage: python studies/isolation_design.py --out DIR [--quick]
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import parse_args, setup_matplotlib, write_json  # noqa: E402

from cablesys.isolation import design, settings_to_toml  # noqa: E402
from cablesys.isolation.example import baseline_scene, dual_scene, example_settings  # noqa: E402
from cablesys.linear.spectra import jonswap  # noqa: E402
from cablesys.linear.stochastic import stochastic_response  # noqa: E402
from cablesys.model import build_model  # noqa: E402
from cablesys.plots import save_figure  # noqa: E402
from cablesys.scene import Sinusoid, TopMotion, dump_scene  # noqa: E402
from cablesys.time_domain import simulate  # noqa: E402

TRANSIENT_S = 100.0


def linear_stats(scene, settings, omega):
    model = build_model(scene)
    st = stochastic_response(model, model.parameters(scene), omega, jonswap(omega, settings.hs, settings.tp, settings.gamma))
    n = scene.n_sections
    lbl = "y_b" if n == 1 else f"y_b_{n}"
    return st, lbl


def sea_realization(settings, n_comp: int, seed: int):
    """Top motion following the surface orbit of a random-phase JONSWAP sea (Wang 1971 eq. 26 at x = 0).

    x_s = sum a_k cos(w_k t + th_k), y_s = -sum a_k sin(w_k t + th_k) (y down), a_k = sqrt(2 S(w_k) dw),
    w_k jittered inside equal bins so the record does not repeat. Given to the model as its sum of
    sinusoids (exact and SX-fast) rather than as a sampled ``TimeSeries``: the spline-interpolated
    series is evaluated in MX and made the same run ~20 times slower (13 s vs 0.6 s for 300 s)."""
    rng = np.random.default_rng(seed)
    edges = np.linspace(settings.omega_min, settings.omega_max, n_comp + 1)
    dw = np.diff(edges)
    w = edges[:-1] + rng.uniform(0.0, 1.0, n_comp) * dw
    a = np.sqrt(2.0 * jonswap(w, settings.hs, settings.tp, settings.gamma) * dw)
    th = rng.uniform(0.0, 2 * np.pi, n_comp)
    top = TopMotion(x=tuple(Sinusoid(amplitude=ak, frequency=wk, phase=tk + np.pi / 2) for ak, wk, tk in zip(a, w, th)),
                    y=tuple(Sinusoid(amplitude=-ak, frequency=wk, phase=tk) for ak, wk, tk in zip(a, w, th)))
    return top, float(np.sqrt(np.sum(a**2) / 2))


def time_domain(scene, top, duration):
    sc = scene.replace(top_motion=top).with_numerics(duration=duration, output_step=0.5)
    t0 = time.perf_counter()
    res = simulate(sc)
    n = scene.n_sections
    lbl = "y_b" if n == 1 else f"y_b_{n}"
    keep = res.time >= TRANSIENT_S
    tens = [res["tension_mid" if n == 1 else f"tension_mid_{i + 1}"][keep] for i in range(n)]
    return {"success": res.success, "message": res.message, "std_y_b_m": float(np.std(res[lbl][keep])),
            "significant_y_b_m": 2 * float(np.std(res[lbl][keep])), "slack_events": len(res.events),
            "min_tension_N": [float(t.min()) for t in tens], "max_tension_N": [float(t.max()) for t in tens],
            "wall_s": time.perf_counter() - t0}, res


def plot_rao(omega, S, curves, out: Path, title: str):
    plt = setup_matplotlib()
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for label, (H, style) in curves.items():
        ax.plot(omega, np.abs(H), style, label=label)
    ax.set_xlabel("wave frequency omega [rad/s]")
    ax.set_ylabel("package heave / sea amplitude [-]")
    ax.set_ylim(0, None)
    ax.grid(True, alpha=0.3)
    ax2 = ax.twinx()
    ax2.fill_between(omega, S, color="tab:blue", alpha=0.12, label="JONSWAP S(omega)")
    ax2.set_ylabel("sea spectrum [m^2 s/rad]")
    ax2.set_ylim(0, 3 * S.max())
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    ax.legend(h1 + h2, l1 + l2, fontsize=8, loc="center right")
    ax.set_title(title, fontsize=9)
    save_figure(fig, out, dpi=110)


def plot_time(results: dict, out: Path):
    plt = setup_matplotlib()
    fig, axes = plt.subplots(2, 1, figsize=(9, 5.5), sharex=True)
    for label, (res, lbl, tlbl) in results.items():
        axes[0].plot(res.time, res[lbl], lw=0.8, label=label)
        axes[1].plot(res.time, res[tlbl] / 1e3, lw=0.8, label=label)
    axes[0].set_ylabel("package depth y_b [m] (down)")
    axes[0].invert_yaxis()
    axes[1].set_ylabel("top tension [kN]")
    axes[1].set_xlabel("time [s]")
    for ax in axes:
        ax.axvline(TRANSIENT_S, color="k", lw=0.6, ls=":")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8, loc="upper right")
    axes[0].set_title("irregular-sea realization, nonlinear time domain (dotted: start of statistics)", fontsize=9)
    save_figure(fig, out, dpi=110)


def parameter_table(base, opt_scene, result) -> str:
    rows = ["| quantity | baseline (one rope) | dual isolation, optimum | bounds |", "|---|---|---|---|"]
    bc = base.sections[0].cable
    for i in range(2):
        c = opt_scene.sections[i].cable
        lo, hi = result.lower[2 * i], result.upper[2 * i]
        rows.append(f"| (AE)_{i + 1} [N] | {bc.ae:.4g}{' (200 m)' if i == 0 else ''} | {c.ae:.4g} ({c.length:g} m) | [{lo:.3g}, {hi:.3g}] |")
        lo, hi = result.lower[2 * i + 1], result.upper[2 * i + 1]
        rows.append(f"| C_I,{i + 1} [N s] | {bc.internal_damping:.4g} | {c.internal_damping:.4g} | [{lo:.3g}, {hi:.3g}] |")
    b1 = opt_scene.sections[0].body
    rows.append(f"| intermediate body | none | damper plate: W = {b1.weight:.0f} N, M_vy = {b1.mass_y:.0f} kg | fixed |")
    for k, v in result.margins.items():
        rows.append(f"| margin {k} | | {v:+.3f} | {'active' if k in result.active else ''} |")
    return "\n".join(rows) + "\n"


def main(argv=None) -> int:
    args = parse_args(__doc__.splitlines()[0], argv)
    settings = example_settings()
    omega = settings.omega
    S = jonswap(omega, settings.hs, settings.tp, settings.gamma)
    base = baseline_scene()
    st_base, lb = linear_stats(base, settings, omega)
    start = dual_scene()
    st_start, ld = linear_stats(start, settings, omega)

    result = design(start, settings)
    v = {n: result.value(n) for n in result.variable_names}
    opt = start
    for i in range(2):
        opt = opt.replace_section(i, cable={"ae": v[f"ae_{i + 1}"], "internal_damping": v[f"internal_damping_{i + 1}"]})
    st_opt, _ = linear_stats(opt, settings, omega)
    sig_base, sig_opt = st_base.significant_amplitude(lb), st_opt.significant_amplitude(ld)
    reduction_db = 20 * np.log10(sig_opt / sig_base)

    plot_rao(omega, S, {"baseline: one 200 m polyester rope": (st_base.transfer[:, st_base.output_labels.index(lb)], "k-"),
                        "dual, same ropes as baseline (NLP start)": (st_start.transfer[:, st_start.output_labels.index(ld)], "C1--"),
                        "dual, optimized AE and C_I": (st_opt.transfer[:, st_opt.output_labels.index(ld)], "C3-")},
             args.out / "isolation_rao.png",
             f"package heave RAO (stochastic linearization, Hs = {settings.hs} m, Tp = {settings.tp} s); "
             f"significant heave {sig_base:.2f} m -> {sig_opt:.2f} m ({reduction_db:+.1f} dB)")
    (args.out / "isolation_parameters.md").write_text(parameter_table(base, opt, result))
    # the same problem for the command line: cablesys design dual_isolation_design.toml
    (args.out / "dual_isolation_design.toml").write_text(dump_scene(start) + "\n" + settings_to_toml(settings))

    duration = 500.0 if args.quick else 1300.0
    top, sea_std = sea_realization(settings, 120 if args.quick else 300, seed=7)
    td_base, r_base = time_domain(base, top, duration)
    td_opt, r_opt = time_domain(opt, top, duration)
    plot_time({"baseline": (r_base, "y_b", "tension_top"), "dual, optimized": (r_opt, "y_b_2", "tension_top_1")},
              args.out / "isolation_time_domain.png")
    td_db = 20 * np.log10(td_opt["std_y_b_m"] / td_base["std_y_b_m"])
    factor_ratio = 10 ** ((td_db - reduction_db) / 20)
    slack = bool(td_base["slack_events"] + td_opt["slack_events"] > 0 or min(td_opt["min_tension_N"]) <= 0.0)
    doc = {
        "quick": args.quick, "converged": result.converged, "status": result.status,
        "nlp_iterations": result.nlp_iterations, "nlp_wall_s": result.nlp_wall_s, "total_wall_s": result.total_wall_s,
        "objective_kind": result.objective_kind, "objective": result.objective,
        "optimal_parameters": v, "bounds": {n: [float(lo), float(hi)] for n, lo, hi in
                                            zip(result.variable_names, result.lower, result.upper)},
        "active": list(result.active), "constraint_margins": result.margins,
        "significant_heave_m": {"baseline": sig_base, "dual_start": st_start.significant_amplitude(ld), "dual_optimum": sig_opt},
        "reduction_db": reduction_db, "time_domain_reduction_db": td_db,
        "time_domain_over_linear_reduction_factor": factor_ratio,
        "within_10_percent": bool(abs(factor_ratio - 1) <= 0.10),
        "slack_in_time_domain": slack,
        "time_domain": {"duration_s": duration, "transient_s": TRANSIENT_S, "sea_std_m": sea_std,
                        "baseline": td_base, "dual_optimum": td_opt},
        "outer_history": list(result.outer_history), "runs": list(result.runs),
    }
    write_json(args.out / "isolation_design.json", doc)
    return 0


if __name__ == "__main__":
    sys.exit(main())
