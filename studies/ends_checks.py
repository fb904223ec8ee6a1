"""Checks of the line's other ends (segmented node model): statics against the closed-form
mooring-line catenary with seabed friction, a line lying on a sloped bed, a resting chain, the
energy of a bouncing line, a package lowered and hauled back in by the winch (``_lift.py``), a span's
free decay and the slack-cable tables.

Writes ``ends_checks.json``, ``mooring_static_shape.png``, ``payout_haulin.png`` and ``seabed_3d_winch.png`` into
``--out``:

- ``catenary_seabed_max_rel_err``: the largest relative error of the fairlead forces (H, V_F), the
  anchor force H_A (V_A for the line that does not touch) and the length on the bed L_B over
  the friction coefficients 0, 0.1, 5 and a line that does not touch, after Richardson
  extrapolation of the two finest N (``catenary_seabed_errors`` has every N's raw errors);
  ``catenary_seabed_order``: the smallest observed order of convergence between the two finest N;
- ``sloped_seabed_max_rel_err``: fairlead and anchor forces of a line lying on a 10 degree slope
  against T(s) = T_A + w sin(alpha) s;
- ``resting_chain_drift_m``: the largest node displacement over the run (1000 s; quick 200 s) of a
  mooring line (mu = 0) started from its static state; ``laid_line_creep_m`` the same with
  mu = 0.5 from the laid-down static state over 1000 s (quick 50 s): the regularised friction
  vanishes at rest, so the line creeps from the laid-down state towards the friction-free one;
- ``contact_energy_drift_rel``: max |E(t) - E(0)| / (E(0) - E_rest) of a line dropped on the bed
  with no drag, no friction and no contact damping, over ``bounce_contacts`` contacts of its
  mid-node (80 s: about 140 in the full run; quick 6 s);
- ``lowering_tension_rel_err``: a 2 kN package (C_D A = 1 m^2) lowered at 1 m/s on 30 mm wire by the
  ``[winch]`` (node model, N = 8, 20 m to 50 m in the water, rtol 1e-8): the top tension over the
  constant-speed part against the closed form W_b + w L - 1/2 rho (C_D A + C_t d L) v^2 (weight in water
  less the drag of the body and of the paid-out cable sliding down through the water, Wang 1971 eq. 32, 44);
  ``payout_mass_rel_err``: the mass the free nodes carry against M_b + m_r L (1 - 1 / (2 N)) (the body and
  the cable in the water less the half element lumped at the sheave) at nine times while paying out, holding and
  hauling back in, and the whole mass matrix after the round trip against the fixed-length model's;
- ``payout_haulin_return_max_abs`` (m): the same package lowered 30 m at 1 m/s, held 5 s and hauled back in at 1 m/s
  (``[[winch.leg]]``, one run, rtol 1e-8): the largest node-position difference from the initial (static) state
  1 s after the winch stops (``payout_haulin`` has the velocities, the top tension and the difference at the
  stop; ``payout_haulin_rtol_sweep`` the same at other rtol: what is left 1 s after the stop is the integrator's
  error and shrinks with rtol); ``haulin_tension_rel_err``: the top tension over the constant-speed haul-in
  against W_b + w L + 1/2 rho (C_D A + C_t d L) v^2, the drag now pulling down with the weight (figure
  ``payout_haulin.png``);
- ``span_decay_vs_modes_max_rel_err``: a span between two supports in water (lambda^2 about 81, node model
  N = 10, drag on) released from its equilibrium plus 1 % of the sag along its first symmetric and
  antisymmetric mode: the frequency read from the time series against the linear mode's
  (``studies/span_dynamics.py``, which also checks the convergence to Irvine's closed forms; ``--quick``: null here,
  named in ``run_elsewhere_in_quick``: those runs are span_dynamics.py --quick's own water decays);
- ``slack_table1_max_rel_err``: Griffin & Rosenthal (1985) Table 1, the inclined cable in water: the
  largest relative difference of the first five in-plane frequencies of the shared cable
  (``slack.converge``, Richardson over three element counts) from Triantafyllou's printed values
  (three significant figures: ``slack_table1_print_rounding`` is half a unit of the last figure,
  relative, per mode); ``slack_table3_frequencies_rad_s``: the nine modes of Table 3 (two masses),
  whose printed values are held out (``slack_table3_modes_inside_band`` stays null, named in
  ``held_out``);
- the seabed in space (``_seabed_3d.py``, node model N = 10 unless said): ``seabed_3d_planar_rhs_max_rel``, the 3-D
  right-hand side of a planar mooring (axial and lateral friction, fairlead in surge and heave) at the planar run's
  states against the planar one (relative to the run's largest node acceleration), and
  ``seabed_3d_planar_run_max_abs_m`` the two runs' node positions (rtol 1e-10; quick 1e-9 over 15 s);
  ``seabed_3d_rotation_max_abs_m``: the same mooring on a 3 degree slope turned by 35 degrees about the vertical,
  turned back, against the unturned run (``seabed_3d_rotation`` has its static state's);
  ``lateral_friction_hold_speed_err_m_s`` and ``lateral_friction_slide_speed_err_m_s``: a line laid along the contour
  of a 20 degree slope, dropped, its middle node's down-slope speed against the closed form of the regularised lateral
  friction (held, mu = 0.6 > tan 20 deg, creeping at v_s atanh(tan a / mu); sliding, mu = 0.2, at (w sin a - mu w cos a)
  / m_e); ``resting_chain_3d_drift_m``: the turned mooring on a bed sloping across it (lateral friction 0.6) left at
  rest 1000 s; ``contact_energy_drift_rel_3d``: a rope bowed sideways and dropped on the bed at a 35 degree bearing, no
  drag, friction or damping (80 s, ``bounce_3d_contacts`` contacts; quick 4 s at N = 6);
- the winch with the other ends (``_winch_ends.py``): ``haulin_mooring_vs_closed_form_max_rel``, the fairlead tension
  of the 300 m chain hauled in 10 m at 0.1 m/s (N = 40; quick 20) against the closed-form catenary of the length at
  each moment, ``haulin_mooring_vs_statics_max_rel`` against the node model's statics of that length (the haul's
  dynamics; ``haulin_mooring`` has the statics' discretisation error); ``haulin_mooring_friction_outside_band_rel``:
  with axial friction 0.5 (N = 10), how far the fairlead tension leaves the band between the friction-free and the
  laid-down statics; ``anchored_payout_mass_rel_err``: an anchored line's mass in the water against m_r L (1 - 1 / N);
  ``winch_3d_rhs_max_rel``, ``winch_3d_turned_max_abs_m``: the lift lowered and recovered in a current, forced through
  the 3-D equations and turned by 40 degrees, against the planar run (figure ``seabed_3d_winch.png``);
- a package lowered onto the bed (``_landing.py``): ``landed_top_tension_N`` per N with the package's footprint
  (``body.bed_area`` 1 m^2: w (L - h / 2), first order) and without (``landed_top_tension_point_body_N``: the line
  takes more of the package as N grows, a landed state that does not converge); ``landing_auto_segments``, the N auto
  runs (it had doubled to its cap of 128), and ``landing_stated_vs_actual_max_ratio``, the largest ratio of a quantity's
  actual error (against runs at N = 64 and 128, quick 16 and 32: the first-order limit of the landed tensions) to the
  error auto states for it (honest: <= 1); ``landing_taut_rule_understatement``, the same ratio of the taut check's
  |f(N) - f(N / 2)| / 3 for the line's pull on the landed package (what auto stated before).

The parts of the issue not built here are present with ``null`` and named in ``not_built``.
Run: ``python studies/ends_checks.py --out DIR [--quick]``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import parse_args, setup_matplotlib, write_json  # noqa: E402
import slack_tables  # noqa: E402
from _lift import lowering, payout_haulin, payout_mass, round_trip_figure  # noqa: E402
import _landing  # noqa: E402
import _seabed_3d  # noqa: E402
import _winch_ends  # noqa: E402
import span_dynamics  # noqa: E402

from cablesys.model import build_model  # noqa: E402
from cablesys.scene import Anchor, Body, Cable, Numerics, Seabed, single_section_scene  # noqa: E402
from cablesys.scene.components import Environment  # noqa: E402
from cablesys.statics.catenary import anchored_line_forces, segmented_steady  # noqa: E402
from cablesys.statics.closed_forms import seabed_catenary, seabed_catenary_span  # noqa: E402
from cablesys.time_domain.run import simulate  # noqa: E402

# a studless chain in water: 300 m, w = 1300 N/m, EA = 50 MN, fairlead 100 m above a flat bed
LENGTH, W, EA, DEPTH, DIAMETER, MASS = 300.0, 1300.0, 5e7, 100.0, 0.1, 150.0
RIGID = 1e11          # Pa/m: a bed this stiff sinks the laid chain by w / (k d) = 1.3e-7 m (the closed form's rigid bed)
FRICTIONS = (0.0, 0.1, 5.0)
# Table 3's printed frequencies (SLACK1 and SLACK2) are held out in our copy of the report: the count of our modes
# inside their band is for whoever holds them; we report our frequencies
HELD_OUT = ["slack_table3_modes_inside_band"]


def chain(n: int, length: float = LENGTH, **kw) -> Cable:
    """The study's chain in ``n`` elements."""
    return Cable(length=length, ae=EA, diameter=DIAMETER, mass_per_length=MASS, weight_per_length=W, segments=n, **kw)


