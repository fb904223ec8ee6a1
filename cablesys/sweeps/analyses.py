"""What one case computes, per analysis (the registry :data:`ANALYSES`), and the per-process cache of models.

Each analysis takes (scene, options, cache) and returns (summary dict, success, message);
the summary is the result's own ``summary()`` where it has one, so statistics and verdicts
added there flow into sweeps (:mod:`.metrics` flattens them). Models are built once per
scene structure and simulators once per (structure, numerics) in each worker process:
every other value enters through the parameter vector ``p``.
"""

from __future__ import annotations

import collections
import dataclasses
import math
from typing import Callable

import numpy as np

from ..errors import ParameterError, SolverError
from ..statistics import half_range
from ..ladder.metrics import forcing_period
from ..model import FunctionCache, build_model, structure_of
from ..scene import Scene, load_scene
from ..slack.scene import SlackScene, load_slack_scene
from ..towed.scene import TowedScene, load_towed_scene


class ModelCache:
    """One model per scene structure (least recently used out), and the ladder's :class:`~cablesys.ladder.rungs.RungCache`."""

    def __init__(self, maxsize: int = 8):
        self.maxsize = maxsize
        self._models = collections.OrderedDict()
        self.builds = 0
        self._rungs = None
        self.functions = FunctionCache()   # the slack model's CasADi functions, keyed by element count

    @property
    def rungs(self):
        """The model ladder's :class:`~cablesys.ladder.rungs.RungCache` of this process (its rungs' models,
        the choice's describing-function solver and the simulators, built once per structure)."""
        if self._rungs is None:
            from ..ladder.rungs import RungCache
            self._rungs = RungCache()
        return self._rungs

    def _get(self, store, key, make):
        if key in store:
            store.move_to_end(key)
            return store[key]
        store[key] = make()
        if len(store) > self.maxsize:
            store.popitem(last=False)
        return store[key]

    def model(self, scene):
        def make():
            self.builds += 1
            return build_model(scene)
        return self._get(self._models, structure_of(scene), make)


def forcing_frequency(scene) -> float | None:
    """Lowest frequency of the top-motion sinusoids with a non-zero amplitude (rad/s; None for an irregular sea or
    a recorded motion): the forcing period of :func:`cablesys.ladder.metrics.forcing_period`, the one definition
    every door uses."""
    period = forcing_period(scene)
    return None if period is None else 2 * math.pi / period


def _outputs(labels) -> list:
    return [lbl for lbl in labels if "_rate" not in lbl and lbl not in ("x_s", "y_s")]


def run(scene, options, cache):
    """Time-domain run of the model :func:`cablesys.simulate` runs for ``scene`` (the ladder's choice, as every door
    runs it); amplitudes (half the peak-to-peak) over the run's statistics window, the one of its summary
    (:func:`cablesys.statistics.window`), or over the last ``periods`` forcing periods when that option is given.

    Option ``model``: a model name of :data:`cablesys.ladder.MODEL_CHOICES` ("auto", "as-built", a rung) in place of
    the scene's ``numerics.model`` (the default; "scene" says the same). The model that ran is reported
    (``model_name``, its reason and estimated error).
    """
    from ..ladder import simulate
    name = options.get("model")
    r = simulate(scene, model=None if name in (None, "scene") else name, jit=bool(options.get("jit", False)),
                 cache=cache.rungs)
    choice = r.stats["model"]
    s = dict(r.summary())
    s["model"] = choice
    s.pop("warnings", None)
    w = forcing_frequency(scene)
    n = options.get("periods")
    try:
        from ..verdict import (  # statistics and the verdict against scene.limits
            passed,
            report,
        )
    except ImportError:          # pragma: no cover
        report = None
    if report is not None and r.time.size > 2:
        s.update(report(scene, r))
        if s.get("verdict"):
            s["verdict_pass"] = passed(s["verdict"])
    if getattr(scene.top_motion, "spectrum", None) is not None:
        w = None                 # an irregular sea: statistics, not amplitudes over periods
    if w and n is None:
        mask = r.window_mask()
        s["amplitude"] = {lbl: half_range(np.asarray(r[lbl])[mask]) for lbl in _outputs(r.labels)}
    elif w and r.time[-1] - r.time[0] >= 2 * int(n) * 2 * math.pi / w:
        s["amplitude"] = {lbl: r.steady_amplitude(lbl, 2 * math.pi / w, int(n)) for lbl in _outputs(r.labels)}
    return s, r.success, r.message


def rao(scene, options, cache):
    """Linearization about the steady state: natural frequencies, |RAO| at the forcing frequency and peaks.

    A chunk of RAO cases is linearized in one mapped call instead (:mod:`.batched`); both end here."""
    from ..linear.linearization import linearize
    model = cache.model(scene)
    return rao_summary(scene, linearize(model, model.parameters(scene)), options)


