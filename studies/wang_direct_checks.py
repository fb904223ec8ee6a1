"""Wang (1971), "Direct checks for simple cases" (report p. 28), as numbers.

Writes ``DIR/wang_direct_checks.json`` with the relative errors against closed forms:
- resonance_rel_err: massless vertical spring driven at its natural frequency, no damping;
  1 ft of top heave grows to 50 pi ft after 50 cycles (the report's "150 feet");
- spring_mass_rel_err: free vibration period of a spring with mass, 2 pi sqrt((M + M_c/3)/k)
  (Timoshenko & Young's first approximation, which Wang's uniform-stretch energy reproduces);
- pendulum_small_rel_err: simple and compound pendulum periods at small angle (Tong);
- pendulum_large_rel_err: simple pendulum at 60 degrees against 4 sqrt(l M / W) K(sin^2(phi_0/2));
- energy_drift: drag and damping off, max |E - E_0| over 100 periods relative to the
  energy of the oscillation.
Plus a figure of the resonance growth and the energy history.

Usage: python studies/wang_direct_checks.py --out DIR [--quick]
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

import numpy as np
from scipy.interpolate import CubicHermiteSpline
from scipy.special import ellipk

from cablesys import units as U
from cablesys.model import build_model
from cablesys.plots import save_figure  # noqa: E402
from cablesys.scene import (
    Body,
    Cable,
    Environment,
    Initial,
    Numerics,
    Sinusoid,
    TopMotion,
    single_section_scene,
)
from cablesys.time_domain import simulate


def spring_scene(*, k_lb_ft=2.0, length_ft=10.0, body_slug=1.0, weight_lb=32.2, cable_slug=0.0,
                 cable_weight_lb=0.0, heave_ft=0.0, omega=1.0, duration=10.0, dt=0.01, ae=None,
                 phi0=None, u0=None, rtol=1e-11, same_mass=True, gamma=0.0):
    """A vertical spring/pendulum in the report's units, drag and damping off."""
    length = length_ft * U.FT
    cable = Cable(length=length, tension_ref=0.0, ae=ae if ae else k_lb_ft * U.LBF / U.FT * length,
                  diameter=0.01 * U.FT, mass_per_length=cable_slug * U.SLUG / length,
                  weight_per_length=cable_weight_lb * U.LBF / length, added_mass_factor=gamma,
                  cd_normal=0.0, ct_tangential=0.0, internal_damping=0.0, tension_floor=-math.inf,
                  cable_mass_switch=1.0 if cable_slug > 0 else -1.0)
    m = body_slug * U.SLUG
    body = Body(weight=weight_lb * U.LBF, mass_x=m, mass_y=m if same_mass else 1.3 * m)
    top = TopMotion(y=(Sinusoid(amplitude=heave_ft * U.FT, frequency=omega),) if heave_ft else (),
                    ramp_s=0.0)    # the closed forms below start abruptly from rest
    return single_section_scene(
        cable=cable, body=body, environment=Environment(density=U.RHO_FRESH), top_motion=top,
        initial=Initial(phi=phi0, u=u0), name="direct check",
        numerics=Numerics(duration=duration, output_step=dt, rtol=rtol, atol=1e-13, drag_segments=1))


def _ok(result):
    """A check computed on a failed run means nothing: stop with the integrator's message."""
    if not result.success:
        raise RuntimeError(result.message)
    return result


def period_from_crossings(t, y, ydot) -> float:
    """Mean period between upward zero crossings of a cubic Hermite fit through (y, y')."""
    roots = CubicHermiteSpline(t, y, ydot).roots(extrapolate=False)
    up = [r for r in roots if np.interp(r, t, ydot) > 0]
    return (up[-1] - up[0]) / (len(up) - 1)


