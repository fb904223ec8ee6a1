"""A span between two supports in the time domain (the segmented node model, top at rest, lower support
an ``[anchor]``): free decay against the linear modes and Irvine's closed form, and forced motion of
a support against the linear and periodic frequency responses.

The span is the slack scene's translation to the node model (:func:`cablesys.slack.shared.to_scene`:
support A the prescribed top, support B the anchor), in three dimensions; its equilibrium and linear
modes are :func:`cablesys.slack.shared.equilibrium` / :func:`~cablesys.slack.shared.modes` (M and K
of the same model, Griffin & Rosenthal 1985 eq. 25). The span: a level wire of 22.9 m
(m = 1.14 kg/m, EA = 8.9e5 N) a little longer than its chord.

Writes ``span_dynamics.json`` and ``span_dynamics.png`` into ``--out``:

- ``decay``: per Irvine parameter lambda^2 (about 35 and 81, either side of the crossover 4 pi^2,
  Irvine & Caughey 1974; Griffin & Rosenthal eq. 4, 6) and per N (10, 20, 40; quick 10, 20), the first
  symmetric (S) and antisymmetric (A) in-plane mode started from q* + a phi (a = ``DECAY_AMPLITUDE``
  x sag, at rest, no drag, no damping, in air): the frequency fitted to the series
  (:func:`fit_frequency`), the node model's linear frequency, Irvine's closed form (eq. 6, 7), and
  the energy drift; ``decay_vs_modes_max_rel_err`` the largest |omega_td / omega_linear - 1|
  over them, ``decay_vs_irvine_rel_err`` each at the finest N,
  ``decay_convergence`` the observed order in N and the Richardson value against Irvine (full run);
- ``energy_drift_rel_max``: max |E(t) - E(0)| / (E(0) - E*) over the decays (E* the energy at rest);
- ``water_decay``: S and A in water with the node model's drag (a = ``WATER_AMPLITUDE`` x sag) and
  ``span_decay_vs_modes_max_rel_err`` the largest error against the linear modes (added mass
  included); the energy column is the loss to drag, ``damping_ratio_mean`` the damping ratio of a
  linear damper that takes as much energy out over the run (the drag's mean at this amplitude);
- ``amplitude``: the shift omega(a) / omega_linear - 1 of S1 (lambda^2 = 81) against the amplitude and
  ``amplitude_shift_order`` the slope of log |shift| against log a (2: the shift of a quadratic and
  cubic restoring force is second order in the amplitude, Nayfeh & Mook 1979 ch. 4, Lindstedt-Poincare; for cables
  Rega, Appl. Mech. Rev. 57, 2004);
- ``forced``: the top support moved vertically, a sin(omega t) (a = ``FORCE_AMPLITUDE``), the span
  (lambda^2 = 89 in water) with the node model's drag (Wang 1971 eq. 42-44), at omega =
  ``FORCE_FRACTIONS`` x the first in-plane mode: the complex amplitude at omega of the quarter-span
  node's vertical motion over the run's last ``WINDOW_PERIODS`` periods (``settled_rel`` against
  the ten before), against the exact periodic orbit (:func:`cablesys.linear.periodic_steady_state`,
  Fourier collocation), the describing function (:func:`cablesys.linear.harmonic_response`, one
  harmonic) and the exact linearization (:meth:`LinearModel.transfer`, undamped in still water:
  unbounded at resonance).

Run: ``python studies/span_dynamics.py --out DIR [--quick]``.
"""

from __future__ import annotations

import dataclasses
import math
import sys
from pathlib import Path

import numpy as np
from scipy.optimize import minimize_scalar

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import parse_args, setup_matplotlib, write_json  # noqa: E402

from cablesys import linear  # noqa: E402
from cablesys.model import build_model  # noqa: E402
from cablesys.scene import Sinusoid, TopMotion  # noqa: E402
from cablesys.slack import irvine, shared  # noqa: E402
from cablesys.slack.scene import SlackCable, SlackScene  # noqa: E402
from cablesys.time_domain.run import simulate  # noqa: E402

