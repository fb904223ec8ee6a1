"""Nonlinear periodic steady state by trigonometric collocation (harmonic balance), with CasADi.

The periodic solution of M(q) q'' = f(q, q', e(t), p) (Wang 1971 eq. 47-48) with period T is
represented by its values q_j at N = 2H + 1 equally spaced times t_j; q' and q'' are exact for
trigonometric polynomials of degree H through the Fourier differentiation matrix D
(Trefethen, "Spectral Methods in MATLAB", ch. 3, odd N). The N nq collocation equations

    M(q_j) (D^2 q)_j - f(q_j, (D q)_j, e(t_j), p) = 0

are solved by Newton's method with the exact Jacobian assembled from per-node blocks,

    dr_j/dq_k = delta_jk dr_j/dq_j + D_jk dr_j/dq'_j + (D^2)_jk M(q_j),

the three n-by-n-free pieces evaluated by one mapped, compiled CasADi function (AD of the node
residual), so a Newton step costs one pass over the nodes and one dense (N nq) solve instead
of differentiating the whole collocation graph (whose symbolic Jacobian has ~2e6 operations);
the machinery is in :mod:`.collocation`.

Starting guess: the same collocation with 3 harmonics (7 nodes: small enough for CasADi's own
Newton rootfinder with the AD Jacobian of the whole residual, compiled, in one call), solved
from the hanging guess of the statics and interpolated onto the N nodes, where Newton then
needs 2-3 steps; the linear response at omega and the describing-function orbit of
:mod:`.equivalent` are the fallbacks. Along a frequency sweep (:func:`periodic_sweep`) each
solution starts from the secant extrapolation of its two neighbours' (continuation).

This is the pseudo-spectral (AFT) harmonic balance: no drag linearization, every harmonic up
to H. The cable must stay taut (no slack switches). A smooth start (``top_motion.ramp_s``) is
switched off: the periodic state is the one after any ramp.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from .. import statistics as st

from ..errors import ParameterError
from ..model import CableModel
from ..results import ResultBase, timed
from .collocation import (
    COARSE_HARMONICS,
    _coarse_guess,
    _harmonic_tail,
    _newton,
    _node_maps,
    _unit_differentiation,
    fourier_differentiation,  # noqa: F401  (re-exported: part of this module's interface)
    trig_interpolate,
)
from .equivalent import harmonic_response


def _without_ramp(model: CableModel, p) -> np.ndarray:
    """``p`` with the smooth start off (the periodic state is the one after any ramp)."""
    p = np.array(p, dtype=float)
    if "top_motion.ramp_s" in model.layout.labels:
        p[model.layout.index("top_motion.ramp_s")] = 0.0
    return p


def _linear_guess(model: CableModel, p, omega: float, input_amplitude, times) -> np.ndarray:
    """Node values of the linear response about the steady state (one complex solve)."""
    from .linearization import linearize
    from .steady import steady_state
    st = steady_state(model, p)
    Qc, _ = linearize(model, p, steady=st).transfer([omega])
    Q = Qc[0] @ np.asarray(input_amplitude, complex)
    return st.q[:, None] + np.real(Q[:, None] * np.exp(1j * omega * times)[None, :])


@dataclasses.dataclass(frozen=True, eq=False)
class PeriodicSolution(ResultBase):
    """Periodic orbit at the collocation times ``time`` (period ``period``) with labelled outputs."""

    period: float
    time: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    outputs: dict
    residual: float
    success: bool
    message: str = ""
    stats: dict = dataclasses.field(default_factory=dict)

    def amplitude(self, label: str, n_fine: int = 4096) -> float:
        """Half the peak-to-peak of the trigonometric interpolant of ``label``."""
        return st.half_range(trig_interpolate(self.outputs[label], n_fine))

    def first_harmonic(self, label: str) -> complex:
        """Complex first-harmonic amplitude Y with y ~ Re(Y e^{i omega t})."""
        y = self.outputs[label]
        return complex(2.0 / len(y) * np.sum(y * np.exp(-2j * np.pi * self.time / self.period)))

    def to_xarray(self):
        import xarray as xr
        return xr.Dataset({k: ("time", v) for k, v in self.outputs.items()}, coords={"time": self.time},
                          attrs={"period": self.period, "residual": self.residual, "success": int(self.success)})


def scene_input_amplitude(scene) -> tuple[float, np.ndarray]:
    """(omega, Z) of a top motion made of sinusoids at one frequency: a sin(wt + ph) = Re(-i a e^{i ph} e^{iwt}).
    Z = (x_s, y_s[, z_s in 3-D][, a vessel's rotation rot_z_s ...], wave amplitudes...), the input order of the
    model's linearization."""
    axes = ("x", "y", "z") if getattr(scene, "three_d", False) else ("x", "y")
    terms = [(ax, s) for ax in axes for s in getattr(scene.top_motion, ax)]
    turns = tuple(f"rot_{a}" for a in getattr(scene, "vessel_rotation_axes", ()))   # a vessel's rotation, after them
    terms += [(ax, s) for ax in turns for s in scene.top_motion.vessel_rotation[ax[4:]]]
    axes += turns
    freqs = {round(s.frequency, 12) for _, s in terms if s.amplitude != 0.0}
    if len(freqs) != 1 or scene.top_motion.series is not None:
        raise ParameterError("top_motion", f"frequencies {sorted(freqs)}"
                             + (" and a sampled series" if scene.top_motion.series is not None else ""),
                             "the periodic solve needs a top motion of sinusoids at one frequency and no sampled "
                             "series; give one frequency or use simulate()")
    Z = np.zeros(len(axes) + len(scene.environment.waves), complex)
    for ax, s in terms:
        if s.amplitude == 0.0:
            continue
        Z[axes.index(ax)] += -1j * s.amplitude * np.exp(1j * s.phase)
    return freqs.pop(), Z


@timed
def periodic_steady_state(model: CableModel, p, omega: float, *, n_harmonics: int = 20,
                          input_amplitude=None, guess: np.ndarray | None = None, t0: float = 0.0) -> PeriodicSolution:
    """Periodic response of period 2 pi / ``omega`` to the top motion in ``p`` (it must have that period).

    Fourier collocation at N = 2 ``n_harmonics`` + 1 nodes solved by Newton; the equations
    of motion are Wang (1971) eq. 47-48 at every node.

    Parameters
    ----------
    model : CableModel
        The Wang (1971) model.
    p : array_like
        Parameter vector whose top motion has period 2 pi / ``omega``.
    omega : float
        Forcing angular frequency (rad/s).
    n_harmonics : int, optional
        Harmonics kept in the collocation.
    input_amplitude : array_like of complex, optional
        Complex x_s, y_s (m) (and wave amplitudes) that seed the guess from the
        describing-function orbit (:func:`harmonic_response`).
    guess : ndarray, optional
        ``(nq, N)`` node values, e.g. a neighbouring solution for continuation.
    t0 : float, optional
        Time of the first node (s).

    Returns
    -------
    PeriodicSolution
        ``success`` is False (with the reason in ``message``) when Newton does not reach a
        residual of 1e-8 or the cable goes slack on the orbit. ``stats``: Newton iterations
        (``coarse_newton_iterations`` of the 3-harmonic start, ``full_newton_iterations``), the
        starts tried, and ``harmonic_tail``, the relative size of the highest harmonic kept.
    """
    n = 2 * n_harmonics + 1
    T = 2 * np.pi / omega
    times = t0 + T * np.arange(n) / n
    p = _without_ramp(model, p)
    if guess is None and input_amplitude is None:
        raise ParameterError("input_amplitude", None, "periodic_steady_state needs input_amplitude "
                             "(complex x_s, y_s) or a guess")
    # each start: (name, () -> (node values, Newton iterations spent making them))
    starts = [] if guess is None else [("given", lambda: (np.asarray(guess, float), 0))]
    if input_amplitude is not None:
        if n > 2 * COARSE_HARMONICS + 1:
            starts.append(("coarse", lambda: _coarse_guess(model, p, omega, times)))
        starts += [("linear", lambda: (_linear_guess(model, p, omega, input_amplitude, times), 0)),
                   ("describing function", lambda: (_describing_guess(model, p, omega, input_amplitude, times), 0))]
    iterations, coarse_iterations, tried = 0, 0, []
    q, res = None, np.inf
    for name, make in starts:
        Q0, it0 = make()
        coarse_iterations += it0
        tried.append(name)
        if Q0 is None:
            continue
        q, res, it = _newton(model, p, times, T, np.array(Q0, dtype=float).reshape(model.nq, n))
        iterations += it
        if res < 1e-8:
            break
    ok = res < 1e-8
    qd = q @ (omega * _unit_differentiation(model, n)).T
    X = np.vstack([q, qd])
    top_map, out_map = _node_maps(model, n)
    E = np.array(top_map(times[None, :], p))
    Y = np.array(out_map(X, E, p))
    outputs = {lbl: Y[i] for i, lbl in enumerate(model.output_labels)}
    msg = "" if ok else (f"collocation residual {res:.3g} > 1e-8: Newton did not converge; try more harmonics, a guess "
                         "from a neighbouring frequency, or simulate()")
    tens_min = float(np.min([v.min() for k, v in outputs.items() if k.startswith("tension")]))
    floors = [p[k] for k in model.layout.section_indices("cable.tension_floor")]
    if ok and tens_min <= max(floors):
        ok, msg = False, (f"the cable goes slack on the orbit (min tension {tens_min:.4g} N): the smooth periodic "
                          "solve does not apply; use simulate()")
    return PeriodicSolution(period=T, time=times, q=q, qd=qd, outputs=outputs, residual=res, success=ok, message=msg,
                            stats={"n_harmonics": n_harmonics, "nodes": n,
                                   "newton_iterations": iterations + coarse_iterations,
                                   "full_newton_iterations": iterations, "coarse_newton_iterations": coarse_iterations,
                                   "starts": tried, "harmonic_tail": _harmonic_tail(q)})


def _describing_guess(model: CableModel, p, omega: float, input_amplitude, times) -> np.ndarray:
    """Node values of the describing-function orbit (:func:`.equivalent.harmonic_response`)."""
    h = harmonic_response(model, p, [omega], input_amplitude, n_theta=32, ladder=4)
    Q = h.q_amplitude[0]
    return h.q_mean[0][:, None] + np.real(Q[:, None] * np.exp(1j * omega * times)[None, :])


def periodic_sweep(model: CableModel, p, omegas, input_amplitude, *, n_harmonics: int = 20) -> list:
    """Periodic steady states along a frequency sweep by continuation.

    The top motion in ``p`` is replaced at each omega by Re(Z e^{i omega t}) with Z =
    ``input_amplitude`` (complex x_s, y_s), i.e. the scene's sinusoids get the frequency omega.
    Each solution starts from its neighbours' node values (the nodes sit at the same phases of
    the period), extrapolated linearly in omega from the last two (secant predictor), so a step
    costs two or three Newton iterations; a failed step restarts cold.

    Parameters
    ----------
    model : CableModel
        The Wang (1971) model.
    p : array_like
        Parameter vector with sinusoidal top motion (amplitudes and phases are replaced by Z).
    omegas : array_like
        Angular frequencies [rad/s], solved in the given order (sorted sweeps continue best).
    input_amplitude : array_like of complex
        Complex x_s, y_s [m].
    n_harmonics : int, optional
        Harmonics kept in the collocation.

    Returns
    -------
    list of PeriodicSolution
        One per omega.
    """
    p = _without_ramp(model, p)
    Z = np.asarray(input_amplitude, complex)
    out, prev = [], []                     # (omega, node values) of the last converged solutions
    for w in np.atleast_1d(np.asarray(omegas, float)):
        pw = _with_sinusoids(model, p, w, Z)
        guess = None
        if len(prev) == 2:                 # secant predictor
            (w0, q0), (w1, q1) = prev
            guess = q1 + (w - w1) / (w1 - w0) * (q1 - q0)
        elif prev:
            guess = prev[-1][1]
        sol = periodic_steady_state(model, pw, w, n_harmonics=n_harmonics, input_amplitude=Z, guess=guess)
        out.append(sol)
        prev = (prev + [(w, sol.q)])[-2:] if sol.success else []
    return out


def _sinusoid_indices(model: CableModel) -> dict:
    """Per axis, the (amplitude, frequency, phase) positions in p of each top-motion sinusoid, in
    order (read from the layout once per model)."""
    def build():
        labels, out = model.layout.labels, {}
        for ax in ("x", "y"):
            ks = sorted({int(lb.split("[")[1].split("]")[0]) for lb in labels if lb.startswith(f"top_motion.{ax}[")})
            out[ax] = [tuple(model.layout.index(f"top_motion.{ax}[{k}].{a}") for a in ("amplitude", "frequency", "phase"))
                       for k in ks]
        return out
    return model.cache.get("periodic_sinusoid_indices", build)


def _with_sinusoids(model: CableModel, p, omega: float, Z) -> np.ndarray:
    """``p`` with the first sinusoid of x and of y set to Re(Z e^{i omega t}) = |Z| sin(omega t + arg(iZ))
    and every other sinusoid silenced."""
    p = np.array(p, dtype=float)
    for (ax, idx), z in zip(_sinusoid_indices(model).items(), Z[:2]):
        if not idx:
            if abs(z) > 0:
                raise ParameterError("input_amplitude", Z, f"the scene has no {ax} sinusoid to carry a {ax} motion")
            continue
        for j, (i_amp, i_freq, i_phase) in enumerate(idx):
            p[i_amp] = abs(z) if j == 0 else 0.0
            p[i_freq] = omega
            p[i_phase] = float(np.angle(1j * z)) if j == 0 else 0.0
    return p