def mooring_scene(n: int, span: float, *, friction: float = 0.0, stiffness: float = RIGID, damping: float = 0.0,
                  duration: float = 60.0, output_step: float = 1.0):
    """Fairlead at the top (at rest), anchor ``span`` m away on the flat bed ``DEPTH`` m below."""
    return single_section_scene(
        cable=chain(n), body=Body(weight=0.0, mass_x=1.0, mass_y=1.0),
        anchor=Anchor(x=span, y=DEPTH),
        seabed=Seabed(depth=DEPTH, stiffness=stiffness, damping=damping, friction_axial=friction),
        numerics=Numerics(duration=duration, output_step=output_step, model="as-built", rtol=1e-8))


def static(scene):
    """(model, p, steady state) of a scene."""
    model = build_model(scene)
    p = model.parameters(scene)
    return model, p, segmented_steady(model, p)


def catenary_case(friction: float, touches: bool = True) -> tuple[float, dict]:
    """(span, closed form): L_B = L/2 on the bed (the touchdown point on a node at even N), or a
    line whose anchor end hangs (span 282 m, V_A > 0)."""
    span = (seabed_catenary_span(length=LENGTH, weight_per_length=W, ea=EA, height=DEPTH, seabed_length=LENGTH / 2,
                                 friction=friction) if touches else 282.0)
    return span, seabed_catenary(length=LENGTH, weight_per_length=W, ea=EA, span=span, height=DEPTH, friction=friction)


