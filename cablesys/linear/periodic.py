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
Starting guess: the same collocation with 3 harmonics (7 nodes: small enough for CasADi's own
Newton rootfinder with the AD Jacobian of the whole residual, compiled, in one call), solved
from the hanging guess of the statics and interpolated onto the N nodes, where Newton then needs 2-3
steps; the linear response at omega and the describing-function orbit of :mod:`.equivalent`
are the fallbacks. Along a frequency sweep (:func:`periodic_sweep`) each solution starts from
the secant extrapolation of its two neighbours' (continuation). This is the pseudo-spectral (AFT) harmonic balance: no drag linearization,
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
    """[r | dr/dq | dr/dq' | M] at n nodes in one (nq, n (1 + 3 nq)) matrix, r = M(q) q'' - f(q, q', e, p)
    (Wang 1971 eq. 47-48) and its blocks by AD; mapped over the nodes, compiled and cached on disk.
    One output, so a Newton step reads one array back from CasADi."""
    def build():
        nq = model.nq
        q, qd, qdd = ca.SX.sym("q", nq), ca.SX.sym("qd", nq), ca.SX.sym("qdd", nq)
        e = ca.SX.sym("e", model.top.size1_out(0))
        p = ca.SX.sym("p", len(model.layout))
        M, f = model.dynamics(q, qd, e, p)
        r = ca.mtimes(M, qdd) - f
        node = ca.Function("colloc_node", [q, qd, qdd, e, p],
                           [ca.cse(ca.horzcat(r, ca.jacobian(r, q), ca.jacobian(r, qd), M))])
        mapped = node.map(n)
        Q, Qd, Qdd = ca.MX.sym("Q", nq, n), ca.MX.sym("Qd", nq, n), ca.MX.sym("Qdd", nq, n)
        E, P = ca.MX.sym("E", e.shape[0], n), ca.MX.sym("p", p.shape[0])
        out = ca.Function(f"colloc_nodes_{n}", [Q, Qd, Qdd, E, P], [mapped(Q, Qd, Qdd, E, P)])
        return compile_functions([out], jacobians=False).functions[out.name()]   # C, cached on disk
    return model.cache.get(f"colloc_nodes_{n}", build)


def _node_maps(model: CableModel, n: int) -> tuple[ca.Function, ca.Function]:
    """The top motion e(t) and the outputs y(x, e, p) mapped over n nodes (built once per model, compiled)."""
    def build():
        maps = [model.top.map(f"colloc_top_{n}", "serial", n, [1], []),
                model.outputs.map(f"colloc_outputs_{n}", "serial", n, [2], [])]
        out = compile_functions(maps, jacobians=False).functions
        return tuple(out[f.name()] for f in maps)
    return model.cache.get(f"colloc_maps_{n}", build)


def _unit_differentiation(model: CableModel, n: int) -> np.ndarray:
    """:func:`fourier_differentiation` for period 2 pi (scale by omega), cached per model."""
    return model.cache.get(f"fourier_D_{n}", lambda: fourier_differentiation(n, 2 * np.pi))


COARSE_HARMONICS = 3      # harmonics of the coarse collocation that makes the Newton start


def _coarse_rootfinder(model: CableModel, n: int) -> ca.Function:
    """CasADi Newton rootfinder of the collocation equations on n (small) nodes: Q(Q_guess, [vec E, p, omega]).

    The whole residual is one SX function of the node values, differentiated by AD (cheap at a
    few nodes) and compiled with its Q-Jacobian, so the coarse Newton runs in C in one call."""
    def build():
        nq = model.nq
        q, qd, qdd = ca.SX.sym("q", nq), ca.SX.sym("qd", nq), ca.SX.sym("qdd", nq)
        e = ca.SX.sym("e", model.top.size1_out(0))
        p = ca.SX.sym("p", len(model.layout))
        M, f = model.dynamics(q, qd, e, p)
        node = ca.Function("colloc_residual", [q, qd, qdd, e, p], [ca.mtimes(M, qdd) - f])
        Q, E, w = ca.SX.sym("Q", nq, n), ca.SX.sym("E", e.shape[0], n), ca.SX.sym("omega")
        D1 = fourier_differentiation(n, 2 * np.pi)          # unit frequency: D = omega D1
        Qd, Qdd = w * ca.mtimes(Q, D1.T), w**2 * ca.mtimes(Q, (D1 @ D1).T)
        R = ca.horzcat(*[node(Q[:, j], Qd[:, j], Qdd[:, j], E[:, j], p) for j in range(n)])
        G = ca.Function(f"colloc_coarse_{n}", [ca.vec(Q), ca.vertcat(ca.vec(E), p, w)], [ca.vec(R)],
                        ["Q", "par"], ["r"])
        G = compile_functions([G], jacobians=("Q",)).functions[G.name()]
        return ca.rootfinder(f"colloc_coarse_newton_{n}", "newton", G,
                             {"abstol": 1e-9, "max_iter": 40, "error_on_fail": False})
    return model.cache.get(f"colloc_coarse_{n}", build)


