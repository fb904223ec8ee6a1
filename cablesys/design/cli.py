"""The ``cablesys design`` sub-command: the isolation-design NLP for a scene with a ``[design]`` table."""

from __future__ import annotations

import json
import sys


def register(sub) -> None:
    """Add ``design SCENE.toml [--out DIR]`` to the cablesys parser."""
    p = sub.add_parser("design", help="tune AE and C_I of each cable section (dual-isolation NLP, IPOPT)",
                       description="Minimize the lower body's vertical significant amplitude (or its band RAO) "
                                   "in the sea state of the scene's [design] table, over AE and C_I per section "
                                   "within the given bounds, with no-slack, working-load and static-strain "
                                   "constraints (Wang 1971 p. 33, dual isolation). Writes design.json.")
    p.add_argument("scene", help="scene TOML file with a [design] table (keys of cablesys.design.DesignSettings)")
    p.add_argument("--out", default="design_out", help="output directory (default: design_out)")
    p.add_argument("--overwrite", action="store_true", help="replace results of another scene in --out")
    p.set_defaults(func=run)


def load(path) -> tuple:
    """(scene, settings) from a scene TOML file with a ``[design]`` table."""
    from ..errors import ParameterError
    from ..reader import located, read_toml
    from ..scene import scene_from_dict
    from .problem import settings_from_dict

    data, source = read_toml(path, "scene file")
    table = data.pop("design", None)
    if table is None:
        raise located(ParameterError("design", "missing", "the scene file needs a [design] table with ae_bounds "
                                     "and damping_bounds"), source)
    return scene_from_dict(data, source), settings_from_dict(table, source)


def run(args) -> int:
    from ..outputs import OutputDir
    from .solve import design

    scene, settings = load(args.scene)
    # --out checked before any work; summary.json says running / success / failed / interrupted
    outdir = OutputDir(args.out, "design", {"scene": scene, "design": settings},
                       overwrite=getattr(args, "overwrite", False), owned=("design.json",))
    with outdir.start(scene=scene.name):
        result = design(scene, settings)
        out = outdir.path
        doc = {"scene": scene.name, **result.to_dict()}
        outdir.write_text("design.json", json.dumps(doc, indent=2, default=float) + "\n")
        outdir.finish("success" if result.converged else "failed", message=str(result.status))
    w = sys.stdout.write
    w(f"{scene.name}\n{'converged' if result.converged else 'NOT converged'} ({result.status}); "
      f"{result.nlp_iterations} IPOPT iterations in {result.nlp_wall_s:.2f} s (total {result.total_wall_s:.2f} s)\n")
    w(f"objective ({result.objective_kind}): {result.objective:.6g}\n")
    for name, v, lo, hi in zip(result.variable_names, result.values, result.lower, result.upper):
        w(f"  {name:<20s} {v:12.5g}   [{lo:.4g}, {hi:.4g}]\n")
    w("constraint margins (>= 0 met): " + ", ".join(f"{k} {v:+.3g}" for k, v in result.margins.items()) + "\n")
    w(f"active: {', '.join(result.active) or 'none'}\nwrote {out / 'design.json'}\n")
    return 0 if result.converged else 1
