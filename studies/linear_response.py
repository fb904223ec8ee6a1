"""Linear response of the Dale et al. model and its full-scale counterpart (Wang 1971, Table 1).

Natural frequencies and modes, exact and describing-function RAOs, the nonlinear RAO from the
periodic solve, a JONSWAP sea by stochastic linearization, and the verification figures
against the nonlinear time domain. Usage: python studies/linear_response.py --out DIR [--quick]
"""

from __future__ import annotations

import argparse
import json
import math
import os
from pathlib import Path

import numpy as np

from cablesys import units as U
from cablesys.linear import modes as modes_of
from cablesys.linear import rao
from cablesys.linear.equivalent import harmonic_response
from cablesys.linear.linearization import linearize
from cablesys.linear.periodic import periodic_steady_state, scene_input_amplitude
from cablesys.linear.plots import (
    plot_modes,
    plot_nonlinear_rao,
    plot_rao_bode,
    plot_response_spectrum,
)
from cablesys.linear.spectra import jonswap
from cablesys.linear.stochastic import stochastic_response
from cablesys.model import build_model
from cablesys.scene import (
    Body,
    Cable,
    Environment,
    Numerics,
    Sinusoid,
    TopMotion,
    dale_scene,
)
from cablesys.scene.dale import OMEGA_N_MEASURED
from cablesys.scene.scene import single_section_scene
from cablesys.time_domain import simulate

FULL_SCALE_OMEGA_N_MEASURED = 0.49     # rad/s, Wang (1971) Table 1, full-scale column


def full_scale_scene(omega: float = FULL_SCALE_OMEGA_N_MEASURED):
    """Table 1 full scale: 50 ft cable of 0.14 in, 5.5 in sphere weighing 4.18 lb in water, 2.3 ft p-p.

    Cable weight, mass and AE are the model's scaled by the diameter ratio squared (same
    construction); sea water; sphere C_D = 0.5 and virtual mass with the sphere's added mass.
    """
    rho, g = U.RHO_SEA, U.G_STANDARD
    ratio2 = (0.14 / 0.025) ** 2
    length = 50.0 * U.FT
    w_c = 0.0036 / 9.0 * ratio2 * U.LBF / U.FT * length
    m_c = 0.000171 / 9.0 * ratio2 * U.SLUG / U.FT * length
    d_b, w_b = 5.5 * U.INCH, 4.18 * U.LBF
    vol = math.pi / 6 * d_b**3
    m_v = w_b / g + 1.5 * rho * vol
    area = math.pi / 4 * d_b**2
    cable = Cable(length=length, tension_ref=w_b + 0.5 * w_c, ae=1000.0 * ratio2 * U.LBF, diameter=0.14 * U.INCH,
                  mass_per_length=m_c / length, weight_per_length=w_c / length, cd_normal=1.4, ct_tangential=0.01)
    body = Body(weight=w_b, mass_x=m_v, mass_y=m_v, drag_area_normal=0.5 * area, drag_area_tangential=0.5 * area)
    a = 0.5 * 2.3 * U.FT
    top = TopMotion(x=(Sinusoid(amplitude=a, frequency=omega, phase=math.pi / 2),),
                    y=(Sinusoid(amplitude=a, frequency=omega, phase=0.0),))
    return single_section_scene(cable=cable, body=body, name="Table 1 full scale (50 ft, 5.5 in sphere)",
                                environment=Environment(density=rho, gravity=g), top_motion=top,
                                numerics=Numerics(duration=300.0, output_step=0.05))


def with_frequency(scene, omega: float, amplitude_x: float | None = None, amplitude_y: float | None = None):
    """The scene's circular top motion at another frequency (and optionally other amplitudes)."""
    tx, ty = scene.top_motion.x[0], scene.top_motion.y[0]
    ax = tx.amplitude if amplitude_x is None else amplitude_x
    ay = ty.amplitude if amplitude_y is None else amplitude_y
    top = TopMotion(x=(Sinusoid(amplitude=ax, frequency=omega, phase=tx.phase),),
                    y=(Sinusoid(amplitude=ay, frequency=omega, phase=ty.phase),))
    return scene.replace(top_motion=top)


def time_domain_amplitudes(scene, omega, n_periods, labels=("x_b", "y_b")):
    T = 2 * np.pi / omega
    times = np.arange(0.0, n_periods * T + 1e-9, T / 200.0)
    res = simulate(scene, times=times)
    return {k: res.steady_amplitude(k, T, 2) for k in labels}, res


