"""Natural frequencies, damping ratios and mode shapes of a linear model.

Damped: eigenvalues lambda of the state matrix A (``scipy.linalg.eig``), omega_d = |Im lambda|,
omega_n = |lambda|, zeta = -Re lambda / |lambda|. Undamped: the generalized eigenproblem
K phi = omega^2 M phi (``scipy.linalg.eigh`` when K and M are symmetric, ``eig`` otherwise,
e.g. with a current whose drag makes K non-symmetric).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import scipy.linalg

from .linearize import LinearModel


@dataclasses.dataclass(frozen=True)
class Modes:
    """Modes sorted by undamped natural frequency; ``shapes[:, k]`` is mode k (max |entry| = 1)."""

    q_labels: tuple
    omega_undamped: np.ndarray       # rad/s
    shapes: np.ndarray               # (nq, n_modes), real
    omega_damped: np.ndarray         # rad/s, |Im lambda| of the matching eigenvalue pair
    omega_natural: np.ndarray        # rad/s, |lambda|
    damping_ratio: np.ndarray        # -Re lambda / |lambda|
    eigenvalues: np.ndarray          # complex, the upper-half-plane eigenvalues of A

    @property
    def dominant(self) -> tuple:
        """Label of the largest entry of each mode shape (``phi`` = pendulum, ``u`` = stretch)."""
        return tuple(self.q_labels[int(np.argmax(np.abs(self.shapes[:, k])))] for k in range(self.shapes.shape[1]))

    def frequency_of(self, label: str) -> float:
        """Undamped natural frequency of the mode dominated by coordinate ``label``."""
        return float(self.omega_undamped[self.dominant.index(label)])

    def to_xarray(self):
        import xarray as xr
        mode = np.arange(len(self.omega_undamped))
        return xr.Dataset(
            {"omega_undamped": ("mode", self.omega_undamped, {"units": "rad/s"}),
             "omega_damped": ("mode", self.omega_damped, {"units": "rad/s"}),
             "omega_natural": ("mode", self.omega_natural, {"units": "rad/s"}),
             "damping_ratio": ("mode", self.damping_ratio),
             "shape": (("q", "mode"), self.shapes)},
            coords={"mode": mode, "q": list(self.q_labels), "dominant": ("mode", list(self.dominant))})


def modes(lin: LinearModel) -> Modes:
    """Undamped and damped modes of ``lin`` (real matrices: exact or stochastic linearization)."""
    M, K, C = (np.real_if_close(np.asarray(a)) for a in (lin.M, lin.K, lin.C))
    if np.iscomplexobj(M) or np.iscomplexobj(K) or np.iscomplexobj(C):
        raise ValueError("modes need real M, C, K (a harmonic equivalent linearization is complex: "
                         "use the exact or stochastic linear model)")
    sym = np.allclose(K, K.T, rtol=1e-10, atol=1e-12 * np.abs(K).max()) and np.allclose(M, M.T)
    if sym:
        w2, shapes = scipy.linalg.eigh(K, M)
    else:
        w2, shapes = scipy.linalg.eig(K, M)
        order = np.argsort(w2.real)
        w2, shapes = w2.real[order], shapes[:, order].real
    shapes = shapes / shapes[np.argmax(np.abs(shapes), axis=0), np.arange(shapes.shape[1])]
    w_u = np.sqrt(np.clip(w2, 0.0, None))
    lam = scipy.linalg.eigvals(lin.A)
    lam = lam[lam.imag >= -1e-12 * np.abs(lam).max()]
    # match each undamped mode to the damped eigenvalue nearest in |lambda|
    lam_sorted = []
    pool = list(lam)
    for w in w_u:
        k = int(np.argmin([abs(abs(l) - w) for l in pool]))
        lam_sorted.append(pool.pop(k))
    lam_sorted = np.array(lam_sorted)
    wn = np.abs(lam_sorted)
    zeta = np.where(wn > 0, -lam_sorted.real / np.where(wn > 0, wn, 1.0), 0.0)
    return Modes(q_labels=lin.q_labels, omega_undamped=w_u, shapes=shapes, omega_damped=np.abs(lam_sorted.imag),
                 omega_natural=wn, damping_ratio=zeta, eigenvalues=lam_sorted)
