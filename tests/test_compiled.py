"""Compiled model functions: on-disk cache, reuse across structures' values, fallback without a compiler."""

import logging
import subprocess
import sys
import textwrap

import casadi as ca
import numpy as np
import pytest

from cablesys.compiled import cache_dir, compile_functions


def _pendulum():
    x, t, p = ca.SX.sym("x", 2), ca.SX.sym("t"), ca.SX.sym("p", 2)
    return ca.Function("pendulum_rhs", [x, t, p], [ca.vertcat(x[1], -p[0] * ca.sin(x[0]) - p[1] * x[1])])


@pytest.fixture
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("CABLESYS_CACHE", str(tmp_path / "cache"))
    monkeypatch.delenv("CABLESYS_CACHE_DIR", raising=False)
    monkeypatch.setenv("CABLESYS_CFLAGS", "-O0")
    monkeypatch.delenv("CABLESYS_CC", raising=False)
    monkeypatch.delenv("CABLESYS_COMPILE", raising=False)
    return tmp_path / "cache"


def test_compiled_equals_virtual_machine_and_is_cached(cache):
    f = _pendulum()
    first = compile_functions([f])
    assert first.compiled and not first.cached and first.library.exists()
    assert first.library.parent == cache_dir() and str(cache) in str(cache_dir())
    g = first.functions["pendulum_rhs"]
    args = ([0.3, -0.2], 0.0, [9.81, 0.1])
    assert np.allclose(np.array(g(*args)), np.array(f(*args)), rtol=1e-15, atol=0)
    # the Jacobian comes from the library too (jac_pendulum_rhs) and is exact
    xs = ca.MX.sym("x", 2)
    J = ca.Function("J", [xs], [ca.jacobian(g(xs, 0.0, ca.DM([9.81, 0.1])), xs)])
    assert np.allclose(np.array(J([0.3, -0.2])), [[0, 1], [-9.81 * np.cos(0.3), -0.1]], rtol=1e-14)
    second = compile_functions([_pendulum()])
    assert second.cached and second.library == first.library
    # a different structure is a different library
    x = ca.SX.sym("x")
    other = compile_functions([ca.Function("pendulum_rhs", [x], [x ** 3])])
    assert other.library != first.library


def test_no_compiler_falls_back_with_one_warning(cache, monkeypatch, caplog):
    monkeypatch.setenv("CABLESYS_CC", "/nonexistent/bin/cc-missing")
    f = _pendulum()
    with caplog.at_level(logging.WARNING, logger="cablesys.compiled"):
        out = compile_functions([f])
    assert not out.compiled and out.functions["pendulum_rhs"] is f
    notes = [r for r in caplog.records if r.name == "cablesys.compiled"]
    assert len(notes) == 1 and "virtual machine" in notes[0].getMessage()


def test_failing_compiler_falls_back_and_leaves_no_library(cache, monkeypatch, caplog):
    monkeypatch.setenv("CABLESYS_CC", "false")          # a compiler that exists and always fails
    f = _pendulum()
    with caplog.at_level(logging.WARNING, logger="cablesys.compiled"):
        out = compile_functions([f])
    assert not out.compiled and out.functions["pendulum_rhs"] is f
    assert any("compilation failed" in r.getMessage() for r in caplog.records)
    assert not list(cache_dir().glob("*.so")) and not list(cache_dir().glob(".build-*"))


def test_concurrent_builds_share_one_library(cache):
    code = textwrap.dedent("""
        import casadi as ca, numpy as np
        from cablesys.compiled import compile_functions
        x = ca.SX.sym("x", 3)
        out = compile_functions([ca.Function("shared_f", [x], [ca.sin(x) * ca.exp(x)])])
        assert out.compiled
        print(out.library, float(out.functions["shared_f"]([1, 2, 3])[2]))
    """)
    procs = [subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
             for _ in range(3)]
    outs = [p.communicate(timeout=300) for p in procs]
    assert all(p.returncode == 0 for p in procs), [o[1][-1000:] for o in outs]
    libs = {o[0].split()[0] for o in outs}
    assert len(libs) == 1 and all(float(o[0].split()[1]) == pytest.approx(np.sin(3) * np.exp(3)) for o in outs)
    assert not list(cache_dir().glob(".build-*"))          # no temporary files left behind


