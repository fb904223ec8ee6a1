"""The result of an open-loop payout on the heave-compensation problem's grid (:mod:`.payout`) and its heave
statistics: the rms body heave in the statistics window and its reduction against the uncompensated run (dB).
"""

from __future__ import annotations

import dataclasses
from typing import ClassVar

import numpy as np

from .. import statistics as st
from ..results import ResultBase


@dataclasses.dataclass(frozen=True)
class PayoutResult(ResultBase):
    """An open-loop optimal payout (or any payout evaluated on the problem's grid) and its response.

    ``times`` (N+1,) s; ``states`` (N+1, nx) with labels ``state_labels``; ``acceleration`` (N,)
    m/s^2, the control alpha on each interval; ``outputs`` (N+1, n_out) with labels
    ``output_labels`` (:data:`cablesys.model.winch.WINCH_OUTPUTS`) and the same for the run
    without compensation (``uncompensated``, alpha = 0). ``status`` is IPOPT's return status,
    ``violated`` the constraint that could not be met ("" when all hold), ``violations`` the
    largest violation of each, relative to its scale (the static tension for forces). ``tension_min_n`` is the
    least of the tension the no-slack floor bounds (:attr:`.payout.HeaveProblem.floor_output`: Wang's F_bc, the node
    model's least element tension), ``tension_max_n`` the largest top tension. ``model`` names the problem's winch
    model and ``model_reason`` says why it ran (:attr:`.payout.HeaveProblem.model_choice`); both are in
    :meth:`summary`.
    """

    times: np.ndarray
    states: np.ndarray
    acceleration: np.ndarray
    outputs: np.ndarray
    uncompensated: np.ndarray
    state_labels: tuple
    output_labels: tuple
    status: str
    violated: str
    violations: dict
    objective: float
    heave_rms_m: float
    uncompensated_heave_rms_m: float
    heave_reduction_db: float
    tension_max_n: float
    tension_min_n: float
    speed_max_m_s: float
    power_max_w: float
    success: bool = True
    message: str = ""
    stats: dict = dataclasses.field(default_factory=dict)
    model: str = ""
    model_reason: str = ""

    VARIABLES: ClassVar[dict] = {
        "heave": ("m", "body heave from rest, earth-fixed (down +)"),
        "heave_uncompensated": ("m", "body heave from rest without compensation"),
        "tension_top": ("N", "cable tension at the sheave"),
        "tension_top_uncompensated": ("N", "cable tension at the sheave without compensation"),
        "tension_mid": ("N", "tension at mid-length: the spring force F_bc of the cable (Wang 1971 eq. 54)"),
        "length": ("m", "unstretched length in the water"), "speed": ("m/s", "payout rate w"),
        "acceleration": ("m/s^2", "payout acceleration (the control)"), "power": ("W", "winch power T_top w")}

    def output(self, name: str, compensated: bool = True) -> np.ndarray:
        """One output's time series (``heave`` is taken from rest)."""
        Y = self.outputs if compensated else self.uncompensated
        y = Y[:, self.output_labels.index(name)]
        return y - Y[0, self.output_labels.index(name)] if name == "heave" else y

    def to_xarray(self):
        """The trajectories on dimension ``time`` (the control on the interval starts)."""
        import xarray as xr
        data = {name: ("time", self.output(name)) for name in ("heave", "tension_mid", "tension_top", "length",
                                                               "speed", "power")}
        data["heave_uncompensated"] = ("time", self.output("heave", False))
        data["tension_top_uncompensated"] = ("time", self.output("tension_top", False))
        data["acceleration"] = ("time", np.append(self.acceleration, np.nan))
        return xr.Dataset(data, coords={"time": self.times})


def statistics_window(times: np.ndarray, start: float | None, top_motion=None) -> np.ndarray:
    """Mask of the samples in the statistics window: from ``start`` (s), by default the window of every run's
    summary (:func:`cablesys.statistics.window` with the top motion's forcing period and smooth start)."""
    if start is None:
        period = None if top_motion is None else top_motion.window_period_s
        ramp = 0.0 if top_motion is None else top_motion.effective_ramp_s
        start = st.window(times, period, ramp)[0]
    return times >= start


def heave_reduction_db(heave, reference, mask) -> float:
    """20 log10(rms(heave) / rms(reference)) over ``mask`` (dB; negative: reduced)."""
    a, b = np.sqrt(np.mean(np.square(heave[mask]))), np.sqrt(np.mean(np.square(reference[mask])))
    return float(20 * np.log10(max(a, 1e-300) / b)) if b > 0 else float("nan")


def payout_result(problem, X, U, *, status: str, violated: str = "", violations=None,
                  objective: float = float("nan"), success: bool = True, message: str = "",
                  stats=None, stats_start: float | None = None) -> PayoutResult:
    """A :class:`PayoutResult` of node states ``X`` and controls ``U`` on the grid of ``problem`` (a
    :class:`.payout.HeaveProblem`); the uncompensated run is its roll-out at alpha = 0."""
    N = len(U)
    t = problem.dt * np.arange(N + 1)
    Uext = np.append(np.ravel(U), 0.0)
    Y = problem.outputs(X, Uext, t)
    X0 = problem.rollout(problem.x_rest, np.zeros(N))
    Y0 = problem.outputs(X0, np.zeros(N + 1), t)
    mask = statistics_window(t, stats_start, problem.scene.top_motion)
    oi = problem.output_labels.index
    h, h0 = Y[:, oi("heave")] - problem.heave_rest, Y0[:, oi("heave")] - problem.heave_rest
    return PayoutResult(times=t, states=np.asarray(X), acceleration=np.ravel(U), outputs=Y, uncompensated=Y0,
                        state_labels=problem.model.state_labels, output_labels=problem.output_labels, status=status,
                        violated=violated, violations=dict(violations or {}), objective=float(objective),
                        heave_rms_m=float(np.sqrt(np.mean(h[mask] ** 2))),
                        uncompensated_heave_rms_m=float(np.sqrt(np.mean(h0[mask] ** 2))),
                        heave_reduction_db=heave_reduction_db(h, h0, mask),
                        tension_max_n=float(np.max(Y[:, oi("tension_top")])),
                        tension_min_n=float(np.min(Y[:, oi(problem.floor_output)])),
                        speed_max_m_s=float(np.max(np.abs(Y[:, oi("speed")]))),
                        power_max_w=float(np.max(np.abs(Y[:, oi("power")]))),
                        success=success, message=message, stats=dict(stats or {}), model=problem.describe(),
                        model_reason=problem.model_reason)
