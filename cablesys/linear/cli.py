"""The ``cablesys rao`` sub-command: steady state, natural frequencies and RAO tables of a scene."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np


def register(sub) -> None:
    """Add ``rao SCENE.toml [--out DIR] [--omega-max W] [--n N]`` to the cablesys parser."""
    p = sub.add_parser("rao", help="linearize about the steady state: natural frequencies and RAOs (CSV + plots)",
                       description="Steady state, exact linearization, natural modes and RAOs of x_b, y_b, phi, u "
                                   "and tension per unit top motion in x and y. With a one-frequency top motion in "
                                   "the scene, also the describing-function RAO at that motion's amplitude.")
    p.add_argument("scene", help="scene TOML file")
    p.add_argument("--out", default="rao_out", help="output directory (default: rao_out)")
    p.add_argument("--omega-max", type=float, default=None, help="largest frequency in rad/s (default: 3 x pendulum)")
    p.add_argument("--n", type=int, default=400, help="number of frequencies (default: 400)")
    p.set_defaults(func=run)


def run(args) -> int:
    from ..errors import ParameterError, SolverError
    from ..model import build_model
    from ..scene import load_scene
    from .equivalent import harmonic_response
    from .linearize import linearize
    from .modal import modes as modes_of
    from .periodic import scene_input_amplitude
    from .plots import plot_modes, plot_rao_bode
    from .frequency_response import rao

    scene = load_scene(args.scene)
    if args.n < 2:
        raise ParameterError("--n", args.n, "must be >= 2")
    model = build_model(scene)
    p = model.parameters(scene)
    lin = linearize(model, p)
    md = modes_of(lin)
    w_max = args.omega_max or 3.0 * float(np.min(md.omega_undamped))
    omega = np.linspace(w_max / args.n, w_max, args.n)
    raos = {"exact linearization": rao(lin, omega)}
    try:
        w_s, Z = scene_input_amplitude(scene)
        for k, inp in enumerate(("x_s", "y_s")):
            if abs(Z[k]) > 0:
                Zk = np.zeros_like(Z)
                Zk[k] = abs(Z[k])
                h = harmonic_response(model, p, omega, Zk)
                raos[f"describing function, |{inp}| = {abs(Z[k]):.3g} m"] = h.rao(label=inp)
    except SolverError:
        pass
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    natural = {f"omega_{d}": float(w) for d, w in zip(md.dominant, md.omega_undamped) if w <= w_max}
    written = []
    for name, r in raos.items():
        tag = "exact" if name.startswith("exact") else "describing"
        for inp in r.input_labels[:2]:
            head, rows = r.table(inp)
            f = out / f"rao_{tag}_{inp}.csv"
            np.savetxt(f, rows, delimiter=",", header=",".join(head), comments="", fmt="%.8g")
            written.append(f.name)
    for inp in ("x_s", "y_s"):
        for o in ("x_b", "y_b", "tension"):
            sel = {k: r for k, r in raos.items() if inp in r.input_labels}
            written.append(plot_rao_bode(sel, o, inp, natural, out / f"rao_{o}_{inp}.png",
                                         title=f"{scene.name}: {o} per unit {inp}").name)
    written.append(plot_modes(md, float(lin.y0[model.output_labels.index("y_b")]), out / "modes.png").name)
    doc = {"scene": scene.name, "steady_state": dict(zip(lin.q_labels, lin.q0.tolist())),
           "natural_frequencies_rad_s": md.omega_undamped.tolist(), "mode_dominant": list(md.dominant),
           "damping_ratios_exact": md.damping_ratio.tolist()}
    (out / "rao_summary.json").write_text(json.dumps(doc, indent=1))
    lines = [f"{scene.name}: natural frequencies " + ", ".join(f"{d} {w:.5g} rad/s" for d, w in
                                                              zip(md.dominant, md.omega_undamped)),
             f"wrote {len(written) + 1} files to {out}"]
    sys.stdout.write("\n".join(lines) + "\n")
    return 0
