"""Auto on scenes generated at random within ranges, against the converged segmented cable (issue 12).

Three families span the ladder: ``short`` (5-20 m stiff cable, light against its body, forcing near
the swing mode: a straight-cable rung), ``heavy`` (50-300 m steel wire weighing 0.5-3x its body,
forcing 0.3-1.6x the first string mode: the segmented cable with N > 1) and ``current`` (20-100 m,
0.3-1 m/s current). Seeds are fixed (deterministic); runs are 7 forcing periods (3 of smooth start)
in CasADi's VM. For each scene auto runs (:func:`cablesys.ladder.simulate`, with its a-posteriori
check) and states its estimate; the reference is the segmented cable at max(16, 2 N) elements, its own
convergence measured against half that N.

Three scenes also run compiled, where auto may step the quasi-static segmented cable with rk23 (COMPILED).

Checks: the actual error is within the tolerance, and the stated estimate is within a factor of 2 of
it where the error is resolved (above a tenth of the tolerance and above twice the reference's own
convergence); below that the estimate must be within the tolerance as well.
"""

import math
import shutil
import warnings

import numpy as np
import pytest
from ladder_pricing import both

from cablesys.errors import NumericalWarning
from cablesys.ladder import metrics, run_rung, simulate
from cablesys.scene import Body, Cable, Environment, Numerics, Sinusoid, TopMotion
from cablesys.scene.scene import single_section_scene

G, RHO = 9.81, 1025.0
STEEL = 7850.0
RESOLVED_FRACTION = 0.1


def random_scene(rng: np.random.Generator, kind: str):
    """A steel wire and a sphere (density 2000 kg/m^3) of family ``kind`` (module docstring)."""
    if kind == "short":
        length, m_b, ratio_w = rng.uniform(5.0, 20.0), rng.uniform(50.0, 200.0), rng.uniform(0.02, 0.2)
    elif kind == "heavy":
        length, m_b, ratio_w = 10 ** rng.uniform(1.7, 2.5), 10 ** rng.uniform(2.0, 3.0), 10 ** rng.uniform(-0.3, 0.5)
    else:
        length, m_b, ratio_w = 10 ** rng.uniform(1.3, 2.0), 10 ** rng.uniform(1.7, 2.7), 10 ** rng.uniform(-1.0, -0.3)
    w_b = 0.5 * m_b * G                                     # a sphere of 2000 kg/m^3 in sea water
    w_c = ratio_w * w_b
    d = math.sqrt(w_c / length / ((STEEL - RHO) * G * math.pi / 4))
    tension = w_b + 0.5 * w_c
    m_l = STEEL * math.pi / 4 * d * d
    cable = Cable(length=length, tension_ref=tension, ae=tension / 10 ** rng.uniform(-3.0, -2.0), diameter=d,
                  mass_per_length=m_l, weight_per_length=w_c / length, cd_normal=1.2)
    r_b = (3 * m_b / (4 * math.pi * 2000.0)) ** (1 / 3)
    area = 0.5 * math.pi * r_b**2                           # C_D A of a sphere, C_D = 0.5
    m_v = m_b + 0.5 * RHO * 4 / 3 * math.pi * r_b**3        # with the sphere's added mass
    body = Body(weight=w_b, mass_x=m_v, mass_y=m_v, drag_area_normal=area, drag_area_tangential=area)
    m_vl = m_l + RHO * math.pi * d * d / 4
    w_string = math.pi / length * math.sqrt(tension / m_vl)
    w_swing = math.sqrt(tension / (length * (m_v + m_vl * length / 3)))     # Wang 1971 eq. 22-25
    if kind == "short":
        omega, a = rng.uniform(0.3, 1.5) * w_swing, rng.uniform(0.05, 0.3)
    elif kind == "heavy":
        omega, a = 10 ** rng.uniform(-0.5, 0.2) * w_string, rng.uniform(0.15, 0.9)
    else:
        omega, a = rng.uniform(0.5, 2.0) * w_swing, rng.uniform(0.15, 0.9)
    mix = rng.uniform(0.0, 1.0)                             # surge share of the top motion
    top = TopMotion(x=(Sinusoid(amplitude=a * mix, frequency=omega, phase=math.pi / 2),),
                    y=(Sinusoid(amplitude=a * (1.3 - mix), frequency=omega),))
    current = rng.uniform(0.3, 1.0) if kind == "current" else rng.uniform(0.0, 0.2)
    period = 2 * math.pi / omega
    return single_section_scene(cable=cable, body=body, environment=Environment(density=RHO, current_speeds=(current,)),
                                top_motion=top, numerics=Numerics(duration=7 * period, output_step=period / 20),
                                name=f"random {kind}")


