"""The winch of the segmented node model driven by a control: L and w states, alpha the input.

The node model's winch (:mod:`.segmented_winch`: the first section's N elements share the zero-tension length
L uniformly, material velocities for drag and Voigt damping, L a prescribed coordinate in Lagrange's equations
with z = L, z' = w, z'' = alpha, Wang 1971 eq. 8-9, and the top tension with the sheave's half element) with
(L, w, alpha) as inputs of the functions instead of the scene's payout profile
(:func:`.segmented.build_segmented_model` with ``winch_input``: the same terms, no copy). Here L and w join the
state, L' = w, w' = alpha, as in Wang's 2-DOF winch (:mod:`.winch`), and the functions have that model's
interface (:class:`.winch.WinchModel`), so the optimal control and the MPC (:mod:`cablesys.control`) run on
either:

State x = (x[1], y[1], ..., x[N], y[N][, s], their rates, L, w): node positions (m, y down from the top's mean
depth; node N the body), with a compensator the sheave's stroke s (m, down +), L (m), w (m/s, + pays out);
control v = (alpha, F_a): alpha (m/s^2), F_a (N, down +) the compensator's actuated force.

The compensator (``compensator=True``; parameters c = (m_p, k_p, c_p, F_pre) as :data:`.winch.COMPENSATOR_PARAMETERS`)
is the 2-DOF model's (:mod:`.winch`): the sheave rides a piston of mass m_p at the stroke s below the crane tip, on
a spring k_p and a damper c_p about the precharge F_pre, pushed by F_a. The cable's top node is the sheave,
(x_s, y_s + s), so the node model sees the top motion e with y_s, y_s', y_s'' replaced by y_s + s, y_s' + s',
y_s'' + s''. The piston's equation is Newton's (the Lagrange equation of s with its kinetic energy
1/2 m_p (y_s' + s')^2 and the cable's generalized force, the vertical component F_y of the cable's force on the
sheave, ``top_force_y`` of :func:`.segmented.build_segmented_model`):

    m_p (y_s'' + s'') = F_pre + F_a - k_p s - c_p s' + F_y(y_s'' + s''),

F_y affine in the sheave's acceleration (its half element's inertia, :func:`.segmented_element.lump_force`), so
s'' is solved in closed form; the free nodes' accelerations do not depend on it (lumped masses: block-diagonal
mass matrix), so the system stays explicit. As in the 2-DOF model the piston's weight is not modelled apart (it is
part of the precharge).

``outputs`` rows: :data:`.winch.WINCH_OUTPUTS` (heave = y_b, the body's depth below the top's mean depth; its
rate; x_b; ``tension_mid`` the section's tension at mid-length, :func:`.segmented.mid_tension`; ``tension_top``
the cable's pull on the sheave with its half element's material acceleration; ``tension_bottom``; ``stretch``
the sum of the element elongations minus L; ``length`` L, ``speed`` w, ``acceleration`` alpha, ``power``
T_top w (W); ``stroke`` s, 0 without a compensator) and then ``tension_least``, the least element tension (N): in the
node model slack starts at the element of least tension, usually the lowest, so the no-slack limit of the
control bounds that row (``floor_output``), where the 2-DOF model, with one uniform stretch, bounds its F_bc.

A chain of sections (a soft insert, an intermediate body: Wang 1971 p. 33's dual isolation) is the node model of
its every section (N elements each, the ladder's convention, :func:`cablesys.ladder.rungs.rung_scene`), the winch
paying out the first (top) section. Then ``heave``, ``heave_rate``, ``x_b`` and ``tension_bottom`` are the lowest
body's (the payload's, ``y_b_K`` of the chain's K sections), ``tension_mid``, ``tension_top`` and ``stretch`` the
first section's, ``tension_least`` the least over every element, and ``stretch_2`` ... ``stretch_K`` (the
elongations of the lower sections, m) and ``tension_top_2`` ... ``tension_top_K`` (the tensions at their tops, N)
follow it.
"""

from __future__ import annotations

import dataclasses

import casadi as ca
import numpy as np

from ..errors import ParameterError
from ..scene import Scene
from ..scene.labels import section_suffix
from .element_coordinates import hanging_stretch, zero_tension_lengths
from .params import ParameterLayout
from .segmented import build_segmented_model
from .winch import WINCH_OUTPUTS, WinchModel

NODE_WINCH_OUTPUTS = WINCH_OUTPUTS + ("tension_least",)
# the node model's output for each WINCH_OUTPUTS row (None: zero, the stroke of an absent compensator)
_FROM_NODE_MODEL = {"heave": "y_b", "heave_rate": "y_b_rate", "x_b": "x_b", "tension_mid": "tension_mid",
                    "tension_top": "tension_top", "tension_bottom": "tension_bottom", "stretch": "u",
                    "length": "winch_length", "speed": "winch_speed", "acceleration": "winch_acceleration",
                    "power": "winch_power", "stroke": None}
_PAYLOAD = ("heave", "heave_rate", "x_b", "tension_bottom")      # in a chain: the lowest body's rows