def resonance(cycles: int) -> dict:
    # weight 400 lb on k = 2 lb/ft: 200 ft of static stretch keeps the spring longer than the
    # 50 pi ft excursion (a spring that passes through zero length has no angle)
    k, m, a = 2.0, 1.0, 1.0                     # lb/ft, slug, ft
    omega = math.sqrt(k / m)
    T = 2 * math.pi / omega
    s = spring_scene(k_lb_ft=k, body_slug=m, weight_lb=400.0, heave_ft=a, omega=omega, duration=cycles * T, dt=T / 64)
    r = _ok(simulate(s))
    t = r.time
    dev = (r["y_b"] - r["y_b"][0]) / U.FT
    exact = a * np.sin(omega * t) + 0.5 * a * (np.sin(omega * t) - omega * t * np.cos(omega * t))
    return {"resonance_rel_err": float(np.max(np.abs(dev - exact)) / np.max(np.abs(exact))),
            "resonance_final_amplitude_ft": float(np.max(np.abs(dev[t > t[-1] - T]))),
            "resonance_exact_amplitude_ft": float(np.max(np.abs(exact[t > t[-1] - T]))), "_series": (t, dev, exact)}


def spring_mass(cycles: int) -> dict:
    k, m, mc = 2.0, 1.0, 0.6
    s = spring_scene(k_lb_ft=k, body_slug=m, cable_slug=mc, weight_lb=20.0)
    model = build_model(s)
    from cablesys.linear import steady_state
    u_s = steady_state(model, model.parameters(s)).q[1]
    T_exact = 2 * math.pi * math.sqrt((m + mc / 3) * U.SLUG / (k * U.LBF / U.FT))
    s = s.replace(initial=Initial(phi=0.0, u=u_s + 0.1 * U.FT),
                  numerics=Numerics(duration=cycles * T_exact, output_step=T_exact / 100, rtol=1e-11, atol=1e-13, drag_segments=1))
    r = _ok(simulate(s, model=model))
    T = period_from_crossings(r.time, r["u"] - u_s, r["u_rate"])
    return {"spring_mass_rel_err": abs(T - T_exact) / T_exact, "spring_mass_period_s": T, "spring_mass_exact_s": T_exact}


def pendulum(phi0: float, cycles: int, *, cable_slug=0.0, cable_weight_lb=0.0) -> tuple[float, float]:
    """(period from the model, closed form) for a nearly inextensible pendulum."""
    m, w, L = 1.0, 32.2, 10.0
    # AE = 1e8 N: the dynamic stretch is ~1e-6 of the length, below the tolerances checked
    s = spring_scene(body_slug=m, weight_lb=w, length_ft=L, ae=1e8, cable_slug=cable_slug,
                     cable_weight_lb=cable_weight_lb, gamma=0.0)
    model = build_model(s)
    from cablesys.linear import steady_state
    u_s = steady_state(model, model.parameters(s)).q[1]
    l = s.cable.length_zero + u_s
    W = s.body.weight + 0.5 * s.cable.total_weight
    M = s.body.mass_x * l**2 + s.cable.total_mass * l**2 / 3                 # A1 at phi = 0 (eq. 47)
    T_small = 2 * math.pi * math.sqrt(M / (l * W))                           # compound pendulum (Tong)
    T_exact = T_small * 2 / math.pi * ellipk(math.sin(phi0 / 2) ** 2)        # exact for the simple pendulum
    # start at rest with the stretch in static balance at phi_0 (k u = W cos phi_0, eq. 49b), so that
    # the stiff stretch mode is not set ringing
    s = s.replace(initial=Initial(phi=phi0, u=u_s * math.cos(phi0)),
                  numerics=Numerics(duration=cycles * T_exact, output_step=T_exact / 128, rtol=1e-11, atol=1e-14, drag_segments=1))
    r = _ok(simulate(s, model=model))
    return period_from_crossings(r.time, r["phi"], r["phi_rate"]), T_exact


