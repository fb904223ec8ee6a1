"""The segmented cable's explicit-form DAE built from its element kernel (MX, mapped over the elements) past
COMPILE_MAX_ELEMENTS: the same equations as the element-by-element SX DAE, C that grows far slower with N, and the
runs it compiles (cablesys.time_domain.integrators.kernel_dae)."""

import json

import numpy as np
import pytest

import cablesys
from cablesys.compiled import generate
from cablesys.derivatives import state_jacobian
from cablesys.examples import example_path
from cablesys.ladder.rungs import build_rung, rung_scene
from cablesys.time_domain import IntegratorSettings, Simulator
from cablesys.time_domain.dae import relative_time_dae, relative_time_jacobian
from cablesys.time_domain.initial import initial_state
from cablesys.time_domain.integrators import COMPILE_MAX_ELEMENTS, compiled_by_default, kernel_dae, kernel_dae_functions

N = COMPILE_MAX_ELEMENTS + 4


@pytest.fixture(scope="module")
def heave():
    scene = cablesys.load_scene(example_path("heave_300m.toml"))
    sc = rung_scene(scene, "segmented", N)
    model = build_rung(scene, "segmented", N)
    p = np.asarray(model.parameters(sc), dtype=float).ravel()
    return sc, model, p, np.asarray(initial_state(sc, model, p), dtype=float).ravel()


@pytest.mark.parametrize("scaled", [False, True])
def test_kernel_dae_and_its_jacobian_equal_the_elementwise_ones(heave, scaled):
    sc, model, p, x0 = heave
    x = x0 + 1e-3 * np.random.default_rng(1).standard_normal(x0.size) * np.maximum(np.abs(x0), 1.0)
    args = (0.37, x, [], np.concatenate([p, [2.0, 0.5]]), [])
    sx, mx = relative_time_dae(model, False, scaled), relative_time_dae(model, False, scaled, kernel=True)
    assert mx.is_a("MXFunction") and not sx.is_a("MXFunction")
    a, b = np.asarray(sx(*args)[0]).ravel(), np.asarray(mx(*args)[0]).ravel()
    assert np.max(np.abs(a - b)) <= 1e-10 * np.max(np.abs(a))
    Jsx, Jmx = state_jacobian(sx, ("x",)), state_jacobian(mx, ("x",))
    k = Jsx.name_out().index("jac_ode_x")                              # the state block (the others are zero)
    da, db = (np.asarray(J(*args, *f(*args))[k].full()) for J, f in ((Jsx, sx), (Jmx, mx)))
    assert np.max(np.abs(da)) > 0.0 and np.max(np.abs(da - db)) <= 1e-9 * np.max(np.abs(da))
    # the Jacobian compiled beside the kernel DAE (the chain rule over the elements) is AD's, in the same signature
    chain = relative_time_jacobian(model, mx, scaled)
    assert chain.name() == Jmx.name() and chain.name_in() == Jmx.name_in() and chain.name_out() == Jmx.name_out()
    jc = chain(*args, *mx(*args))
    dc = np.asarray(jc[k].full())
    assert np.max(np.abs(da - dc)) <= 1e-9 * np.max(np.abs(da))
    assert all(jc[i].nnz() == 0 for i in range(len(jc)) if i != k)     # the other blocks structurally zero


def test_kernel_c_grows_far_slower_with_n(heave):
    _, model, _, _ = heave
    ratio = len(generate([relative_time_dae(model, False, True)], jacobians=("x", "z"))) / len(
        generate(kernel_dae_functions(model, True), jacobians=False))
    assert ratio > 3.0          # what each compiles: the SX DAE and AD's Jacobian, the kernel DAE and the chain rule's


def test_the_choice_needs_a_compiler_an_explicit_form_and_the_kernel(heave, monkeypatch):
    _, model, _, _ = heave
    monkeypatch.setenv("CABLESYS_COMPILE", "1")
    assert kernel_dae(model, implicit=False) and not kernel_dae(model, implicit=True)
    assert compiled_by_default(model, "cvodes-bdf2") and not compiled_by_default(model, "idas")
    small = build_rung(heave[0], "segmented", 4)
    assert not kernel_dae(small, implicit=False)          # up to COMPILE_MAX_ELEMENTS: the element-wise SX C
    monkeypatch.setenv("CABLESYS_COMPILE", "0")
    assert not kernel_dae(model, implicit=False)


def test_a_compiled_run_equals_the_vm_run(heave, compiling):
    sc, model, p, x0 = heave
    times = np.linspace(0.0, 12.0, 49)
    runs = [Simulator(model, times, IntegratorSettings(method="cvodes-bdf2", rtol=1e-9, atol=1e-10, compiled=c)).run(p, x0)
            for c in (False, True)]
    assert all(r.success for r in runs)
    for lbl in ("y_b", "tension_top"):
        a, b = np.asarray(runs[0][lbl]), np.asarray(runs[1][lbl])
        assert np.max(np.abs(a - b)) <= 1e-4 * np.max(np.abs(a)), lbl


def test_the_kernel_dae_benchmark_runs_quick(run_study):
    out = run_study("bench_kernel_dae", "--quick")
    (row,) = json.loads((out / "bench_kernel_dae.json").read_text())["rows"]
    assert row["kernel_dae"] and row["success"] and row["c_bytes_kernel"] < row["c_bytes_elementwise"]
    assert row["max_diff_tension_top_rel"] < 1e-2 and (out / "bench_kernel_dae.png").stat().st_size > 10_000