def rao_summary(scene, lin, options):
    """(summary, success, message) of one linear model: natural frequencies, RAO peaks on a grid
    (options ``omega_min``, ``omega_max``, ``n_omega``) and |RAO| and amplitudes at the forcing frequency, per top input
    (x_s, y_s, and z_s in 3-D) and body axis (x_b, y_b, and z_b in 3-D)."""
    from ..ladder.auto import require_at_rest
    from ..linear import modes
    from ..linear.periodic import scene_input_amplitude
    require_at_rest(scene, "the rao analysis")
    md = modes(lin)
    s = {"omega_n": {f"{k}_rad_s": float(w) for k, w in enumerate(md.omega_undamped)},
         "damping_ratio": {str(k): float(z) for k, z in enumerate(md.damping_ratio)},
         "mode_dominant": {str(k): str(d) for k, d in enumerate(md.dominant)}}
    outs = _outputs(lin.output_labels)
    # bin midpoints: an undamped model (no current, no C_I) never meets a natural frequency exactly;
    # its peak height is then set by the grid, its peak frequency is not
    w_max = float(options.get("omega_max", 3.0 * float(np.max(md.omega_undamped))))
    w_min = float(options.get("omega_min", 0.0))
    n = int(options.get("n_omega", 300))
    omega = w_min + (w_max - w_min) * (np.arange(n) + 0.5) / n
    _, Y = lin.transfer(omega)
    tops = [k for k in lin.input_labels if not k.startswith("wave[")]   # x_s, y_s (z_s in 3-D, a vessel's rotations)
    for j, inp in enumerate(tops):
        for o in ("x_b", "y_b", "z_b", "tension_mid"):
            if o in lin.output_labels:
                a = np.abs(Y[:, lin.output_labels.index(o), j])
                k = int(np.argmax(a))
                s[f"rao_peak_{o}_{inp}"] = float(a[k])
                s[f"rao_peak_omega_{o}_{inp}_rad_s"] = float(omega[k])
    w = forcing_frequency(scene)
    if w:
        _, Yf = lin.transfer([w])
        try:
            _, Z = scene_input_amplitude(scene)
        except SolverError:        # several frequencies: per-unit RAOs only
            Z = None
        for o in outs:
            i = lin.output_labels.index(o)
            for j, inp in enumerate(tops):
                s[f"rao_{o}_{inp}"] = float(abs(Yf[0, i, j]))
            if Z is not None:
                s[f"amplitude_{o}"] = float(abs(Yf[0, i, :Z.size] @ Z))
    return s, True, ""


def periodic(scene, options, cache):
    """Nonlinear periodic steady state (harmonic balance) at the top motion's one frequency."""
    from ..ladder.auto import require_at_rest
    from ..linear.periodic import periodic_steady_state, scene_input_amplitude
    require_at_rest(scene, "the periodic analysis")
    model = cache.model(scene)
    w, Z = scene_input_amplitude(scene)
    sol = periodic_steady_state(model, model.parameters(scene), w, input_amplitude=Z,
                                n_harmonics=int(options.get("n_harmonics", 20)))
    s = {"amplitude": {o: sol.amplitude(o) for o in _outputs(sol.outputs)}, "residual": sol.residual,
         "success": sol.success}
    for o, y in sol.outputs.items():
        if o.startswith("tension"):
            s[f"{o}_min_N"], s[f"{o}_max_N"] = float(np.min(y)), float(np.max(y))
    return s, sol.success, sol.message


SEA_OPTIONS = ("hs", "tp", "gamma", "omega_min", "omega_max", "direction")


