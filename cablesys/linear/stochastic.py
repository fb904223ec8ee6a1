"""Gaussian (stochastic) equivalent linearization for an irregular sea, iterated to self-consistency.

N = E[dr/dxi] over xi ~ N(xi_mean, Sigma) (Atalik & Utku 1976; Roberts & Spanos, "Random
Vibration and Statistical Linearization", ch. 5): for one zero-mean drag element |v| v this is
sqrt(8/pi) sigma_v, with a mean flow U it tends to the exact slope 2|U|. Sigma is the
covariance of the linear response, Sigma = int Re(Xi(w) Xi(w)^H) S(w) dw, and the mean obeys
E[r] = 0 (the drag's rectified mean force shifts the equilibrium). The expectation is a
scrambled-Sobol quadrature with antithetic pairs of the model's own CasADi Jacobian: one
mapped function sums r and dr/dxi over the samples (compiled and cached on disk by
:mod:`cablesys.compiled`), so an iteration is one call; the outputs'
Jacobian is averaged once, after the iteration has settled. A neighbouring solution
(``start``: a nearby design, sea state or parameter) warm-starts the covariance and the
mean shift, and the iteration then settles in a few passes.

The sea enters through the top: the top follows the surface particle orbit of Wang (1971)
eq. 26 at x = 0 (a buoy), x_s = a cos wt, y_s = -a sin wt, i.e. input (1, i) per unit wave
amplitude; other input directions can be given.
"""

from __future__ import annotations

import dataclasses
from typing import ClassVar

import casadi as ca
import numpy as np
from scipy.stats import norm, qmc

from ..compiled import compile_functions
from ..errors import ParameterError
from ..model import CableModel
from ..results import ResultBase, timed
from .linearization import (
    LinearModel,
    top_inputs,
    from_jacobian,
    functions,
    linearize,
    operating_xi,
    taut_parameters,
    xi_blocks,
)
from .sea_response import input_transfers
from .spectra import significant_amplitude, slack_probability

BUOY = np.array([1.0, 1.0j])
SEA_POINTS = 60             # frequencies over a scene sea's band (SeaSpectrum.band: 0.1 % - 99.9 % of its energy)


def sea_inputs(scene, model: CableModel, n_omega: int = SEA_POINTS) -> tuple:
    """The scene's irregular sea as the linearization's input: (omega, S(omega), D, weights), the same sea and top
    motion the time-domain run realises (:func:`cablesys.scene.sea.sea_sinusoids`).

    ``omega``: ``n_omega`` points over the sea's band (rad/s); S: its spectrum (m^2 s/rad); D (n_dir, n_omega, inputs)
    and ``weights`` (n_dir): the top's motion per unit wave amplitude per wave direction, and the directions' weights,
    of :func:`cablesys.linear.sea_response.input_transfers` (the sea response's), turned from the elevation's
    convention eta = Re(-i e^{i omega t}) to x = Re(D e^{i omega t}). The sea's particle velocities at the cable are not
    an input of this linearization: refused, named, rather than left out.
    """
    sea = scene.top_motion.spectrum
    if sea is None:
        raise ParameterError("top_motion.spectrum", None, "must be given for the scene's own sea")
    if sea.waves_at_cable:
        raise ParameterError("top_motion.spectrum.waves_at_cable", True,
                             "must be false for the stochastic linearization (it moves the top only; the sea's "
                             "particle velocities at the cable are not among its inputs); the time-domain run has them")
    lo, hi = sea.band()
    omega = np.linspace(lo, hi, int(n_omega))
    weights, T = input_transfers(scene, omega, top_inputs(model))
    return omega, sea.density(omega), -1j * T, weights


