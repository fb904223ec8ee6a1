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

The same equations come in two forms: the element-by-element node model (:func:`cablesys.model.build_model`, one SX
expression whose size grows with the number of elements N, what the time domain runs) and the span's element-kernel
form :class:`SpanKernel` (:func:`span_kernel`: the element kernel and its AD Jacobian mapped over the elements,
:func:`cablesys.model.segmented_kernel.kernel_statics`, a graph of constant size at any N), built in a fraction of
the time and never stored. :func:`span_equilibrium` and :func:`span_matrices` take either; they give the same numbers
to rounding (``tests/test_span_kernel.py``).
"""

from __future__ import annotations

import dataclasses

import casadi as ca
import numpy as np
import scipy.sparse as sp

from ..errors import ParameterError, SolverError
from ..model.params import ParameterLayout
from ..model.segmented import drag_points
from ..model.segmented_kernel import kernel_statics
from ..scene import Scene
from .catenary import NODE_KINSOL, anchored_equilibrium, segmented_equilibrium
from .problem import static_parameters, total_weight


@dataclasses.dataclass(frozen=True, eq=False)
class SpanKernel:
    """A span's node model in its element-kernel form (:func:`span_kernel`): the statics and the linear mass and
    stiffness of the segmented model's equations (:mod:`cablesys.model.segmented`) from mapped element kernels.

    ``forces(q, p) -> (M, f)`` and ``stiffness(q, p) -> K`` (:func:`cablesys.model.segmented_kernel.kernel_statics`:
    mass blocks, 9 x n column-major per free node, kg; forces f(q, q' = 0, e = 0, p), N; K = -df/dq, N/m, sparse),
    ``residual(q, p)`` the statics' scaled residual f / W (W the total weight in the medium, as
    :func:`cablesys.statics.problem.static_residual`) and ``rootfinder`` KINSOL on it with -K / W as its Jacobian
    (the chain rule over the elements' AD: CasADi's AD of the mapped residual costs a colour of the
    block-tridiagonal pattern per direction through every element, several times more to set up and evaluate).
    q = (x_1, y_1, z_1, ...): the free nodes, the anchor's node fixed (not a coordinate).
    """

    layout: ParameterLayout
    segments: tuple
    forces: ca.Function
    stiffness: ca.Function
    residual: ca.Function
    rootfinder: ca.Function
    dim: int = 3
    anchored: bool = True
    slack_index: tuple = ()          # no slack switches (:func:`cablesys.statics.problem.static_zeroed`)
    name: str = "segmented (element kernels)"

    @property
    def n_sections(self) -> int:
        return len(self.segments)

    @property
    def n_elements(self) -> int:
        return int(sum(self.segments))

    @property
    def nq(self) -> int:
        return self.dim * (self.n_elements - 1)

    def parameters(self, scene) -> np.ndarray:
        """Numeric parameter vector of ``scene`` (same structure, SI)."""
        return self.layout.values(scene)


def span_kernel(scene: Scene) -> SpanKernel:
    """The :class:`SpanKernel` of a span scene: a 3-D segmented scene with an ``[anchor]`` (the top and the anchor
    the two supports) without a seabed, winch or rigid body. Its functions depend on the scene's structure only
    (sections, elements, parameter labels), every value entering through p."""
    if not isinstance(scene, Scene) or scene.anchor is None or not scene.three_d or scene.seabed is not None \
            or scene.winch is not None or any(s.body.is_rigid for s in scene.sections):
        raise ParameterError("scene", getattr(scene, "name", type(scene).__name__),
                             "must be a 3-D scene with an [anchor] and point bodies, without a seabed or winch "
                             "(a span between the top and the anchor)")
    layout = ParameterLayout.from_scene(scene)
    forces, stiffness = kernel_statics(scene, lambda n_el: drag_points(scene, n_el))
    q, p = ca.MX.sym("q", forces.size1_in(0)), ca.MX.sym("p", forces.size1_in(1))
    f, K = forces(q, p)[1], stiffness(q, p)
    W = total_weight(layout.labels, p)         # the static residual's force scale, as residual_scales
    residual = ca.Function("static_residual", [q, p], [f / W], ["q", "p"], ["r"])
    jac = ca.Function("static_residual_jacobian", [q, p], [-K / W], ["q", "p"], ["jac"])
    rootfinder = ca.rootfinder("span_kernel_kinsol", "kinsol", residual, dict(NODE_KINSOL, jacobian_function=jac))
    return SpanKernel(layout=layout, segments=tuple(s.cable.segments for s in scene.sections), forces=forces,
                      stiffness=stiffness, residual=residual, rootfinder=rootfinder)


def _require_span(model) -> None:
    if isinstance(model, SpanKernel):
        return
    if not getattr(model, "anchored", False) or getattr(model, "dim", 2) != 3:
        raise ParameterError("model", getattr(model, "name", type(model).__name__),
                             "must be a 3-D anchored segmented model (a span between the top and an [anchor])")


def span_equilibrium(model, p, *, guess=None):
    """Node positions q* (m) of the span at rest and the scaled residual reached.

    The node model's statics (:func:`.catenary.anchored_equilibrium`: KINSOL on its static residual; ``model`` the
    element-by-element node model or its :class:`SpanKernel`), first with every element elastic both ways (tension
    floor -(AE)_r: the law (AE)_r strain for any strain > -1, the lumped chain's potential energy of Griffin &
    Rosenthal's bars), so that a guess with slack elements still has a regular Jacobian (a slack element of the
    cable's own law has no stiffness), then from that solution with the scene's own law; a static shape with an
    element in compression is refused (it would not hang). ``guess``: starting node positions (x_1, y_1, z_1, ...),
    default the anchored line's guess.
    """
    _require_span(model)
    p = static_parameters(model, p)
    if isinstance(model, SpanKernel):
        q, r = anchored_equilibrium(model, p, guess, functions=(model.residual, model.rootfinder))
        strain = _element_strains(model, q, p)
    else:
        q, r = segmented_equilibrium(model, p, guess=guess)
        x = np.concatenate([q, np.zeros_like(q)])
        y = np.array(model.outputs(x, np.zeros(model.top.size1_out(0)), p)).ravel()
        strain = y[_strain_indices(model)]
    if strain.min() <= 0.0:
        raise SolverError(f"the span's static shape has an element in compression (strain {strain.min():.3g} at "
                          f"element {int(strain.argmin())}): it does not hang between its supports; check the length, "
                          "the masses and the supports")
    return q, r


def _element_strains(span: SpanKernel, q, p) -> np.ndarray:
    """Every element's strain (l - h_0) / h_r at the free nodes q (top and anchor fixed): the node model's element
    law (:func:`cablesys.model.segmented_element.element_terms`; Wang 1971 eq. 1 per element, h_r = l_r / N and
    h_0 = l_0 / N with l_0 = l_r (1 - T_r / (AE)_r))."""
    lay = span.layout
    val = lambda i, name: float(p[lay.section_index(i, name)])     # noqa: E731
    h_r = np.concatenate([[val(i, "cable.length") / n] * n for i, n in enumerate(span.segments)])
    h_0 = np.concatenate([[val(i, "cable.length") * (1 - val(i, "cable.tension_ref") / val(i, "cable.ae")) / n] * n
                          for i, n in enumerate(span.segments)])
    anchor = [float(p[lay.index(f"anchor.{c}")]) for c in "xyz"]
    nodes = np.vstack([np.zeros(3), np.asarray(q, float).reshape(-1, 3), anchor])
    return (np.linalg.norm(np.diff(nodes, axis=0), axis=1) - h_0) / h_r


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
    if isinstance(model, SpanKernel):
        blocks, Kd = model.forces(q, p)[0], model.stiffness(q, p)
        n = model.nq // 3
        data = np.array(blocks).T.reshape(n, 3, 3).transpose(0, 2, 1)      # node j's 3 x 3 block (column-major)
        M = sp.bsr_matrix((data, np.arange(n), np.arange(n + 1)), shape=(3 * n, 3 * n)).tocsc()
        K = _to_csc(Kd)
    else:
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