@pytest.mark.parametrize("method", ["cvodes", "idas"])
def test_simulation_compiled_agrees_with_virtual_machine(cache, method):
    from cablesys.model import build_model
    from cablesys.scene import dale_scene
    from cablesys.time_domain import Simulator, simulate
    from cablesys.time_domain.integrators import IntegratorSettings
    scene = dale_scene().with_numerics(duration=3.0, drag_segments=2)
    model = build_model(scene)
    res = {}
    for compiled in (True, False):
        sim = Simulator(model, scene.output_times, IntegratorSettings(method=method, rtol=1e-9, atol=1e-11,
                                                                        compiled=compiled))
        res[compiled] = simulate(scene, model=model, simulator=sim)
        assert res[compiled].success and res[compiled].stats["compiled"] is compiled
    for lbl in ("phi", "u", "x_b"):
        a, b = res[True][lbl], res[False][lbl]
        assert np.max(np.abs(a - b)) < 1e-6 * (1e-3 + np.max(np.abs(b)))
    st = res[True].stats
    assert {"build_s", "load_s", "run_s"} <= set(st) and st["load_s"] >= 0.0


def test_run_summary_reports_build_load_and_run_time(cache, tmp_path):
    import json

    from cablesys.cli import main
    from cablesys.scene import dale_scene, dump_scene
    f = tmp_path / "dale.toml"
    f.write_text(dump_scene(dale_scene(duration=2.0, output_step=0.1)))
    for out in (tmp_path / "first", tmp_path / "second"):          # the second run loads the cached library
        assert main(["run", str(f), "--out", str(out)]) == 0
        timing = json.loads((out / "summary.json").read_text())["timing"]
        assert set(timing) == {"build_s", "load_s", "run_s"} and all(v >= 0.0 for v in timing.values())
    assert len(list(cache_dir().glob("*.so"))) >= 1


def _heavier(scene, factor=1.3):
    """The same structure with another body weight."""
    import dataclasses
    sec = scene.sections[0]
    body = dataclasses.replace(sec.body, weight=factor * sec.body.weight)
    return dataclasses.replace(scene, sections=(dataclasses.replace(sec, body=body),) + scene.sections[1:])


def test_second_start_loads_the_stored_model_and_library_without_building(cache, monkeypatch):
    """A second build of the same structure (other values) comes from the disk; its compiled DAE
    is found by the structure index (no graph built, no compiler run) and runs identically."""
    from cablesys.compiled import DerivedStore
    from cablesys.model import build_model
    from cablesys.scene import dale_scene
    from cablesys.time_domain import Simulator, simulate
    from cablesys.time_domain.integrators import IntegratorSettings
    scene = dale_scene().with_numerics(duration=2.0, drag_segments=2)
    first = build_model(scene)
    assert first.build_info["stored"] is False and isinstance(first.cache.store, DerivedStore)
    settings = IntegratorSettings(rtol=1e-9, atol=1e-11)
    ref = simulate(scene, model=first, simulator=Simulator(first, scene.output_times, settings))
    libraries = sorted(cache_dir().glob("*.so"))
    heavier = _heavier(scene)                               # same structure, other values
    second = build_model(heavier)
    assert second.build_info["stored"] is True
    assert second.build_info["structure_key"] == first.build_info["structure_key"]
    sim = Simulator(second, scene.output_times, settings)
    assert sim.compiled.compiled and sim.compiled.cached and second.cache.hits >= 2   # the DAE and the output functions
    assert sorted(cache_dir().glob("*.so")) == libraries                                 # nothing compiled
    again = simulate(scene, model=second, simulator=sim)
    for lbl in ("phi", "u", "x_b", "tension_mid"):
        assert np.array_equal(again[lbl], ref[lbl])          # the same machine code on the same numbers
    # the stored functions are CasADi's exact graphs: equal to a fresh symbolic build in the VM
    x = np.array([0.1, 0.2, 0.01, -0.02])
    p = second.parameters(heavier)
    monkeypatch.setenv("CABLESYS_COMPILE", "0")
    fresh = build_model(heavier)
    assert fresh.build_info["stored"] is False
    assert np.array_equal(np.array(second.ode(x, 0.7, p)), np.array(fresh.ode(x, 0.7, p)))
    # each stored function is deserialized on first use: a run never asked for the energy
    assert "energy" not in vars(second) and "ode" in vars(second)
    e = np.array(second.top(0.7, p)).ravel()
    assert all(np.array_equal(np.array(a), np.array(b)) for a, b in zip(second.energy(x, e, p), fresh.energy(x, e, p)))
    assert "energy" in vars(second) and second.energy is second.energy