@dataclasses.dataclass(frozen=True, eq=False)
class StochasticResponse(ResultBase):
    """Self-consistent Gaussian linearization and the response statistics it predicts.

    ``success``: the response standard deviations settled to ``tol``; ``stats['iterations']``."""

    omega: np.ndarray
    spectrum: np.ndarray
    linear: LinearModel
    output_labels: tuple
    transfer: np.ndarray            # (n_omega, ny) outputs per unit sea amplitude
    output_mean: np.ndarray
    output_std: np.ndarray
    tension_floor: float
    success: bool = True
    message: str = ""
    stats: dict = dataclasses.field(default_factory=dict)
    covariance: np.ndarray | None = None     # Sigma of xi (last iterate), for warm starts
    mean_shift: np.ndarray | None = None     # q mean minus the static q0 (rectified drag)

    VARIABLES: ClassVar[dict] = {"sea_spectrum": ("m^2 s/rad", "sea elevation spectrum"),
                                  "response_spectrum": ("SI^2 s/rad", "output spectrum"), "mean": ("SI", "output mean"),
                                  "std": ("SI", "output standard deviation"), "output": ("1", "output")}

    @property
    def converged(self) -> bool:
        """Alias of :attr:`success`."""
        return self.success

    @property
    def iterations(self) -> int:
        """Fixed-point iterations done (``stats['iterations']``)."""
        return int(self.stats.get("iterations", 0))

    def response_spectrum(self, output: str) -> np.ndarray:
        return np.abs(self.transfer[:, self.output_labels.index(output)]) ** 2 * self.spectrum

    def significant_amplitude(self, output: str) -> float:
        return significant_amplitude(self.omega, self.response_spectrum(output))

    def std(self, output: str) -> float:
        return float(self.output_std[self.output_labels.index(output)])

    def slack_probability(self, output: str = "tension_mid") -> float:
        """P(tension < TENS) under the Gaussian assumption."""
        i = self.output_labels.index(output)
        return slack_probability(self.output_mean[i], self.output_std[i], self.tension_floor)

    def to_xarray(self):
        import xarray as xr
        S_y = np.abs(self.transfer) ** 2 * self.spectrum[:, None]
        return xr.Dataset({"sea_spectrum": ("omega", self.spectrum), "response_spectrum": (("omega", "output"), S_y),
                           "mean": ("output", self.output_mean), "std": ("output", self.output_std)},
                          coords={"omega": self.omega, "output": list(self.output_labels)},
                          attrs={"iterations": self.iterations})


def _normal_samples(dim: int, n_log2: int, seed: int) -> np.ndarray:
    u = qmc.Sobol(dim, scramble=True, seed=seed).random_base2(n_log2)
    z = norm.ppf(np.clip(u, 1e-12, 1 - 1e-12))
    return np.vstack([z, -z])                         # antithetic: odd moments exactly zero


def _moment_functions(model: CableModel, n: int) -> tuple[ca.Function, ca.Function]:
    """Sums over n samples xi_k (columns of X) of (r, dr/dxi) and of (y, dy/dxi): one mapped,
    reduced CasADi function each, compiled (cached on disk)."""
    def build():
        fns = functions(model)
        b = xi_blocks(model)
        xi, p = ca.SX.sym("xi", b["n"]), ca.SX.sym("p", len(model.layout))
        r = fns["residual"](xi, p)
        y, Jy = fns["out_jac"](xi, p)
        # r and its Jacobian from one graph (shared subexpressions without the cost of ca.cse)
        rj = ca.Function("stoch_rj", [xi, p], [ca.vertcat(r, ca.vec(ca.jacobian(r, xi)))])
        yj = ca.Function("stoch_yj", [xi, p], [ca.vertcat(y, ca.vec(Jy))])
        mapped = [f.map(f"{f.name()}_sum_{n}", "serial", n, [1], [0]) for f in (rj, yj)]
        out = compile_functions(mapped, jacobians=False).functions
        return tuple(out[m.name()] for m in mapped)
    return model.cache.get(f"stochastic_moments_{n}", build)


def _xi_amplitudes(b: dict, Q: np.ndarray, D: np.ndarray, omega: np.ndarray) -> np.ndarray:
    """Complex amplitudes of xi = (q, q', q'', z, z', z'', w) on the grid, per wave direction: (n_dir, n_omega, n_xi)
    (:func:`cablesys.linear.equivalent.complex_xi` for every frequency and direction at once)."""
    s = 1j * omega[None, :, None]
    nz = b["z"].stop - b["z"].start       # the top's inputs: x_s, y_s (and z_s in 3-D, a vessel's rotations)
    Z = D[..., :nz]
    return np.concatenate([Q, s * Q, s**2 * Q, Z, s * Z, s**2 * Z, D[..., nz:]], axis=-1)


