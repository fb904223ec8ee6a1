"""The ``cablesys rao`` sub-command: steady state, natural frequencies and RAO tables of a scene."""

from __future__ import annotations

import dataclasses
import json
import sys

import numpy as np

# frequency-grid size limit: each frequency is a complex linear solve and, with a one-frequency
# top motion, a harmonic balance (KINSOL); 1e8 frequencies hung
MAX_FREQUENCIES = 10_000
# phase samples of the describing function's harmonic balance: the one-harmonic averages of |v| v drag to
# 4 digits (x_b 0.07117 vs 0.07118 m at 16 and 64 on the Dale and 300 m heave scenes, cablesys.ladder.estimate)
DF_PHASES = 32
# consecutive slack orbits (ascending frequency) after which the describing function is not solved further up
SLACK_STOP = 5


def register(sub) -> None:
    """Add ``rao SCENE.toml [--out DIR] [--omega-max W] [--n N]`` to the cablesys parser."""
    p = sub.add_parser("rao", help="linearize about the steady state: natural frequencies and RAOs (CSV + plots)",
                       description="Steady state, exact linearization, natural modes and RAOs of x_b, y_b, phi, u "
                                   "and tension per unit top motion in x and y (and of z_b per unit sway z in a 3-D "
                                   "scene). With a one-frequency top motion in the scene, also the describing-function "
                                   "RAO at that motion's amplitude, per direction of the top motion.")
    p.add_argument("scene", help="scene TOML file")
    p.add_argument("--out", default="rao_out", help="output directory (default: rao_out)")
    p.add_argument("--omega-max", type=float, default=None,
                   help="largest frequency in rad/s (default: 3 x the largest natural or forcing frequency)")
    p.add_argument("--n", type=int, default=400, help="number of frequencies (default: 400)")
    p.add_argument("--overwrite", action="store_true", help="replace results of another scene in --out")
    p.add_argument("--units", default=None, choices=("SI", "fps"),
                   help="units of the console, tables and figures (default: those of the scene file)")
    p.set_defaults(func=run)


def run(args) -> int:
    from ..options import option_int, option_number
    from ..outputs import OutputDir
    from ..scene import load_scene

    option_int("--n", args.n, lo=2, hi=MAX_FREQUENCIES, why="the frequency-grid size limit")
    if args.omega_max is not None:
        option_number("--omega-max", args.omega_max, lo=0.0, lo_open=True, hi=1e6, unit="rad/s")
    scene = load_scene(args.scene)
    # --out checked before any work; summary.json says running / success / failed / interrupted
    outdir = OutputDir(args.out, "rao", scene, overwrite=getattr(args, "overwrite", False),
                       owned=("rao_summary.json", "modes.png"))
    with outdir.start(scene=scene.name):
        return _analyse(args, scene, outdir)


