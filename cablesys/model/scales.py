"""Natural scales of a model's states, for per-state absolute tolerances by state scaling.

CVODES and IDAS (through CasADi 3.8) take one scalar absolute tolerance. The integrators
(:mod:`cablesys.time_domain.integrators`) therefore integrate x~ = S^-1 x with S = diag of the
scales below, so that the scalar atol acts on state i as atol x S_i: "small" means the same
fraction of every state's natural size, and the answer no longer depends on the unit system
(an fps scene and its SI twin are integrated alike).

The scales are CasADi expressions of the parameter vector p (:func:`state_scales`), so one
compiled DAE serves every parameter value of a structure. Per model kind (``model.kind``):

- ``wang`` (Wang 1971, 2-DOF per section): stretch u_i by the section's static stretch
  T_i L_i / (AE)_i (eq. 46, 54: k = AE / L); the swing angle phi by the top's displacement
  amplitude over the line's length, A / L (between 1e-3 and 1 rad); rates by these times the
  highest forcing frequency (the top's sinusoids; without any, the pendulum frequency sqrt(g / L)).
- ``quasi-static``: the angles of the same (the stretch is not a state).
- ``segmented``: the node positions by one element's static stretch T h / AE, the rates by the
  top's speed or the element's own axial speed, whichever is larger; a rigid body's pitch by
  ANGLE_SCALE_MIN, its rate by that times the last section's speed / stretch.

T_i is the section's ``tension_ref`` when set, else W_b + w L / 2 (its body and half its cable).
"""

from __future__ import annotations

import functools

import casadi as ca
import numpy as np

from .params import ParameterLayout, section_suffix

ANGLE_SCALE_MIN = 1e-3   # rad: the swing scale when nothing moves the top (static or current-driven scenes)
ANGLE_SCALE_MAX = 1.0    # rad


def section_tension(layout: ParameterLayout, i: int):
    """T_i: section ``i``'s ``tension_ref``, or W_b + w L / 2 when that is 0 (N, SX of p)."""
    p = layout.symbol

    def c(name):
        return p[layout.section_index(i, name)]
    hanging = c("body.weight") + c("cable.weight_per_length") * c("cable.length") / 2
    return ca.if_else(c("cable.tension_ref") > 0, c("cable.tension_ref"), hanging)


def static_stretch(layout: ParameterLayout, i: int, n_elements: int = 1):
    """Static stretch of one of ``n_elements`` equal elements of section ``i``: T_i h / (AE)_i with
    h = L_i / n_elements (Wang 1971 eq. 46: tension = AE x strain). m, SX of p."""
    p = layout.symbol
    h = p[layout.section_index(i, "cable.length")] / n_elements
    return ca.fabs(section_tension(layout, i)) * h / p[layout.section_index(i, "cable.ae")]


def _sinusoids(layout: ParameterLayout) -> list[tuple]:
    """(amplitude, frequency) SX pairs of the top's sinusoids, both axes."""
    p, out = layout.symbol, []
    for lbl in layout.labels:
        if lbl.startswith("top_motion.") and lbl.endswith(".amplitude"):
            out.append((p[layout.index(lbl)], p[layout.index(lbl[: -len("amplitude")] + "frequency")]))
    return out


def top_amplitude(layout: ParameterLayout):
    """The top's displacement scale: sum of |a| of its sinusoids plus half the span of a sampled
    series per axis (m, SX of p)."""
    a = sum((ca.fabs(amp) for amp, _ in _sinusoids(layout)), ca.SX(0))
    series = layout.series_samples
    if series is not None:
        # the samples are numbers of the structure (top_motion.py): an SX max over the p entries
        # cost ~3 operations per sample in every DAE evaluation
        for v in series[1:]:
            a = a + (max(v) - min(v)) / 2
    return a


def top_speed(layout: ParameterLayout):
    """The top's velocity amplitude: sum of |a| omega over its sinusoids (m/s, SX of p)."""
    return sum((ca.fabs(amp * w) for amp, w in _sinusoids(layout)), ca.SX(0))


def forcing_frequency(layout: ParameterLayout, length):
    """The highest frequency of the top's sinusoids; without any, the pendulum's sqrt(g / L) (rad/s)."""
    sines = _sinusoids(layout)
    if sines:
        return ca.fmax(ca.mmax(ca.vertcat(*[ca.fabs(w) for _, w in sines])), 1e-6)
    return ca.sqrt(layout.sym("environment.gravity") / length)


def _section_of(model, label: str) -> int:
    """Section of a Wang stretch coordinate (``u``, ``u_2``), by the one labelling rule."""
    n = model.n_sections
    return next(i for i in range(n) if label == "u" + section_suffix(n, i))


def _wang_scales(model) -> ca.SX:
    lay = model.layout
    n = model.n_sections
    length = sum(lay.symbol[lay.section_index(i, "cable.length")] for i in range(n))
    angle = ca.fmin(ca.fmax(top_amplitude(lay) / length, ANGLE_SCALE_MIN), ANGLE_SCALE_MAX)
    omega = forcing_frequency(lay, length)
    pos = [angle if lbl.startswith("phi") else static_stretch(lay, _section_of(model, lbl)) for lbl in model.q_labels]
    pos = ca.vertcat(*pos)
    return ca.vertcat(pos, pos * omega)


