"""Nonlinear periodic steady state by trigonometric collocation (harmonic balance), with CasADi.

The periodic solution of M(q) q'' = f(q, q', e(t), p) (Wang 1971 eq. 47-48) with period T is
represented by its values q_j at N = 2H + 1 equally spaced times t_j; q' and q'' are exact for
trigonometric polynomials of degree H through the Fourier differentiation matrix D
(Trefethen, "Spectral Methods in MATLAB", ch. 3, odd N). The N nq collocation equations

    M(q_j) (D^2 q)_j - f(q_j, (D q)_j, e(t_j), p) = 0

are solved by Newton's method with the exact Jacobian assembled from per-node blocks,

    dr_j/dq_k = delta_jk dr_j/dq_j + D_jk dr_j/dq'_j + (D^2)_jk M(q_j),

the three n-by-n-free pieces evaluated by one mapped CasADi function (AD of the node
residual), so a Newton step costs one pass over the nodes and one dense (N nq) solve instead
of differentiating the whole collocation graph (whose symbolic Jacobian has ~2e6 operations).
Starting guess: the linear response at omega about the steady state (one complex solve), or
the describing-function orbit of :mod:`.equivalent` when that does not converge; along a
frequency sweep (:func:`periodic_sweep`) each solution starts from its neighbour's
(continuation). This is the pseudo-spectral (AFT) harmonic balance: no drag linearization,
every harmonic up to H. The cable must stay taut (no slack switches). A smooth start
(``top_motion.ramp_s``) is switched off: the periodic state is the one after any ramp.
"""

from __future__ import annotations

import dataclasses

import casadi as ca
import numpy as np

from ..compiled import compile_functions
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


def _node_function(model: CableModel, n: int) -> ca.Function:
    """Residual r = M(q) q'' - f(q, q', e, p) at n nodes and its blocks dr/dq, dr/dq', M (mapped)."""
    def build():
        nq = model.nq
        q, qd, qdd = ca.SX.sym("q", nq), ca.SX.sym("qd", nq), ca.SX.sym("qdd", nq)
        e = ca.SX.sym("e", model.top.size1_out(0))
        p = ca.SX.sym("p", len(model.layout))
        M, f = model.dynamics(q, qd, e, p)
        r = ca.mtimes(M, qdd) - f
        node = ca.Function("colloc_node", [q, qd, qdd, e, p], [r, ca.jacobian(r, q), ca.jacobian(r, qd), M])
        mapped = node.map(n)
        return compile_functions([mapped], jacobians=False).functions[mapped.name()]   # C, cached on disk
    return model.cache.get(f"colloc_node_{n}", build)


def _without_ramp(model: CableModel, p) -> np.ndarray:
    """``p`` with the smooth start off (the periodic state is the one after any ramp)."""
    p = np.array(p, dtype=float)
    if "top_motion.ramp_s" in model.layout.labels:
        p[model.layout.index("top_motion.ramp_s")] = 0.0
    return p