SPAN, MASS, EA = 22.9, 1.14, 8.9e5          # m, kg/m, N: the level wire
SLACKS = (0.0006, 0.0024)                   # 1 - l / L: lambda^2 about 35 and 81 in air, either side of 4 pi^2
DECAY_AMPLITUDE = 0.001                     # largest initial node displacement / sag
DECAY_PERIODS = 8
QUICK_PERIODS = 5                           # --quick: fewer periods per decay
WATER_AMPLITUDE = 0.01                      # / sag, the decays in water (drag on)
AMPLITUDES = (0.0025, 0.005, 0.01, 0.02)    # / sag, the amplitude sweep
FORCE_AMPLITUDE = 0.01                      # m, vertical motion of the top support
FORCE_FRACTIONS = (0.5, 1.0)                # forcing frequency / first in-plane mode
FORCE_PERIODS, WINDOW_PERIODS = 60, 10
RTOL = 1e-10                                # CVODES tolerances of the small decays
QUICK_RTOL = 1e-9                           # ... in --quick
SWEEP_RTOL = 1e-8                           # ... of the amplitude sweep (its frequency error ~5e-7, the least shift 1e-5)
                                            # and of the decays in water
PERIODIC_HARMONICS = 8


def span_scene(slack: float, n: int, medium: str = "air") -> SlackScene:
    """The level span with L = l / (1 - ``slack``), in ``n`` elements."""
    cable = SlackCable(length=SPAN / (1.0 - slack), mass_per_length=MASS, ae=EA,
                       specific_gravity=7.8 if medium == "water" else None)
    return SlackScene(cable=cable, span=SPAN, n_elements=n, medium=medium)


def with_run(main, *, duration: float, output_step: float, drag: bool, rtol: float = RTOL, top_motion=None):
    """The node scene set up for a run: duration, output step, tolerances, the scene's own model
    (no ladder), the cable drag kept or removed (C_D = C_t = 0), an optional top motion."""
    secs = main.sections if drag else tuple(
        dataclasses.replace(s, cable=dataclasses.replace(s.cable, cd_normal=0.0, ct_tangential=0.0)) for s in main.sections)
    num = dataclasses.replace(main.numerics, duration=duration, output_step=output_step, model="as-built",
                              rtol=rtol, atol=rtol)
    return dataclasses.replace(main, sections=secs, numerics=num,
                               **({} if top_motion is None else {"top_motion": top_motion}))


def node_shape(shape: np.ndarray) -> np.ndarray:
    """A mode shape of :func:`shared.modes` ((x, y out of plane, z up) per node, supports included) as
    a displacement of the node model's free coordinates (x, y down, z out of plane), max |.| = 1."""
    dq = np.column_stack([shape[1:-1, 0], -shape[1:-1, 2], shape[1:-1, 1]]).ravel()
    return dq / np.abs(dq).max()


def fit_frequency(t, y, omega0: float, rel: float = 0.02) -> float:
    """Angular frequency (rad/s) of the sinusoid that fits ``y(t)`` best in least squares, with a mean
    and a second harmonic (the quadratic nonlinearity's): y ~ c0 + sum_{k=1,2} a_k cos k w t + b_k sin k w t,
    the linear coefficients eliminated (variable projection), w searched within ``rel`` of ``omega0``."""
    t, y = np.asarray(t, float), np.asarray(y, float)

    def residual(w):
        A = np.column_stack([np.ones_like(t), np.cos(w * t), np.sin(w * t), np.cos(2 * w * t), np.sin(2 * w * t)])
        coef, *_ = np.linalg.lstsq(A, y, rcond=None)
        return float(np.sum((A @ coef - y) ** 2))

    grid = omega0 * np.linspace(1 - rel, 1 + rel, 81)
    k = int(np.argmin([residual(w) for w in grid]))
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
    w = float(minimize_scalar(residual, bounds=(lo, hi), method="bounded").x)
    # the bounded search stops at ~1.5e-8 relative (its sqrt(eps) tolerance); the residual is quadratic about
    # its minimum, so the vertex of the parabola through w and w +- h takes it to rounding
    h = 1e-5 * w
    r_m, r_0, r_p = residual(w - h), residual(w), residual(w + h)
    curv = r_p - 2 * r_0 + r_m
    return w - h * (r_p - r_m) / (2 * curv) if curv > 0 else w


def energy_series(model, X, t, p) -> np.ndarray:
    """Total energy (kinetic + potential, J; :meth:`model.energy`) of each stored state."""
    return np.array([sum(float(v) for v in model.energy(X[:, i], model.top(t[i], p), p)) for i in range(len(t))])