def test_structure_key_follows_structure_not_values():
    from cablesys.ladder.rungs import with_segments
    from cablesys.model.store import structure_key
    from cablesys.scene import dale_scene
    scene = dale_scene()
    key = structure_key(scene)
    assert structure_key(_heavier(scene, 2.0)) == key
    assert structure_key(scene.with_numerics(drag_segments=3)) != key
    assert structure_key(with_segments(scene, 4)) != key


def test_corrupt_entries_are_detected_and_rebuilt(cache, caplog):
    from cablesys.model import build_model
    from cablesys.scene import dale_scene
    scene = dale_scene().with_numerics(drag_segments=2)
    model = build_model(scene)
    stored = next(cache_dir().glob("models/*.model"))
    stored.write_bytes(stored.read_bytes()[:-100])                 # truncated
    with caplog.at_level(logging.WARNING):
        again = build_model(scene)
    assert again.build_info["stored"] is False and "unreadable" in caplog.text
    assert build_model(scene).build_info["stored"] is True        # rewritten whole
    x, p = np.array([0.1, 0.2, 0.0, 0.0]), model.parameters(scene)
    assert np.array_equal(np.array(again.ode(x, 0.0, p)), np.array(model.ode(x, 0.0, p)))
    # a library that does not load is removed and built again (a garbage file where the library
    # of a function never loaded in this process is expected: rewriting a loaded one would fault)
    from cablesys.compiled import _compiler_identity, cache_key, compiler_command
    x = ca.SX.sym("x", 2)
    f = ca.Function("corrupt_check", [x], [ca.vertcat(x[1], -x[0])])
    ser = [f.serialize()]
    cmd = compiler_command(len(ser[0]))
    target = cache_dir() / f"{cache_key(ser, True, _compiler_identity(cmd), cmd)}.so"
    target.write_bytes(b"\x7fELF garbage")
    with caplog.at_level(logging.WARNING):
        out = compile_functions([f])
    assert out.compiled and not out.cached and out.library == target and "does not load" in caplog.text
    assert np.array_equal(np.array(out.functions["corrupt_check"]([1.0, 2.0])).ravel(), [2.0, -1.0])


def test_eviction_removes_least_recently_used_first(cache, monkeypatch):
    import os

    from cablesys.disk_cache import cap_bytes, evict
    from cablesys.errors import ParameterError
    folder = cache_dir()
    folder.mkdir(parents=True)
    files = []
    for k in range(4):                                       # 4 entries of 1000 bytes, used at t = k
        f = folder / f"entry{k}.so"
        f.write_bytes(b"x" * 1000)
        os.utime(f, (1000 + k, 1000 + k))
        files.append(f)
    os.utime(files[0], (2000, 2000))                         # entry0 used last
    locks = [f.with_suffix(".lock") for f in files]
    for lock in locks:
        lock.touch()
    removed = evict(cap=2500)
    assert set(removed) == {files[1], files[2]}             # the two least recently used
    assert files[0].exists() and files[3].exists()
    assert [lock.exists() for lock in locks] == [True, False, False, True]     # with their build locks
    monkeypatch.setenv("CABLESYS_CACHE_MB", "0.0015")
    assert cap_bytes() == 1500 and evict(keep=[files[3]]) == [files[0]]
    monkeypatch.setenv("CABLESYS_CACHE_MB", "inf")
    assert cap_bytes() > 1e18
    for bad in ("-1", "nan", "lots"):
        monkeypatch.setenv("CABLESYS_CACHE_MB", bad)
        with pytest.raises(ParameterError, match="CABLESYS_CACHE_MB"):
            cap_bytes()