def source_labels(n_sections: int) -> dict:
    """{WINCH_OUTPUTS row: the node model's output label} of a chain of ``n_sections`` sections (module docstring:
    the payload's rows from the lowest section, the winch's from the first; None: the absent compensator's stroke)."""
    top, low = section_suffix(n_sections, 0), section_suffix(n_sections, n_sections - 1)
    out = {}
    for row, src in _FROM_NODE_MODEL.items():
        if src is not None and not src.startswith("winch_"):         # the winch's rows carry no section suffix
            src += low if row in _PAYLOAD else top
        out[row] = src
    return out


@dataclasses.dataclass(frozen=True)
class NodeWinchModel(WinchModel):
    """CasADi functions of the controlled node-model winch of one scene structure (SX, SI units; module docstring):
    :class:`.winch.WinchModel`'s functions and state layout on the node model.

    ``ode(x, v, t, p, c) -> x'``; ``outputs(x, v, t, p, c) -> y`` (labels :data:`NODE_WINCH_OUTPUTS`);
    ``accel(q, qd, e, winch, p, c) -> q''`` with e the top's exogenous vector (:data:`.signals.EXO_LABELS`) and
    winch = (L, w, alpha, F_a); ``outputs_e(q, qd, e, winch, p, c) -> y``. ``c`` holds the compensator's parameters
    (:data:`.winch.COMPENSATOR_PARAMETERS`; accepted and unused without one), so the control code calls both models
    alike. ``segments`` is N, the first section's elements.
    """

    segments: int = 1
    sections: int = 1
    hanging: ca.Function | None = None      # (p) -> (h_0, u) of every element, top first: the rest state's start
    output_labels: tuple = NODE_WINCH_OUTPUTS
    floor_output: str = "tension_least"
    name: str = "segmented"

    def parameters(self, scene: Scene) -> np.ndarray:
        """The scene's parameter vector (the node model's tension law max(TENS, ...) needs no switch)."""
        return self.layout.values(scene)

    def output_index(self, name: str) -> int:
        return self.output_labels.index(name)

    def describe(self) -> str:
        per = f" per section, {self.sections} sections" if self.sections > 1 else ""
        return (f"segmented node model with winch, N = {self.segments}{per} (cablesys.model.segmented_winch_control)"
                + (", compensator" if self.compensator else ""))


