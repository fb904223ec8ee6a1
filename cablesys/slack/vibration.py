"""Linear in-plane and out-of-plane modes of the lumped-mass cable about its equilibrium.

Equations of motion M q'' + K q = 0 about the static shape:
- in plane, K is the Hessian of the potential energy (statics module);
- out of plane, K is the geometric stiffness T_e / l_e of each element (the
  y-block of the 3-D Hessian of the same energy; in- and out-of-plane motion
  decouple exactly about a plane equilibrium);
- M is lumped at the nodes; in water the cable's added mass acts normal to
  the cable only and a point mass's added mass in every direction
  (Griffin & Rosenthal 1985 section 7: added mass affects the transverse
  motion, not the longitudinal/elastic motion; eq. 26).

Modes are mass-normalized as eq. 25 (sum of psi^2 dm including the
discrete masses equals 1) and classified O / A / S / H by their mirror
symmetry about the perpendicular bisector of the chord (:mod:`.modal`).

:func:`analyze` and :func:`converge` run on the shared cable (:mod:`.shared`, the node model's
span); :func:`modes` of a chain equilibrium is their independent check on the same nodes.
"""

from __future__ import annotations

import logging
import math
import time

import numpy as np
import scipy.linalg
import scipy.sparse as sp
import scipy.sparse.linalg

from ..errors import ParameterError, SolverError
from ..results import timed
from .results import Convergence, Equilibrium, ModeSet, SlackAnalysis
from .modal import SYMMETRY_THRESHOLD, _eig, classify_rows, symmetric_fraction  # noqa: F401 (re-exported)
from .shared import analyze as analyze_span, section_segments
from .statics import Discretization, solve_equilibrium, stiffness_inplane

log = logging.getLogger(__name__)

def _tangents(eq: Equilibrium) -> np.ndarray:
    """Unit tangent at every node (mean of the adjacent element directions)."""
    d = np.stack([np.diff(eq.x), np.diff(eq.z)], axis=1)
    d /= np.linalg.norm(d, axis=1)[:, None]
    t = np.zeros((len(eq.x), 2))
    t[:-1] += d
    t[1:] += d
    return t / np.linalg.norm(t, axis=1)[:, None]


def mass_matrices(eq: Equilibrium, d: Discretization):
    """(M_inplane, M_outofplane) as sparse matrices on the interior nodes.

    In-plane ordering [x_1..x_{n-1}, z_1..z_{n-1}] matches the statics NLP.
    Node block: (m + a_iso + a_t) I - a_t t t^T (added mass normal to the cable).
    """
    t = _tangents(eq)[1:-1]
    m = d.mass[1:-1] + d.added_isotropic[1:-1]
    a = d.added_transverse[1:-1]
    mxx = m + a * (1 - t[:, 0] ** 2)
    mzz = m + a * (1 - t[:, 1] ** 2)
    mxz = -a * t[:, 0] * t[:, 1]
    Min = sp.bmat([[sp.diags(mxx), sp.diags(mxz)], [sp.diags(mxz), sp.diags(mzz)]], format="csc")
    Mout = sp.diags(m + a, format="csc")
    return Min, Mout


def stiffness_outofplane(eq: Equilibrium) -> sp.csc_matrix:
    """Geometric stiffness T_e / l_e assembled on the interior nodes (tridiagonal)."""
    k = eq.tension / eq.element_lengths
    main = k[:-1] + k[1:]
    off = -k[1:-1]
    return sp.diags([off, main, off], [-1, 0, 1], format="csc")


def modes(eq: Equilibrium, n_modes: int | None = None, *, solver: str = "auto") -> ModeSet:
    """The ``n_modes`` lowest natural modes about an equilibrium (in-plane and out-of-plane merged), ascending.

    The slack model's counterpart of :func:`cablesys.modes` (the Wang model's modes of a
    linearization): M q'' + K q = 0 about the static shape, Griffin & Rosenthal (1985)
    section 7, mass-normalized by their eq. 25.

    Parameters
    ----------
    eq : Equilibrium
        The static shape (:func:`~cablesys.slack.solve_equilibrium`), with its ``discretization``.
    n_modes : int, optional
        Number of modes (>= 1); default ``eq.scene.n_modes``.
    solver : str, optional
        'auto', 'dense' (scipy.linalg.eigh) or 'sparse' (shift-invert eigsh).

    Returns
    -------
    ModeSet
        Frequencies omega (rad/s), types O/A/S/H and mass-normalized shapes (eq. 25).
    """
    d = eq.discretization
    if d is None:
        raise ParameterError("eq.discretization", None, "an Equilibrium from solve_equilibrium or "
                             "solve_equilibrium_shooting (it carries the element layout the modes need)")
    n_modes = eq.scene.n_modes if n_modes is None else n_modes
    if isinstance(n_modes, bool) or int(n_modes) != n_modes or n_modes < 1:
        raise ParameterError("n_modes", n_modes, "must be an integer >= 1")
    t0 = time.perf_counter()
    nn = len(eq.x)
    Kin = stiffness_inplane(eq, d)
    Kout = stiffness_outofplane(eq)
    Min, Mout = mass_matrices(eq, d)
    w_in, V_in, used = _eig(Kin, Min, n_modes, solver)
    w_out, V_out, _ = _eig(Kout, Mout, n_modes, solver)
    rows = []
    ni = nn - 2
    for j in range(len(w_in)):
        shape = np.zeros((nn, 3))
        shape[1:-1, 0] = V_in[:ni, j]
        shape[1:-1, 2] = V_in[ni:, j]
        rows.append((w_in[j], None, np.nan, shape))
    for j in range(len(w_out)):
        shape = np.zeros((nn, 3))
        shape[1:-1, 1] = V_out[:, j]
        rows.append((w_out[j], "O", np.nan, shape))
    return classify_rows(eq, rows, n_modes, n_elements=d.n_elements, solver=used, seconds=time.perf_counter() - t0)


