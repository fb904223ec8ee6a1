"""A run that is not stepped: its states, or its series, known at the output times (the periodic orbit of the frequency
rung, the steady tow or turn of the steady rung: :mod:`cablesys.ladder`), labelled as a time-domain run's are, into
the same :class:`~.record.RunRecord`."""

from __future__ import annotations

import numpy as np

from .columns import Columns
from .record import RunRecord


def label_states(model, times, X, modes, p, top=None, outputs=None) -> dict:
    """Labelled outputs and top motion (``x_s``, ``y_s``, in 3-D ``z_s``; a vessel's rotation ``rot_z_s`` ... where it
    moves several prescribed points) of the states ``X`` at ``times``.

    Parameters
    ----------
    model : CableModel
        The model whose ``top`` and ``outputs`` functions label the states.
    times : array_like
        (n,) output times (s).
    X : numpy.ndarray or None
        (2 nq, n) states; None: the top motion's series alone.
    modes : numpy.ndarray or None
        Slack switches (None: ``p``'s own), one row per gap of ``model.cable_force`` and column per time (entries of ``p`` at the
        model's ``slack_index``; the node model has none).
    p : array_like
        Parameter vector.
    top, outputs : Columns, optional
        The model's ``top`` and ``outputs`` over columns (a simulator's compiled ones; default: the model's own).

    Returns
    -------
    dict
        ``{label: (n,) array}`` in SI units.
    """
    T = np.asarray(times, float)
    n = T.size
    P = np.tile(np.asarray(p, float)[:, None], (1, n))
    if modes is not None and len(model.slack_index):
        P[list(model.slack_index), :] = modes
    block = min(256, max(n, 1))
    # the model's own functions over columns, mapped once per model and block (model.derive), not per call
    columns = lambda name: model.derive(f"columns_{name}_{block}", lambda: Columns(getattr(model, name), block))  # noqa: E731
    E = (top or columns("top"))(T[None, :], P)[0]
    data = {}
    if X is not None:
        Y = (outputs or columns("outputs"))(np.asarray(X, float), E, P)[0]
        data = {lbl: Y[i] for i, lbl in enumerate(model.output_labels)}
    data["x_s"], data["y_s"] = E[1], E[2]
    vessel = getattr(model, "vessel_inputs", ())    # a vessel's rotation after (t, z, z', z'') (model/system.py)
    n_t = (E.shape[0] - 1 - 3 * len(vessel)) // 3
    if n_t == 3:                              # a 3-D top input (t, x, y, z and their rates, accelerations)
        data["z_s"] = E[3]
    for m, name in enumerate(vessel):         # the vessel's rotation about the node axes (rad)
        data[name] = E[1 + 3 * n_t + m]
    return data


def sampled_record(scene, model, p, times, *, states=None, modes=None, data=None, success: bool = True,
                   message: str = "", stats: dict | None = None, model_info: dict | None = None) -> RunRecord:
    """The :class:`~.record.RunRecord` of a run known at ``times`` without stepping.

    Parameters
    ----------
    scene : Scene
        The scene it answers (its name).
    model : CableModel
        The model the states or series belong to.
    p : array_like
        Its parameter vector.
    times : array_like
        (n,) output times (s).
    states : numpy.ndarray, optional
        (2 nq, n) states: every output is the model's output function on them (:func:`label_states`).
    modes : numpy.ndarray, optional
        Slack switches of those states, one row per gap of ``model.cable_force`` (default: all taut).
    data : dict, optional
        Series already labelled (without states: the periodic orbit's Fourier series); the top motion's are added.
    success, message : optional
        How the solve ended.
    stats : dict, optional
        The run's statistics (``nsteps`` 0: nothing was stepped).
    model_info : dict, optional
        ``{name, segments}`` of the rung that ran.

    Returns
    -------
    RunRecord
    """
    T = np.asarray(times, float)
    extra = {}
    if states is not None:
        M = np.zeros((model.cable_force.size1_out(0), T.size)) if modes is None else np.asarray(modes, float)
        extra = {"states": np.asarray(states, float), "modes": M, "state_labels": model.state_labels}
    out = label_states(model, T, states, extra.get("modes"), p)
    out.update(data or {})
    return RunRecord(time=T, data=out, success=bool(success), message=message, stats=dict(stats or {}, nsteps=0),
                     scene_name=scene.name, model_info=dict(model_info or {}), **extra)
