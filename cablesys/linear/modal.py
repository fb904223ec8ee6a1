"""Natural frequencies, damping ratios and mode shapes of a linear model.

Damped: eigenvalues lambda of the state matrix A (``scipy.linalg.eig``), omega_d = |Im lambda|,
omega_n = |lambda|, zeta = -Re lambda / |lambda|. Undamped: the generalized eigenproblem
K phi = omega^2 M phi (``scipy.linalg.eigh`` when K and M are symmetric, ``eig`` otherwise,
e.g. with a current whose drag makes K non-symmetric).
"""

from __future__ import annotations

import dataclasses
from typing import ClassVar

import numpy as np
import scipy.linalg

from ..errors import ParameterError
from ..results import ResultBase, timed
from .linearization import LinearModel


@dataclasses.dataclass(frozen=True)
class Modes(ResultBase):
    """Modes sorted by undamped natural frequency; ``shapes[:, k]`` is mode k (max |entry| = 1)."""

    q_labels: tuple
    omega_undamped: np.ndarray       # rad/s
    shapes: np.ndarray               # (nq, n_modes), real
    omega_damped: np.ndarray         # rad/s, |Im lambda| of the matching eigenvalue pair
    omega_natural: np.ndarray        # rad/s, |lambda|
    damping_ratio: np.ndarray        # -Re lambda / |lambda|
    eigenvalues: np.ndarray          # complex, the upper-half-plane eigenvalues of A
    success: bool = True
    message: str = ""
    stats: dict = dataclasses.field(default_factory=dict)

    VARIABLES: ClassVar[dict] = {"omega_undamped": ("rad/s", "undamped natural frequency"),
                                  "omega_damped": ("rad/s", "damped natural frequency |Im lambda|"),
                                  "omega_natural": ("rad/s", "natural frequency |lambda|"),
                                  "damping_ratio": ("1", "damping ratio -Re lambda / |lambda|"),
                                  "shape": ("1", "mode shape (largest entry 1)"), "mode": ("1", "mode number"),
                                  "q": ("1", "generalized coordinate"), "dominant": ("1", "largest coordinate of the mode")}

    @property
    def dominant(self) -> tuple:
        """Label of the largest entry of each mode shape (``phi`` = pendulum, ``u`` = stretch)."""
        return tuple(self.q_labels[int(np.argmax(np.abs(self.shapes[:, k])))] for k in range(self.shapes.shape[1]))

    def frequency_of(self, label: str) -> float:
        """Undamped natural frequency of the mode dominated by coordinate ``label``."""
        return float(self.omega_undamped[self.dominant.index(label)])

    def summary(self) -> dict:
        """Natural frequencies (rad/s), damping ratios and dominant coordinates, JSON-able.

        Returns
        -------
        dict
            ``success``, ``message``, ``stats`` and one entry per mode.
        """
        return {**super().summary(), "modes": [
            {"dominant": d, "omega_undamped_rad_s": float(w), "omega_damped_rad_s": float(wd),
             "damping_ratio": float(z)}
            for d, w, wd, z in zip(self.dominant, self.omega_undamped, self.omega_damped, self.damping_ratio)]}

    def to_xarray(self):
        """Frequencies and damping ratios on dimension ``mode``, shapes on (``q``, ``mode``).

        Returns
        -------
        xarray.Dataset
            With units and long names.
        """
        import xarray as xr
        mode = np.arange(len(self.omega_undamped))
        return xr.Dataset(
            {"omega_undamped": ("mode", self.omega_undamped, {"units": "rad/s"}),
             "omega_damped": ("mode", self.omega_damped, {"units": "rad/s"}),
             "omega_natural": ("mode", self.omega_natural, {"units": "rad/s"}),
             "damping_ratio": ("mode", self.damping_ratio),
             "shape": (("q", "mode"), self.shapes)},
            coords={"mode": mode, "q": list(self.q_labels), "dominant": ("mode", list(self.dominant))})


@timed
def modes(lin: LinearModel) -> Modes:
    """Undamped and damped modes of ``lin`` (real matrices: exact or stochastic linearization).

    Undamped: K phi = omega^2 M phi; damped: eigenvalues lambda of the state matrix A, each
    matched to the undamped mode nearest in |lambda|.

    Parameters
    ----------
    lin : LinearModel
        Real M, C, K (an exact or stochastic linearization, :func:`linearize`).

    Returns
    -------
    Modes
        Sorted by undamped natural frequency (rad/s), with damping ratios and shapes.

    Raises
    ------
    ParameterError
        If the matrices are complex (a harmonic equivalent linearization).
    """
    M, K, C = (np.real_if_close(np.asarray(a)) for a in (lin.M, lin.K, lin.C))
    if np.iscomplexobj(M) or np.iscomplexobj(K) or np.iscomplexobj(C):
        raise ParameterError("lin.kind", lin.kind, "real M, C, K: an exact or stochastic linearization "
                             "(a harmonic equivalent linearization is complex)")
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
