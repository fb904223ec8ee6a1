"""Response spectra and short-term statistics of the linearized system in the scene's irregular sea.

The sea (``scene.top_motion.spectrum``) reaches the top through the motion RAO
(``scene.top_motion.rao`` or a vessel's 6-DOF ``scene.top_motion.vessel``,
:func:`cablesys.scene.sea.top_transfer`); the RAOs of the exact linearization carry it to every
output:

    H_o(omega) = RAO(o, x_s) X_s(omega) + RAO(o, y_s) Y_s(omega) [+ RAO(o, z_s) Z_s(omega) in 3-D]
                 [+ sum_a RAO(o, rot_a_s) Theta_a(omega), a vessel's rotation moving several points],
    S_o = |H_o|^2 S(omega),

and :func:`cablesys.statistics.frequency_domain` turns S_o into sigma, T_z and the most probable
extremes about the static value. The waves at the cable (``waves_at_cable``) are not included
in this linear transfer (see ``stochastic_response`` for the drag-linearized sea).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from .. import statistics as st
from ..errors import ParameterError
from ..scene.sea import top_transfer


@dataclasses.dataclass(frozen=True, eq=False)
class SeaResponse:
    """Sea spectrum, per-output response spectra and their statistics."""

    omega: np.ndarray            # rad/s
    sea: np.ndarray              # S(omega), m^2 s/rad
    spectra: dict                # output -> S_o(omega), unit^2 s/rad
    statistics: dict             # output -> cablesys.statistics.frequency_domain dict
    exposure: float              # s


def input_transfers(scene, omega, labels) -> tuple[np.ndarray, np.ndarray]:
    """(weights, T): the top's motion per unit wave amplitude in the scene's sea, per wave direction, for each input
    of ``labels`` (a linearization's top inputs: ``x_s``, ``y_s``, ``z_s`` in 3-D, a vessel's rotation ``rot_*_s``).

    The directions and their weights are :meth:`cablesys.scene.sea.SeaSpectrum.direction_quadrature`'s (the heading
    alone for a long-crested sea, DNV-RP-C205 3.5.8 for a spread one); T (n_dir, n_omega, len(labels)) holds the motion
    RAO read at each direction (:func:`cablesys.scene.sea.top_transfer`: none, the top heaves with the surface;
    [top_motion.rao]; [top_motion.vessel] at its lever arm, and its rotation where ``labels`` take it), multipliers of
    the elevation's complex amplitude (eta = Re(-i e^{i omega t}) = sin omega t), the time-domain run's
    (:func:`cablesys.scene.sea.sea_sinusoids`). A motion on an input ``labels`` lack (sway on planar equations) raises
    a ParameterError."""
    top = scene.top_motion
    theta, weight = top.spectrum.direction_quadrature()
    turns = any(k.startswith("rot_") for k in labels)          # a vessel's rotation moving further points
    blocks = []
    for t in theta:
        cols = dict(zip(("x_s", "y_s", "z_s"), top_transfer(top.vessel or top.rao, omega, float(t))))
        if turns:
            cols.update(zip(("rot_x_s", "rot_y_s", "rot_z_s"), top.vessel.rotation_transfer(omega, float(t))))
        left = [k for k, v in cols.items() if k not in labels and np.any(np.asarray(v) != 0.0)]
        if left:
            raise ParameterError("top_motion", left, f"moves inputs the linear model does not take ({', '.join(labels)}): "
                                 "linearize the scene's own model (the 3-D equations for sway)")
        blocks.append(np.stack([np.asarray(cols[k], complex) for k in labels], axis=1))
    return np.asarray(weight, float), np.stack(blocks)


def sea_response(scene, lin, *, outputs=None, exposure: float | None = None, n: int = 800) -> SeaResponse | None:
    """The linear response of ``lin`` (a :class:`~cablesys.linear.LinearModel` of ``scene``) to its sea.

    Parameters
    ----------
    scene : Scene
        With ``top_motion.spectrum`` (returns None without one).
    lin : LinearModel
        The exact linearization about the steady state (inputs ``x_s``, ``y_s``).
    outputs : sequence of str, optional
        Outputs to evaluate (default: the body motion and every tension output).
    exposure : float, optional
        Duration of the most probable extremes (s); default ``scene.limits.exposure`` or 3 h.
    n : int
        Frequencies over the sea's band.

    Returns
    -------
    SeaResponse or None
    """
    from .frequency_response import is_tension, rao, response_outputs
    sea = scene.top_motion.spectrum
    if sea is None:
        return None
    lo, hi = sea.band()
    omega = np.linspace(lo, hi, n)
    S = sea.density(omega)
    r = rao(lin, omega)
    inputs = [i for i in r.input_labels if not i.startswith("wave[")]   # the top's (and a vessel's rotation)
    weight, T = input_transfers(scene, omega, inputs)   # a spread sea: sum_j w_j |H(omega, theta_j)|^2
    if outputs is None:
        outputs = response_outputs(r.output_labels, scene)
    limits = getattr(scene, "limits", None)
    exposure = exposure or getattr(limits, "exposure", None) or 3 * 3600.0
    mean = dict(zip(lin.output_labels, np.asarray(lin.y0, float)))
    spectra, stats = {}, {}
    for o in outputs:
        H2 = sum(wj * np.abs(sum(r(o, i) * Tj[:, k] for k, i in enumerate(inputs))) ** 2 for wj, Tj in zip(weight, T))
        spectra[o] = H2 * S
        stats[o] = st.frequency_domain(omega, spectra[o], exposure, mean=float(mean.get(o, 0.0)),
                                       nonnegative=is_tension(o))      # a tension-only cable: >= 0
    return SeaResponse(omega=omega, sea=S, spectra=spectra, statistics=stats, exposure=float(exposure))


def side_by_side(scene, td_statistics: dict, exposure: float) -> dict:
    """Time-domain statistics of a run next to the linear frequency-domain ones of the same sea.

    Parameters
    ----------
    scene : Scene
        With a sea (else {} is returned).
    td_statistics : dict
        {label: cablesys.statistics.time_domain dict} of the run.
    exposure : float
        The exposure used for the time-domain most probable extremes (s).

    Returns
    -------
    dict
        {label: {statistic: {"time_domain": v, "frequency_domain": v}}}; {} when the steady state
        or linearization fails (the run's own statistics still stand).
    """
    from ..errors import SolverError
    from ..model import build_model
    from .linearization import linearize
    if scene.top_motion.spectrum is None:
        return {}
    try:
        model = build_model(scene)
        lin = linearize(model, model.parameters(scene))
        resp = sea_response(scene, lin, outputs=[k for k in td_statistics if k in lin.output_labels],
                            exposure=exposure)
    except SolverError:
        return {}
    return {k: st.side_by_side(td_statistics[k], resp.statistics.get(k)) for k in td_statistics}