def _analyse(args, scene, outdir) -> int:
    from ..errors import ParameterError, SolverError
    from ..export import convert_rao_table, units_of_file
    from ..ladder import linear_model
    from ..units import output_unit
    from .band import RELEVANT_FACTOR, default_band, forcing_frequencies, relevant_modes
    from .equivalent import HB_TOLERANCE, harmonic_model, harmonic_response
    from .frequency_response import rao, response_outputs
    from .linearization import linearize
    from .modal import modes as modes_of
    from .periodic import scene_input_amplitude
    from .plots import (
        is_noise,
        noise_floor,
        plot_modes,
        plot_rao_bode,
        plot_sea_response,
    )
    from .sea_response import sea_response
    units = getattr(args, "units", None) or units_of_file(args.scene)
    scene, model, which = linear_model(scene)      # the ladder's model for the scene, and why (cablesys.ladder)
    p = model.parameters(scene)
    lin = linearize(model, p)
    md = modes_of(lin)
    forcing = forcing_frequencies(scene)
    omega = default_band(relevant_modes(md.omega_undamped, forcing.values()), forcing.values(), n=args.n,
                         omega_max=args.omega_max)
    w_max = float(omega[-1])
    raos = {"exact linearization": rao(lin, omega)}
    if not (np.all(np.isfinite(raos["exact linearization"].values)) and np.all(np.isfinite(md.omega_undamped))):
        raise SolverError("the linearization about the steady state gives non-finite natural frequencies or RAOs "
                          "(a singular mass or stiffness matrix): check the scene's masses and stiffnesses")
    try:
        w_s, Z = scene_input_amplitude(scene)
    except ParameterError:      # no one-frequency top motion: the describing-function RAO does not apply
        Z = None
    failures, describing = [], {}
    # one describing function per direction of the top's motion (surge, heave, and sway in 3-D: the inputs of the
    # linearization, in the order of scene_input_amplitude), each at the scene's amplitude in that direction alone
    tops = [i for i in ("x_s", "y_s", "z_s") if i in lin.input_labels]
    # the node model's balance in its element coordinates (the same physics and outputs; equivalent.harmonic_model)
    df_model = harmonic_model(scene, model) if Z is not None and np.any(np.abs(Z[:len(tops)]) > 0) else model
    skipped = None
    if Z is not None and getattr(scene, "system", None) is not None:
        # a graph of lines has no element coordinates: its balance in node coordinates overstates a swinging node's
        # response (equivalent.harmonic_model) and solves ~100 coordinates per frequency: not drawn, said
        skipped = ("not computed for a system of lines joined at points: it has no element coordinates, and the balance "
                   "in node coordinates overstates a swinging node's tension (a node on an arc); the exact "
                   "linearization is drawn: cablesys run gives the drag's amplitude dependence")
        Z = None
    for k, inp in enumerate(tops if Z is not None else ()):
        if abs(Z[k]) > 0:
            Zk = np.zeros_like(Z)
            Zk[k] = abs(Z[k])
            # the describing function holds the scene's amplitude: it means something near the scene's forcing,
            # up to the band where that forcing excites modes (linear.band.RELEVANT_FACTOR), not far above it
            band = omega[omega <= RELEVANT_FACTOR * w_s]
            h = harmonic_response(df_model, p, band, Zk, n_theta=DF_PHASES, slack_stop=SLACK_STOP, linear_models=False)
            valid = h.solved & ~h.slack & (h.residual < HB_TOLERANCE)
            bad = h.solved & ~h.slack & ~(h.residual < HB_TOLERANCE)
            if np.any(bad):
                failures.append(f"describing function for {inp}: {h.message}")
            describing[inp] = _describing_record(h, valid, abs(Z[k]), raos["exact linearization"], inp)
            describing[inp]["coordinates"] = ", ".join(df_model.q_labels[:3]) + (" ..." if df_model.nq > 3 else "")
            if np.any(valid):
                r = h.rao(label=inp)
                slack = band[h.solved & h.slack]
                # the legend says where the curve ends and why: the orbit goes slack there
                ends = f" (slack from {slack.min():.2g} rad/s)" if slack.size else ""
                raos[f"describing function, |{inp}| = {abs(Z[k]):.3g} m{ends}"] = dataclasses.replace(
                    r, omega=r.omega[valid], values=r.values[valid])
    out = outdir.path
    unique = len(set(md.dominant)) == len(md.dominant)        # else name by mode number: one key per mode
    natural = {f"omega_{d}" if unique else f"mode {k + 1} ({d})": float(w)
               for k, (d, w) in enumerate(zip(md.dominant, md.omega_undamped)) if omega[0] <= w <= w_max}
    written = []
    # a vessel's rotation moving further prescribed points (model/system.py): its RAOs per rad, drawn apart
    turns = [i for i in lin.input_labels if i.startswith("rot_")]
    for name, r in raos.items():
        tag = "exact" if name.startswith("exact") else "describing"
        for inp in [i for i in r.input_labels if i in tops + turns]:
            head, rows = convert_rao_table(*r.table(inp), units)
            f = f"rao_{tag}_{inp}.csv"
            with outdir.writing(f) as tmp:
                np.savetxt(tmp, rows, delimiter=",", header=",".join(head), comments="", fmt="%.8g")
            written.append(f)
    plotted = response_outputs(lin.output_labels, scene)
    zero = []
    for inp in tops + turns:
        group = turns if inp in turns else tops     # per m of translation, per rad of rotation: each its own floor
        for o in plotted:
            sel = {k: r for k, r in raos.items() if inp in r.input_labels}
            floor = noise_floor([r.amplitude(o, i) for r in sel.values() for i in r.input_labels if i in group])
            if all(is_noise(r.amplitude(o, inp), floor) for r in sel.values()):
                zero.append(f"{o} per unit {inp}")
                continue
            with outdir.writing(f"rao_{o}_{inp}.png") as tmp:
                plot_rao_bode(sel, o, inp, natural, tmp, title=f"{scene.name}: {o} per unit {inp}", forcing=forcing,
                              units=units)
            written.append(f"rao_{o}_{inp}.png")
    resp = sea_response(scene, lin)
    if resp is not None:
        with outdir.writing("sea_response.png") as tmp:
            plot_sea_response(resp, natural, tmp, title=f"{scene.name}: response spectra in the sea", forcing=forcing,
                              units=units)
        written.append("sea_response.png")
    graph = {}
    if getattr(scene, "system", None) is not None:      # lines joined at points: each line drawn apart, points by kind
        from ..model.system import topology
        point_nodes, line_nodes, _ = topology(scene.system)
        graph = dict(lines=line_nodes, points={p.name: (p.kind, j) for p, j in zip(scene.system.point, point_nodes)})
    with outdir.writing("modes.png") as tmp:
        plot_modes(md, lin, tmp, title=f"{scene.name}: mode shapes about the steady state", units=units,
                   n_shown=len(relevant_modes(md.omega_undamped, forcing.values())), **graph)
    written.append("modes.png")
    doc = {"scene": scene.name, "model": which, "steady_state": dict(zip(lin.q_labels, lin.q0.tolist())),
           "natural_frequencies_rad_s": md.omega_undamped.tolist(), "mode_dominant": list(md.dominant),
           "damping_ratios_exact": md.damping_ratio.tolist(),
           "band_rad_s": [float(omega[0]), w_max], "forcing_rad_s": forcing, "zero_responses": zero,
           "linearizations": {"exact": "about the steady state (Jacobians by AD): small amplitudes; without a current "
                                       "the drag has no slope there and the resonances are undamped",
                              **{f"describing function {k}": v for k, v in describing.items()},
                              **({"describing function": skipped} if skipped else {})}}
    verdict = {}
    if resp is not None:
        from ..verdict import evaluate
        verdict = evaluate(getattr(scene, "limits", None), resp.statistics)
        from ..verdict import group_by_quantity
        doc["sea_statistics"] = {"exposure_s": resp.exposure, **group_by_quantity(resp.statistics)}
        doc["verdict_frequency_domain"] = verdict
    outdir.write_text("rao_summary.json", json.dumps(doc, indent=1))
    shown = [(d, w) for d, w in zip(md.dominant, md.omega_undamped) if w <= w_max]
    above = len(md.omega_undamped) - len(shown)
    lines = [_model_line(which), f"{scene.name}: natural frequencies " + (", ".join(f"{d} {w:.5g} rad/s" for d, w in shown) or "none in the band")
             + (f"; {above} more above the band (rao_summary.json)" if above else ""),
             f"band {omega[0]:.3g} .. {w_max:.3g} rad/s; forcing: "
             + (", ".join(k for k in forcing if not k.startswith("sea band")) or "none")]
    if zero:
        lines.append("zero (below 1e-9 of the input, not drawn): " + ", ".join(zero))
    for inp, d in describing.items():
        lines.append(f"describing function at |{inp}| = {d['amplitude_m']:.3g} m: " + d["statement"])
    if skipped:
        lines.append(f"describing function: {skipped}")
    if resp is not None:
        from ..verdict import format_statistics, format_table, group_by_quantity
        lines.append(f"frequency domain, the scene's sea (linear, exposure {resp.exposure:.5g} s):")
        lines += ["  " + ln for ln in format_statistics(group_by_quantity(resp.statistics), units)]
        if verdict:
            lines += ["  " + ln for ln in format_table(verdict, lambda u: output_unit(u, units))]
    lines.append(f"wrote {len(written) + 1} files to {out}")
    sys.stdout.write("\n".join(lines) + "\n")
    if failures:             # written, but marked failed: a value that did not converge is not a success
        outdir.finish("failed", message="; ".join(failures))
        sys.stderr.write("cablesys rao: " + "; ".join(failures) + "\n")
        return 1
    return 0


