"""The initial state of a time-domain run: ``scene.initial`` completed by the steady state."""

from __future__ import annotations

import numpy as np

from ..model import CableModel
from ..scene import Scene
from ..statics.steady import steady_state


def initial_state(scene: Scene, model: CableModel, p) -> np.ndarray:
    """x0 from ``scene.initial``; unset angle/stretch come from the steady state.

    Parameters
    ----------
    scene : Scene
        The scene (its ``initial`` table).
    model : CableModel
        The model of the scene.
    p : array_like
        Parameter vector.

    Returns
    -------
    ndarray
        x0 = (q, q') in SI.
    """
    if model.kind == "element-coordinates":   # the node model's state mapped to (phi_k, u_k)
        x_n = initial_state(scene, model.node_model, p)
        e = np.array(model.top(float(scene.output_times[0]), p)).ravel()
        return np.array(model.from_nodes(x_n, e, np.asarray(p, dtype=float))).ravel()
    track = getattr(scene.top_motion, "track", None)
    if getattr(model, "segments", None) and track is not None:     # a chain or a system of lines on a track
        if track.is_circle:                                     # towing in a circle: the steady turn
            from ..statics.turning import turning_initial_state
            return turning_initial_state(scene, model, p)
        from ..statics.tow import straight_tow_state            # a path: the steady straight tow before it
        return straight_tow_state(scene, model, p)
    if getattr(scene, "system", None) is not None:   # lines joined at points: at rest in its static state
        from ..statics.system import system_initial_state
        return system_initial_state(scene, model, p, float(scene.output_times[0]))
    if getattr(model, "segments", None):      # node coordinates: the segmented cable
        from ..statics.catenary import segmented_initial_state
        return segmented_initial_state(scene, model, p)
    ini = scene.initial
    labels = model.q_labels
    out_of_plane = any(lbl.startswith("phi_z") for lbl in labels)
    q = steady_state(model, p).q if (ini.phi is None or ini.u is None or out_of_plane) else None

    def start(i: int, lbl: str) -> float:
        if lbl.startswith("phi_z"):            # the out-of-plane angle starts at its steady state
            return q[i]
        given = ini.phi if _in_plane_angle(lbl) else ini.u
        return given if given is not None else q[i]
    q0 = np.array([start(i, lbl) for i, lbl in enumerate(labels)])
    qd0 = np.array([ini.phi_rate if _in_plane_angle(lbl) else (0.0 if lbl.startswith("phi_z") else ini.u_rate)
                    for lbl in model.q_labels])
    return np.concatenate([q0, qd0])


def _in_plane_angle(label: str) -> bool:
    """True for a swing angle in the vertical x-y plane (``phi``, ``phi_2``), not the out-of-plane ``phi_z``."""
    return label.startswith("phi") and not label.startswith("phi_z")
