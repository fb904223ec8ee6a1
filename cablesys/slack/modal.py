"""The eigen problem of a span's small motions and the classification of its modes.

K phi = omega^2 M phi for the in-plane and the out-of-plane blocks (both ends fixed: K positive
definite), the shapes mass-normalized as Griffin & Rosenthal (1985) eq. 25 (sum of psi^2 dm including
the discrete masses equals 1), in-plane modes typed S / A / H by their mirror symmetry about the
perpendicular bisector of the chord (Irvine & Caughey's symmetric and antisymmetric families).
Shared by the lumped chain (:mod:`.vibration`) and the node model's span (:mod:`.shared`).
"""

from __future__ import annotations

import math

import numpy as np
import scipy.linalg
import scipy.sparse.linalg

from ..errors import ParameterError, SolverError
from .results import Equilibrium, ModeSet

#: symmetric fraction above which an in-plane mode is 'S', below 1 - this 'A'
SYMMETRY_THRESHOLD = 0.9
#: largest generalized problem solved densely; above it sparse shift-invert
DENSE_LIMIT = 1200


def _eig(K, M, k: int, solver: str):
    """k lowest eigenpairs of K phi = omega^2 M phi (phi^T M phi = 1)."""
    k = min(k, K.shape[0])
    if solver == "auto":
        solver = "dense" if K.shape[0] <= DENSE_LIMIT else "sparse"
    if solver == "dense" or k >= K.shape[0] - 1:
        lam, V = scipy.linalg.eigh(K.toarray(), M.toarray(), subset_by_index=[0, k - 1])
    elif solver == "sparse":
        # shift-invert about 0: K is positive definite (both ends fixed), so
        # the largest eigenvalues of K^-1 M are the lowest modes; one sparse LU.
        lam, V = scipy.sparse.linalg.eigsh(K.tocsc(), k=k, M=M.tocsc(), sigma=0.0, which="LM")
        order = np.argsort(lam)
        lam, V = lam[order], V[:, order]
    else:
        raise ParameterError("solver", solver, "must be 'auto', 'dense' or 'sparse'")
    if np.any(lam <= 0):
        raise SolverError(f"non-positive eigenvalue {lam.min():.3g}: the equilibrium is not stable")
    # eq. 25: psi / psi_R with psi_R^2 = psi^T M psi (discrete masses included)
    V = V / np.sqrt(np.einsum("ij,ij->j", V, M @ V))[None, :]
    return np.sqrt(lam), V, solver


def symmetric_fraction(eq: Equilibrium, ux: np.ndarray, uz: np.ndarray) -> float:
    """Share of the in-plane displacement that is mirror symmetric about mid-chord.

    Mirror: chordwise component u_c(s) -> -u_c(L - s), normal u_n(s) -> u_n(L - s)
    (the symmetric modes of Irvine & Caughey: vertical motion symmetric,
    horizontal antisymmetric). Arc-length quadrature weights.
    """
    th = eq.scene.inclination
    uc = ux * math.cos(th) + uz * math.sin(th)
    un = -ux * math.sin(th) + uz * math.cos(th)
    s = eq.s
    L = s[-1]
    uc_m = -np.interp(L - s, s, uc)
    un_m = np.interp(L - s, s, un)
    wq = np.zeros(len(s))
    wq[:-1] += np.diff(s) / 2
    wq[1:] += np.diff(s) / 2
    sym = wq @ (((uc + uc_m) / 2) ** 2 + ((un + un_m) / 2) ** 2)
    tot = wq @ (uc ** 2 + un ** 2)
    return float(sym / tot)


def classify_rows(eq: Equilibrium, rows, n_modes: int, *, n_elements: int, solver: str, seconds: float) -> ModeSet:
    """The :class:`ModeSet` of mode rows (omega rad/s, type 'O' or None for in-plane, nan, node shape (x, y, z)):
    in-plane rows typed S / A / H by :func:`symmetric_fraction`, all sorted by frequency, the lowest
    ``n_modes`` kept, each signed so that its largest displacement component is positive."""
    for k, (om, typ, _, shape) in enumerate(rows):
        if typ is None:
            f = symmetric_fraction(eq, shape[:, 0], shape[:, 2])
            typ = "S" if f >= SYMMETRY_THRESHOLD else "A" if f <= 1 - SYMMETRY_THRESHOLD else "H"
            rows[k] = (om, typ, f, shape)
    rows.sort(key=lambda r: r[0])
    rows = rows[: int(n_modes)]
    for r in rows:  # sign convention: largest displacement component positive
        k = np.unravel_index(np.argmax(np.abs(r[3])), r[3].shape)
        if r[3][k] < 0:
            r[3][...] *= -1
    return ModeSet(omega=np.array([r[0] for r in rows]), mode_type=tuple(r[1] for r in rows),
                   symmetric_fraction=np.array([r[2] for r in rows]),
                   shapes=np.stack([r[3] for r in rows]), s=eq.s.copy(),
                   n_elements=n_elements, solver=solver, seconds=seconds)