def test_simulate_without_a_compiler_runs_in_the_virtual_machine(cache, monkeypatch, caplog):
    """The default (compiled) path on a machine with no C compiler: one notice, same results."""
    from cablesys.scene import dale_scene
    from cablesys.time_domain import simulate
    monkeypatch.setenv("CABLESYS_CC", "cc-not-installed-anywhere")
    scene = dale_scene().with_numerics(duration=1.0, drag_segments=2)
    with caplog.at_level(logging.WARNING, logger="cablesys.compiled"):
        res = simulate(scene)
    assert res.success and res.stats["compiled"] is False
    notes = {r.getMessage() for r in caplog.records if r.name == "cablesys.compiled"}
    assert len(notes) == 1 and "no C compiler" in notes.pop()
    assert not list(cache_dir().glob("*.so"))


@pytest.mark.filterwarnings("ignore:model 'frequency'")     # forced outside its validity: warned, as it should
def test_run_summary_timing_of_the_frequency_rung(cache, tmp_path, monkeypatch):
    """The frequency rung has no time-domain run: its summary reports the ladder's build and run."""
    import json

    from cablesys.cli import main
    from cablesys.scene import dale_scene, dump_scene
    monkeypatch.setenv("CABLESYS_COMPILE", "0")
    f = tmp_path / "dale.toml"
    f.write_text(dump_scene(dale_scene(duration=2.0, output_step=0.1)))
    assert main(["run", str(f), "--model", "frequency", "--out", str(tmp_path / "out")]) == 0
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    timing, ladder = summary["timing"], summary["stats"]["ladder_timing"]
    assert set(timing) == {"build_s", "load_s", "run_s"}
    assert timing["run_s"] == ladder["run_s"] > 0.0 and timing["build_s"] == ladder["build_s"] >= 0.0


def test_cache_folder_is_versioned_and_overridable(tmp_path, monkeypatch):
    from cablesys import __version__
    from cablesys.disk_cache import CACHE_FORMAT, cache_root
    monkeypatch.delenv("CABLESYS_CACHE", raising=False)
    monkeypatch.setenv("CABLESYS_CACHE_DIR", str(tmp_path / "old-name"))
    assert cache_root() == tmp_path / "old-name"                     # the former setting still works
    monkeypatch.setenv("CABLESYS_CACHE", str(tmp_path / "new"))
    assert cache_root() == tmp_path / "new"                          # and CABLESYS_CACHE wins
    assert cache_dir() == tmp_path / "new" / f"cablesys-{__version__}_casadi-{ca.__version__}_v{CACHE_FORMAT}"


def test_concurrent_first_starts_share_one_stored_model(cache):
    """Processes of a sweep starting one structure together on an empty cache: every one gets a
    working model, one stored entry results, and a later start loads it."""
    code = textwrap.dedent("""
        import numpy as np
        from cablesys.model import build_model
        from cablesys.scene import dale_scene
        scene = dale_scene().with_numerics(drag_segments=2)
        m = build_model(scene)
        print(float(np.array(m.ode([0.1, 0.2, 0.0, 0.0], 0.5, m.parameters(scene)))[2, 0]), m.build_info["structure_key"])
    """)
    procs = [subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
             for _ in range(3)]
    outs = [p.communicate(timeout=300) for p in procs]
    assert all(p.returncode == 0 for p in procs), [o[1][-1000:] for o in outs]
    assert len({o[0].strip() for o in outs}) == 1                      # the same numbers and structure key
    key = outs[0][0].split()[1]
    assert [f.name for f in cache_dir().glob("models/*.model")] == [f"{key}.model"]
    assert not [f for f in cache_dir().rglob("*.tmp*")]                 # no temporary file left behind
    from cablesys.disk_cache import code_fingerprint
    from cablesys.model import build_model
    from cablesys.scene import dale_scene
    code_fingerprint.cache_clear()           # this process's fingerprint may predate an edit in a shared tree
    again = build_model(dale_scene().with_numerics(drag_segments=2))
    assert again.build_info["structure_key"] == key and again.build_info["stored"] is True