def free_decay(slack: float, n: int, mode_type: str, amplitude: float, periods: int = DECAY_PERIODS,
               rtol: float = RTOL, medium: str = "air") -> dict:
    """The first in-plane mode of type ``mode_type`` ('S' or 'A') of the span started at q* + a sag phi,
    at rest: fitted frequency, linear frequency, Irvine's, energy drift, the modal time series. In air
    without drag; in water with the node model's drag (the energy then falls: ``energy_drift_rel`` is
    the loss)."""
    sc = span_scene(slack, n, medium)
    eq = shared.equilibrium(sc)
    ms = shared.modes(eq, 8)
    j = list(ms.mode_type).index(mode_type)
    _, q, p = eq.node_state                     # the equilibrium and modes ran on the model's element-kernel form
    model = shared.span_model(shared.to_scene(sc))
    dq = node_shape(ms.shapes[j])
    w_lin = float(ms.omega[j])
    T = 2 * math.pi / w_lin
    scene = with_run(shared.to_scene(sc), duration=periods * T, output_step=T / 40, drag=medium == "water",
                     rtol=rtol)
    a = amplitude * eq.sag
    rec = simulate(scene, model=model, x0=np.concatenate([q + a * dq, np.zeros_like(q)]))
    X, t = np.asarray(rec.states), np.asarray(rec.time)
    eta = dq @ (X[:model.nq] - q[:, None]) / (dq @ dq)            # displacement along the mode (m)
    w_td = fit_frequency(t, eta, w_lin)
    E = energy_series(model, X, t, p)
    E_rest = energy_series(model, np.concatenate([q, 0 * q])[:, None], t[:1], p)[0]
    m_virtual = MASS + (sc.cable.weight_and_added_mass(medium, sc.gravity)[1] if medium == "water" else 0.0)
    ref = irvine.irvine_modes(8, lambda2=eq.lambda2, span=SPAN, H=eq.horizontal_tension, m=m_virtual)
    w_irv = [m.omega for m in ref if m.mode_type == mode_type][0]
    return {"slack": slack, "n": n, "mode": mode_type, "medium": medium, "amplitude_over_sag": amplitude, "sag_m": eq.sag,
            "H_N": eq.horizontal_tension, "mass_per_length_virtual": m_virtual, "periods": periods,
            "lambda2": eq.lambda2, "omega_td": w_td, "omega_linear": w_lin, "omega_irvine": w_irv,
            "td_vs_linear": w_td / w_lin - 1, "td_vs_irvine": w_td / w_irv - 1,
            "energy_drift_rel": float(np.max(np.abs(E - E[0])) / (E[0] - E_rest)), "success": bool(rec.success),
            # the mean damping ratio that takes the oscillation's energy from E(0) to E(end): E ~ e^{-2 zeta omega t}
            # for a linear damper; the drag's is amplitude dependent, so this is the run's average at this amplitude
            "damping_ratio_mean": float(math.log((E[0] - E_rest) / (E[-1] - E_rest)) / (2 * w_td * t[-1])),
            "t": t, "eta": eta}


def decay_table(ns, periods: int = DECAY_PERIODS, rtol: float = RTOL) -> list[dict]:
    """Free decays of S and A at every slack and N (small amplitude)."""
    return [free_decay(s, n, typ, DECAY_AMPLITUDE, periods, rtol) for s in SLACKS for n in ns for typ in "SA"]


def observed_order(rows, ns) -> dict:
    """Per (slack, mode), with three N doubling: the observed order p = log2(|w_1 - w_2| / |w_2 - w_3|) of the
    fitted frequencies and the Richardson value w_3 + (w_3 - w_2) / 3 (order 2) against Irvine's; None
    with fewer than three N."""
    out = {}
    for s in SLACKS:
        for typ in "SA":
            w = [r["omega_td"] for n in ns for r in rows if r["slack"] == s and r["mode"] == typ and r["n"] == n]
            # Irvine's closed form at the finest N's H and lambda^2 (both converge in N too)
            irv = [r["omega_irvine"] for r in rows if r["slack"] == s and r["mode"] == typ and r["n"] == ns[-1]][0]
            key = f"slack={s:g} {typ}"
            if len(w) >= 3:
                order = math.log2(abs(w[-3] - w[-2]) / abs(w[-2] - w[-1]))
                rich = w[-1] + (w[-1] - w[-2]) / 3
                out[key] = {"order": order, "richardson_vs_irvine": rich / irv - 1}
            else:
                out[key] = {"order": None, "richardson_vs_irvine": None}
    return out