def stochastic(scene, options, cache):
    """Gaussian equivalent linearization in an irregular sea: the scene's own ([top_motion.spectrum] and its motion
    RAO, :func:`cablesys.linear.stochastic.sea_inputs`: the sea its time-domain run realises), unless the options
    define one: a JONSWAP sea from ``hs``, ``tp``, ``gamma`` (default 2 m, 8 s, 3.3), the band
    ``omega_min``/``omega_max`` (0.25-3 rad/s) and the top's ``direction`` per unit sea amplitude (default the surface
    orbit of :mod:`cablesys.linear.stochastic`, the isolation design's), which a scene without a sea takes too.
    ``sea`` (text) says which sea ran and why. ``n_omega``: frequencies over the band."""
    from ..ladder.auto import require_at_rest
    from ..linear.spectra import jonswap
    from ..linear.stochastic import sea_inputs, stochastic_response
    require_at_rest(scene, "the stochastic analysis")
    model = cache.model(scene)
    n_omega = int(options.get("n_omega", 60))
    sea = scene.top_motion.spectrum
    given = [k for k in SEA_OPTIONS if k in options]
    if sea is not None and not given:
        omega, S, D, weights = sea_inputs(scene, model, n_omega)
        spread = "" if sea.long_crested else f" spread cos^{sea.spreading_n:g} ({weights.size} directions)"
        words = (f"the scene's {sea.kind} sea, Hs {sea.hs:g} m, Tp {sea.tp:g} s, heading {sea.heading_deg:g} deg{spread}, "
                 f"{omega[0]:.3g}-{omega[-1]:.3g} rad/s, the top moved by "
                 + ("[top_motion.vessel]" if scene.top_motion.vessel is not None else
                    "[top_motion.rao]" if scene.top_motion.rao is not None else "the surface (no motion RAO)"))
        hs, tp = sea.hs, sea.tp
    else:
        hs, tp, gamma = float(options.get("hs", 2.0)), float(options.get("tp", 8.0)), float(options.get("gamma", 3.3))
        omega = np.linspace(float(options.get("omega_min", 0.25)), float(options.get("omega_max", 3.0)), n_omega)
        S = jonswap(omega, hs, tp, gamma)
        D = np.asarray(options["direction"], complex) if "direction" in options else None
        weights = None
        why = (f"options {', '.join(given)} in place of the scene's [top_motion.spectrum] and motion RAO" if sea is not None
               else "no [top_motion.spectrum] in the scene" + (f", options {', '.join(given)}" if given else
                                                                 ", the analysis defaults"))
        words = (f"JONSWAP Hs {hs:g} m, Tp {tp:g} s, gamma {gamma:g}, {omega[0]:.3g}-{omega[-1]:.3g} rad/s, the top "
                 + ("moved along options.direction" if D is not None else "on the surface orbit (Wang 1971 eq. 26)")
                 + f": {why}")
    kw = {} if D is None else {"direction": D, "weights": weights}
    st = stochastic_response(model, model.parameters(scene), omega, S, n_log2=int(options.get("n_log2", 8)), **kw)
    outs = _outputs(st.output_labels)
    s = {"sea": words, "sea_hs_m": float(hs), "sea_tp_s": float(tp),
         "mean": {o: float(st.output_mean[st.output_labels.index(o)]) for o in outs},
         "std": {o: st.std(o) for o in outs},
         "slack_probability": {o: st.slack_probability(o) for o in outs if o.startswith("tension")},
         "iterations": st.iterations, "converged": st.converged}
    if hasattr(st, "summary"):               # the result's own headline numbers (statistics, verdicts) on top
        s.update(st.summary())
    return s, bool(st.converged), "" if st.converged else "the Gaussian linearization did not converge"


def design(scene, options, cache):
    """The isolation design NLP (Wang 1971 p. 33) with ``options['settings']`` (fields variable as ``design.<field>``)."""
    from ..isolation import DesignSettings
    from ..isolation import design as solve
    from ..ladder.auto import require_at_rest
    require_at_rest(scene, "the design analysis")
    settings = options.get("settings")
    if not isinstance(settings, DesignSettings):
        raise ParameterError("options['settings']", settings, "a design sweep needs a DesignSettings")
    changes = {k: v for k, v in options.items() if k != "settings"}
    if changes:
        settings = dataclasses.replace(settings, **changes)
    res = solve(scene, settings, model=cache.model(scene))
    return res.to_dict(), bool(res.converged), "" if res.converged else f"not converged: {res.status}"


def ladder(scene, options, cache):
    """The model ladder's choice for the scene, without running it (:func:`cablesys.ladder.choose`): the rung,
    its elements, the deciding numbers and every rung's estimated error (option ``tolerance``)."""
    from ..ladder import choose
    c = choose(scene, options.get("tolerance"), question=options.get("question", "time"))
    est = {k: {q: v for q, v in e.items() if q in ("body", "tension")} for k, e in c.numbers.get("estimates", {}).items()}
    numbers = {k: v for k, v in c.numbers.get("scene", {}).items() if isinstance(v, (int, float))}
    return {"model": c.as_dict(), "numbers": numbers, "estimates": est}, True, ""


def slack(scene, options, cache):
    """Statics and natural modes of a slack span (:func:`cablesys.slack.analyze`, Griffin & Rosenthal 1985), option
    ``solver`` ('auto', 'dense', 'sparse'): the equilibrium's tensions (N), sag (m) and Irvine parameter lambda^2
    (eq. 4, 22), the natural frequencies ``omega_n`` (rad/s, ascending, as ``rao`` names them) with their mode types,
    and the verdict of the element tensions against ``scene.limits``."""
    from ..slack import analyze
    r = analyze(scene, solver=options.get("solver", "auto"), cache=cache.functions)
    eq = r.equilibrium.summary()
    s = {k: v for k, v in eq.items() if k not in ("result", "success", "message", "stats", "seconds", "method")}
    s["omega_n"] = {f"{k}_rad_s": float(w) for k, w in enumerate(r.modes.omega)}
    s["mode_type"] = {str(k): t for k, t in enumerate(r.modes.mode_type)}
    s["stats"] = dict(r.stats)
    return _with_verdict(s, r), r.success, r.message


