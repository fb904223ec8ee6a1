"""Nonlinear periodic steady state by trigonometric collocation (harmonic balance), with CasADi.

The periodic solution of M(q) q'' = f(q, q', e(t), p) (Wang 1971 eq. 47-48) with period T is
represented by its values q_j at N = 2H + 1 equally spaced times t_j; q' and q'' are exact for
trigonometric polynomials of degree H through the Fourier differentiation matrix D
(Trefethen, "Spectral Methods in MATLAB", ch. 3, odd N). The N nq collocation equations

    M(q_j) (D^2 q)_j - f(q_j, (D q)_j, e(t_j), p) = 0

are solved with a CasADi rootfinder (Newton, dense AD Jacobian) from the describing-function
orbit of :mod:`.equivalent`. This is the pseudo-spectral (AFT) harmonic balance: no drag
linearization, every harmonic up to H. The cable must stay taut (no slack switches).
"""

from __future__ import annotations

import dataclasses

import casadi as ca
import numpy as np

from ..errors import ParameterError
from ..model import CableModel
from ..results import ResultBase, timed
from .equivalent import harmonic_response


def fourier_differentiation(n: int, period: float) -> np.ndarray:
    """D with (D q)_j = q'(t_j) for trigonometric interpolation on n (odd) points over ``period``."""
    if n % 2 == 0:
        raise ValueError("n must be odd")
    k = np.arange(n)
    diff = k[:, None] - k[None, :]
    with np.errstate(divide="ignore"):
        D = 0.5 * (-1.0) ** diff / np.sin(np.pi * diff / n)
    D[k, k] = 0.0
    return D * (2 * np.pi / period)


def trig_interpolate(values: np.ndarray, n_fine: int) -> np.ndarray:
    """Trigonometric interpolation of periodic samples (last axis, odd count) onto ``n_fine`` points."""
    n = values.shape[-1]
    c = np.fft.rfft(values, axis=-1)
    out = np.fft.irfft(c, n_fine, axis=-1) * n_fine / n
    return out


def _collocation_rootfinder(model: CableModel, n: int) -> tuple[ca.Function, ca.Function]:
    """Newton on the collocation residual at n nodes, and that residual (built once per model and n)."""
    return model.cache.get(f"colloc_{n}", lambda: _build_collocation(model, n))


def _build_collocation(model: CableModel, n: int) -> tuple[ca.Function, ca.Function]:
    nq = model.nq
    Q = ca.SX.sym("Q", nq, n)
    T = ca.SX.sym("T")
    t0 = ca.SX.sym("t0")
    p = ca.SX.sym("p", len(model.layout))
    D = fourier_differentiation(n, 1.0) / T            # D scales as 1/T
    Qd = ca.mtimes(Q, D.T)
    Qdd = ca.mtimes(Qd, D.T)
    times = t0 + T * np.arange(n) / n
    E = model.top.map(n)(ca.transpose(times), p)
    Mf = model.dynamics.map(n)
    M, f = Mf(Q, Qd, E, p)
    res = []
    for j in range(n):
        Mj = M[:, j * nq:(j + 1) * nq]
        res.append(ca.mtimes(Mj, Qdd[:, j]) - f[:, j])
    g = ca.vec(ca.horzcat(*res))
    G = ca.Function("colloc", [ca.vec(Q), ca.vertcat(T, t0, p)], [g])
    rf = ca.rootfinder("colloc_solve", "newton", G, {"abstol": 1e-12, "max_iter": 50, "error_on_fail": False})
    return rf, G


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
        y = trig_interpolate(self.outputs[label], n_fine)
        return 0.5 * float(y.max() - y.min())

    def first_harmonic(self, label: str) -> complex:
        """Complex first-harmonic amplitude Y with y ~ Re(Y e^{i omega t})."""
        y = self.outputs[label]
        return complex(2.0 / len(y) * np.sum(y * np.exp(-2j * np.pi * self.time / self.period)))

    def to_xarray(self):
        import xarray as xr
        return xr.Dataset({k: ("time", v) for k, v in self.outputs.items()}, coords={"time": self.time},
                          attrs={"period": self.period, "residual": self.residual, "success": int(self.success)})


def scene_input_amplitude(scene) -> tuple[float, np.ndarray]:
    """(omega, Z) of a top motion made of sinusoids at one frequency: a sin(wt + ph) = Re(-i a e^{i ph} e^{iwt})."""
    terms = [(ax, s) for ax in ("x", "y") for s in getattr(scene.top_motion, ax)]
    freqs = {round(s.frequency, 12) for _, s in terms if s.amplitude != 0.0}
    if len(freqs) != 1 or scene.top_motion.series is not None:
        raise ParameterError("top_motion", f"frequencies {sorted(freqs)}"
                             + (" and a sampled series" if scene.top_motion.series is not None else ""),
                             "the periodic solve needs a top motion of sinusoids at one frequency and no sampled "
                             "series; give one frequency or use simulate()")
    Z = np.zeros(2 + len(scene.environment.waves), complex)
    for ax, s in terms:
        if s.amplitude == 0.0:
            continue
        Z[0 if ax == "x" else 1] += -1j * s.amplitude * np.exp(1j * s.phase)
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
        residual of 1e-8 or the cable goes slack on the orbit.
    """
    n = 2 * n_harmonics + 1
    T = 2 * np.pi / omega
    times = t0 + T * np.arange(n) / n
    p = np.asarray(p, float)
    if guess is None:
        if input_amplitude is None:
            raise ParameterError("input_amplitude", None, "periodic_steady_state needs input_amplitude "
                                 "(complex x_s, y_s) or a guess")
        h = harmonic_response(model, p, [omega], input_amplitude, n_theta=32, ladder=4)
        Q = h.q_amplitude[0]
        guess = h.q_mean[0][:, None] + np.real(Q[:, None] * np.exp(1j * omega * times)[None, :])
    rf, G = _collocation_rootfinder(model, n)
    par = np.concatenate([[T, t0], p])
    sol = np.array(rf(np.asarray(guess, float).ravel(order="F"), par)).ravel()
    res = float(np.max(np.abs(np.array(G(sol, par))))) if np.all(np.isfinite(sol)) else np.inf
    ok = res < 1e-8
    q = sol.reshape(model.nq, n, order="F")
    qd = q @ fourier_differentiation(n, T).T
    X = np.vstack([q, qd])
    E = np.array(model.top.map(n)(times[None, :], p))
    Y = np.array(model.outputs.map(n)(X, E, p))
    outputs = {lbl: Y[i] for i, lbl in enumerate(model.output_labels)}
    msg = "" if ok else (f"collocation residual {res:.3g} > 1e-8: Newton did not converge; try more harmonics, a guess "
                         "from a neighbouring frequency, or simulate()")
    tens_min = float(np.min([v.min() for k, v in outputs.items() if k.startswith("tension")]))
    floors = [p[k] for k in model.layout.section_indices("cable.tension_floor")]
    if ok and tens_min <= max(floors):
        ok, msg = False, (f"the cable goes slack on the orbit (min tension {tens_min:.4g} N): the smooth periodic "
                          "solve does not apply; use simulate()")
    return PeriodicSolution(period=T, time=times, q=q, qd=qd, outputs=outputs, residual=res, success=ok, message=msg,
                            stats={"n_harmonics": n_harmonics, "nodes": n})