def amplitude_sweep(n: int, slack: float = SLACKS[1], amplitudes=AMPLITUDES, periods: int = DECAY_PERIODS) -> dict:
    """Frequency shift of the S mode against its amplitude, and the fitted power of the shift."""
    rows = [free_decay(slack, n, "S", a, periods, rtol=SWEEP_RTOL) for a in amplitudes]
    w0 = rows[0]["omega_linear"]
    shifts = np.array([r["omega_td"] / w0 - 1 for r in rows])
    slope = float(np.polyfit(np.log(amplitudes), np.log(np.abs(shifts)), 1)[0])
    return {"n": n, "slack": slack, "amplitude_over_sag": list(amplitudes), "shift": shifts.tolist(),
            "order": slope, "energy_drift_rel": [r["energy_drift_rel"] for r in rows]}


def quarter_node(model) -> int:
    """Index in q of the vertical coordinate (y) of the node nearest a quarter of the span."""
    return 3 * (model.n_elements // 4 - 1) + 1


def fourier_amplitude(t, y, omega: float) -> complex:
    """Complex amplitude Y of y ~ mean + Re(Y e^{i omega t}) over whole periods of ``t`` (equally spaced)."""
    t, y = np.asarray(t, float), np.asarray(y, float)
    return complex(2.0 * np.mean((y - y.mean()) * np.exp(-1j * omega * t)))


def forced(n: int, fraction: float, amplitude: float = FORCE_AMPLITUDE, periods: int = FORCE_PERIODS) -> dict:
    """The span in water (drag on), its top moved vertically a sin(omega t), omega = ``fraction`` x the
    first in-plane mode: the quarter-span node's vertical amplitude at omega from the run's last
    periods and from the three frequency-domain routes (complex amplitudes: modulus and phase)."""
    sc = span_scene(SLACKS[1], n, medium="water")
    eq = shared.equilibrium(sc)
    ms = shared.modes(eq, 8)
    j = next(k for k, t in enumerate(ms.mode_type) if t != "O")
    w1 = float(ms.omega[j])
    w = fraction * w1
    T = 2 * math.pi / w
    _, q, p = eq.node_state                     # the equilibrium and modes ran on the model's element-kernel form
    model = shared.span_model(shared.to_scene(sc))
    top = TopMotion(y=(Sinusoid(amplitude=amplitude, frequency=w),), ramp_s=3 * T)
    scene = with_run(shared.to_scene(sc), duration=periods * T, output_step=T / 32, drag=True, rtol=1e-8, top_motion=top)
    forced_model = build_model(scene)           # the sinusoid is part of the model's structure
    rec = simulate(scene, model=forced_model, x0=np.concatenate([q, np.zeros_like(q)]))
    X, t = np.asarray(rec.states), np.asarray(rec.time)
    k = quarter_node(model)
    last = t >= t[-1] - WINDOW_PERIODS * T - 1e-9 * T
    prev = (t >= t[-1] - 2 * WINDOW_PERIODS * T - 1e-9 * T) & (t < t[-1] - WINDOW_PERIODS * T - 1e-9 * T)
    Y_td = fourier_amplitude(t[last][:-1], X[k, last][:-1], w)
    Y_prev = fourier_amplitude(t[prev], X[k, prev], w)
    Z = np.array([0.0, -1j * amplitude, 0.0])                 # a sin(wt) = Re(-i a e^{i w t}), inputs (x_s, y_s, z_s)
    per = linear.periodic_steady_state(forced_model, forced_model.parameters(scene), w,
                                       n_harmonics=PERIODIC_HARMONICS, input_amplitude=Z)
    Y_per = fourier_amplitude(per.time, per.q[k], w)
    hb = linear.harmonic_response(model, p, [w], Z)
    Y_hb = complex(hb.q_amplitude[0][k])
    lin = linear.linearize(model, p)
    Y_lin = complex(lin.transfer(np.array([w]))[0][0][k] @ Z)
    rel = lambda Y: abs(Y) / abs(Y_td) - 1
    return {"n": n, "fraction": fraction, "omega": w, "omega_mode": w1, "mode": ms.mode_type[j],
            "input_amplitude_m": amplitude, "amplitude_td_m": abs(Y_td), "amplitude_periodic_m": abs(Y_per),
            "amplitude_describing_m": abs(Y_hb), "amplitude_linear_m": abs(Y_lin),
            "phase_td": float(np.angle(Y_td)), "phase_periodic": float(np.angle(Y_per)),
            "phase_describing": float(np.angle(Y_hb)), "phase_linear": float(np.angle(Y_lin)),
            "periodic_vs_td": rel(Y_per), "describing_vs_td": rel(Y_hb), "linear_vs_td": rel(Y_lin),
            "settled_rel": abs(Y_td - Y_prev) / abs(Y_td), "max_out_of_plane_m": float(np.abs(X[2:model.nq:3]).max()),
            "periodic_success": bool(per.success), "describing_success": bool(hb.success), "success": bool(rec.success),
            "t": t, "y": X[k] - q[k]}


def figure(path: Path, decays, sweep, forcing) -> None:
    """Four panels: free decays along S1 and A1; the decay frequencies against Irvine's lambda^2 with the
    closed-form curves and their crossover; the frequency shift against amplitude; the forced response at
    resonance with the periodic orbit's and the describing function's amplitudes."""
    plt = setup_matplotlib()
    fig, ((a0, a1), (a2, a3)) = plt.subplots(2, 2, figsize=(13, 9.5))
    n_max = max(x["n"] for x in decays if x["medium"] == "air")
    for r, c in zip([d for d in decays if d["n"] == n_max and d["slack"] == SLACKS[1] and d["medium"] == "air"], ("C0", "C1")):
        a0.plot(r["t"], r["eta"] * 1e3, color=c, lw=1,
                label=f"{r['mode']}1: {r['omega_td']:.5f} rad/s fitted, {r['omega_linear']:.5f} linear mode")
    a0.set_xlabel("time (s)")
    a0.set_ylabel("displacement along the mode (mm)")
    a0.set_title(f"free decay in air, no drag: level span {SPAN} m, lambda^2 = {decays[-1]['lambda2']:.0f}, N = {n_max}",
                 fontsize=10)
    lim = 1e3 * max(np.abs(r["eta"]).max() for r in decays)
    a0.set_ylim(-1.2 * lim, 1.7 * lim)
    a0.legend(fontsize=8, loc="upper right")
    a0.grid(alpha=0.3)
    lam = np.linspace(5.0, 120.0, 200)
    s1 = [[m.omega for m in irvine.irvine_modes(4, lambda2=v, span=1.0, H=1.0, m=1.0) if m.mode_type == "S"][0] for v in lam]
    a1.plot(lam, s1, "C0-", lw=1, label="Irvine S1 (eq. 6)")
    a1.axhline(2 * math.pi, color="C1", lw=1, label="Irvine A1 = 2 pi (eq. 7)")
    a1.axvline(irvine.LAMBDA2_CROSSOVER, color="0.5", ls=":", lw=1, label="crossover lambda^2 = 4 pi^2")
    for typ, c in (("S", "C0"), ("A", "C1")):
        for n, mk in zip(sorted({d["n"] for d in decays}), ("x", "+", "o")):
            pts = [d for d in decays if d["mode"] == typ and d["n"] == n and d["medium"] == "air"]
            a1.plot([d["lambda2"] for d in pts],
                    [d["omega_td"] * SPAN / math.sqrt(d["H_N"] / d["mass_per_length_virtual"]) for d in pts], mk, color=c,
                    mfc="none", ms=7, label=f"{typ}1 from the time series, N = {n}")
    a1.set_xlabel("Irvine's lambda^2")
    a1.set_ylabel("omega l / sqrt(H / m)")
    a1.legend(fontsize=7)
    a1.grid(alpha=0.3)
    amp = np.array(sweep["amplitude_over_sag"])
    sh = np.abs(sweep["shift"])
    a2.loglog(amp, sh, "o-", label=f"S1, time domain (slope {sweep['order']:.2f})")
    a2.loglog(amp, sh[-1] * (amp / amp[-1]) ** 2, "k--", lw=0.8, label="slope 2")
    a2.set_xlabel("initial amplitude / sag")
    a2.set_ylabel("|omega(a) / omega_linear - 1|")
    a2.set_title(f"nonlinear frequency shift (softening), N = {sweep['n']}", fontsize=10)
    a2.legend(fontsize=8)
    a2.grid(alpha=0.3, which="both")
    f = max(forcing, key=lambda r: r["fraction"])
    a3.plot(f["t"], f["y"] * 1e3, "C0-", lw=0.7, label=f"time domain: {f['amplitude_td_m'] * 1e3:.3f} mm at omega")
    mean = 1e3 * float(np.mean(f["y"][f["t"] >= f["t"][-1] - WINDOW_PERIODS * 2 * math.pi / f["omega"]]))
    for key, c, lab in (("amplitude_periodic_m", "C2", "periodic orbit"), ("amplitude_describing_m", "C3", "describing function")):
        a3.axhline(mean + f[key] * 1e3, color=c, ls="--", lw=1, label=f"{lab}: {f[key] * 1e3:.3f} mm")
        a3.axhline(mean - f[key] * 1e3, color=c, ls="--", lw=1)
    away = min(forcing, key=lambda r: r["fraction"])
    a3.set_xlabel("time (s)")
    a3.set_ylabel("vertical displacement (mm)")
    a3.set_title(f"quarter-span node, top moved vertically {FORCE_AMPLITUDE * 1e3:g} mm at the first in-plane mode\n"
                 f"({f['omega']:.3f} rad/s, in water with drag, N = {f['n']}; at {away['fraction']:g} x it: "
                 f"{away['amplitude_td_m'] * 1e3:.3f} mm, linear {away['amplitude_linear_m'] * 1e3:.3f} mm)", fontsize=9)
    top = 1e3 * float(np.abs(f["y"]).max())
    a3.set_ylim(-1.2 * top, 1.9 * top)
    a3.legend(fontsize=8, loc="upper right", ncol=1)
    a3.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def strip(row: dict) -> dict:
    return {k: v for k, v in row.items() if k not in ("t", "eta", "y")}


def main(argv=None) -> dict:
    args = parse_args(__doc__.splitlines()[0], argv)
    quick = args.quick
    ns = (10, 20) if quick else (10, 20, 40)
    periods = QUICK_PERIODS if quick else DECAY_PERIODS
    rtol = QUICK_RTOL if quick else RTOL
    decays = decay_table(ns, periods, rtol)
    water = [free_decay(SLACKS[1], 10 if quick else 20, typ, WATER_AMPLITUDE, periods, SWEEP_RTOL, medium="water")
             for typ in "SA"]
    sweep = amplitude_sweep(10 if quick else 20, amplitudes=AMPLITUDES[:3] if quick else AMPLITUDES, periods=periods)
    forcing = [forced(10 if quick else 20, f) for f in FORCE_FRACTIONS]
    finest = [r for r in decays if r["n"] == ns[-1]]
    out = {
        "quick": quick, "N": list(ns), "decay_periods": periods, "decay_rtol": rtol,
        "decay": [strip(r) for r in decays],
        "decay_vs_modes_max_rel_err": max(abs(r["td_vs_linear"]) for r in decays),
        "decay_vs_irvine_rel_err": {f"slack={r['slack']:g} {r['mode']}": r["td_vs_irvine"] for r in finest},
        "decay_convergence": observed_order(decays, ns),
        "lambda2": {f"slack={s:g}": [r["lambda2"] for r in decays if r["slack"] == s][0] for s in SLACKS},
        "energy_drift_rel_max": max(r["energy_drift_rel"] for r in decays),
        "water_decay": [strip(r) for r in water],
        "span_decay_vs_modes_max_rel_err": max(abs(r["td_vs_linear"]) for r in water),
        "amplitude": sweep, "amplitude_shift_order": sweep["order"],
        "forced": [strip(f) for f in forcing],
    }
    figure(args.out / "span_dynamics.png", decays, sweep, forcing)
    write_json(args.out / "span_dynamics.json", out)
    return out


if __name__ == "__main__":
    res = main()
    print({k: v for k, v in res.items() if not isinstance(v, (dict, list))})