def _describing_record(h, valid, amplitude: float, exact, inp: str) -> dict:
    """What ``rao_summary.json`` says of one describing-function RAO: where it holds, where the orbit goes slack,
    what was not solved, its convergence, and its difference from the exact linearization (the drag's effect:
    where it is small the exact linearization alone would do)."""
    w = h.omega
    ok = w[valid]
    d = {"amplitude_m": amplitude, "phases": int(h.stats["n_theta"]),
         "frequencies": int(w.size), "valid": int(valid.sum()),
         "valid_band_rad_s": [float(ok.min()), float(ok.max())] if ok.size else None,
         "slack_rad_s": [float(x) for x in w[h.slack]], "not_solved_from_rad_s": (float(w[~h.solved].min())
                                                                                if np.any(~h.solved) else None),
         "max_residual": float(np.nanmax(h.residual[valid])) if ok.size else None,
         "newton_iterations_max": int(max(h.stats["newton_iterations"])),
         "least_tension_N": [float(x) for x in h.least_tension]}
    if ok.size:
        # |exact - DF| / |DF| per unit input of the body's motion and the top tension: the drag's effect, which the
        # exact linearization leaves out (where it is small the exact RAO alone would do)
        body = {"x_s": "x_b", "y_s": "y_b", "z_s": "z_b"}[inp]
        d["exact_vs_describing_max_rel"] = {}
        for out in (body, "tension_top"):
            if out in h.output_labels and out in exact.output_labels:
                ex = np.abs(exact.values[:, exact.output_labels.index(out), exact.input_labels.index(inp)])
                ex = np.interp(ok, exact.omega, ex)
                df = np.abs(h.output_amplitude[valid, h.output_labels.index(out)]) / amplitude
                d["exact_vs_describing_max_rel"][out] = float(np.max(np.abs(ex - df) / np.maximum(df, 1e-300)))
    text = (f"holds (taut, converged) at {d['valid']} of {d['frequencies']} frequencies"
            + (f", {ok.min():.3g} .. {ok.max():.3g} rad/s" if ok.size else ""))
    if np.any(h.slack):
        text += (f"; the orbit goes slack at {int(h.slack.sum())} (from {w[h.slack].min():.3g} rad/s: "
                 "snap loads, not drawn: use cablesys run)")
    if np.any(~h.solved):
        text += f"; not solved from {w[~h.solved].min():.3g} rad/s up (above {SLACK_STOP} consecutive slack orbits)"
    d["statement"] = text
    return d


def _model_line(which: dict) -> str:
    """The console line naming the linearized model and its estimated error."""
    e = which["estimated_error"]
    fmt = lambda v: "not estimated" if v is None else f"{100 * v:.2g} %"
    seg = f", N = {which['segments']}" if which["segments"] > 1 else ""
    return f"model {which['name']}{seg} linearized: estimated error body {fmt(e['body'])}, tension {fmt(e['tension'])}"