def _segmented_scales(model) -> ca.SX:
    lay = model.layout
    pos, speed = [], top_speed(lay)
    for i, n_el in enumerate(model.segments):
        p = lay.symbol
        delta = static_stretch(lay, i, n_el)
        h = p[lay.section_index(i, "cable.length")] / n_el
        omega_e = ca.sqrt(p[lay.section_index(i, "cable.ae")] / (p[lay.section_index(i, "cable.mass_per_length")] * h**2))
        pos += [delta] * (getattr(model, "dim", 2) * n_el)  # x[j], y[j] (z[j] in 3-D) of the section's nodes
        speed = ca.fmax(speed, delta * omega_e)
    pos = pos[: model.nq - getattr(model, "n_rotations", 0)]   # an anchored line's fixed last node is no state
    rates = [speed] * len(pos)
    # a rigid body's pitch (rad) by ANGLE_SCALE_MIN, its rate by that times the element's frequency speed / delta
    n_rot = getattr(model, "n_rotations", 0)
    return ca.vertcat(*pos, *([ANGLE_SCALE_MIN] * n_rot), *rates, *([ANGLE_SCALE_MIN * speed / delta] * n_rot))


def _system_scales(model) -> ca.SX:
    """A system of lines (model/system.py): every free node's position by the static stretch T h / AE of an element of
    the line section it lies in (a point's node: the smallest of its lines' end sections'), T the section's
    ``tension_ref`` when set, else the bodies' weight shared among the lines plus half the line's weight (N); the rates
    by the top's speed or the elements' axial speed, whichever is larger; a rigid body's orientation as the chain's."""
    lay, p = model.layout, model.layout.symbol
    sym = lambda k, s, name: p[lay.index(f"system.line[{k}].section[{s}].{name}")]
    bodies = sum((ca.fabs(p[i]) for i, lb in enumerate(lay.labels) if lb.endswith("body.weight")), ca.SX(0))
    share = bodies / max(len(model.line_nodes), 1)
    node_scale, speed = {}, top_speed(lay)
    for k, (seq, segs) in enumerate(zip(model.line_nodes, model.line_segments)):
        w_line = sum((sym(k, s, "weight_per_length") * sym(k, s, "length") for s in range(len(segs))), ca.SX(0))
        pos = 0
        for s, n_el in enumerate(segs):
            h = sym(k, s, "length") / n_el
            hanging = share + ca.fabs(w_line) / 2
            T = ca.if_else(sym(k, s, "tension_ref") > 0, sym(k, s, "tension_ref"), hanging)
            delta = ca.fabs(T) * h / sym(k, s, "ae")
            speed = ca.fmax(speed, delta * ca.sqrt(sym(k, s, "ae") / (sym(k, s, "mass_per_length") * h**2)))
            for j in seq[pos:pos + n_el + 1]:
                node_scale[j] = delta if j not in node_scale else ca.fmin(node_scale[j], delta)
            pos += n_el
    dim = model.dim
    free = sorted((q0, j) for j, q0 in enumerate(model.node_q) if q0 >= 0)
    pos = [node_scale[j] for _, j in free for _ in range(dim)]
    # a rigid body's orientation coordinates (rad, or the quaternion's entries) by ANGLE_SCALE_MIN, their rates by
    # that times the fastest element's frequency, as the chain's
    n_rot = getattr(model, "n_rotations", 0)
    rot_rate = ANGLE_SCALE_MIN * speed / functools.reduce(ca.fmin, pos) if n_rot else 0.0
    return ca.vertcat(*pos, *([ANGLE_SCALE_MIN] * n_rot), *([speed] * len(pos)), *([rot_rate] * n_rot))


# the scale provider of each model kind (``model.kind``): model -> SX (2 nq,) in p
PROVIDERS = {"wang": _wang_scales, "quasi-static": _wang_scales, "segmented": _segmented_scales}


def state_scales(model) -> ca.Function:
    """``state_scales(p) -> S``: the natural scale of every state of ``model`` (SI units of the
    state), an SX function of the parameter vector, built once per model.

    Parameters
    ----------
    model : CableModel
        A model of a kind in :data:`PROVIDERS` (``wang``, ``quasi-static``, ``segmented``); any
        other kind gets S = 1 (atol then stays absolute, in SI).

    Returns
    -------
    casadi.Function
        (len(p),) -> (2 nq,) positive scales, positions then rates (see the module docstring).
    """
    def build():
        provider = _system_scales if getattr(model, "line_nodes", None) is not None else PROVIDERS.get(model.kind)
        S = provider(model) if provider is not None else ca.SX.ones(2 * model.nq)
        if S.numel() != 2 * model.nq:
            raise ValueError(f"state scales of a {model.kind!r} model: {S.numel()} for {2 * model.nq} states")
        return ca.Function("state_scales", [model.layout.symbol], [S], ["p"], ["S"])
    return model.derive("state_scales", build)


def state_scale_values(model, p) -> np.ndarray:
    """Numeric :func:`state_scales` at ``p`` (model parameters, without the integrators' (t_0, h))."""
    return np.array(state_scales(model)(np.asarray(p, dtype=float)[: len(model.layout)])).ravel()
