"""The Dale et al. comparison (Wang 1971, Table 2): lower-body amplitudes at four frequencies.

    python studies/wang_dale_table2.py --out DIR [--quick]

Runs the default Dale scene (``cablesys.scene.dale_scene``: 9 ft cable, 1 in sphere,
circular top motion of 5 in peak to peak) at omega/omega_n = 0.5, 1.0, 1.5, 2.0 with
omega_n = 1.14 rad/s (the measured natural frequency) and writes the steady-state
amplitudes of the lower body, half peak-to-peak over the last K periods, in feet:
DIR/wang_dale_table2.json (keys ``omega_over_omega_n``, ``xbA_ft``, ``ybA_ft``) and
DIR/wang_dale_table2.png.

Steady state is checked, not assumed: the amplitude over the last K periods is compared
with that over the K periods before (``steady_change_ft``); the run is extended if they
differ by more than ``STEADY_TOL_FT``.

Inputs the report does not print (chosen in ``cablesys/scene/dale.py``, with reasons there):
sphere C_D = 0.5, cable normal C_D = 1.4, tangential C_t = 0.01, AE = 1000 lb. Their
influence is shown by re-running with sphere C_D 0.4/0.7, cable C_D 1.2/1.8 (``drag_sensitivity``)
and AE 5 lb (``ae_sensitivity_max_change_ft``; the report, p. 29-30: AE between 5 and 1000 lb
changes the amplitudes by less than 0.01 ft). The report's Table 2 values are not used here.
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import parse_args, setup_matplotlib, write_json  # noqa: E402

from cablesys import units as U  # noqa: E402
from cablesys.linear import modes  # noqa: E402
from cablesys.linear.linearization import linearize  # noqa: E402
from cablesys.model import build_model  # noqa: E402
from cablesys.plots import save_figure  # noqa: E402
from cablesys.scene import dale_scene  # noqa: E402
from cablesys.scene.dale import (  # noqa: E402
    CABLE_CD,
    CABLE_CT,
    OMEGA_N_MEASURED,
    SPHERE_CD,
    TOP_MOTION_PEAK_TO_PEAK,
)
from cablesys.time_domain import IntegratorSettings, Simulator  # noqa: E402
from cablesys.time_domain.run import initial_state  # noqa: E402

RATIOS = (0.5, 1.0, 1.5, 2.0)
K_PERIODS = 3                  # amplitude = half peak-to-peak over the last K periods
SAMPLES_PER_PERIOD = 200
STEADY_TOL_FT = 1e-4           # last K periods vs the K before
SPHERE_AREA = math.pi / 4 * U.INCH**2


class DaleRunner:
    """One model for every run (all the varied numbers are parameters: nothing is rebuilt)."""

    def __init__(self, n_periods: int, rtol: float):
        self.model = build_model(dale_scene())
        self.n_periods = n_periods
        self.rtol = rtol
        self._sims = {}
        self.wall = 0.0

    def _sim(self, ratio, n_periods):
        key = (ratio, n_periods)
        if key not in self._sims:
            period = 2 * math.pi / (ratio * OMEGA_N_MEASURED)
            times = np.arange(n_periods * SAMPLES_PER_PERIOD + 1) * (period / SAMPLES_PER_PERIOD)
            self._sims[key] = Simulator(self.model, times, IntegratorSettings(method="cvodes", rtol=self.rtol,
                                                                               atol=1e-12))
        return self._sims[key]

    def amplitudes(self, ratio: float, *, ae_lb=1000.0, sphere_cd=SPHERE_CD, cable_cd=CABLE_CD) -> dict:
        scene = dale_scene(omega_ratio=ratio, ae_lb=ae_lb).replace_section(
            0, cable={"cd_normal": cable_cd},
            body={"drag_area_normal": sphere_cd * SPHERE_AREA, "drag_area_tangential": sphere_cd * SPHERE_AREA})
        p = self.model.parameters(scene)
        x0 = initial_state(scene, self.model, p)
        n = self.n_periods
        while True:
            sim = self._sim(ratio, n)
            t0 = time.perf_counter()
            r = sim.run(p, x0)
            self.wall += time.perf_counter() - t0
            if not r.success:
                raise RuntimeError(f"Dale run at omega/omega_n = {ratio} failed: {r.message}")
            period = 2 * math.pi / (ratio * OMEGA_N_MEASURED)
            out = {lbl: r.steady_amplitude(lbl, period, K_PERIODS) / U.FT for lbl in ("x_b", "y_b")}
            out["steady_change_ft"] = max(r.amplitude_drift(lbl, period, K_PERIODS) for lbl in ("x_b", "y_b")) / U.FT
            out["n_periods"] = n
            out["n_events"] = len(r.events)
            out["series"] = (r.time, r["x_b"], r["y_b"], r["x_s"], r["y_s"])
            if out["steady_change_ft"] <= STEADY_TOL_FT or n >= 8 * self.n_periods:
                return out
            n *= 2


def model_frequencies(model) -> dict:
    """Undamped small-motion frequencies of the model at rest (cablesys.linear; drag has no linear part)."""
    scene = dale_scene()
    m = modes(linearize(model, model.parameters(scene)))
    w = np.sort(m.omega_undamped)
    return {"pendulum_rad_s": float(w[0]), "stretch_rad_s": float(w[-1]),
            "pendulum_over_measured_omega_n": float(w[0] / OMEGA_N_MEASURED)}


def main(argv=None) -> int:
    args = parse_args(__doc__.splitlines()[0], argv)
    n_periods = 8 if args.quick else 20
    runner = DaleRunner(n_periods, rtol=1e-7 if args.quick else 1e-8)
    top_amp_ft = 0.5 * TOP_MOTION_PEAK_TO_PEAK / U.FT
    res = {
        "omega_over_omega_n": list(RATIOS),
        "omega_n_rad_s": OMEGA_N_MEASURED,
        "top_amplitude_ft": top_amp_ft,
        "amplitude_definition": f"half peak-to-peak over the last {K_PERIODS} periods",
        "inputs": {"sphere_cd": SPHERE_CD, "cable_cd": CABLE_CD, "cable_ct": CABLE_CT, "ae_lb": 1000.0,
                   "why": "see cablesys/scene/dale.py: sphere C_D 0.5 (steady-flow sphere curve 0.40-0.47 at "
                          "Re 1e3-5e3, raised by oscillatory flow at KC 10-30); cable C_D 1.4 (circular cylinder "
                          "at Re ~ 50-150); C_t 0.01; AE 1000 lb (report: half steel by area)"},
        "quick": bool(args.quick),
    }
    base = {r: runner.amplitudes(r) for r in RATIOS}
    res["xbA_ft"] = [base[r]["x_b"] for r in RATIOS]
    res["ybA_ft"] = [base[r]["y_b"] for r in RATIOS]
    res["steady_change_ft"] = [base[r]["steady_change_ft"] for r in RATIOS]
    res["n_periods_run"] = [base[r]["n_periods"] for r in RATIOS]
    res["slack_events"] = [base[r]["n_events"] for r in RATIOS]
    res["model_frequencies"] = model_frequencies(runner.model)
    for r in RATIOS:
        print(f"omega/omega_n = {r:3.1f}: x_bA = {base[r]['x_b']:.4f} ft, y_bA = {base[r]['y_b']:.4f} ft "
              f"(steady to {base[r]['steady_change_ft']:.1e} ft after {base[r]['n_periods']} periods)")

    # AE from 5 to 1000 lb (report p. 29-30)
    ae_values = (5.0, 100.0, 1000.0) if not args.quick else (5.0, 1000.0)
    ae = {a: ({r: base[r] for r in RATIOS} if a == 1000.0 else {r: runner.amplitudes(r, ae_lb=a) for r in RATIOS})
          for a in ae_values}
    res["ae_sensitivity"] = {f"{a:g}": {"xbA_ft": [ae[a][r]["x_b"] for r in RATIOS],
                                        "ybA_ft": [ae[a][r]["y_b"] for r in RATIOS]} for a in ae_values}
    res["ae_sensitivity_max_change_ft"] = max(
        abs(ae[a][r][lbl] - base[r][lbl]) for a in ae_values for r in RATIOS for lbl in ("x_b", "y_b"))
    print(f"AE 5-1000 lb: largest amplitude change {res['ae_sensitivity_max_change_ft']:.2e} ft")

    # drag coefficients
    variants = [("sphere_cd", 0.4), ("sphere_cd", 0.7), ("cable_cd", 1.2), ("cable_cd", 1.8)]
    if args.quick:
        variants = [("sphere_cd", 0.7), ("cable_cd", 1.8)]
    drag = [{"sphere_cd": SPHERE_CD, "cable_cd": CABLE_CD,
             "xbA_ft": res["xbA_ft"], "ybA_ft": res["ybA_ft"]}]
    for name, value in variants:
        kw = {name: value}
        a = {r: runner.amplitudes(r, **kw) for r in RATIOS}
        drag.append({"sphere_cd": kw.get("sphere_cd", SPHERE_CD), "cable_cd": kw.get("cable_cd", CABLE_CD),
                     "xbA_ft": [a[r]["x_b"] for r in RATIOS], "ybA_ft": [a[r]["y_b"] for r in RATIOS]})
    res["drag_sensitivity"] = drag
    for row in drag:
        print(f"  sphere C_D {row['sphere_cd']:.1f}, cable C_D {row['cable_cd']:.1f}: x_bA = "
              + ", ".join(f"{v:.4f}" for v in row["xbA_ft"]) + " ft")

    # a frequency-response curve for the plot (full mode only)
    if not args.quick:
        curve = np.round(np.arange(0.3, 2.51, 0.1), 2)
        res["response_curve"] = {"omega_over_omega_n": curve.tolist(),
                                 "xbA_ft": [runner.amplitudes(float(r))["x_b"] for r in curve]}
    res["simulation_wall_s"] = runner.wall
    write_json(args.out / "wang_dale_table2.json", res)
    plot(args.out / "wang_dale_table2.png", res, base)
    return 0


def plot(path, res, base):
    plt = setup_matplotlib()
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.2))
    ax = axes[0]
    styles = {(0.5, 1.4): ("k", "-"), (0.4, 1.4): ("tab:blue", "--"), (0.7, 1.4): ("tab:red", "--"),
              (0.5, 1.2): ("tab:green", ":"), (0.5, 1.8): ("tab:purple", ":")}
    if "response_curve" in res:
        rc = res["response_curve"]
        ax.plot(rc["omega_over_omega_n"], rc["xbA_ft"], color="0.6", lw=1, label="x_bA, finer sweep (nominal)")
    for row in res["drag_sensitivity"]:
        c, ls = styles.get((row["sphere_cd"], row["cable_cd"]), ("0.5", "-"))
        nominal = (row["sphere_cd"], row["cable_cd"]) == (0.5, 1.4)
        ax.plot(RATIOS, row["xbA_ft"], color=c, ls=ls, marker="o", lw=2 if nominal else 1.2,
                label=f"x_bA: sphere C_D {row['sphere_cd']:.1f}, cable C_D {row['cable_cd']:.1f}"
                      + (" (nominal)" if nominal else ""))
    ax.plot(RATIOS, res["ybA_ft"], color="k", marker="s", ls="-.", label="y_bA (nominal)")
    ax.axhline(res["top_amplitude_ft"], color="0.3", lw=0.8, ls="--", label="top amplitude 2.5 in")
    ax.set_xlabel("omega / omega_n  (omega_n = 1.14 rad/s)")
    ax.set_ylabel("lower-body amplitude (ft, half peak-to-peak)")
    ax.set_title("Dale et al. model: steady-state amplitudes of the sphere")
    ax.set_ylim(0, None)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="lower left")
    ax = axes[1]
    for r, c in zip(RATIOS, ("tab:blue", "tab:orange", "tab:green", "tab:red")):
        t, xb, yb, xs, ys = base[r]["series"]
        n = K_PERIODS * SAMPLES_PER_PERIOD + 1
        ax.plot(xb[-n:] / U.FT, (yb[-n:] - yb[-n:].mean()) / U.FT, color=c, label=f"body, omega/omega_n = {r:g}")
    ax.plot(xs[-n:] / U.FT, ys[-n:] / U.FT, color="k", ls="--", lw=1, label="top (5 in circle)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.invert_yaxis()
    ax.set_xlabel("x (ft)")
    ax.set_ylabel("y (ft, positive down; body: from its mean depth)")
    ax.set_title(f"body paths over the last {K_PERIODS} periods")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    save_figure(fig, path, dpi=110)


if __name__ == "__main__":
    raise SystemExit(main())