def _newton(model: CableModel, p, times, T, Q, *, tol: float = 1e-8, max_iter: int = 50):
    """Newton on the collocation equations from node values ``Q`` (nq, n); exact block Jacobian,
    step halving when the residual does not decrease. Returns (Q, max |r|, iterations)."""
    nq, n = Q.shape
    D = fourier_differentiation(n, T)
    D2 = D @ D
    node = _node_function(model, n)
    E = np.array(model.top.map(n)(times[None, :], p))
    idx = np.arange(n)

    def evaluate(Qv):
        return [o.full() for o in node(Qv, Qv @ D.T, Qv @ D2.T, E, p)]

    R, A, B, C = evaluate(Q)
    res = float(np.max(np.abs(R)))
    it = 0
    while res > tol and it < max_iter and np.isfinite(res):
        it += 1
        # J[j a, k b] = delta_jk A_j[a, b] + D[j, k] B_j[a, b] + D2[j, k] C_j[a, b]  (node-major ordering)
        Aj, Bj, Cj = (X.reshape(nq, n, nq).transpose(1, 0, 2) for X in (A, B, C))
        J4 = D[:, None, :, None] * Bj[:, :, None, :] + D2[:, None, :, None] * Cj[:, :, None, :]
        J4[idx, :, idx, :] += Aj
        J = J4.reshape(n * nq, n * nq)
        step = np.linalg.solve(J, R.T.ravel()).reshape(n, nq).T
        lam = 1.0
        while True:
            Qn = Q - lam * step
            Rn, An, Bn, Cn = evaluate(Qn)
            rn = float(np.max(np.abs(Rn)))
            if (np.isfinite(rn) and rn < res) or lam < 1e-3:
                break
            lam *= 0.5
        Q, R, A, B, C, res = Qn, Rn, An, Bn, Cn, rn
    return Q, res, it


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
    p = _without_ramp(model, p)
    if guess is None and input_amplitude is None:
        raise ParameterError("input_amplitude", None, "periodic_steady_state needs input_amplitude "
                             "(complex x_s, y_s) or a guess")
    starts = [] if guess is None else [("given", lambda: np.asarray(guess, float))]
    if input_amplitude is not None:
        starts += [("linear", lambda: _linear_guess(model, p, omega, input_amplitude, times)),
                   ("describing function", lambda: _describing_guess(model, p, omega, input_amplitude, times))]
    iterations, tried = 0, []
    for name, make in starts:
        q, res, it = _newton(model, p, times, T, np.array(make(), dtype=float).reshape(model.nq, n))
        iterations += it
        tried.append(name)
        if res < 1e-8:
            break
    ok = res < 1e-8
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
                            stats={"n_harmonics": n_harmonics, "nodes": n, "newton_iterations": iterations,
                                   "starts": tried})


def _describing_guess(model: CableModel, p, omega: float, input_amplitude, times) -> np.ndarray:
    """Node values of the describing-function orbit (:func:`.equivalent.harmonic_response`)."""
    h = harmonic_response(model, p, [omega], input_amplitude, n_theta=32, ladder=4)
    Q = h.q_amplitude[0]
    return h.q_mean[0][:, None] + np.real(Q[:, None] * np.exp(1j * omega * times)[None, :])


def periodic_sweep(model: CableModel, p, omegas, input_amplitude, *, n_harmonics: int = 20) -> list:
    """Periodic steady states along a frequency sweep by continuation.

    The top motion in ``p`` is replaced at each omega by Re(Z e^{i omega t}) with Z =
    ``input_amplitude`` (complex x_s, y_s), i.e. the scene's sinusoids get the frequency omega.
    Each solution starts from its neighbour's node values (the nodes sit at the same phases of
    the period), so a step costs a few Newton iterations; a failed step restarts from the
    linear guess.

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
    out, guess = [], None
    for w in np.atleast_1d(np.asarray(omegas, float)):
        pw = _with_sinusoids(model, p, w, Z)
        sol = periodic_steady_state(model, pw, w, n_harmonics=n_harmonics, input_amplitude=Z, guess=guess)
        out.append(sol)
        guess = sol.q if sol.success else None
    return out


def _with_sinusoids(model: CableModel, p, omega: float, Z) -> np.ndarray:
    """``p`` with the first sinusoid of x and of y set to Re(Z e^{i omega t}) = |Z| sin(omega t + arg(iZ))
    and every other sinusoid silenced."""
    p = np.array(p, dtype=float)
    labels = model.layout.labels
    for ax, z in zip(("x", "y"), Z[:2]):
        ks = sorted({int(lb.split("[")[1].split("]")[0]) for lb in labels if lb.startswith(f"top_motion.{ax}[")})
        if not ks:
            if abs(z) > 0:
                raise ParameterError("input_amplitude", Z, f"the scene has no {ax} sinusoid to carry a {ax} motion")
            continue
        for k in ks:
            pre = f"top_motion.{ax}[{k}]."
            p[model.layout.index(pre + "amplitude")] = abs(z) if k == ks[0] else 0.0
            p[model.layout.index(pre + "frequency")] = omega
            p[model.layout.index(pre + "phase")] = float(np.angle(1j * z)) if k == ks[0] else 0.0
    return p