def analyse(scene, omega_meas, tag, out: Path, quick: bool) -> dict:
    model = build_model(scene)
    p = model.parameters(scene)
    lin = linearize(model, p)
    md = modes_of(lin)
    w_n = md.frequency_of("phi")
    natural = {"omega_phi (model)": w_n, "omega_n measured": omega_meas}
    w_s, Z = scene_input_amplitude(scene)
    a = abs(Z[0])
    omega = np.linspace(0.25 * w_n, 2.5 * w_n, 40 if quick else 160)
    r_exact = rao(lin, omega)
    h_circ = harmonic_response(model, p, omega, Z, n_theta=32 if quick else 64)
    Zx = np.array([a, 0.0], complex)
    h_x = harmonic_response(model, p, omega, Zx, n_theta=32 if quick else 64)
    raos = {"exact linearization": r_exact, f"describing function, x only, a = {a:.3g} m": h_x.rao(label="x_s"),
            f"describing function, circular, a = {a:.3g} m": h_circ.rao(label="x_s")}
    plot_rao_bode(raos, "x_b", "x_s", natural, out / f"{tag}_rao_x_b.png", title=f"{scene.name}: x_b RAO")
    plot_rao_bode(raos, "tension_mid", "x_s", natural, out / f"{tag}_rao_tension.png",
                  title=f"{scene.name}: mid-length tension RAO")
    plot_modes(md, lin, out / f"{tag}_modes.png", title=f"{scene.name}: modes")     # about the real rest shape

    # nonlinear RAO: periodic solve along frequency (continuation) vs describing function
    w_nl = np.linspace(omega[0], omega[-1], 6 if quick else 24)
    amp_nl = []
    guess = None
    for w in w_nl:
        sc = with_frequency(scene, w)
        sol = periodic_steady_state(model, model.parameters(sc), w, input_amplitude=Z if guess is None else None,
                                    guess=guess, n_harmonics=20)
        guess = sol.q if sol.success else None
        amp_nl.append(sol.amplitude("x_b") / a if sol.success else np.nan)
    plot_nonlinear_rao(omega, {"describing function (circular top motion)": h_circ.amplitude("x_b") / a,
                               "exact linearization (x only; undamped)": np.minimum(r_exact.amplitude("x_b", "x_s"), 10)},
                       natural, "x_b amplitude / top amplitude [-]", out / f"{tag}_nonlinear_rao.png",
                       title=f"{scene.name}: nonlinear vs linear RAO",
                       points={"periodic solve (nonlinear, half peak-to-peak)": (w_nl, np.array(amp_nl))})

    # irregular sea (JONSWAP) through the buoy top, stochastic linearization
    w_sea = np.linspace(0.1 * w_n, 5 * w_n, 150 if quick else 400)
    S = jonswap(w_sea, hs=4 * a / 2, tp=2 * np.pi / w_n)
    st = stochastic_response(model, p, w_sea, S, n_log2=8 if quick else 10)
    md_st = modes_of(st.linear)
    plot_response_spectrum(st, "x_b", natural, out / f"{tag}_response_spectrum.png",
                            title=f"{scene.name}: JONSWAP Hs = {2 * a:.3g} m, Tp = {2 * np.pi / w_n:.3g} s")

    # verification 1: small amplitude, x only, off and near resonance
    eps = 0.02 * a
    small = {}
    for ratio in ((0.8,) if quick else (0.5, 0.8, 1.2)):
        w = ratio * w_n
        sc = with_frequency(scene, w, amplitude_x=eps, amplitude_y=0.0)
        td, _ = time_domain_amplitudes(sc, w, 25 if quick else 40)
        hs = harmonic_response(model, p, [w], np.array([eps, 0.0], complex))
        ex = rao(lin, [w]).amplitude("x_b", "x_s")[0] * eps
        small[f"{ratio:g}"] = {"time_domain_m": td["x_b"], "describing_m": float(hs.amplitude("x_b")[0]),
                               "exact_m": float(ex),
                               "rel_err_describing": abs(hs.amplitude("x_b")[0] / td["x_b"] - 1),
                               "rel_err_exact": abs(ex / td["x_b"] - 1)}
    # verification 2: the Dale amplitudes (circular motion at omega / omega_n,measured)
    dale = {}
    for ratio in ((1.0, 2.0) if quick else (0.5, 1.0, 1.5, 2.0)):
        w = ratio * omega_meas
        sc = with_frequency(scene, w)
        td, _ = time_domain_amplitudes(sc, w, 20 if quick else 30)
        hb = harmonic_response(model, model.parameters(sc), [w], Z)
        per = periodic_steady_state(model, model.parameters(sc), w, input_amplitude=Z)
        dale[f"{ratio:g}"] = {"time_domain_x_m": td["x_b"], "time_domain_y_m": td["y_b"],
                              "describing_x_m": float(hb.amplitude("x_b")[0]), "describing_y_m": float(hb.amplitude("y_b")[0]),
                              "periodic_first_harmonic_x_m": abs(per.first_harmonic("x_b")),
                              "rel_err_x": abs(hb.amplitude("x_b")[0] / td["x_b"] - 1),
                              "rel_err_y": abs(hb.amplitude("y_b")[0] / td["y_b"] - 1),
                              "rel_err_x_vs_first_harmonic": abs(hb.amplitude("x_b")[0] / abs(per.first_harmonic("x_b")) - 1)}
    # verification 3: periodic solve vs the time domain, node by node over the last period
    per = periodic_steady_state(model, p, w_s, input_amplitude=Z)
    T = 2 * np.pi / w_s
    k = 15 if quick else 30
    times = np.concatenate([np.arange(0.0, (k - 1) * T, T / 40), (k - 1) * T + per.time])
    res = simulate(scene, times=times)
    nl_err = float(np.max(np.abs(res["x_b"][-per.time.size:] - per.outputs["x_b"])) / per.amplitude("x_b"))

    pk_w, pk_a = h_circ.rao(label="x_s").peak("x_b", "x_s")
    pk_nl = int(np.nanargmax(amp_nl))
    return {
        "scene": scene.name,
        "steady_state": dict(zip(lin.q_labels, lin.q0.tolist())),
        "natural_frequencies_rad_s": md.omega_undamped.tolist(),
        "mode_dominant": list(md.dominant),
        "omega_n_measured_rad_s": omega_meas,
        "omega_phi_computed_rad_s": w_n,
        "damping_ratios": md_st.damping_ratio.tolist(),
        "damping_ratios_note": "stochastic linearization for the JONSWAP sea below (exact linearization: 0, "
                               "quadratic drag has no slope in still water)",
        "rao_peaks": {"describing_circular_x_b": {"omega_rad_s": pk_w, "amplitude_per_m": pk_a},
                      "nonlinear_periodic_x_b": {"omega_rad_s": float(w_nl[pk_nl]), "amplitude_per_m": float(amp_nl[pk_nl])},
                      "exact_x_b_per_x_s": {"omega_rad_s": r_exact.peak("x_b", "x_s")[0], "note": "undamped: unbounded"}},
        "sea_state": {"hs_m": 2 * a, "tp_s": 2 * np.pi / w_n, "gamma": 3.3,
                      "significant_amplitude_x_b_m": st.significant_amplitude("x_b"),
                      "significant_amplitude_tension_mid_N": st.significant_amplitude("tension_mid"),
                      "mean_tension_mid_N": float(st.output_mean[model.output_labels.index("tension_mid")]),
                      "slack_probability": st.slack_probability(), "iterations": st.iterations,
                      "converged": st.converged},
        "small_amplitude": small,
        "small_amplitude_rel_err": max(v["rel_err_describing"] for v in small.values()),
        "dale_amplitudes": dale,
        "dale_equivalent_linearization_rel_err": max(max(v["rel_err_x"], v["rel_err_y"]) for v in dale.values()),
        "nonlinear_rao_rel_err": nl_err,
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", required=True, type=Path)
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args(argv)
    os.environ.setdefault("MPLBACKEND", "Agg")
    args.out.mkdir(parents=True, exist_ok=True)
    doc = {"dale": analyse(dale_scene(), OMEGA_N_MEASURED, "dale", args.out, args.quick)}
    if not args.quick:
        doc["full_scale"] = analyse(full_scale_scene(), FULL_SCALE_OMEGA_N_MEASURED, "full_scale", args.out, False)
    else:
        doc["full_scale"] = analyse(full_scale_scene(), FULL_SCALE_OMEGA_N_MEASURED, "full_scale", args.out, True)
    (args.out / "linear_response.json").write_text(json.dumps(doc, indent=1, default=float))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