def test_quasi_static_rung_is_stored_with_its_iterations(cache, monkeypatch):
    """The quasi-static reduction is stored like build_model's models; its unrolled Newton
    iterations (chosen from the scene's values) are part of the key."""
    from cablesys.model.quasistatic import build_quasistatic
    from cablesys.scene import dale_scene
    scene = dale_scene().with_numerics(drag_segments=2)
    first = build_quasistatic(scene)
    again = build_quasistatic(scene)
    assert not first.build_info["stored"] and again.build_info["stored"] and again.kind == "quasi-static"
    other = build_quasistatic(scene, iterations=7)
    assert other.build_info["structure_key"] != first.build_info["structure_key"]
    monkeypatch.setenv("CABLESYS_COMPILE", "0")
    fresh = build_quasistatic(scene)
    x, p = np.array([0.1, 0.02]), again.parameters(scene)
    assert np.array_equal(np.array(again.ode(x, 0.3, p)), np.array(fresh.ode(x, 0.3, p)))


def test_stored_segmented_model_keeps_every_function(cache, monkeypatch):
    """A loaded segmented model has all its functions, including ``accel``, a field with a default (a
    class attribute that a lazy load must not expose as None), equal to a fresh build's."""
    from cablesys.ladder.rungs import with_segments
    from cablesys.model import build_model
    from cablesys.scene import dale_scene
    scene = with_segments(dale_scene().with_numerics(duration=1.0), 3)
    first = build_model(scene)
    second = build_model(scene)
    assert first.build_info["stored"] is False and second.build_info["stored"] is True
    nq = 2 * 3
    q, qd = np.linspace(0.1, 0.6, nq), np.linspace(-0.2, 0.2, nq)
    p = second.parameters(scene)
    e = np.array(second.top(0.3, p)).ravel()
    assert isinstance(second.accel, ca.Function)
    assert np.array_equal(np.array(second.accel(q, qd, e, p)), np.array(first.accel(q, qd, e, p)))


def test_large_segmented_models_compile_their_element_kernel_by_default(cache, monkeypatch):
    """simulate() compiles the element-by-element code up to COMPILE_MAX_ELEMENTS elements; above, gcc's minutes
    and gigabytes over it are not spent: the explicit-form DAE is compiled from the mapped element kernel (one
    library, :func:`~cablesys.time_domain.integrators.kernel_dae`), and the implicit form, which has no kernel,
    runs in the VM (the same rule as the ladder's). The output functions are compiled while their C is predicted
    small (HELPERS_MAX_C_BYTES), else they stay in the VM."""
    from cablesys.ladder.rungs import with_segments
    from cablesys.scene import dale_scene
    from cablesys.time_domain import integrators, simulate
    from cablesys.time_domain.integrators import COMPILE_MAX_ELEMENTS
    scene = dale_scene().with_numerics(duration=0.1, output_step=0.05)
    big = with_segments(scene, COMPILE_MAX_ELEMENTS + 1)
    limit = integrators.HELPERS_MAX_C_BYTES
    monkeypatch.setattr(integrators, "HELPERS_MAX_C_BYTES", 0)      # outputs predicted too large: the VM
    implicit = simulate(big, method="idas")
    assert implicit.success and implicit.stats["compiled"] is False
    assert not list(cache_dir().glob("*.so"))                  # nothing was handed to the compiler
    explicit = simulate(big, method="cvodes")
    assert explicit.success and explicit.stats["compiled"] is True
    assert len(list(cache_dir().glob("*.so"))) == 1            # the kernel DAE alone (outputs in the VM)
    monkeypatch.setattr(integrators, "HELPERS_MAX_C_BYTES", limit)
    assert simulate(big, method="cvodes").success
    assert len(list(cache_dir().glob("*.so"))) == 2            # and the outputs' library, predicted small
    np.testing.assert_allclose(explicit["y_b"], implicit["y_b"], rtol=1e-5)
    small = simulate(with_segments(scene, 2))
    assert small.success and small.stats["compiled"] is True


