"""Gaussian (stochastic) equivalent linearization for an irregular sea, iterated to self-consistency.

N = E[dr/dxi] over xi ~ N(xi_mean, Sigma) (Atalik & Utku 1976; Roberts & Spanos, "Random
Vibration and Statistical Linearization", ch. 5): for one zero-mean drag element |v| v this is
sqrt(8/pi) sigma_v, with a mean flow U it tends to the exact slope 2|U|. Sigma is the
covariance of the linear response, Sigma = int Re(Xi(w) Xi(w)^H) S(w) dw, and the mean obeys
E[r] = 0 (the drag's rectified mean force shifts the equilibrium). The expectation is a
scrambled-Sobol quadrature with antithetic pairs of the model's own CasADi Jacobian.

The sea enters through the top: the top follows the surface particle orbit of Wang (1971)
eq. 26 at x = 0 (a buoy), x_s = a cos wt, y_s = -a sin wt, i.e. input (1, i) per unit wave
amplitude; other input directions can be given.
"""

from __future__ import annotations

import dataclasses
from typing import ClassVar

import numpy as np
from scipy.stats import norm, qmc

from ..errors import ParameterError
from ..model import CableModel
from ..results import ResultBase, timed
from .equivalent import complex_xi
from .linearization import (
    LinearModel,
    from_jacobian,
    functions,
    linearize,
    operating_xi,
    taut_parameters,
    xi_blocks,
)
from .spectra import significant_amplitude, slack_probability

BUOY = np.array([1.0, 1.0j])


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

    def slack_probability(self, output: str = "tension") -> float:
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


@timed
def stochastic_response(model: CableModel, p, omega, spectrum, *, direction=BUOY, n_log2: int = 10,
                        tol: float = 1e-4, max_iter: int = 60, relax: float = 0.5, seed: int = 0) -> StochasticResponse:
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
        Input amplitudes per unit sea amplitude (default: the buoy orbit (1, i), Wang (1971) eq. 26).
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

    Returns
    -------
    StochasticResponse
        ``success`` False (with ``message``) if the iteration did not settle.

    Raises
    ------
    ParameterError
        If ``omega`` and ``spectrum`` are not 1-D arrays of the same length (>= 8).
    """
    p = taut_parameters(model, p)
    omega = np.asarray(omega, float)
    S = np.asarray(spectrum, float)
    if omega.shape != S.shape or omega.ndim != 1 or omega.size < 8:
        raise ParameterError("omega, spectrum", (omega.shape, S.shape), "1-D arrays of the same length, at least 8 points")
    lin = linearize(model, p)
    direction = np.broadcast_to(np.asarray(direction, complex), (omega.size, len(direction)))
    nu = len(lin.input_labels)
    b = xi_blocks(model)
    D = np.zeros((omega.size, nu), complex)
    D[:, :direction.shape[1]] = direction
    fns = functions(model)
    z = _normal_samples(b["n"], n_log2, seed)
    n = z.shape[0]
    jac_map, res_map, out_map = fns["jac"].map(n), fns["residual"].map(n), fns["out_jac"].map(n)
    xi_mean = operating_xi(model, lin.q0)
    Q = np.zeros((omega.size, model.nq), complex)
    sigma_old, Sigma = None, None
    converged, it = False, 0
    for it in range(1, max_iter + 1):
        Xi = np.array([complex_xi(model, Q[k], D[k], omega[k]) for k in range(omega.size)])
        Sig_new = np.trapezoid(np.real(Xi[:, :, None] * np.conj(Xi[:, None, :])) * S[:, None, None], omega, axis=0)
        Sigma = Sig_new if Sigma is None else (1 - relax) * Sigma + relax * Sig_new
        lam, V = np.linalg.eigh(0.5 * (Sigma + Sigma.T))
        X = xi_mean[:, None] + (V * np.sqrt(np.clip(lam, 0, None))) @ z.T
        J = np.array(jac_map(X, p)).reshape(model.nq, n, b["n"]).mean(axis=1)
        r_mean = np.array(res_map(X, p)).mean(axis=1)
        y, Jy = (np.array(a) for a in out_map(X, p))
        Jy = Jy.reshape(y.shape[0], n, b["n"]).mean(axis=1)
        xi_mean[b["q"]] -= np.linalg.solve(J[:, b["q"]], r_mean)          # E[r] = 0: rectified mean drag
        lin = from_jacobian(model, J, Jy, xi_mean[b["q"]].copy(), y.mean(axis=1), kind="stochastic")
        Qw, _ = lin.transfer(omega)
        Q = np.einsum("kqi,ki->kq", Qw, D)
        sigma = np.sqrt(np.clip(np.diag(Sig_new), 0, None))
        if sigma_old is not None and np.all(np.abs(sigma - sigma_old) <= tol * np.maximum(sigma, 1e-30)):
            converged = True
            break
        sigma_old = sigma
    _, Yw = lin.transfer(omega)
    Y = np.einsum("kyi,ki->ky", Yw, D)
    std = np.sqrt(np.trapezoid(np.abs(Y) ** 2 * S[:, None], omega, axis=0))
    floors = [p[k] for k in model.layout.section_indices("cable.tension_floor")]
    return StochasticResponse(omega=omega, spectrum=S, linear=lin, output_labels=model.output_labels, transfer=Y,
                              output_mean=lin.y0, output_std=std, tension_floor=float(max(floors)),
                              success=converged, stats={"iterations": it, "samples": n},
                              message="" if converged else (f"the standard deviations did not settle to {tol:g} in "
                                                            f"{max_iter} iterations: raise max_iter or lower relax"))
