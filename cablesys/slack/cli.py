"""The ``cablesys slack`` sub-command: a user's own cable from a TOML scene."""

from __future__ import annotations

import json
import logging
import sys

from ..errors import ParameterError

log = logging.getLogger(__name__)


def register(sub) -> None:
    """Add ``slack SCENE.toml [--out DIR] [--example]`` to the cablesys parser."""
    p = sub.add_parser("slack", help="slack cable: equilibrium, tensions, natural modes (Griffin & Rosenthal 1985)",
                       description="Static equilibrium and linear natural modes of a slack extensible cable "
                                   "with point masses, in air or water. SCENE.toml is in SI units; "
                                   "see `cablesys slack --example` for every field.")
    p.add_argument("scene", nargs="?", help="scene TOML file")
    p.add_argument("--out", default="slack_out", help="output directory (default: slack_out)")
    p.add_argument("--example", action="store_true", help="print an example scene TOML and exit")
    p.add_argument("--overwrite", action="store_true", help="replace results of another scene in --out")
    p.set_defaults(func=run)


def run(args) -> int:
    from .scene import EXAMPLE_TOML, load_slack_scene
    if args.example:
        sys.stdout.write(EXAMPLE_TOML)
        return 0
    if not args.scene:
        raise ParameterError("scene", None, "a scene TOML file is required (or --example)")
    from ..outputs import OutputDir
    from .vibration import analyze
    from .plots import plot_equilibrium, plot_mode_shapes

    scene = load_slack_scene(args.scene)
    # --out checked before any work; summary.json says running / success / failed / interrupted
    outdir = OutputDir(args.out, "slack", {"scene": scene}, overwrite=getattr(args, "overwrite", False),
                       owned=("slack_result.json", "equilibrium.png", "mode_shapes.png"))
    with outdir.start(scene=str(args.scene)):
        res = analyze(scene)
        eq, modes = res.equilibrium, res.modes
        _check_strain(scene, eq)
        out = outdir.path
        doc = {"scene": str(args.scene), "medium": scene.medium, "n_elements": modes.n_elements,
               "units": {"omega_rad_s": "rad/s", "s_m": "m", "x_m": "m", "z_m": "m", "element_tension_N": "N",
                         "shapes": "kg^-1/2 m"},
               "equilibrium": eq.to_dict(), "modes": modes.table(),
               "mode_shapes": {"s_m": modes.s.tolist(), "dof": ["x", "y", "z"],
                               "normalization": "Griffin & Rosenthal (1985) eq. 25",
                               "shapes": modes.shapes.tolist()}}
        outdir.write_text("slack_result.json", json.dumps(doc, indent=1))
        with outdir.writing("equilibrium.png") as tmp:
            plot_equilibrium(eq, tmp)
        with outdir.writing("mode_shapes.png") as tmp:
            plot_mode_shapes(eq, modes, tmp, n=min(6, scene.n_modes))
    lines = [f"sag/L = {eq.sag_to_length:.6g}, H = {eq.horizontal_tension:.6g} N, "
             f"max tension = {eq.tension.max():.6g} N",
             "mode  type  omega (rad/s)"]
    lines += [f"{k + 1:4d}  {t:>4s}  {w:.6g}" for k, (t, w) in enumerate(zip(modes.mode_type, modes.omega))]
    lines.append(f"wrote {out / 'slack_result.json'}, equilibrium.png, mode_shapes.png")
    sys.stdout.write("\n".join(lines) + "\n")
    return 0


def _check_strain(scene, eq) -> None:
    """The linear-elastic model holds up to ``cable.max_strain``; a heavier load is an input error."""
    import numpy as np
    strain = float(np.max(eq.element_lengths / np.diff(eq.s) - 1.0))
    if not strain <= scene.cable.max_strain:
        raise ParameterError("cable.max_strain", scene.cable.max_strain,
                             f"the equilibrium stretches the cable by {strain:.4g}, beyond its allowed strain: the "
                             "weights and masses are too large for this cable's EA (or raise max_strain)")