def towed(scene, options, cache):
    """The towed cable's response (:func:`cablesys.towed.analyze`, Kennedy & Strahan 1981): its ``summary()``
    (steady tensions in N, damping times in s, the theory's coefficients, |H| and c* (m/s) at the far end at the
    lowest and highest frequency) with the modes one group each, and the verdict of the steady tensions against
    ``scene.limits``."""
    from ..towed import analyze
    r = analyze(scene)
    s = dict(r.summary())
    s["modes"] = {str(k): m for k, m in enumerate(s["modes"])}
    return _with_verdict(s, r), r.success, r.message


def _with_verdict(summary: dict, result) -> dict:
    """``summary`` with the static verdict of ``result`` (:func:`cablesys.verdict.judge`) when its scene has limits."""
    from ..verdict import judge, passed
    if getattr(result.scene, "limits", None) is not None:
        summary["verdict"] = judge(result)
        summary["verdict_pass"] = passed(summary["verdict"])
    return summary


@dataclasses.dataclass(frozen=True)
class SceneKind:
    """A kind of scene a sweep varies: its class, the file loader of the command line, and how it is named."""

    cls: type
    load: Callable
    name: str
    text: str


SCENES = {"wang": SceneKind(Scene, load_scene, "Wang scene", "a Wang scene (cablesys.load_scene, cablesys.dale_scene)"),
          "slack": SceneKind(SlackScene, load_slack_scene, "slack scene",
                             "a slack scene (cablesys.slack.load_slack_scene)"),
          "towed": SceneKind(TowedScene, load_towed_scene, "towed scene",
                             "a towed scene (cablesys.towed.load_towed_scene)")}


@dataclasses.dataclass(frozen=True)
class Analysis:
    """One analysis a sweep runs: ``compute(scene, options, cache) -> (summary, success, message)``, the kind of scene
    it takes (a key of :data:`SCENES`), what it computes (generated into :func:`cablesys.sweep`'s docstring, the
    command's help and the README), its options (None: not checked here) and whether the command line offers it."""

    compute: Callable
    scene: str
    text: str
    options: tuple | None = None
    cli: bool = True


ANALYSES = {
    "run": Analysis(run, "wang", "time domain (Wang 1971 eq. 47-48) of the model the ladder chooses; amplitudes, "
                                 "statistics and the verdict against [limits]"),
    "rao": Analysis(rao, "wang", "linearization: natural frequencies omega_n, damping ratios, RAOs"),
    "periodic": Analysis(periodic, "wang", "harmonic balance: the nonlinear periodic steady state"),
    "stochastic": Analysis(stochastic, "wang", "Gaussian linearization in the scene's irregular sea "
                                               "([top_motion.spectrum] and its motion RAO; without one a JONSWAP sea, "
                                               "options hs, tp, gamma)"),
    "design": Analysis(design, "wang", "the isolation design NLP (options={'settings': DesignSettings(...)})",
                       cli=False),
    "ladder": Analysis(ladder, "wang", "which model the scene needs (cablesys.ladder.choose), without running it"),
    "slack": Analysis(slack, "slack", "statics and natural modes of a slack span (Griffin & Rosenthal 1985): "
                                      "omega_n, mode types, lambda^2, tensions, the verdict against [limits]",
                      options=("solver",)),
    "towed": Analysis(towed, "towed", "a towed cable's transfer function, c*, modes and damping time (Kennedy & "
                                      "Strahan 1981): steady tensions, far-end |H| and c*, the verdict against [limits]",
                      options=()),
}
"""The registry of sweep analyses, name -> :class:`Analysis` (the one list: docstring, help and README come from it)."""

ANALYSIS = {name: a.compute for name, a in ANALYSES.items()}
"""name -> compute function of :data:`ANALYSES`."""


def analyses_text() -> str:
    """The analyses as one sentence of the docstring: ``name`` (what, on which scene); ..."""
    return "; ".join(f"``{n}`` ({a.text}; {SCENES[a.scene].text})" for n, a in ANALYSES.items())


def analyses_markdown() -> str:
    """The analyses as the README's list (one line each: name, scene kind, what it computes)."""
    return "\n".join(f"- `{n}` on {SCENES[a.scene].text}: {a.text}" + ("" if a.cli else " (Python only)")
                     for n, a in ANALYSES.items())
