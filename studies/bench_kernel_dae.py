"""Benchmark: the segmented cable's CVODES runs past COMPILE_MAX_ELEMENTS, built from the element kernel.

    python studies/bench_kernel_dae.py --out DIR [--quick]

Past :data:`cablesys.time_domain.integrators.COMPILE_MAX_ELEMENTS` elements the node model's element-by-element
(SX) DAE and its Jacobian are megabytes of straight-line C that gcc takes minutes over, so they ran in CasADi's
virtual machine. :func:`cablesys.time_domain.integrators.kernel_dae` builds the same DAE from the element kernel
mapped over the elements (MX, :mod:`cablesys.model.segmented_kernel`) and compiles that instead. For each N this
measures, in one run and one process: the generated C of both forms (bytes), the kernel form's compile time (a
private, initially empty cache), one CVODES run of the 300 m heave example (``cablesys/data/heave_300m.toml``,
BDF order <= 2, scaled states, rtol 1e-7) in the VM and compiled, their ratio, and the largest difference of the
body heave and of the top tension between the two runs (both at the same tolerance; their difference is the
integrator's, the equations being the same to rounding: ``tests/test_kernel_dae.py``).

Writes DIR/bench_kernel_dae.json and DIR/bench_kernel_dae.png.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import parse_args, setup_matplotlib, write_json  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def measure(n: int, duration: float) -> dict:
    import cablesys
    from cablesys.compiled import generate
    from cablesys.ladder.rungs import build_rung, rung_scene
    from cablesys.time_domain import IntegratorSettings, Simulator
    from cablesys.time_domain.dae import relative_time_dae
    from cablesys.time_domain.initial import initial_state
    from cablesys.time_domain.integrators import kernel_dae, kernel_dae_functions

    scene = cablesys.load_scene(ROOT / "cablesys" / "data" / "heave_300m.toml")
    sc = rung_scene(scene, "segmented", n)
    model = build_rung(scene, "segmented", n)
    row = {"segments": n, "kernel_dae": kernel_dae(model, implicit=False)}
    row["c_bytes_elementwise"] = len(generate([relative_time_dae(model, False, True)], jacobians=("x", "z")))
    row["c_bytes_kernel"] = len(generate(kernel_dae_functions(model, True), jacobians=False))
    p = model.parameters(sc)
    x0 = initial_state(sc, model, p)
    times = np.linspace(0.0, duration, int(duration * 4) + 1)
    runs = {}
    for compiled in (False, True):
        settings = IntegratorSettings(method="cvodes-bdf2", rtol=1e-7, atol=1e-8, compiled=compiled)
        t0 = time.perf_counter()
        sim = Simulator(model, times, settings)
        build = time.perf_counter() - t0
        t0 = time.perf_counter()
        r = sim.run(p, x0)
        runs[compiled] = (r, build, time.perf_counter() - t0)
    (vm, _, vm_s), (cc, build_s, cc_s) = runs[False], runs[True]
    row.update(vm_run_s=vm_s, compiled_build_s=build_s, compiled_run_s=cc_s, speedup=vm_s / cc_s,
               success=bool(vm.success and cc.success),
               max_diff_y_b_m=float(np.max(np.abs(np.asarray(vm["y_b"]) - np.asarray(cc["y_b"])))),
               max_diff_tension_top_rel=float(np.max(np.abs(np.asarray(vm["tension_top"]) - np.asarray(cc["tension_top"])))
                                              / np.max(np.abs(np.asarray(vm["tension_top"])))))
    return row


def main(argv=None) -> int:
    args = parse_args(__doc__.splitlines()[0], argv)
    os.environ["CABLESYS_COMPILE"] = "1"
    os.environ["CABLESYS_CACHE"] = tempfile.mkdtemp(prefix="bench-kernel-dae-")   # cold: the compile is measured
    sizes = (24,) if args.quick else (24, 32, 64, 128)
    duration = 5.0 if args.quick else 40.0
    t0 = time.perf_counter()
    rows = []
    for n in sizes:
        rows.append(measure(n, duration))
        print({k: (round(v, 4) if isinstance(v, float) else v) for k, v in rows[-1].items()})
    load = os.getloadavg()
    write_json(args.out / "bench_kernel_dae.json",
               {"what": __doc__.splitlines()[0], "scene": "cablesys/data/heave_300m.toml", "duration_s": duration,
                "quick": bool(args.quick), "rows": rows, "wall_s": time.perf_counter() - t0,
                "load_average_end": list(load), "cpu_count": os.cpu_count()})
    plt = setup_matplotlib()
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    n = [r["segments"] for r in rows]
    a.loglog(n, [r["c_bytes_elementwise"] / 1e6 for r in rows], "o-", label="element by element (SX)")
    a.loglog(n, [r["c_bytes_kernel"] / 1e6 for r in rows], "s-", label="element kernel (MX, mapped)")
    a.set(xlabel="elements N", ylabel="generated C, DAE + Jacobian (MB)", title="Code size")
    a.legend()
    b.semilogx(n, [r["speedup"] for r in rows], "o-", label="VM run time / compiled kernel run time")
    b.semilogx(n, [r["compiled_build_s"] for r in rows], "s--", label="kernel build + compile (s)")
    b.set(xlabel="elements N", ylabel="ratio  /  seconds", title=f"CVODES, {duration:g} s of the 300 m heave example")
    b.axhline(1.0, color="0.6", lw=0.8)
    b.legend()
    from matplotlib.ticker import NullFormatter, ScalarFormatter
    for ax in (a, b):
        ax.set_xticks(n, [str(k) for k in n])
        ax.xaxis.set_minor_formatter(NullFormatter())
    a.yaxis.set_major_formatter(ScalarFormatter())
    a.yaxis.set_minor_formatter(NullFormatter())
    fig.savefig(args.out / "bench_kernel_dae.png", dpi=110)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