def catenary_errors(n: int, friction: float, touches: bool = True) -> dict:
    """Relative errors of the node model's statics at N = ``n`` against :func:`seabed_catenary`."""
    span, cf = catenary_case(friction, touches)
    model, p, st = static(mooring_scene(n, span, friction=friction))
    f = anchored_line_forces(model, st, p)
    keys = ("H", "V_F", "H_A", "L_B") if touches else ("H", "V_F", "H_A", "V_A")
    # H_A = 0 (mu = 5: the line slack at the anchor) is compared in N of the fairlead force
    return {k: (f[k] - cf[k]) / (abs(cf[k]) if cf[k] != 0 else cf["H"]) for k in keys}


def catenary_convergence(ns) -> dict:
    """Raw errors per case and N, Richardson-extrapolated errors of the two finest N, observed orders."""
    cases = {f"mu={mu:g}": (mu, True) for mu in FRICTIONS} | {"no touch": (0.0, False)}
    out, rich_max, orders = {}, 0.0, []
    for name, (mu, touches) in cases.items():
        errs = [catenary_errors(n, mu, touches) for n in ns]
        keys = list(errs[0])
        e1, e2 = np.array([errs[-2][k] for k in keys]), np.array([errs[-1][k] for k in keys])
        rich = (4 * e2 - e1) / 3                              # second order: e(h) = C h^2 + O(h^4)
        big = np.abs(e1) > 1e-12                              # H_A = 0 exactly (slack at the anchor): no order
        order = np.log2(np.abs(e1[big] / e2[big]))
        out[name] = {"N": list(ns), "errors": {k: [e[k] for e in errs] for k in keys},
                     "richardson": dict(zip(keys, rich)), "order": dict(zip(np.array(keys)[big], order))}
        rich_max = max(rich_max, float(np.max(np.abs(rich))))
        orders += list(order)
    return dict(cases=out, max_rel_err=rich_max, order=float(min(orders)))