def build_node_winch_model(scene: Scene, *, compensator: bool = False) -> NodeWinchModel:
    """Build the controlled winch on the node model of a planar ``scene``: one section, or a chain (module docstring),
    N = each section's ``cable.segments``, the winch paying out the first.

    Raises
    ------
    ParameterError
        Sections of unequal N, a 3-D scene, an anchor, a rigid body, a ``[winch]`` profile (the control drives L:
        the scene's prescribed payout would be dropped).
    """
    ns = sorted({s.cable.segments for s in scene.sections})
    if len(ns) > 1:
        raise ParameterError("cable.segments", ns, "must be one N for every section of the controlled winch's chain")
    if scene.three_d:
        raise ParameterError("three_d", True, "the controlled node-model winch is planar")
    if scene.anchor is not None:
        raise ParameterError("anchor", "set", "a winch-lowered line hangs free: no [anchor]")
    for sec in scene.sections:
        if sec.body.is_rigid:
            raise ParameterError("body.pitch_inertia", sec.body.pitch_inertia,
                                 "must be unset: the controlled winch's bodies are points (no pitch coordinate yet)")
    if getattr(scene, "winch", None) is not None:
        raise ParameterError("winch", "set", "must be unset: the control drives the payout (a [winch] profile "
                                             "would be ignored)")
    z = ca.SX.sym("winch", 3)
    seg = build_segmented_model(scene, winch_input=z)
    nn = len(seg.q_labels)                             # the node coordinates
    q_labels = seg.q_labels + (("s",) if compensator else ())
    nq = len(q_labels)
    labels = seg.output_labels
    q, qd, e = ca.SX.sym("q", nq), ca.SX.sym("qd", nq), ca.SX.sym("e", 7)
    winch = ca.SX.sym("winch", 4)                       # L, w, alpha, F_a
    p = seg.layout.symbol
    c = ca.SX.sym("c", 4)
    zc = winch[:3]
    qn, qdn = q[:nn], qd[:nn]
    if compensator:          # the sheave at the stroke s below the tip: the cable's top is (x_s, y_s + s)
        a = ca.SX.sym("a_sheave")                       # the sheave's vertical acceleration y_s'' + s''
        e_a = ca.vertcat(e[:2], e[2] + q[nn], e[3], e[4] + qd[nn], e[5], a)
        f_y = seg.outputs(ca.vertcat(qn, qdn), e_a, p, zc)[labels.index("top_force_y")]
        k_a, f_0 = ca.jacobian(f_y, a), ca.substitute(f_y, a, 0.0)      # f_y = f_0 + k_a a (affine)
        m_p, k_p, c_p, f_pre = (c[i] for i in range(4))
        a_s = (f_pre + winch[3] - k_p * q[nn] - c_p * qd[nn] + f_0) / (m_p - k_a)     # module docstring
        e_c = ca.substitute(e_a, a, a_s)
        qdd = ca.vertcat(seg.accel(qn, qdn, e_c, p, zc), a_s - e[6])
    else:
        e_c = e
        qdd = seg.accel(qn, qdn, e, p, zc)
    y = seg.outputs(ca.vertcat(qn, qdn), e_c, p, zc)
    k_sec = len(scene.sections)
    src_of = source_labels(k_sec)
    rows = [y[labels.index(src)] if src else (q[nn] if compensator else ca.SX(0.0))
            for src in (src_of[n] for n in WINCH_OUTPUTS)]
    tens = [y[labels.index(f"element_tension[{k}]")] for k in range(seg.n_elements)]
    rows.append(ca.mmin(ca.vertcat(*tens)))
    lower = range(1, k_sec)                 # a chain's lower sections: their elongations and top tensions
    rows += [y[labels.index("u" + section_suffix(k_sec, i))] for i in lower]
    rows += [y[labels.index("tension_top" + section_suffix(k_sec, i))] for i in lower]
    out_labels = (NODE_WINCH_OUTPUTS + tuple(f"stretch_{i + 1}" for i in lower)
                  + tuple(f"tension_top_{i + 1}" for i in lower))
    names = ["q", "qd", "e", "winch", "p", "c"]
    accel = ca.Function("accel", [q, qd, e, winch, p, c], [qdd], names, ["qdd"])
    out_e = ca.Function("node_winch_outputs_e", [q, qd, e, winch, p, c], [ca.vertcat(*rows)], names, ["y"])
    top = seg.top
    xs, vs, ts = ca.SX.sym("x", 2 * nq + 2), ca.SX.sym("v", 2), ca.SX.sym("t")
    ex = top(ts, p)
    wx = ca.vertcat(xs[2 * nq], xs[2 * nq + 1], vs[0], vs[1])
    xdot = ca.vertcat(xs[nq:2 * nq], accel(xs[:nq], xs[nq:2 * nq], ex, wx, p, c), xs[2 * nq + 1], vs[0])
    ode = ca.Function("node_winch_ode", [xs, vs, ts, p, c], [xdot], ["x", "v", "t", "p", "c"], ["xdot"])
    outputs = ca.Function("node_winch_outputs", [xs, vs, ts, p, c], [out_e(xs[:nq], xs[nq:2 * nq], ex, wx, p, c)],
                          ["x", "v", "t", "p", "c"], ["y"])
    return NodeWinchModel(layout=seg.layout, compensator=compensator, q_labels=q_labels, ode=ode, outputs=outputs,
                          accel=accel, top=top, outputs_e=out_e, segments=int(seg.segments[0]), sections=k_sec,
                          output_labels=out_labels, hanging=ca.Function(
                              "hanging", [p], [ca.vertcat(*zero_tension_lengths(scene, seg.layout)),
                                               hanging_stretch(scene, seg.layout)(p)], ["p"], ["h0", "u"]))


def rest_state(model: NodeWinchModel, p, c=None, length: float | None = None) -> np.ndarray:
    """The state at rest: top still (e = 0), w = 0, zero-tension length ``length`` of the first section (default l_0
    of Wang 1971 eq. 1; a chain's lower sections at their own l_0), the node positions solving q'' = 0 by Newton's
    method with a line search (CasADi ``rootfinder``, KINSOL) from the straight vertical line of zero-tension element
    lengths stretched by the weight hanging below each element's middle (``hanging``:
    :func:`.element_coordinates.zero_tension_lengths` and :func:`.element_coordinates.hanging_stretch`, eq. 1, 12)."""
    p = np.asarray(p, float)
    c = np.zeros(4) if c is None else np.asarray(c, float)
    h0, u = (np.array(v, float).ravel() for v in model.hanging(p))
    n = model.segments
    if length is not None:
        h0[:n] = float(length) / n
    L = float(np.sum(h0[:n]))
    y = np.cumsum(h0 + u)                                          # node j's depth below the top
    guess = np.concatenate([np.ravel(np.column_stack([np.zeros(y.size), y])), np.zeros(model.nq - 2 * y.size)])
    qs = ca.SX.sym("q", model.nq)
    wz = ca.DM([L, 0, 0, 0])
    res = model.accel(qs, ca.DM.zeros(model.nq), ca.DM.zeros(7), wz, p, c)
    # Newton with a line search (KINSOL): a current bows the line far from the vertical guess
    solve = ca.rootfinder("node_rest", "kinsol", ca.Function("r", [qs], [res]),
                          {"abstol": 1e-8, "strategy": "linesearch", "error_on_fail": False})   # m/s^2: 1e-9 g
    qr = np.array(solve(guess)).ravel()
    if not np.all(np.isfinite(qr)) or np.max(np.abs(np.array(model.accel(qr, np.zeros(model.nq), np.zeros(7), wz,
                                                                          p, c)))) > 1e-6:
        raise ParameterError("scene", "rest state", "the node-model winch found no static equilibrium")
    return np.concatenate([qr, np.zeros(model.nq), [L, 0.0]])
