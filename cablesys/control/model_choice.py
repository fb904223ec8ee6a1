"""Which winch model the control runs on a scene, and why.

``cablesys.simulate`` and ``cablesys run`` run the scene's ``[numerics] model``: by default ("auto") the model the
ladder chooses (:mod:`cablesys.ladder`), checked a posteriori against N / 2, which may grow N (the packaged ROV lift:
the quasi-static cable at N = 4 a priori, the node model at N = 28 after the checks of its 600 s sea). The control
takes the ladder's a priori choice, not the checked N (a winch form at the checked N would multiply the design's
and the plant's cost, and the check needs the runs it checks), and says so in its reason. Every door of the control (:func:`.payout.heave_problem`,
:func:`.mpc.compare_compensation`'s plant, :func:`.design_problem.time_design_problem` and ``cablesys control``, with
and without ``--design``) resolves its ``model`` here, so that for one scene they run one model, with one N and one
stated reason. The control has winch forms of two models only: Wang's 2-DOF cable (:mod:`cablesys.model.winch`,
"wang") and the segmented node model of N elements (:mod:`cablesys.model.segmented_winch_control`, "segmented").
The ladder's rung maps to them as follows:

- ``wang`` and ``frequency`` (whose orbit is Wang's model's): Wang's 2-DOF winch;
- ``segmented`` at N: the node model's winch at N;
- ``quasi-static`` at N > 1 (the node model with its stiff axial element modes eliminated): the node model at N
  stands for it, axial modes kept (the quasi-static form has no winch); at N = 1 (the straight cable with a
  quasi-static stretch) Wang's 2-DOF model stands for it, its stretch kept as a coordinate;
- a registered rung: the node model at its N (at least 2) stands for it.
- a chain of sections (a soft insert, an intermediate body): Wang's 2-DOF winch has one section, so the node model
  at N = 1 per section (one straight element per section, as Wang's chain) stands for ``wang`` and for the
  quasi-static rung at N = 1, and the node model at the rung's N for the others.

A stand-in is said in the reason. ``model="wang"`` or ``"segmented"`` runs that model as asked.
"""

from __future__ import annotations

import dataclasses
import numbers

from ..errors import ParameterError

AUTO = "auto"
# the control's winch models: Wang's 2-DOF winch, the segmented node model's winch
MODELS = ("wang", "segmented")
CHOICES = (AUTO,) + MODELS


@dataclasses.dataclass(frozen=True, kw_only=True)
class ModelChoice:
    """The control's model for a scene: ``model`` ("wang" or "segmented"), ``segments`` (N of the node model; None
    for Wang's, or for a segmented model asked without N: the scene's ``cable.segments``), ``reason`` (why, in one
    line: the ladder's choice and its first reason, or "as asked"), ``ladder`` (the ladder's choice for the scene,
    :meth:`cablesys.ladder.Choice.as_dict`, when the choice was the ladder's; else None)."""

    model: str
    segments: int | None
    reason: str
    ladder: dict | None = None

    def as_dict(self) -> dict:
        """JSON-able ``{model, segments, reason, ladder}``."""
        return dataclasses.asdict(self)


def ladder_choice(scene):
    """The ladder's :class:`cablesys.ladder.Choice` for the (uncompensated) scene, as ``cablesys run`` takes it: the
    scene's ``[numerics] model`` (``auto``: the ladder chooses; a rung name: that rung, :func:`cablesys.ladder.decide`).
    ``as-built`` is answered by :func:`resolve_model` without the ladder."""
    from ..ladder.auto import decide
    return decide(scene, None, None, None)[0]


def _scene_segments(scene) -> int:
    return max(s.cable.segments for s in scene.sections)


def _first(reason: str) -> str:
    return reason.split("; ")[0]


def winch_form(name: str, segments: int, chain: bool = False) -> tuple:
    """(model, N, stand-in note) of the control for the ladder's rung ``name`` at ``segments`` elements (module
    docstring; ``chain``: the scene has more than one section, which only the node model's winch carries); the note
    is "" where the control runs the rung's own model."""
    from ..ladder.rungs import get_rung
    base = getattr(get_rung(name), "model_of", None) or name
    if chain and (base == "wang" or segments <= 1):
        return "segmented", 1, ("the node model at N = 1 per section (one straight element per section, as Wang's "
                                "chain) stands for it: Wang's 2-DOF winch has one section, a chain's winch is the "
                                "node model's")
    if base == "wang":
        return "wang", None, ""
    if base == "segmented":
        return "segmented", max(int(segments), 2), ""
    if base == "quasi-static" and segments <= 1:
        return "wang", None, ("Wang's 2-DOF model stands for it (the control has no winch in the quasi-static form; "
                              "Wang's keeps the stretch as a coordinate)")
    n = max(int(segments), 2)
    if base == "quasi-static":
        return "segmented", n, (f"the node model at N = {n} stands for it (the control has no winch in the "
                                "quasi-static form, whose stiff axial modes it eliminates)")
    return "segmented", n, (f"the node model at N = {n} stands for it (the control has winch forms of Wang's 2-DOF "
                            "model and the node model only)")