def sloped_case(n: int, slope_deg: float = 10.0, strain: float = 1e-3) -> dict:
    """A taut line lying on a slope from the top (on the bed) to the anchor ``l_r`` = 100 m down the slope,
    given at the reference tension T_r = EA strain (l_0 = l_r (1 - strain)); frictionless, the tension
    grows up the slope by the weight's component: T(s) = T_A + w sin(alpha) s (s reference arc from the
    anchor), and the stretch int T / EA ds = l_r - l_0 fills the distance: T_A = EA strain - w
    sin(alpha) l_r / 2. Returns the relative errors of the fairlead's and the anchor's force along the bed."""
    L, a = 100.0, np.radians(slope_deg)
    scene = single_section_scene(
        cable=chain(n, L, tension_ref=EA * strain), body=Body(weight=0.0, mass_x=1.0, mass_y=1.0),
        anchor=Anchor(x=L * np.cos(a), y=L * np.sin(a)),
        seabed=Seabed(depth=DEPTH, slope_deg=slope_deg, stiffness=RIGID, damping=0.0),
        environment=Environment(top_depth=DEPTH))
    model, p, st = static(scene)
    y, t_b = st.outputs, np.array([np.cos(a), np.sin(a)])
    nx = np.array([y[f"node_x[{j}]"] for j in range(n + 1)])
    ny = np.array([y[f"node_y[{j}]"] for j in range(n + 1)])
    T = np.array([y[f"element_tension[{k}]"] for k in range(n)])
    et = lambda k: np.array([nx[k + 1] - nx[k], ny[k + 1] - ny[k]]) / np.hypot(nx[k + 1] - nx[k], ny[k + 1] - ny[k])
    half = np.array([0.0, 0.5 * W * L / n])                   # the half element lumped at each end (y down)
    fairlead = (T[0] * et(0) + half) @ t_b                    # the line's pull on the top, down the slope
    anchor = (-T[-1] * et(n - 1) + half) @ -t_b              # its pull on the anchor, up the slope
    T_A = EA * strain - W * np.sin(a) * L / 2
    return {"fairlead": fairlead / (T_A + W * np.sin(a) * L) - 1, "anchor": anchor / T_A - 1}


def max_drift(rec) -> float:
    """Largest displacement of any node from its start over a run (m)."""
    X = np.asarray(rec.states)
    nq = X.shape[0] // 2
    q = X[:nq].reshape(-1, 2, X.shape[1])
    return float(np.max(np.hypot(*(q - q[:, :, :1]).transpose(1, 0, 2))))


def resting(duration: float, friction: float, n: int = 20) -> float:
    """Node drift (m) of the mooring line left at rest from its static state for ``duration`` s (MoorDyn's
    default bed: k = 3 MPa/m, c = 0.3 MPa s/m)."""
    span, _ = catenary_case(friction)
    scene = mooring_scene(n, span, friction=friction, stiffness=3e6, damping=3e5, duration=duration, output_step=5.0)
    return max_drift(simulate(scene))


