"""The winch checks of ``ends_checks.py``: a package lowered and hauled back in by the ``[winch]`` (node model), its
top tension against the quasi-static closed forms of both directions, the return to the initial state, and the
mass of the cable in the water (see that study's docstring for the keys)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from _common import setup_matplotlib

from cablesys.model import build_model
from cablesys.scene import Body, Cable, Leg, Numerics, Winch, single_section_scene
from cablesys.scene.components import Environment
from cablesys.time_domain.run import simulate

# the lift of the lowering and round-trip checks: a 2 kN package (C_D A = 1 m^2) on 30 mm wire, C_I / AE = 0.05 s
LIFT_L0, LIFT_RHO = 20.0, 1025.0
LIFT_CABLE = dict(length=LIFT_L0, ae=2e7, diameter=0.03, mass_per_length=3.0, weight_per_length=25.0, cd_normal=1.5,
                  ct_tangential=0.3, internal_damping=1e6)
LIFT_BODY = Body(weight=2000.0, mass_x=400.0, mass_y=400.0, drag_area_normal=1.0, drag_area_tangential=1.0)


def lift_scene(winch: Winch, duration: float, n: int = 8, rtol: float = 1e-8, atol: float = 1e-9):
    """The package on its wire in still water, the first section's length driven by ``winch``."""
    return single_section_scene(cable=Cable(**LIFT_CABLE, segments=n), body=LIFT_BODY,
                                environment=Environment(density=LIFT_RHO),
                                numerics=Numerics(duration=duration, output_step=0.25, model="as-built", rtol=rtol,
                                                  atol=atol),
                                winch=winch)


def lift_tension(L, v):
    """Quasi-static top tension (N) of the lift moving at the constant payout speed v (m/s, + lowers): the weight in
    water W_b + w L less, lowering, or plus, hauling in, the drag of the body (C_D A) and of the paid-out cable
    sliding along itself through the water (C_t d per unit length), both opposing the motion:
    W_b + w L - sign(v) 1/2 rho (C_D A + C_t d L) v^2 (Wang 1971 eq. 32 and 44 with the normal velocity zero; no
    inertia at constant speed)."""
    c, b = LIFT_CABLE, LIFT_BODY
    return (b.weight + c["weight_per_length"] * L
            - np.sign(v) * 0.5 * LIFT_RHO * (b.drag_area_normal + c["ct_tangential"] * c["diameter"] * L) * v ** 2)


def lowering(n: int = 8, speed: float = 1.0, ramp: float = 3.0) -> dict:
    """The lowering check (module docstring): relative error of the top tension over the constant-speed part."""
    out = 30.0
    duration = out / speed + ramp
    rec = simulate(lift_scene(Winch(speed=speed, duration=duration, ramp=ramp, max_length=LIFT_L0 + out + 5.0),
                              duration, n))
    t, L, T = np.asarray(rec.time), rec["winch_length"], rec["tension_top"]
    steady = (t > ramp + 1.0) & (t < duration - ramp)
    closed = lift_tension(L, speed)
    return {"max_rel_err": float(np.max(np.abs(T[steady] / closed[steady] - 1))),
            "drag_share": float(np.max(1 - closed[steady] / (LIFT_BODY.weight + LIFT_CABLE["weight_per_length"]
                                                              * L[steady]))),
            "N": n, "speed_m_s": speed, "length_m": [float(L[0]), float(L[-1])]}


def round_trip_winch(speed: float = 1.0, out: float = 30.0, hold: float = 5.0, ramp: float = 3.0) -> Winch:
    """Pay ``out`` m out at ``speed``, hold, haul the same ``out`` m back in: each leg pays out speed x duration
    (scene.ends.legs_profile), so L returns to l_0 exactly."""
    d = out / speed
    return Winch(leg=(Leg(speed=speed, duration=d), Leg(speed=0.0, duration=hold), Leg(speed=-speed, duration=d)),
                 ramp=ramp, max_length=LIFT_L0 + out + 5.0)