def resolve_model(scene, model=AUTO, segments: int | None = None, *, names=("model", "segments")) -> ModelChoice:
    """The control's model for ``scene`` (module docstring).

    Parameters
    ----------
    scene : Scene
        The scene the model will run (one section, or a chain: the node model's winch only).
    model : str or ModelChoice
        "auto" (default): the scene's ``[numerics] model`` through the ladder, as ``cablesys run`` runs it; "wang" or
        "segmented": that model, as asked; a :class:`ModelChoice` is returned as it is (``segments`` unset or its N).
    segments : int, optional
        N of the node model: with "segmented" (default the scene's ``cable.segments``), or with "auto" in place of
        the ladder's N (refused where the ladder runs Wang's 2-DOF model, which has one straight element).
    names : (str, str)
        The caller's names of ``model`` and ``segments``, in errors and in the reason ("as asked (model = ...)").

    Returns
    -------
    ModelChoice
    """
    field, n_field = names
    if isinstance(model, ModelChoice):
        if segments is not None and segments != model.segments:
            raise ParameterError(n_field, segments, f"must be unset or {model.segments} with a resolved ModelChoice "
                                                    f"({model.model}, N = {model.segments})")
        return model
    if not isinstance(model, str) or model not in CHOICES:
        raise ParameterError(field, model, f"allowed: {', '.join(CHOICES)} (or a built winch model)")
    if segments is not None and not (isinstance(segments, numbers.Integral) and not isinstance(segments, bool)
                                     and segments >= 1):
        raise ParameterError(n_field, segments, "must be an integer >= 1")
    if model != AUTO:
        n = segments if segments is not None or model == "wang" else _scene_segments(scene)
        n = n if n is None or n > 1 or model == "wang" else None      # none: control_model says N is needed
        asked = f"{field} = '{model}'" + (f", {n_field} = {segments}" if segments is not None else "")
        note = "" if segments is not None or n is None else f"; N = {n}, the scene's cable.segments"
        return ModelChoice(model=model, segments=None if n is None else int(n), reason=f"as asked ({asked}){note}")
    from ..ladder.auto import AS_BUILT
    if getattr(scene.numerics, "model", AUTO) == AS_BUILT:
        n = _scene_segments(scene)
        chain = len(scene.sections) > 1
        kind, n = ("wang", None) if n <= 1 and not chain else ("segmented", n if chain else max(n, 2))
        choice = ModelChoice(model=kind, segments=n, reason="numerics.model = 'as-built': the scene's own model "
                                                            f"({'Wang' if n is None else f'N = {n}'}), no ladder choice")
    else:
        lc = ladder_choice(scene)
        kind, n, stand_in = winch_form(lc.name, lc.segments, chain=len(scene.sections) > 1)
        rung = f"{lc.name}, N = {lc.segments}" if lc.segments > 1 else lc.name
        if getattr(scene.numerics, "model", AUTO) == AUTO:       # the deciding numbers follow the first "; "
            reason = f"the ladder's a priori choice is {rung}: {_first(lc.reason)}"
        else:                                                    # a named rung: all of it (its validity too)
            reason = f"the scene's numerics.model, {rung}: {lc.reason}"
        reason += (f"; {stand_in}" if stand_in else "") + ("; a priori: cablesys run checks it against N / 2 and "
                                                            "may run a larger N, the control does not")
        choice = ModelChoice(model=kind, segments=n, reason=reason, ladder=lc.as_dict())
    if segments is None or segments == choice.segments:
        return choice
    if choice.model == "wang":
        raise ParameterError(n_field, segments, f"must be unset for this scene: {choice.reason}, one straight "
                                                 f"element (ask for {field}='segmented' to run N elements)")
    return dataclasses.replace(choice, segments=int(segments),
                               reason=f"{choice.reason}; N = {segments} as asked ({n_field}) in place of "
                                      f"{choice.segments}")


def ladder_note(scene, choice: ModelChoice) -> dict:
    """What the model ladder runs for the uncompensated scene and why, against the control's model ``choice``:
    ``ladder`` (one line), ``ladder_choice`` (:meth:`cablesys.ladder.Choice.as_dict`) and ``ladder_agrees`` (the
    control runs the ladder's model at its N, or its winch form's stand-in: the plant's reason says so). For the scene's
    ``as-built`` model the ladder is not asked."""
    lc = choice.ladder
    if lc is None:
        from ..ladder.auto import AS_BUILT
        if getattr(scene.numerics, "model", AUTO) == AS_BUILT:
            return {"ladder": "not asked: numerics.model = 'as-built'", "ladder_choice": None}
        lc = ladder_choice(scene).as_dict()
    kind, n, stand_in = winch_form(lc["name"], lc["segments"])
    seg = f", N = {lc['segments']}" if lc["segments"] > 1 else ""
    other_n = choice.segments is not None and n is not None and choice.segments != n
    if kind != choice.model:
        verdict = ": NOT the control's model, whose results then carry that model's error"
    elif other_n:
        verdict = (f": the control's model at another N ({choice.segments} against the ladder's {n}), whose results "
                   "then carry that N's error")
    elif stand_in:
        verdict = f": {stand_in}"
    else:
        verdict = ": the control's model"
    return {"ladder": f"{lc['name']}{seg} for the uncompensated scene{verdict} ({_first(lc['reason'])})",
            "ladder_choice": lc, "ladder_agrees": kind == choice.model and not other_n}