def _coarse_guess(model: CableModel, p, omega: float, times) -> tuple[np.ndarray | None, int]:
    """Node values at ``times`` from the periodic solution with ``COARSE_HARMONICS`` harmonics,
    trigonometrically interpolated: the start whose nonlinearity (drag at resonance) is already
    resolved, so the full collocation needs 2-3 steps. The coarse Newton starts from the
    statics' first hanging guess (every angle 0, each section's stretch under the weight below
    it): at 7 nodes it converges from there in 4-8 steps, as from the exact steady state or the
    linear response, which would cost a KINSOL solve and a linearization. Returns (node values
    or None when the coarse Newton fails, coarse Newton iterations)."""
    from ..statics.steady import _guesses
    n, nc = times.size, 2 * COARSE_HARMONICS + 1
    T = 2 * np.pi / omega
    tc = times[0] + T * np.arange(nc) / nc
    Q0 = np.repeat(next(_guesses(model, p))[:, None], nc, axis=1)
    E = np.array(_node_maps(model, nc)[0](tc[None, :], p))
    par = np.concatenate([E.ravel(order="F"), p, [omega]])
    rf = _coarse_rootfinder(model, nc)
    Qc = np.array(rf(Q0.ravel(order="F"), par)).reshape(model.nq, nc, order="F")
    stats = rf.stats()
    it = int(stats.get("iter_count", 0))
    if not (stats.get("success", True) and np.all(np.isfinite(Qc))):
        return None, it
    return trig_interpolate(Qc, n), it


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
    D = _unit_differentiation(model, n) * (2 * np.pi / T)
    D2 = D @ D
    node = _node_function(model, n)
    E = _node_maps(model, n)[0](times[None, :], p)          # DM: E and p are converted once, not per call
    p_dm = ca.DM(p)
    idx = np.arange(n)
    # J[j a, k b] = delta_jk A_j[a, b] + D[j, k] B_j[a, b] + D2[j, k] C_j[a, b]  (node-major ordering)
    DD = np.stack([D, D2])[:, :, None, :, None]

    def evaluate(Qv):
        """(R, blocks): R (nq, n) and blocks (3, n, nq, nq) = [dr/dq, dr/dq', M] at every node."""
        out = np.asarray(node(Qv, Qv @ D.T, Qv @ D2.T, E, p_dm)).reshape(nq, n, 1 + 3 * nq)  # per node [r A B C]
        return out[:, :, 0], out[:, :, 1:].reshape(nq, n, 3, nq).transpose(2, 1, 0, 3)

    R, blk = evaluate(Q)
    res = float(np.max(np.abs(R)))
    it, step_size, prev_size = 0, np.inf, np.inf
    # stop on a small residual *and* a small error estimate: the residual tolerance is absolute (N),
    # and converging the node values as well makes the orbit independent of where Newton started
    while (res > tol or step_size > 1e-9 * (1.0 + np.max(np.abs(Q)))) and it < max_iter and np.isfinite(res):
        it += 1
        J4 = np.sum(DD * blk[1:, :, :, None, :], axis=0)
        J4[idx, :, idx, :] += blk[0]
        step = np.linalg.solve(J4.reshape(n * nq, n * nq), R.T.ravel()).reshape(n, nq).T
        lam = 1.0
        while True:
            Qn = Q - lam * step
            Rn, blk_n = evaluate(Qn)
            rn = float(np.max(np.abs(Rn)))
            if (np.isfinite(rn) and (rn < res or rn <= tol)) or lam < 1e-3:
                break
            lam *= 0.5
        size = lam * float(np.max(np.abs(step)))
        # error left after a full step: about the next step, size^2 / previous size (quadratic convergence)
        step_size = min(size, size**2 / prev_size) if lam == 1.0 and np.isfinite(prev_size) else size
        Q, R, blk, res, prev_size = Qn, Rn, blk_n, rn, size
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


def _harmonic_tail(q: np.ndarray) -> float:
    """Largest, over the coordinates, of |highest harmonic kept| / |largest harmonic|: a truncation
    indicator (the error of the orbit is of this order, up to ~10x for the Dale scene's stretch,
    whose |v| v drag makes the spectrum decay algebraically); raise ``n_harmonics`` when it is not
    well below the accuracy wanted."""
    c = np.abs(np.fft.rfft(q, axis=-1))[:, 1:]
    big = c.max(axis=1)
    keep = big > 0
    return float(np.max(c[keep, -1] / big[keep])) if np.any(keep) else 0.0


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