def payout_haulin(rtol: float = 1e-8, n: int = 8, settle: float = 1.0, series: bool = False) -> dict:
    """Lower the package 30 m at 1 m/s, hold 5 s, haul it back in at 1 m/s (:func:`round_trip_winch`), then rest
    ``settle`` s. The rest state at l_0 is unique, so the final state must be the initial one (the static
    equilibrium): returns the largest node-position (m) and node-velocity (m/s) difference and the top tension's
    relative difference, ``settle`` s after the stop and at the stop itself (there the elements still lag their
    static stretch by the Voigt damping's strain rate, a physical difference, first order in w, that decays with
    the axial mode's damping, ~25 /s: below 1e-15 m after 1 s, so that what is left then is the integrator's);
    and the top tension over the constant-speed parts of both directions against :func:`lift_tension`.
    ``series``: also the run's (t, L, T_top) and the closed form."""
    winch = round_trip_winch()
    rec = simulate(lift_scene(winch, winch.end + settle, n, rtol=rtol, atol=rtol / 10))
    X, t, T, L = np.asarray(rec.states), np.asarray(rec.time), rec["tension_top"], rec["winch_length"]
    nq = X.shape[0] // 2
    (v0, d0), (_, dh), (v2, _) = winch.legs
    tau2 = winch.start + d0 + dh                              # the haul-in leg starts
    down = (t > winch.start + winch.ramp + 1.0) & (t < winch.start + d0)
    up = (t > tau2 + winch.ramp + 1.0) & (t < winch.end - winch.ramp)
    stop = int(np.argmin(np.abs(t - winch.end)))
    out = {"rtol": rtol, "N": n, "success": bool(rec.success), "settle_s": settle,
           "return_max_abs_m": float(np.max(np.abs(X[:nq, -1] - X[:nq, 0]))),
           "return_velocity_max_abs_m_s": float(np.max(np.abs(X[nq:, -1] - X[nq:, 0]))),
           "return_tension_rel": float(abs(T[-1] / T[0] - 1)),
           "at_stop_max_abs_m": float(np.max(np.abs(X[:nq, stop] - X[:nq, 0]))),
           "length_m": [float(L[0]), float(L.max()), float(L[-1])],
           "haulin_tension_rel_err": float(np.max(np.abs(T[up] / lift_tension(L[up], v2) - 1))),
           "haulin_drag_share": float(np.max(lift_tension(L[up], v2) / lift_tension(L[up], 0.0) - 1)),
           "payout_tension_rel_err": float(np.max(np.abs(T[down] / lift_tension(L[down], v0) - 1)))}
    if series:
        closed = np.where(down, lift_tension(L, v0), np.where(up, lift_tension(L, v2), np.nan))
        out["series"] = (t, L, T, closed, down | up)
    return out


def round_trip_figure(path: Path, run: dict) -> None:
    """The round trip's length and top tension against the quasi-static closed forms of both directions."""
    plt = setup_matplotlib()
    t, L, T, closed, steady = run.pop("series")
    fig, (ax, axt) = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True)
    ax.plot(t, L, "k-")
    ax.set_ylabel("zero-tension length in the water L (m)")
    ax.set_title(f"2 kN package on 30 mm wire: lowered {L.max() - L[0]:g} m at 1 m/s, held 5 s, hauled back in\n"
                 f"node model N = {run['N']}, rtol {run['rtol']:g}: back at L = {L[-1]:g} m, nodes within "
                 f"{run['return_max_abs_m']:.1e} m of the start {run['settle_s']:g} s after the stop", fontsize=10)
    ax.grid(alpha=0.3)
    axt.plot(t, T / 1e3, "k-", lw=1, label="node model, top tension")
    axt.plot(t[steady], closed[steady] / 1e3, "o", color="C1", ms=3, mfc="none",
             label="closed form W_b + w L -/+ 1/2 rho (C_D A + C_t d L) v^2 (lowering / hauling in)")
    axt.plot(t, (LIFT_BODY.weight + LIFT_CABLE["weight_per_length"] * L) / 1e3, "--", color="0.5", lw=1,
             label="weight in water W_b + w L (no drag)")
    axt.set_xlabel("time t (s)")
    axt.set_ylabel("top tension (kN)")
    lo, hi = np.min(T) / 1e3, np.max(T) / 1e3
    axt.set_ylim(lo - 0.1 * (hi - lo), hi + 0.45 * (hi - lo))           # room for the legend above the curves
    axt.legend(fontsize=8, loc="upper left")
    axt.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def payout_mass(n: int = 5) -> float:
    """Largest relative error of the free nodes' mass against M_b + m_r L (1 - 1 / (2 N)) while paying out and hauling
    back in (the cable in the water is m_r L whichever way the winch turns), and of the whole mass matrix after the
    round trip against the fixed-length model's (a model built without the winch)."""
    cable = Cable(length=50.0, ae=1e6, diameter=0.02, mass_per_length=1.0, weight_per_length=8.0, added_mass_factor=0.0,
                  segments=n)
    body = Body(weight=500.0, mass_x=100.0, mass_y=100.0)
    winch = Winch(leg=(Leg(speed=2.0, duration=5.0), Leg(speed=0.0, duration=2.0), Leg(speed=-2.0, duration=5.0)),
                  start=1.0, ramp=2.0, max_length=65.0)
    sc = single_section_scene(cable=cable, body=body, numerics=Numerics(duration=20.0, output_step=0.5), winch=winch)
    plain = dataclasses.replace(sc, winch=None)
    model, fixed = build_model(sc), build_model(plain)
    p = model.parameters(sc)
    q = np.concatenate([[0.0, (j + 1) * 50.0 / n] for j in range(n)])
    mass = lambda m, pp, t: np.array(m.dynamics(q, np.zeros_like(q), np.r_[t, np.zeros(6)], pp)[0])
    errs = []
    for t in (0.0, 2.0, 4.5, 7.0, 9.0, 11.5, 14.0, 16.0, 20.0):
        L = 50.0 + winch.profile(t)[0]
        expected = 100.0 + 1.0 * L * (1 - 1 / (2 * n))
        errs.append(abs(np.trace(mass(model, p, t)[0::2, 0::2]) / expected - 1))
    M_end, M_fixed = mass(model, p, winch.end), mass(fixed, fixed.parameters(plain), 0.0)
    errs.append(float(np.max(np.abs(M_end - M_fixed)) / np.max(np.abs(M_fixed))))
    return float(max(errs))