def _weighted(A: np.ndarray, weights: np.ndarray, S: np.ndarray, omega: np.ndarray) -> np.ndarray:
    """A (n_dir, n_omega, m) scaled by sqrt(w_d S(omega_k) dw_k), the directions' weights times the trapezoid's on the
    grid: sum over d and k of Re(a a^H) of its rows is sum_d w_d int Re(A_d A_d^H) S d omega."""
    dw = np.zeros(omega.size)
    dw[1:] += 0.5 * np.diff(omega)
    dw[:-1] += 0.5 * np.diff(omega)
    return A * np.sqrt(weights[:, None, None] * (S * dw)[None, :, None])


@timed
def stochastic_response(model: CableModel, p, omega, spectrum, *, direction=BUOY, weights=None, n_log2: int = 10,
                        tol: float = 1e-4, max_iter: int = 60, relax: float = 0.5, seed: int = 0,
                        start: StochasticResponse | None = None) -> StochasticResponse:
    """Iterate N = E[J] <-> Sigma(N) until the response standard deviations change by < ``tol``.

    Gaussian equivalent linearization (Roberts & Spanos ch. 5): N = E[dr/dxi] over the
    response distribution, Sigma = int Re(Xi Xi^H) S(omega) d omega, E[r] = 0.

    Parameters
    ----------
    model : CableModel
        The Wang (1971) model.
    p : array_like
        Parameter vector; slack switches are cleared.
    omega : array_like
        Angular frequency grid (rad/s), at least 8 points.
    spectrum : array_like
        Sea elevation spectrum S(omega) (m^2 s/rad) on ``omega``.
    direction : array_like of complex, optional
        Input amplitudes per unit sea amplitude, x = Re(D e^{i omega t}) (default: the buoy orbit (1, i), Wang (1971)
        eq. 26): one per input (the first of ``input_labels``), or one row per frequency of ``omega`` (a motion RAO,
        :func:`sea_inputs`), or one such block per wave direction of a spread sea (n_dir, n_omega, inputs).
    weights : array_like, optional
        The directions' weights (n_dir, summing to 1: :meth:`cablesys.scene.sea.SeaSpectrum.direction_quadrature`):
        Sigma = sum_d w_d int Re(Xi_d Xi_d^H) S d omega, the directions' responses uncorrelated (DNV-RP-C205 3.5.8);
        default one direction. ``transfer`` then holds sqrt(sum_d w_d |Y_d|^2), the magnitude whose square times S
        is the response spectrum.
    n_log2 : int, optional
        log2 of the Sobol sample count of the expectation.
    tol : float, optional
        Relative change of the standard deviations that stops the iteration.
    max_iter : int, optional
        Iteration limit.
    relax : float, optional
        Under-relaxation of the covariance update (0 < relax <= 1).
    seed : int, optional
        Seed of the scrambled Sobol sequence.
    start : StochasticResponse, optional
        A neighbouring solution (same model and grid; e.g. the previous design point): its
        covariance and mean shift start the iteration, which converges to the same fixed point.

    Returns
    -------
    StochasticResponse
        ``success`` False (with ``message``) if the iteration did not settle.

    Raises
    ------
    ParameterError
        If ``omega`` and ``spectrum`` are not 1-D arrays of the same length (>= 8), or ``direction`` fits neither
        shape.
    """
    p = taut_parameters(model, p)
    omega = np.asarray(omega, float)
    S = np.asarray(spectrum, float)
    if omega.shape != S.shape or omega.ndim != 1 or omega.size < 8:
        raise ParameterError("omega, spectrum", (omega.shape, S.shape), "1-D arrays of the same length, at least 8 points")
    lin = linearize(model, p)
    direction = np.asarray(direction, complex)
    if direction.ndim == 1:
        direction = np.broadcast_to(direction, (omega.size, direction.size))
    if direction.ndim == 2:
        direction = direction[None]
    weights = np.ones(1) if weights is None else np.asarray(weights, float).ravel()
    if (direction.ndim != 3 or direction.shape[1] != omega.size or direction.shape[2] > len(lin.input_labels)
            or direction.shape[0] != weights.size):
        raise ParameterError("direction", direction.shape, f"(inputs,), (n_omega = {omega.size}, inputs) or (n_dir = "
                             f"{weights.size} weights, n_omega, inputs), at most {len(lin.input_labels)} inputs "
                             f"({', '.join(lin.input_labels)})")
    if np.any(weights < 0) or not abs(weights.sum() - 1.0) <= 1e-9:
        raise ParameterError("weights", weights.tolist(), "must be >= 0 and sum to 1")
    nu = len(lin.input_labels)
    b = xi_blocks(model)
    D = np.zeros(direction.shape[:2] + (nu,), complex)
    D[..., :direction.shape[2]] = direction
    z = _normal_samples(b["n"], n_log2, seed)     # a value (the seed) varies between calls: computed, never a cache key
    n = z.shape[0]
    rj_sum, yj_sum = _moment_functions(model, n)
    q_static = lin.q0.copy()
    xi_mean = operating_xi(model, lin.q0)
    ny = len(model.output_labels)
    Q = np.zeros((D.shape[0], omega.size, model.nq), complex)
    sigma_old, Sigma = None, None

    def samples(Sigma):
        # the symmetric square root Sigma^(1/2) = V sqrt(L) V^T maps the fixed standard-normal points
        # continuously (V sqrt(L) alone jumps when eigenvectors swap or flip sign, and the iteration
        # then wanders between quadrature realizations instead of settling)
        lam, V = np.linalg.eigh(0.5 * (Sigma + Sigma.T))
        return xi_mean[:, None] + ((V * np.sqrt(np.clip(lam, 0, None))) @ V.T) @ z.T

    last = {}

    def update(Sigma):
        """N = E[dr/dxi] over N(xi_mean, Sigma), the mean step E[r] = 0, and the new transfer."""
        X = samples(Sigma)
        m = np.array(rj_sum(X, p)).ravel() / n
        r_mean, J = m[:model.nq], m[model.nq:].reshape(b["n"], model.nq).T
        last.update(X=X, J=J)
        xi_mean[b["q"]] -= np.linalg.solve(J[:, b["q"]], r_mean)          # E[r] = 0: rectified mean drag
        lin = from_jacobian(model, J, np.zeros((ny, b["n"])), xi_mean[b["q"]].copy(), np.zeros(ny), kind="stochastic")
        Qw, _ = lin.transfer(omega)
        return np.einsum("kqi,dki->dkq", Qw, D)

    if start is not None and start.covariance is not None and start.covariance.shape == (b["n"], b["n"]):
        Sigma = np.array(start.covariance, float)
        xi_mean[b["q"]] += start.mean_shift
        Q = update(Sigma)
    converged, it = False, 0
    for it in range(1, max_iter + 1):
        A = _weighted(_xi_amplitudes(b, Q, D, omega), weights, S, omega).reshape(-1, b["n"])
        Sig_new = np.real(A.T @ np.conj(A))
        Sigma = Sig_new if Sigma is None else (1 - relax) * Sigma + relax * Sig_new
        Q = update(Sigma)
        sigma = np.sqrt(np.clip(np.diag(Sig_new), 0, None))
        if sigma_old is not None and np.all(np.abs(sigma - sigma_old) <= tol * np.maximum(sigma, 1e-30)):
            converged = True
            break
        sigma_old = sigma
    my = np.array(yj_sum(last["X"], p)).ravel() / n      # outputs over the last iterate's samples
    lin = from_jacobian(model, last["J"], my[ny:].reshape(b["n"], ny).T,
                        xi_mean[b["q"]].copy(), my[:ny], kind="stochastic")
    _, Yw = lin.transfer(omega)
    Yd = np.einsum("kyi,dki->dky", Yw, D)
    Y = Yd[0] if weights.size == 1 else np.sqrt(np.einsum("d,dky->ky", weights, np.abs(Yd) ** 2)) + 0j
    std = np.sqrt(np.trapezoid(np.abs(Y) ** 2 * S[:, None], omega, axis=0))
    floors = [p[k] for k in model.layout.section_indices("cable.tension_floor")]
    return StochasticResponse(omega=omega, spectrum=S, linear=lin, output_labels=model.output_labels, transfer=Y,
                              output_mean=lin.y0, output_std=std, tension_floor=float(max(floors)),
                              success=converged, stats={"iterations": it, "samples": n, "warm_start": start is not None},
                              covariance=Sigma, mean_shift=xi_mean[b["q"]] - q_static,
                              message="" if converged else (f"the standard deviations did not settle to {tol:g} in "
                                                            f"{max_iter} iterations: raise max_iter or lower relax"))