def energy_drift(periods: int) -> dict:
    s = spring_scene(k_lb_ft=400.0, body_slug=1.0, weight_lb=32.2, cable_slug=0.3, cable_weight_lb=2.0, gamma=1.0)
    model = build_model(s)
    from cablesys.linear import steady_state
    p = model.parameters(s)
    q_s = steady_state(model, p).q
    T = 2 * math.pi * math.sqrt(s.cable.length / U.G_STANDARD)
    s = s.replace(initial=Initial(phi=0.6, u=q_s[1] + 0.02),
                  numerics=Numerics(duration=periods * T, output_step=T / 20, rtol=1e-11, atol=1e-14, drag_segments=1))
    r = _ok(simulate(s, model=model))
    X = np.vstack([r["phi"], r["u"], r["phi_rate"], r["u_rate"]])
    K, V = (np.array(v).ravel() for v in model.energy.map(X.shape[1])(X, np.zeros((7, X.shape[1])), np.tile(p[:, None], (1, X.shape[1]))))
    E = K + V
    V_eq = float(model.energy(np.concatenate([q_s, [0, 0]]), np.zeros(7), p)[1])
    drift = float(np.max(np.abs(E - E[0])) / (E[0] - V_eq))
    return {"energy_drift": drift, "_energy": (r.time, (E - E[0]) / (E[0] - V_eq))}


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True, type=Path)
    ap.add_argument("--quick", action="store_true", help="fewer cycles (CI)")
    a = ap.parse_args(argv)
    a.out.mkdir(parents=True, exist_ok=True)
    res = resonance(50)                                   # the report's 50 cycles, also in quick mode
    res.update(spring_mass(5 if a.quick else 20))
    T_simple, T_simple_x = pendulum(1e-3, 3 if a.quick else 10)
    T_comp, T_comp_x = pendulum(1e-3, 3 if a.quick else 10, cable_slug=0.4, cable_weight_lb=5.0)
    T_large, T_large_x = pendulum(math.pi / 3, 3 if a.quick else 10)
    res["pendulum_small_rel_err"] = max(abs(T_simple - T_simple_x) / T_simple_x, abs(T_comp - T_comp_x) / T_comp_x)
    res["pendulum_simple_period_s"], res["pendulum_compound_period_s"] = T_simple, T_comp
    res["pendulum_large_rel_err"] = abs(T_large - T_large_x) / T_large_x
    res["pendulum_large_period_s"], res["pendulum_large_exact_s"] = T_large, T_large_x
    res.update(energy_drift(30 if a.quick else 100))
    _plot(res, a.out)
    out = {k: v for k, v in res.items() if not k.startswith("_")}
    (a.out / "wang_direct_checks.json").write_text(json.dumps(out, indent=2))
    return out


def _plot(res: dict, out: Path) -> None:
    import matplotlib.pyplot as plt
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 7))
    t, dev, exact = res["_series"]
    ax1.plot(t, dev, lw=0.8, label="cablesys (CVODES)")
    ax1.plot(t, 0.5 * (t * math.sqrt(2.0)) + 1, "k--", lw=0.8, label=r"envelope $a(1 + \omega t/2)$")
    ax1.plot(t, -(0.5 * (t * math.sqrt(2.0)) + 1), "k--", lw=0.8)
    ax1.set(xlabel="time (s)", ylabel="lower-body heave (ft)",
            title=f"Massless spring driven at resonance, 1 ft top heave: rel. error {res['resonance_rel_err']:.1e}")
    ax1.legend(loc="upper left")
    te, de = res["_energy"]
    ax2.plot(te, de, lw=0.8)
    ax2.set(xlabel="time (s)", ylabel=r"$(E - E_0)/(E_0 - V_{eq})$",
            title="Energy with drag and damping off (rtol 1e-11)")
    save_figure(fig, out / "wang_direct_checks.png", dpi=120)


if __name__ == "__main__":
    for k, v in main().items():
        print(f"{k:32s} {v:.6g}" if isinstance(v, float) else f"{k:32s} {v}")