@timed
def analyze(scene, n_modes: int | None = None, *, n_elements: int | None = None, solver: str = "auto",
            cache=None, segments: tuple[int, ...] | None = None) -> SlackAnalysis:
    """Statics then natural modes of a slack scene on the shared cable, as one result.

    The span is the node model's (:mod:`.shared`: support A the top, B the anchor, the point masses the
    sections' bodies): its equilibrium from the node model's statics and its modes from the model's
    own mass matrix and the AD Jacobian of its forces, in-plane and out-of-plane (Griffin & Rosenthal
    1985 section 7, eq. 25). The lumped chain of this module (:func:`solve_equilibrium` and
    :func:`modes`) solves the same discrete equations by another route (energy NLP and its Hessian).

    Parameters
    ----------
    scene : SlackScene
        The slack-cable scene (SI).
    n_modes : int, optional
        Number of modes (default ``scene.n_modes``).
    n_elements : int, optional
        Elements (default from the scene), shared among the sections between masses by length.
    solver : str, optional
        'auto', 'dense' (scipy.linalg.eigh) or 'sparse' (shift-invert eigsh).
    cache : FunctionCache, optional
        Keeps the node models' element-kernel forms by structure (see :func:`.shared.span_form`).
    segments : tuple of int, optional
        Elements per section (overrides ``n_elements``).

    Returns
    -------
    SlackAnalysis
        ``equilibrium`` (static shape, tensions in N) and ``modes`` (omega in rad/s).
    """
    return analyze_span(scene, n_modes, n_elements=n_elements, segments=segments, solver=solver, cache=cache)


@timed
def converge(scene, n_modes: int | None = None, *, levels: tuple[int, ...] = (48, 96, 192),
             solver: str = "auto", cache=None) -> Convergence:
    """Solve at each element count on the shared cable (:func:`analyze`) and Richardson-extrapolate (h^2 convergence).

    Modes are matched by family ('O' versus in-plane) and index within the
    family, so that a change of in-plane order near a crossover between
    levels cannot pair different modes across families.

    Parameters
    ----------
    scene : SlackScene
        The slack-cable scene (SI).
    n_modes : int, optional
        Number of modes reported (default ``scene.n_modes``).
    levels : tuple of int, optional
        Element counts, each twice the previous (at least three); the first is shared among the sections
        between masses by length and every section's count doubles with the level.
    solver : str, optional
        'auto', 'dense' (scipy.linalg.eigh) or 'sparse' (shift-invert eigsh).
    cache : FunctionCache, optional
        Keeps the CasADi functions per element count (see :func:`solve_equilibrium`).

    Returns
    -------
    Convergence
        Frequencies (rad/s) per level, observed orders and Richardson extrapolation.
    """
    if len(levels) < 3:
        raise ParameterError("levels", levels, "needs at least three element counts")
    n_modes = scene.n_modes if n_modes is None else n_modes
    base = section_segments(scene, levels[0])
    for a, b in zip(levels[:-1], levels[1:]):
        if b != 2 * a:
            raise ParameterError("levels", levels, "must double from one element count to the next (h^2 Richardson)")
    fam_w = []
    types = None
    n_extra = n_modes + 4
    for n in levels:            # every section's element count doubles with the level: h halves everywhere
        segs = tuple(k * (n // levels[0]) for k in base)
        ms = analyze(scene, n_extra * 2, segments=segs, solver=solver, cache=cache).modes
        o = ms.of_type("O")
        i = ms.of_type("A", "S", "H")
        ti = [t for t in ms.mode_type if t != "O"]
        fam_w.append((o, i, ti))
    no = min(len(f[0]) for f in fam_w)
    ni = min(len(f[1]) for f in fam_w)
    W = np.array([np.concatenate([f[0][:no], f[1][:ni]]) for f in fam_w])
    types = ["O"] * no + fam_w[-1][2][:ni]
    rich = W[-1] + (W[-1] - W[-2]) / (2.0 ** 2 - 1.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        order = np.log2(np.abs((W[-3] - W[-2]) / (W[-2] - W[-1])))
    keep = np.argsort(rich)[:n_modes]   # ascending converged frequency
    ok = bool(np.all(np.isfinite(rich[keep])))
    return Convergence(levels=tuple(levels), mode_type=tuple(types[k] for k in keep),
                       omega=W[:, keep], order=order[keep], richardson=rich[keep], success=ok,
                       message="" if ok else "a Richardson extrapolation is not finite: check the element counts")
