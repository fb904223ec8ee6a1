"""The model ladder's stated error against the actual one, per reported quantity, on scenes it was not tuned on.

    python studies/ladder_quantities.py --out DIR [--quick]

For each scene, auto runs as a user runs it (``cablesys.simulate(scene)``) and the segmented cable at N_ref
(at least twice auto's N) is the reference. For every quantity auto reports (each body coordinate's amplitude
and mean, each tension extreme at every end and junction: :func:`cablesys.ladder.metrics.statistics`) the study
writes the actual relative error (:func:`cablesys.ladder.metrics.quantity_errors`, floors of 1 cm or a tenth of the
largest body amplitude, and 1 % of the top tension), the stated one (``model.estimated_error_per_quantity``; ``None`` where the run was not checked
a posteriori) and whether the actual one is within the tolerance and the stated one within 2x of it or above
(``stated_honest``; an actual error below RESOLVED x its tolerance counts as resolved whatever is stated).

Scenes: a wire in a sheared current surged and heaved (the surge converges slowly in N); the dual-isolation chain
(an intermediate body, heave at 0.7 rad/s); the 1000 m heavy wire (surge-dominated: a few centimetres of surge
under 1 m of heave, held to the body and tension groups, ``quantities=()``, which the per-quantity result then
judges). Writes ``ladder_quantities.json`` and ``ladder_quantities.png`` (stated against actual, per quantity).
"""

from __future__ import annotations

import dataclasses
import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import parse_args, setup_matplotlib, write_json  # noqa: E402
from _ladder_checks import QUANTITY_TOL as TOL, quantity_rows  # noqa: E402

import cablesys  # noqa: E402
from cablesys.isolation.example import dual_scene  # noqa: E402
from cablesys.ladder import metrics  # noqa: E402
from cablesys.scene import Body, Cable, Environment, Numerics, Scene, Section, TopMotion  # noqa: E402
from cablesys.scene.harmonics import Sinusoid  # noqa: E402


def sheared_scene(length: float = 150.0, duration: float = 90.0) -> Scene:
    """25 mm wire, a 4 kN sphere, current 1.2 / 0.6 / 0.1 m/s over the depth, 1.5 m surge and 1 m heave at 9 s."""
    w = 0.698
    cable = Cable(length=length, tension_ref=4000.0 + 9.8 * length, ae=4.0e7, diameter=0.025, mass_per_length=2.5,
                  weight_per_length=19.6, cd_normal=1.2, ct_tangential=0.01, internal_damping=1.2e5, tension_floor=0.0)
    body = Body(weight=4000.0, mass_x=1500.0, mass_y=1500.0, drag_area_normal=1.0, drag_area_tangential=1.0,
                axis_angle_deg=999.0)
    env = Environment(density=1025.0, current_depths=(0.0, 0.27 * length, length), current_speeds=(1.2, 0.6, 0.1))
    top = TopMotion(x=(Sinusoid(amplitude=1.5, frequency=w, phase=np.pi / 2),), y=(Sinusoid(amplitude=1.0, frequency=w),))
    return Scene(name=f"{length:g} m wire, sheared current, surge + heave at T = 9 s", sections=(Section(cable=cable, body=body),),
                 environment=env, top_motion=top, numerics=Numerics(duration=duration, output_step=0.1),
                 angles="per_section")


def chain_scene(duration: float = 120.0) -> Scene:
    """The dual-isolation chain (ship - rope - plate - rope - package) heaved 1 m at 0.7 rad/s."""
    base = dual_scene(duration=duration)
    top = TopMotion(y=(Sinusoid(amplitude=1.0, frequency=0.7),))
    return dataclasses.replace(base, name="dual-isolation chain, 1 m heave at 0.7 rad/s", top_motion=top)


def case(name: str, scene: Scene, quantities=None) -> dict:
    period = metrics.forcing_period(scene)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t0 = time.perf_counter()
        auto = cablesys.simulate(scene, quantities=quantities)
        wall = time.perf_counter() - t0
        m = auto.stats["model"]
        n_ref = max(32, 2 * int(m.get("segments") or 1))
        ref = cablesys.simulate(scene, model="segmented", segments=n_ref)
    actual = metrics.quantity_errors(metrics.statistics(auto, period), metrics.statistics(ref, period))
    stated = m.get("estimated_error_per_quantity") or {}
    rows = quantity_rows(actual, stated, quantities)
    return {"case": name, "scene": scene.name, "model": {k: m.get(k) for k in ("name", "segments", "checked")},
            "reference_segments": n_ref, "auto_wall_s": wall, "quantities_held": "all" if quantities is None
            else list(quantities), "rows": rows,
            "all_held_within_tolerance": all(r["within_tolerance"] for r in rows if r["held"]),
            "all_stated_honest": all(r["stated_honest"] is not False for r in rows)}


def plot(cases: list, path: Path) -> None:
    plt = setup_matplotlib()
    fig, ax = plt.subplots(figsize=(7.5, 6.0))
    markers = "osD^v"
    for c, mk in zip(cases, markers):
        pts = [(r["actual"], r["stated"]) for r in c["rows"] if r["stated"] is not None]
        if pts:
            a, s = np.array(pts).T
            ax.loglog(np.maximum(a, 1e-6), s, mk, alpha=0.8,
                      label=f"{c['case']}: {c['model']['name']} N = {c['model']['segments']}")
    lim = (1e-6, 1.0)
    ax.plot(lim, lim, "k-", lw=0.8, label="stated = actual")
    ax.plot(lim, (0.5e-6, 0.5), "k--", lw=0.8, label="stated = actual / 2 (the honest bound)")
    ax.axvline(TOL["body"], color="tab:red", lw=0.8, ls=":", label="body tolerance 1 %")
    ax.set(xlim=lim, ylim=(1e-5, 1.0), xlabel="actual relative error against the segmented reference",
           ylabel="stated relative error (a posteriori, per quantity)",
           title="Model ladder: stated against actual error, every reported quantity")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    from cablesys.plots import save_figure
    save_figure(fig, path)


def main(argv=None) -> int:
    args = parse_args(__doc__.splitlines()[0], argv)
    if args.quick:
        cases = [case("sheared-100m", sheared_scene(100.0, 60.0))]
    else:
        cases = [case("sheared-150m", sheared_scene(150.0, 90.0)), case("sheared-300m", sheared_scene(300.0, 120.0)),
                 case("chain", chain_scene()),
                 case("heavy1000-groups", cablesys.heavy_wire_scene(duration=120.0), quantities=())]
    write_json(args.out / "ladder_quantities.json", {"quick": args.quick, "tolerance": TOL, "cases": cases})
    plot(cases, args.out / "ladder_quantities.png")
    for c in cases:
        worst = max(c["rows"], key=lambda r: r["actual"] / r["tolerance"])
        print(f"{c['case']:18s} {c['model']['name']} N = {c['model']['segments']} ({c['auto_wall_s']:.1f} s): worst "
              f"{worst['quantity']} actual {worst['actual']:.2g} stated {worst['stated']}; held within tolerance "
              f"{c['all_held_within_tolerance']}, stated honest {c['all_stated_honest']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
