"""A span between two supports on the node model: its equilibrium and its linear mass and stiffness.

A span is a segmented scene whose top (the prescribed point, at rest) and ``[anchor]`` are the two
supports and whose sections' bodies are the attached point masses (:mod:`cablesys.model.segmented`:
the body of a section sits at the node joining it to the next; the last section's body sits at the
anchor and loads the support only). Built in three dimensions (``scene.three_d``), so that one set
of equations holds the in-plane and the out-of-plane motion.

About an equilibrium q* (q' = 0, top at rest) the equations of motion M(q) q'' = f(q, q') linearize
to M(q*) dq'' + K dq = 0 with K = -df/dq at (q*, 0) (Lagrange's equations of the node model,
Wang 1971 eq. 8-9 with the lumped element terms of eq. 5, 12, 23-24, 46); the drag terms are
quadratic in the relative velocity, so in still fluid they add nothing to K or to a damping matrix.
K is the CasADi Jacobian of the model's own force vector, M its own block-diagonal mass matrix.
About a plane equilibrium (z = 0) the out-of-plane coordinates z_j decouple exactly from (x_j, y_j)
(the energy is even in z): :func:`span_matrices` returns both blocks and the largest coupling entry
(zero up to rounding) so a caller can check it.
"""

from __future__ import annotations

import casadi as ca
import numpy as np
import scipy.sparse as sp

from ..errors import ParameterError, SolverError
from .catenary import segmented_equilibrium
from .problem import static_parameters


def _require_span(model) -> None:
    if not getattr(model, "anchored", False) or getattr(model, "dim", 2) != 3:
        raise ParameterError("model", getattr(model, "name", type(model).__name__),
                             "must be a 3-D anchored segmented model (a span between the top and an [anchor])")


def span_equilibrium(model, p, *, guess=None):
    """Node positions q* (m) of the span at rest and the scaled residual reached.

    The node model's statics (:func:`.catenary.segmented_equilibrium`: KINSOL on its static residual),
    first with every element elastic both ways (tension floor -(AE)_r: the law (AE)_r strain for any
    strain > -1, the lumped chain's potential energy of Griffin & Rosenthal's bars), so that a guess
    with slack elements still has a regular Jacobian (a slack element of the cable's own law has no
    stiffness), then from that solution with the scene's own law; a static shape with an element in
    compression is refused (it would not hang). ``guess``: starting node positions (x_1, y_1, z_1, ...),
    default the anchored line's guess.
    """
    _require_span(model)
    p = static_parameters(model, p)
    both_ways = p.copy()
    for i in range(model.n_sections):
        both_ways[model.layout.section_index(i, "cable.tension_floor")] = -p[model.layout.section_index(i, "cable.ae")]
    q, _ = segmented_equilibrium(model, both_ways, guess=guess)
    q, r = segmented_equilibrium(model, p, guess=q)
    x = np.concatenate([q, np.zeros_like(q)])
    y = np.array(model.outputs(x, np.zeros(model.top.size1_out(0)), p)).ravel()
    strain = y[_strain_indices(model)]
    if strain.min() <= 0.0:
        raise SolverError(f"the span's static shape has an element in compression (strain {strain.min():.3g} at "
                          f"element {int(strain.argmin())}): it does not hang between its supports; check the length, "
                          "the masses and the supports")
    return q, r


def _strain_indices(model) -> np.ndarray:
    """Positions of ``element_strain[0..]`` in the model's outputs (one contiguous block)."""
    first = model.output_labels.index("element_strain[0]")
    return np.arange(first, first + model.n_elements)


def _jacobian_function(model):
    def build():
        q = ca.SX.sym("q", model.nq)
        p = ca.SX.sym("p", len(model.layout))
        M, f = model.dynamics(q, ca.SX.zeros(model.nq), ca.SX.zeros(model.top.size1_out(0)), p)
        return ca.Function("span_matrices", [q, p], [M, -ca.jacobian(f, q)], ["q", "p"], ["M", "K"])
    return model.derive("span_matrices", build)


def _to_csc(D) -> sp.csc_matrix:
    sps = D.sparsity()
    return sp.csc_matrix((np.asarray(D.nonzeros(), float), np.asarray(sps.row()), np.asarray(sps.colind())),
                         shape=D.shape)


def span_matrices(model, q, p) -> dict:
    """Mass and stiffness of the span's small motions about q* (SI: kg, N/m), split by plane.

    Returns
    -------
    dict
        ``M_in``, ``K_in`` on the in-plane coordinates (x_1, y_1, x_2, y_2, ...), ``M_out``, ``K_out``
        on the out-of-plane ones (z_1, z_2, ...), scipy CSC; ``coupling``: the largest |K| or |M| entry
        between the two sets over the largest |K| or |M| entry (0 about a plane equilibrium).
    """
    _require_span(model)
    p = static_parameters(model, p)
    Md, Kd = _jacobian_function(model)(q, p)
    M, K = _to_csc(Md), _to_csc(Kd)
    n = model.nq // 3
    ins = np.ravel(np.column_stack([3 * np.arange(n), 3 * np.arange(n) + 1]))
    out = 3 * np.arange(n) + 2

    def coupling(A):
        scale = abs(A).max()
        return float(abs(A[ins][:, out]).max() / scale) if scale > 0 else 0.0

    return dict(M_in=M[ins][:, ins].tocsc(), K_in=K[ins][:, ins].tocsc(), M_out=M[out][:, out].tocsc(),
                K_out=K[out][:, out].tocsc(), coupling=max(coupling(K), coupling(M)))