def test_the_kernel_dae_compiles_at_least_at_O1_up_to_its_cap(monkeypatch):
    """The element-kernel DAE's C grows with N past the size rule's -O1 limit (2.05 MB at N = 56 planar), where -O0
    made each step 2-3x dearer: it gets -O1 there, up to KERNEL_O1_MAX_BYTES; elsewhere the size rule's flag."""
    from cablesys.compiled import SIZE_FLAGS, compiler_command
    from cablesys.time_domain.integrators import KERNEL_O1_MAX_BYTES, kernel_dae_optimization
    monkeypatch.delenv("CABLESYS_CFLAGS", raising=False)      # the user's flags win over both rules
    o1_limit = next(limit for limit, flag in SIZE_FLAGS if flag == "-O1")
    for size in (1_000, o1_limit - 1):           # -O2 / -O1 by size: never lowered
        assert kernel_dae_optimization(size) is None
    for size in (o1_limit, 2_050_000, KERNEL_O1_MAX_BYTES):
        assert kernel_dae_optimization(size) == "-O1"
        assert "-O1" in compiler_command(size, kernel_dae_optimization(size))
    assert kernel_dae_optimization(KERNEL_O1_MAX_BYTES + 1) is None      # the compiler's memory: the size rule
    assert "-O0" in compiler_command(KERNEL_O1_MAX_BYTES + 1, kernel_dae_optimization(KERNEL_O1_MAX_BYTES + 1))


def test_the_rk_loop_of_a_large_segmented_model_compiles_its_kernel_alone(cache, monkeypatch):
    """Past COMPILE_MAX_ELEMENTS the fixed-step RK4 loop still compiles: it steps the mapped element
    kernel, whose C does not grow with N; the output functions, which do, stay in the VM once predicted past
    HELPERS_MAX_C_BYTES (here: set to 0). The compiled run gives the VM run's states."""
    from cablesys.ladder.rungs import with_segments
    from cablesys.model import build_model
    from cablesys.scene import dale_scene
    from cablesys.time_domain import IntegratorSettings, Simulator, simulate
    from cablesys.time_domain.integrators import (
        COMPILE_MAX_ELEMENTS,
        compiled_by_default,
    )
    from cablesys.time_domain import integrators
    monkeypatch.setattr(integrators, "HELPERS_MAX_C_BYTES", 0)
    scene = with_segments(dale_scene().with_numerics(duration=0.02, output_step=0.01, steps_per_output=160),
                          COMPILE_MAX_ELEMENTS + 1)
    model = build_model(scene)
    assert compiled_by_default(model, "rk") and not compiled_by_default(model, "idas")
    run = simulate(scene, model=model, method="rk")
    assert run.success and run.stats["compiled"] is True
    assert len(list(cache_dir().glob("*.so"))) == 1              # the loop alone
    ref = Simulator(model, scene.output_times, IntegratorSettings(method="rk", steps_per_output=160, compiled=False))
    x_vm = ref.run(model.parameters(scene), run.states[:, 0]).states
    np.testing.assert_allclose(run.states, x_vm, rtol=1e-9, atol=1e-12)


def test_code_too_large_for_a_compiler_run_stays_in_the_vm(cache, monkeypatch, caplog):
    """Generated C above MAX_C_BYTES is not handed to the compiler (its memory grows with the code: a 120 MB
    dense Jacobian ran cc1 out of memory): the functions run in CasADi's VM, with one logged reason."""
    import logging

    import cablesys.compiled as C
    monkeypatch.setattr(C, "MAX_C_BYTES", 1000)
    f = _pendulum()
    with caplog.at_level(logging.WARNING, logger="cablesys.compiled"):
        out = compile_functions([f])
    assert not out.compiled and out.functions["pendulum_rhs"] is f
    assert "MB of generated C" in out.note and "MB of generated C" in caplog.text
    assert not list(cache.glob("*.so"))