def bouncing(duration: float, n: int = 10, chord: float = 20.0, lift: float = 1.0, ea: float = 1e6) -> dict:
    """A soft rope between two points on the bed, lifted into the arc y = -lift sin(pi x / chord) at
    zero strain (its nodes equally spaced along the arc, the rope as long as the arc) and dropped:
    no drag, no friction, no contact damping, no internal damping. Returns the energy drift
    max |E(t) - E(0)| / (E(0) - E_rest) (E_rest: the rope's energy lying flat at its static
    penetration, a lower bound of its energy) and the mid-node's number of contacts."""
    from scipy.integrate import cumulative_trapezoid

    xs = np.linspace(0.0, chord, 20001)
    slope = -lift * np.pi / chord * np.cos(np.pi * xs / chord)
    s = cumulative_trapezoid(np.hypot(1.0, slope), xs, initial=0.0)
    arc = float(s[-1])
    cab = Cable(length=arc, ae=ea, diameter=DIAMETER, mass_per_length=MASS, weight_per_length=W, segments=n,
                cd_normal=0.0, ct_tangential=0.0)
    k_bed = 3e6
    scene = single_section_scene(
        cable=cab, body=Body(weight=0.0, mass_x=1.0, mass_y=1.0), anchor=Anchor(x=chord, y=0.0),
        seabed=Seabed(depth=DEPTH, stiffness=k_bed, damping=0.0), environment=Environment(top_depth=DEPTH),
        numerics=Numerics(duration=duration, output_step=0.02, model="as-built", rtol=1e-10, atol=1e-10))
    model = build_model(scene)
    p = model.parameters(scene)
    x_k = np.interp(arc * np.arange(1, n) / n, s, xs)
    q0 = np.column_stack([x_k, -lift * np.sin(np.pi * x_k / chord)]).ravel()
    rec = simulate(scene, model=model, x0=np.concatenate([q0, np.zeros_like(q0)]))
    X, t = np.asarray(rec.states), np.asarray(rec.time)
    energy = lambda x, ti: sum(float(v) for v in model.energy(x, model.top(ti, p), p))
    E = np.array([energy(X[:, i], t[i]) for i in range(len(t))])
    sink = W / (k_bed * DIAMETER)                             # static penetration of a lying node
    q_rest = np.column_stack([chord * np.arange(1, n) / n, np.full(n - 1, sink)]).ravel()
    E_rest = energy(np.concatenate([q_rest, 0 * q_rest]), 0.0)
    touching = X[2 * (n // 2 - 1) + 1] > 0.0                  # the mid node below the bed's surface (y = 0)
    return {"energy_drift_rel": float(np.max(np.abs(E - E[0])) / (E[0] - E_rest)),
            "contacts": int(np.sum(touching[1:] & ~touching[:-1])), "duration_s": duration,
            "success": bool(rec.success), "reached_s": float(t[-1])}


def figure(path: Path, n: int) -> None:
    """The mooring line's static shape on the bed and its tension, node model and closed form, per friction
    coefficient (the suspended shapes coincide: friction acts on the laid part only)."""
    plt = setup_matplotlib()
    fig, (ax, axt) = plt.subplots(2, 1, figsize=(8, 7.5), sharex=True)
    for mu, c in zip(FRICTIONS, ("C0", "C1", "C2")):
        span, cf = catenary_case(mu)
        model, p, st = static(mooring_scene(n, span, friction=mu))
        y = st.outputs
        nx = np.array([y[f"node_x[{j}]"] for j in range(n + 1)])
        ny = np.array([y[f"node_y[{j}]"] for j in range(n + 1)])
        x, z, T = cf["shape"](np.linspace(0, LENGTH, 601))
        ax.plot(span - x, DEPTH - z, "-", color=c, lw=1)
        ax.plot(nx, ny, "o", color=c, ms=3, mfc="none" if mu else c, label=f"mu = {mu:g}: anchor at x = {span:.2f} m")
        Te = np.array([y[f"element_tension[{k}]"] for k in range(n)])
        axt.plot(span - x, T / 1e3, "-", color=c, lw=1)
        axt.plot(0.5 * (nx[1:] + nx[:-1]), Te / 1e3, "o", color=c, ms=3, label=f"mu = {mu:g}")
    ax.axhline(DEPTH, color="0.4", lw=2)
    ax.text(120, DEPTH - 3, "seabed (flat, rigid)", color="0.3", va="bottom")
    ax.plot([0], [0], "ks", ms=7)
    ax.text(6, 2, "fairlead (top)", va="center")
    ax.plot([span], [DEPTH], "k^", ms=8)
    ax.text(span - 4, DEPTH - 6, "anchor", ha="right")
    ax.invert_yaxis()
    ax.set_ylabel("depth below the fairlead y (m)")
    ax.set_title(f"{LENGTH:g} m chain, w = {W:g} N/m, EA = {EA / 1e6:g} MN, half its length on the bed\n"
                 f"node model N = {n} (dots), closed-form catenary with seabed friction (lines)", fontsize=10)
    ax.legend(fontsize=8, loc="center right")
    ax.grid(alpha=0.3)
    axt.set_xlabel("horizontal position from the fairlead x (m)")
    axt.set_ylabel("tension (kN)")
    axt.legend(fontsize=8, title="element tension, friction coefficient", title_fontsize=8)
    axt.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def slack_table1(levels) -> dict:
    """Table 1 of Griffin & Rosenthal (1985) from the shared cable against Triantafyllou's printed values."""
    printed = slack_tables.read_reference()[1]["Triantafyllou_1984b"]
    _, rep = slack_tables.do_table1(levels, {"Triantafyllou_1984b": printed})
    err = np.array(rep["rel_err_vs_Triantafyllou_1984b"])
    return {"max_rel_err": float(np.max(np.abs(err))), "rel_err": err.tolist(),
            "print_rounding": (0.005 / np.array(printed)).tolist()}


def slack_table3(levels) -> list[dict]:
    """Table 3 of Griffin & Rosenthal (1985): the span with two 4.5 kg masses, l/L = 0.962, nine modes."""
    length = slack_tables.SPAN6 / 0.962
    conv = slack_tables.converge(slack_tables.scene6(0.962, slack_tables.masses_two(length)), 9, levels=levels)
    return [{"mode_type": r["mode_type"], "omega_rad_s": r["omega_rad_s"]} for r in conv.table()]


def ends_3d(quick: bool) -> dict:
    """The keys of the seabed in space and of the winch with the other ends (module docstring)."""
    S, WE = _seabed_3d, _winch_ends
    planar = S.planar_equivalence(duration=15.0, rtol=1e-9) if quick else S.planar_equivalence()
    turned = S.rotated(duration=15.0, rtol=1e-9) if quick else S.rotated()
    hold, slide = S.lateral_slide(0.6, duration=4.0, series=True), S.lateral_slide(0.2, duration=0.5, series=True)
    rest = S.resting(1000.0)
    bounce = S.bouncing(4.0, n=6, rtol=1e-8) if quick else S.bouncing(80.0)
    haul = WE.haulin(20 if quick else 40, 0.1, series=True)
    rough = WE.haulin(10, 0.1, friction=0.5)
    w3 = WE.winch_3d(n=4, rtol=1e-9) if quick else WE.winch_3d()
    return {
        "seabed_3d_planar_rhs_max_rel": planar["rhs_max_rel"],
        "seabed_3d_planar_run_max_abs_m": planar["run_positions_max_abs_m"],
        "seabed_3d_planar": planar,
        "seabed_3d_rotation_max_abs_m": turned["run_max_abs_m"],
        "seabed_3d_rotation": turned,
        "lateral_friction_hold_speed_err_m_s": hold["speed_max_abs_err_m_s"],
        "lateral_friction_slide_speed_err_m_s": slide["speed_max_abs_err_m_s"],
        "lateral_friction_hold": hold, "lateral_friction_slide": slide,
        "resting_chain_3d_drift_m": rest["drift_max_m"],
        "resting_chain_3d": rest,
        "contact_energy_drift_rel_3d": bounce["energy_drift_rel"],
        "bounce_3d_contacts": bounce["contacts"],
        "bounce_3d": bounce,
        "haulin_mooring_vs_closed_form_max_rel": haul["vs_closed_form_max_rel"],
        "haulin_mooring_vs_statics_max_rel": haul["vs_statics_max_rel"],
        "haulin_mooring": haul,
        "haulin_mooring_friction_outside_band_rel": rough["outside_band_max_rel"],
        "haulin_mooring_friction": rough,
        "anchored_payout_mass_rel_err": WE.anchored_mass(),
        "winch_3d_rhs_max_rel": w3["rhs_max_rel"],
        "winch_3d_turned_max_abs_m": w3["turned_max_abs_m"],
        "winch_3d": w3,
        **landing(quick),
    }


def landing(quick: bool) -> dict:
    """The keys of the package lowered onto the bed (module docstring)."""
    ns = (8, 16) if quick else (8, 16, 32, 64)
    foot = [_landing.landed_state(n, 1.0) for n in ns]
    point = [_landing.landed_state(n, None) for n in ns]
    hon = _landing.honesty(32 if quick else 128)
    taut = hon["taut_rule"]
    return {
        "landed_N": list(ns),
        "landed_top_tension_N": [r["tension_top_N"] for r in foot],
        "landed_top_tension_point_body_N": [r["tension_top_N"] for r in point],
        "landed_closed_form_top_tension_N": _landing.W_R * _landing.DEPTH,
        "landing_auto_segments": hon["N"],
        "landing_stated_vs_actual_max_ratio": max(hon["ratio"].values()),
        "landing_taut_rule_understatement": taut["actual"]["tension_bottom_min"] / taut["stated"]["tension_bottom_min"],
        "landing": hon,
    }


def seabed_3d_figure(path: Path, series: dict, res: dict) -> None:
    """The lateral friction holding and sliding a laid line (node model and the regularised law's closed form), and the
    fairlead tension of the mooring line hauled in (run, the node model's statics and the closed-form catenary)."""
    plt = setup_matplotlib()
    fig, (ax, axh) = plt.subplots(2, 1, figsize=(8, 8))
    for key, c, label in (("lateral_friction_hold", "C0", "mu = 0.6 > tan 20 deg: held, creeping at v_s atanh(tan a / mu)"),
                          ("lateral_friction_slide", "C3", "mu = 0.2 < tan 20 deg: slides")):
        t, v, v_cf = series[key]
        ax.plot(t, v_cf, "-", color=c, lw=1.2, label=f"{label} (closed form)")
        ax.plot(t[::2], v[::2], "o", color=c, ms=3, mfc="none", label="node model, middle node")
    ax.set_yscale("log")
    ax.set_ylim(1e-3, 5.0)
    ax.set_xlabel("time t (s)")
    ax.set_ylabel("down-slope speed (m/s)")
    ax.set_title("a 20 m chain laid along the contour of a 20 deg slope, dropped: lateral friction\n"
                 f"speed errors {res['lateral_friction_hold_speed_err_m_s']:.1e} (held), "
                 f"{res['lateral_friction_slide_speed_err_m_s']:.1e} m/s (sliding, 0.5 s)", fontsize=10)
    ax.legend(fontsize=8, loc="upper right")
    ax.grid(alpha=0.3, which="both")
    L, T, Ls, st, cf = series["haulin_mooring"]
    h = res["haulin_mooring"]
    axh.plot(L, T / 1e3, "k-", lw=1, label=f"node model N = {h['N']}, hauled in at {h['speed_m_s']:g} m/s")
    axh.plot(Ls, st / 1e3, "s", color="C1", ms=6, mfc="none", label="node model's statics of that length")
    axh.plot(Ls, cf / 1e3, "x", color="C2", ms=8, label="closed-form catenary with seabed contact")
    axh.invert_xaxis()
    axh.set_xlabel("zero-tension length in the water L (m), decreasing as the winch hauls in")
    axh.set_ylabel("fairlead tension (kN)")
    axh.set_title(f"300 m chain from its anchor, 150 m on the bed at the start, hauled in {h['haul_m']:g} m at the "
                  f"fairlead:\nvs closed form {h['vs_closed_form_max_rel']:.1e}, vs statics "
                  f"{h['vs_statics_max_rel']:.1e} (the haul's dynamics)", fontsize=10)
    axh.legend(fontsize=8, loc="upper left")
    axh.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def main(argv=None) -> dict:
    args = parse_args(__doc__.splitlines()[0], argv)
    quick = args.quick
    ns = (40, 80) if quick else (40, 80, 160)
    conv = catenary_convergence(ns)
    slope = sloped_case(20)
    bounce = bouncing(6.0 if quick else 80.0)
    table1 = slack_table1((30, 60, 120) if quick else (60, 120, 240))
    lower = lowering()
    trip = payout_haulin(1e-8, series=True)
    # the sweep's rtol 1e-8 is the round trip above (the same run; series only adds its output)
    sweep = [{k: v for k, v in trip.items() if k != "series"} if r == 1e-8 else payout_haulin(r)
             for r in ((1e-6, 1e-8) if quick else (1e-5, 1e-6, 1e-7, 1e-8, 1e-9))]
    # --quick: the span's two decays in water are studies/span_dynamics.py --quick's own water decays (the same runs:
    # N = 10, amplitude, periods, rtol), checked by tests/test_span_dynamics.py; not run twice
    decays = None if quick else [span_dynamics.free_decay(span_dynamics.SLACKS[1], 10, mode,
                                                          span_dynamics.WATER_AMPLITUDE, span_dynamics.QUICK_PERIODS,
                                                          span_dynamics.SWEEP_RTOL, medium="water") for mode in "SA"]
    out = {
        "quick": quick,
        "catenary_seabed_max_rel_err": conv["max_rel_err"],
        "catenary_seabed_order": conv["order"],
        "catenary_seabed_N": list(ns),
        "catenary_seabed_errors": conv["cases"],
        "sloped_seabed_max_rel_err": max(abs(v) for v in slope.values()),
        "resting_chain_drift_m": resting(200.0 if quick else 1000.0, 0.0),
        "laid_line_creep_m": resting(50.0 if quick else 1000.0, 0.5),
        "laid_line_creep_duration_s": 50.0 if quick else 1000.0,
        "resting_duration_s": 200.0 if quick else 1000.0,
        "contact_energy_drift_rel": bounce["energy_drift_rel"],
        "bounce_contacts": bounce["contacts"],
        "bounce_duration_s": bounce["duration_s"],
        "bounce": bounce,
        "lowering_tension_rel_err": lower["max_rel_err"],
        "lowering": lower,
        "payout_mass_rel_err": payout_mass(),
        "payout_haulin_return_max_abs": trip["return_max_abs_m"],
        "haulin_tension_rel_err": trip["haulin_tension_rel_err"],
        "payout_haulin": trip,
        "payout_haulin_rtol_sweep": sweep,
        "span_decay_vs_modes_max_rel_err": None if decays is None else max(abs(r["td_vs_linear"]) for r in decays),
        "slack_table1_max_rel_err": table1["max_rel_err"],
        "slack_table1_rel_err": table1["rel_err"],
        "slack_table1_print_rounding": table1["print_rounding"],
        "slack_table3_frequencies_rad_s": slack_table3((24, 48, 96) if quick else (48, 96, 192)),
        **dict.fromkeys(HELD_OUT),
        "held_out": HELD_OUT,
        "not_built": [],
    }
    if quick:
        out["run_elsewhere_in_quick"] = {"span_decay_vs_modes_max_rel_err": "studies/span_dynamics.py --quick "
                                         "(span_decay_vs_modes_max_rel_err, the same decays in water)"}
    out.update(ends_3d(quick))
    series = {k: out[k].pop("series") for k in ("lateral_friction_hold", "lateral_friction_slide", "haulin_mooring")}
    figure(args.out / "mooring_static_shape.png", 40)
    round_trip_figure(args.out / "payout_haulin.png", trip)
    seabed_3d_figure(args.out / "seabed_3d_winch.png", series, out)
    write_json(args.out / "ends_checks.json", out)
    return out


if __name__ == "__main__":
    res = main()
    print({k: v for k, v in res.items() if not isinstance(v, (dict, list))})
