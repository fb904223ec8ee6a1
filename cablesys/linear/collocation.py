"""Fourier collocation of the periodic equations of motion: the numerical machinery of
:mod:`.periodic` (differentiation matrix, node functions, block Newton, the coarse start).

The collocation residual at node j is r_j = M(q_j) (D^2 q)_j - f(q_j, (D q)_j, e(t_j), p)
(Wang 1971 eq. 47-48), D the Fourier differentiation matrix (Trefethen, "Spectral Methods in
MATLAB", ch. 3, odd N). Newton's Jacobian is assembled from per-node AD blocks,
dr_j/dq_k = delta_jk dr_j/dq_j + D_jk dr_j/dq'_j + (D^2)_jk M(q_j); a small problem (the
3-harmonic coarse start) is instead solved whole by CasADi's Newton rootfinder.
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from ..compiled import compile_functions
from ..model import CableModel


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


def _node_residual(model: CableModel):
    """Symbols (q, q', q'', e, p), the residual r = M(q) q'' - f(q, q', e, p) (Wang 1971 eq. 47-48)
    and M, in SX."""
    nq = model.nq
    q, qd, qdd = ca.SX.sym("q", nq), ca.SX.sym("qd", nq), ca.SX.sym("qdd", nq)
    e = ca.SX.sym("e", model.top.size1_out(0))
    p = ca.SX.sym("p", len(model.layout))
    M, f = model.dynamics(q, qd, e, p)
    return (q, qd, qdd, e, p), ca.mtimes(M, qdd) - f, M


def _node_function(model: CableModel, n: int) -> ca.Function:
    """(Q, E, p, omega) -> [r | dr/dq | dr/dq' | M] at n nodes in one (nq, n (1 + 3 nq)) matrix,
    r = M(q) q'' - f(q, q', e, p) (Wang 1971 eq. 47-48) with q' = omega Q D1^T, q'' = omega^2 Q (D1^2)^T
    (D1 the differentiation matrix of period 2 pi) and its blocks by AD; mapped over the nodes,
    compiled and cached on disk. One array in, one out: a Newton step converts little."""
    def build():
        nq = model.nq
        (q, qd, qdd, e, p), r, M = _node_residual(model)
        node = ca.Function("colloc_node", [q, qd, qdd, e, p],
                           [ca.cse(ca.horzcat(r, ca.jacobian(r, q), ca.jacobian(r, qd), M))])
        mapped = node.map(n)
        D1 = fourier_differentiation(n, 2 * np.pi)
        Q, E, P, w = ca.MX.sym("Q", nq, n), ca.MX.sym("E", e.shape[0], n), ca.MX.sym("p", p.shape[0]), ca.MX.sym("w")
        Qd, Qdd = w * ca.mtimes(Q, ca.DM(D1.T)), w**2 * ca.mtimes(Q, ca.DM((D1 @ D1).T))
        out = ca.Function(f"colloc_nodes_{n}", [Q, E, P, w], [mapped(Q, Qd, Qdd, E, P)])
        return compile_functions([out], jacobians=False).functions[out.name()]   # C, cached on disk
    return model.cache.get(f"colloc_nodes_w_{n}", build)


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
        (q, qd, qdd, e, p), r, _ = _node_residual(model)
        node = ca.Function("colloc_residual", [q, qd, qdd, e, p], [r])
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
    from ..statics.steady import starting_guesses
    n, nc = times.size, 2 * COARSE_HARMONICS + 1
    T = 2 * np.pi / omega
    tc = times[0] + T * np.arange(nc) / nc
    Q0 = np.repeat(next(starting_guesses(model, p))[:, None], nc, axis=1)
    E = np.array(_node_maps(model, nc)[0](tc[None, :], p))
    par = np.concatenate([E.ravel(order="F"), p, [omega]])
    rf = _coarse_rootfinder(model, nc)
    Qc = np.array(rf(Q0.ravel(order="F"), par)).reshape(model.nq, nc, order="F")
    stats = rf.stats()
    it = int(stats.get("iter_count", 0))
    if not (stats.get("success", True) and np.all(np.isfinite(Qc))):
        return None, it
    return trig_interpolate(Qc, n), it


def _newton(model: CableModel, p, times, T, Q, *, tol: float = 1e-8, max_iter: int = 50):
    """Newton on the collocation equations from node values ``Q`` (nq, n); exact block Jacobian,
    step halving when the residual does not decrease. Returns (Q, max |r|, iterations)."""
    nq, n = Q.shape
    omega = 2 * np.pi / T
    D = _unit_differentiation(model, n) * omega
    D2 = D @ D
    node = _node_function(model, n)
    E = _node_maps(model, n)[0](times[None, :], p)          # DM: E and p are converted once, not per call
    p_dm = ca.DM(p)
    idx = np.arange(n)
    # J[j a, k b] = delta_jk A_j[a, b] + D[j, k] B_j[a, b] + D2[j, k] C_j[a, b]  (node-major ordering)
    DD = np.stack([D, D2])[:, :, None, :, None]

    def evaluate(Qv):
        """(R, blocks): R (nq, n) and blocks (3, n, nq, nq) = [dr/dq, dr/dq', M] at every node."""
        out = np.asarray(node(Qv, E, p_dm, omega)).reshape(nq, n, 1 + 3 * nq)  # per node [r A B C]
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


def _harmonic_tail(q: np.ndarray) -> float:
    """Largest, over the coordinates, of |highest harmonic kept| / |largest harmonic|: a truncation
    indicator (the error of the orbit is of this order, up to ~10x for the Dale scene's stretch,
    whose |v| v drag makes the spectrum decay algebraically); raise ``n_harmonics`` when it is not
    well below the accuracy wanted."""
    c = np.abs(np.fft.rfft(q, axis=-1))[:, 1:]
    big = c.max(axis=1)
    keep = big > 0
    return float(np.max(c[keep, -1] / big[keep])) if np.any(keep) else 0.0