def auto_against_reference(scene):
    """(auto's model dict, actual errors, the reference's own convergence, tolerance dict)."""
    period = metrics.forcing_period(scene)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NumericalWarning)
        got = simulate(scene)
    model = got.stats["model"]
    n_ref = max(16, 2 * model["segments"])
    ref = metrics.statistics(run_rung(scene, "segmented", n_ref), period)
    half = metrics.statistics(run_rung(scene, "segmented", n_ref // 2), period)
    actual = metrics.errors(metrics.statistics(got, period), ref)
    return model, actual, metrics.errors(half, ref)


def check(model, actual, convergence, tol=(0.01, 0.02)):
    """The ladder's two promises; returns a list of what failed (empty: pass): the actual error within the tolerance,
    and the stated error never below half the actual one (the stated-error rule) nor above 4x it (a cost rule: an
    estimate far above the error buys elements it does not need; a posteriori against a coarse N / 2 it may be 2-3x)."""
    bad = []
    for k, t in zip(("body", "tension"), tol):
        if actual[k] > t:
            bad.append(f"{k}: actual {actual[k]:.3g} above the tolerance {t:.3g}")
        e = model["estimated_error"][k]
        if actual[k] > max(RESOLVED_FRACTION * t, 2 * convergence[k]):
            if not (e is not None and 0.5 <= e / actual[k] <= 4.0):
                bad.append(f"{k}: stated {e} vs actual {actual[k]:.3g} (below half of it or above 4x)")
        elif e is None or e > t:
            bad.append(f"{k}: stated {e} above the tolerance where the actual error {actual[k]:.3g} is below resolution")
    return bad


KNOWN = {   # measured misses, kept visible (strict: an xfail that starts passing fails)
    # ("short", 1) passes since the integrators scale the states: its actual 0.105 % body error held integration
    # error (one SI atol); 0.081 % now, below a tenth of the tolerance (the estimate states 0.028 %)
    # ("short", 2) passes since every rung's rtol is at most its stated error / 20 (auto.STATED_ROOM): it was
    # 0.39 % actual vs 0.13 % stated, of which 0.15 % was BDF2's numerical damping of the swing forced at its
    # resonance (omega/omega_swing = 1.02) at rtol 1e-4; at 1e-5 the actual is 0.26 % (ratio 0.52: the rest is the
    # steady model error, 0.15 %, and the 7-period window's start-up transient, 0.09 %)
    # ("heavy", 3) passes since the continuum estimate hangs its string (tension growing toward the top): Wang's
    # straight cable is estimated at 0.38 % (actual 0.10 %, unresolved) where the mean-tension string said 4.4 %
    # and auto ran N = 5 (1.1 % actual, 0.20 % stated)
    # ("heavy", 3) passes since the a posteriori check keeps its tight run and states the a priori estimate of the N
    # that ran: the static check (ladder.static_check) finds Wang's straight cable 8 % off the converged mean offset
    # (1.7 vs 1.57 cm, judged on the 1 cm floor) and runs the node model at N = 5, which its check grows to 14; the
    # stated body error was N = 5's a priori 0.97 % (carried with the grown N) against an actual 0.12 %, of which
    # most was the integration error of the kept rtol 1e-4 run; now the rtol 1e-5 run is kept (actual 0.049 %) and
    # states 0.072 % (N = 14's a priori; the check's 0.019 % plus an integration part of 0.020 %)
}

CASES = [("short", 2), ("short", 3), ("short", 1), ("heavy", 1), ("heavy", 2), ("heavy", 3)]


@pytest.mark.slow
@pytest.mark.parametrize("kind,seed", [pytest.param(k, s, marks=pytest.mark.xfail(strict=True, reason=KNOWN[(k, s)]))
                                       if (k, s) in KNOWN else (k, s) for k, s in CASES])
def test_auto_within_tolerance_and_estimate_within_factor_2(kind, seed):
    scene = random_scene(np.random.default_rng(seed), kind)
    model, actual, conv = auto_against_reference(scene)
    bad = check(model, actual, conv)
    assert not bad, (model["name"], model["segments"], bad, model["reason"])


def test_random_families_span_the_ladder():
    """The families reach both ends of the ladder: a straight-cable rung for short light cables and the
    segmented cable with N > 1 for heavy cables forced near their string modes (a priori choice only); a
    heavy cable whose straight-cable estimate is within the tolerance may run straight (heavy-3: forced at
    0.37 of its first string mode, Wang's error 0.10 % against N = 16). Compiled (as users run) and in the VM
    alike, but for the rung taking the elements: compiled, heavy-2's N = 3 are the quasi-static segmented cable's
    (omega/omega_ax > 1/30: cheaper only stepped by the rk23 pair), the node model's in the VM."""
    names = {}
    for kind, seed in CASES:
        compiled, vm = both(random_scene(np.random.default_rng(seed), kind))
        for how, c in (("compiled", compiled), ("vm", vm)):
            names.setdefault((how, kind), []).append((c.name, c.segments, c.estimated_error["body"]))
        if (kind, seed) == ("heavy", 2):
            assert (compiled.name, compiled.segments, vm.name, vm.segments) == ("quasi-static", 3, "segmented", 3)
            assert compiled.numbers["plan"]["explicit_only"]
        else:
            assert (compiled.name, compiled.segments) == (vm.name, vm.segments), (kind, seed)
    for how in ("compiled", "vm"):
        assert all(n in ("quasi-static", "wang", "frequency") and s == 1 for n, s, _ in names[how, "short"])
        assert all(s > 1 or e <= 0.01 for n, s, e in names[how, "heavy"])
        assert sum(s > 1 for _, s, _ in names[how, "heavy"]) >= 2


STIFF = [("heavy", 2), ("current", 3)]


@pytest.mark.slow
@pytest.mark.parametrize("kind,seed", STIFF)
def test_stiff_cables_run_quasi_static_segmented_within_tolerance(kind, seed):
    """The same scenes with AE x 300 (static strain 3e-6 to 3e-5, omega/omega_ax < 1/30): auto takes the
    quasi-static segmented cable, and against the node-model segmented reference (its element stretches
    stepped) its error is within the tolerance and its estimate within a factor of 2."""
    scene = random_scene(np.random.default_rng(seed), kind)
    scene = scene.replace_section(0, cable={"ae": scene.cable.ae * 300})
    model, actual, conv = auto_against_reference(scene)
    assert model["name"] == "quasi-static" and model["segments"] > 1, model["reason"]
    bad = check(model, actual, conv)
    assert not bad, (model["segments"], bad)


COMPILED = [("heavy", 4), ("current", 1), ("current", 6)]


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("cc") is None, reason="no C compiler")
@pytest.mark.parametrize("kind,seed", COMPILED)
def test_compiled_auto_takes_the_quasi_static_segmented_cable_within_tolerance(compiling, monkeypatch, kind, seed):
    """Compiled, auto steps the quasi-static segmented cable with rk23 where it is cheaper than the node model
    (omega/omega_ax 0.09-0.10 here, above the 1/30 of the stiff rule: cablesys.ladder.choice.element_plan; in the
    VM these scenes run the node model): its error against the node model at N = 32 (CasADi's VM, its own
    convergence against N = 16 0.05-0.12 %) is within the tolerance and its estimate within 2x of it (measured:
    heavy-4 N = 5 0.37 % vs 0.47 % stated, current-1 N = 4 0.50 / 0.43 %, current-6 N = 5 0.34 / 0.32 %)."""
    scene = random_scene(np.random.default_rng(seed), kind)
    period = metrics.forcing_period(scene)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NumericalWarning)
        got = simulate(scene, quantities=())      # the body and tension groups: the plan's own measure
    model = got.stats["model"]
    # the plan takes the quasi-static segmented cable; its a posteriori check against N / 2 may grow N, past the
    # explicit pair's reach on to the node model: either way the result must be within the tolerance, honestly stated
    assert "stepped by the compiled rk23 pair" in model["reason"], model["reason"]
    assert model["segments"] > 1 and model["name"] in ("quasi-static", "segmented")
    monkeypatch.setenv("CABLESYS_COMPILE", "0")          # the references in the VM: nothing to compile
    ref = metrics.statistics(run_rung(scene, "segmented", 32), period)
    half = metrics.statistics(run_rung(scene, "segmented", 16), period)
    actual = metrics.errors(metrics.statistics(got, period), ref)
    bad = check(model, actual, metrics.errors(half, ref))
    assert not bad, (model["segments"], bad)
