"""A slack scene on the shared cable: the node model's span, its equilibrium and its modes.

:func:`to_scene` writes a :class:`~cablesys.slack.scene.SlackScene` (Griffin & Rosenthal 1985: a cable
between support A at (0, 0) and B at (span, rise), z up, with attached point masses, in air or in
water) as a main :class:`cablesys.scene.Scene` of the segmented node model (:mod:`cablesys.model.segmented`):

- support A is the top (prescribed, no motion), support B the ``[anchor]`` at (x, y) = (span, -rise)
  (the node model's y points down);
- the cable is cut at the point masses into sections; section i's body is point mass i (weight in
  the medium and virtual mass M + C_am M / S in every direction, eq. 26); the last section's body sits at
  the anchor, where it loads the support only (weight 0, any positive mass);
- each section has the cable's EA, mass per length m and weight per length w in the medium, zero
  tension at its reference length (tension_ref = 0: the slack cable's lengths are unstretched) and
  no lateral contraction; elements per section in proportion to the section's length; a cable
  stretched between its supports (chord >= L) is described at a reference tension past the chord
  with the same zero-tension length, stiffness and totals (see :func:`to_scene`);
- in water the cable's transverse added mass per length m_a (C_am m / S, or the scene's override) is
  the node model's gamma rho pi d^2 / 4 (Wang 1971 eq. 23) with d the diameter of the displaced
  volume, pi d^2 / 4 = m / (rho S) (rho = :data:`WATER_DENSITY`); in air there is no added mass
  (gamma = 0) and d is that of a steel cable (:data:`STEEL_SPECIFIC_GRAVITY`) when S is unset:
  d enters the drag only, which is zero at rest and in the linear modes in still fluid.

:func:`equilibrium` solves the node model's statics (:func:`cablesys.statics.span.span_equilibrium`)
and :func:`modes` its linear modes from the model's own mass matrix and the Jacobian of its forces
(:func:`cablesys.statics.span.span_matrices`), in-plane and out-of-plane, with the eigen solver,
mass normalisation (eq. 25) and mode classification of :mod:`.vibration`. Both use the node model's
element-kernel form (:func:`span_form`: the same equations from the element kernel mapped over the
elements, built at constant size and never stored); :func:`span_model` is the element-by-element node model
itself, for the time domain about that equilibrium.
"""

from __future__ import annotations

import hashlib
import math
import time
from collections import OrderedDict

import numpy as np

from ..errors import ParameterError, SolverError
from ..model import FunctionCache, build_model
from ..model.params import ParameterLayout, structure_of
from ..results import timed
from ..scene import Anchor, Body, Cable, Environment, Numerics, Scene, Section
from ..statics.span import SpanKernel, span_equilibrium, span_kernel, span_matrices
from .results import Equilibrium, SlackAnalysis
from .scene import SlackScene, _buoyancy_and_added
from .statics import Discretization, shooting_nodes, solve_equilibrium
from .modal import _eig, classify_rows

WATER_DENSITY = 1025.0          # kg/m^3, sea water (the node model's default environment.density)
AIR_DENSITY = 1.225             # kg/m^3, standard sea-level air (drag only)
STEEL_SPECIFIC_GRAVITY = 7.85   # of a steel wire: its diameter in air when the scene gives no S (drag only)
ANCHOR_BODY_MASS = 1.0          # kg: the last section's body sits at the anchor and moves with it (no effect)
REACH_MARGIN = 1.0 + 1e-6       # a stretched span's reference length past its chord (relative)
KINSOL_SOLVES = 2               # span_equilibrium: elements elastic both ways, then the cable's own law
MODEL_CACHE_SIZE = 16           # node models kept in memory, by structure (the last used) ...
MODEL_CACHE_ELEMENTS = 4000     # ... holding at most this many elements in all (the newest always kept)


def section_segments(scene: SlackScene, n_elements: int | None = None) -> tuple[int, ...]:
    """Elements per section (the cable cut at its point masses): in proportion to each section's
    unstretched length, at least one, about ``n_elements`` in all (default ``scene.n_elements``)."""
    n = int(n_elements or scene.n_elements)
    cuts = _cuts(scene)
    return tuple(max(1, round(n * (b - a) / scene.cable.length)) for a, b in zip(cuts[:-1], cuts[1:]))


def _cuts(scene: SlackScene) -> list[float]:
    """Arc lengths (m from A) of the section ends: 0, the point masses in order, L."""
    pos = sorted(pm.position for pm in scene.masses)
    if any(b - a <= 1e-9 * scene.cable.length for a, b in zip(pos[:-1], pos[1:])):
        raise ParameterError("masses", pos, "must sit at distinct positions along the cable (merge coincident "
                             "masses into one)")
    return [0.0] + pos + [scene.cable.length]


def to_scene(scene: SlackScene, n_elements: int | None = None, segments: tuple[int, ...] | None = None) -> Scene:
    """The main scene of the span (see the module docstring): top = A, anchor = B, bodies = masses.

    ``segments``: elements per section (default :func:`section_segments` of ``n_elements``).
    """
    if not isinstance(scene, SlackScene):
        raise ParameterError("scene", type(scene).__name__, "must be a SlackScene")
    cuts = _cuts(scene)
    segs = section_segments(scene, n_elements) if segments is None else tuple(segments)
    if len(segs) != len(cuts) - 1 or any(not isinstance(k, int) or k < 1 for k in segs):
        raise ParameterError("segments", segs, f"must be {len(cuts) - 1} positive integers (one per section)")
    g, water = scene.gravity, scene.medium == "water"
    rho = WATER_DENSITY if water else AIR_DENSITY
    c = scene.cable
    w, m_a = c.weight_and_added_mass(scene.medium, g)
    S = c.specific_gravity if c.specific_gravity is not None else STEEL_SPECIFIC_GRAVITY
    area = c.mass_per_length / (WATER_DENSITY * S)          # displaced volume per length, pi d^2 / 4
    diameter = math.sqrt(4.0 * area / math.pi)
    gamma = m_a / (rho * area) if water else 0.0             # eq. 23: gamma rho pi d^2/4 = m_a
    # a chord at or beyond L (a cable stretched between its supports, up to max_strain) is described at a
    # reference tension T_r whose length l_r reaches past the chord: the node model's law
    # T = (AE)_r (l - h_0) / h_r with l_0 = l_r (1 - T_r / (AE)_r) = L, (AE)_r / l_r = EA / L and the
    # totals m_r l_r = m L, w_r l_r = w L is Griffin & Rosenthal's EA (l - L_0) / L_0 (Wang 1971 eq. 1, 5, 12)
    stretch = max(1.0, REACH_MARGIN * scene.chord / c.length)          # l_r / L
    masses = sorted(scene.masses, key=lambda pm: pm.position)
    sections = []
    for i, n_el in enumerate(segs):
        cable = Cable(length=stretch * (cuts[i + 1] - cuts[i]), ae=c.ae * stretch, tension_ref=c.ae * (stretch - 1.0),
                      diameter=diameter, mass_per_length=c.mass_per_length / stretch,
                      weight_per_length=w / stretch, added_mass_factor=gamma, segments=n_el)
        if i < len(masses):
            pm = masses[i]
            wp, ap = _buoyancy_and_added(pm.mass, pm.specific_gravity, pm.added_mass_factor, scene.medium, g, "mass")
            body = Body(weight=wp, mass_x=pm.mass + ap, mass_y=pm.mass + ap, mass_z=pm.mass + ap)
        else:
            body = Body(weight=0.0, mass_x=ANCHOR_BODY_MASS, mass_y=ANCHOR_BODY_MASS, mass_z=ANCHOR_BODY_MASS)
        sections.append(Section(cable=cable, body=body))
    return Scene(name="span", sections=tuple(sections), anchor=Anchor(x=scene.span, y=-scene.rise),
                 environment=Environment(density=rho, gravity=g), numerics=Numerics(dimensions=3))


_MODELS: OrderedDict = OrderedDict()


def span_model(scene: Scene, cache: FunctionCache | None = None):
    """The element-by-element node model of a span scene (:func:`cablesys.model.build_model`: what the time domain
    runs), kept by structure (see :func:`_kept`). The statics and modes here do not need it: they use
    :func:`span_form`."""
    return _kept("span_model_", scene, lambda: build_model(scene), cache)


def span_form(scene: Scene, cache: FunctionCache | None = None) -> SpanKernel:
    """The element-kernel form of a span scene's node model (:func:`cablesys.statics.span.span_kernel`: its statics,
    mass and stiffness from the element kernel mapped over the elements, a graph of constant size at any number of
    elements), kept by structure (see :func:`_kept`)."""
    return _kept("span_kernel_", scene, lambda: span_kernel(scene), cache)


def _kept(prefix: str, scene: Scene, build, cache: FunctionCache | None):
    """``build()`` kept by the scene's structure (sections, elements, parameter labels): in ``cache`` when given,
    else in a module store of the last used structures (at most :data:`MODEL_CACHE_SIZE` of them and
    :data:`MODEL_CACHE_ELEMENTS` elements in all)."""
    key = prefix + hashlib.sha256(repr((structure_of(scene), ParameterLayout.from_scene(scene).labels))
                                  .encode()).hexdigest()[:32]
    if cache is not None:
        return cache.get(key, build)
    if key not in _MODELS:
        _MODELS[key] = build()
        while len(_MODELS) > 1 and (len(_MODELS) > MODEL_CACHE_SIZE
                                    or sum(m.n_elements for m in _MODELS.values()) > MODEL_CACHE_ELEMENTS):
            _MODELS.popitem(last=False)
    _MODELS.move_to_end(key)
    return _MODELS[key]


def _discretization(scene: SlackScene, main: Scene) -> Discretization:
    """The node layout of ``main`` in the slack vocabulary (arc lengths, element lengths, nodal loads)."""
    s, cuts = [0.0], _cuts(scene)
    for i, sec in enumerate(main.sections):
        n = sec.cable.segments
        s += list(cuts[i] + (cuts[i + 1] - cuts[i]) * np.arange(1, n + 1) / n)
    s = np.array(s)
    L0 = np.diff(s)
    half = np.zeros(len(s))
    half[:-1] += L0 / 2
    half[1:] += L0 / 2
    w, ma = scene.cable.weight_and_added_mass(scene.medium, scene.gravity)
    weight, mass, added_i = w * half, scene.cable.mass_per_length * half, np.zeros(len(s))
    nodes = []
    for pm in scene.masses:
        i = int(np.argmin(np.abs(s - pm.position)))
        wp, ap = _buoyancy_and_added(pm.mass, pm.specific_gravity, pm.added_mass_factor, scene.medium,
                                     scene.gravity, "mass")
        weight[i] += wp
        mass[i] += pm.mass
        added_i[i] += ap
        nodes.append(i)
    return Discretization(s=s, L0=L0, weight=weight, mass=mass, added_transverse=ma * half,
                          added_isotropic=added_i, mass_nodes=tuple(nodes))


def equilibrium(scene: SlackScene, *, n_elements: int | None = None, segments=None,
                cache: FunctionCache | None = None) -> Equilibrium:
    """The span's static shape from the node model's statics (KINSOL on its static residual,
    :func:`cablesys.statics.span.span_equilibrium`), started from the same lumped chain solved by shooting
    on the support force (:func:`.statics.shooting_nodes`, statically determinate; where that route cannot
    start, the chain's energy NLP :func:`.statics.solve_equilibrium`); an :class:`Equilibrium`
    (``method`` 'node model', ``iterations`` the KINSOL solves: the node statics do not count their Newton
    steps; the scaled residual is below the statics' tolerance, else a SolverError)."""
    t0 = time.perf_counter()
    main = to_scene(scene, n_elements, segments)
    model = span_form(main, cache)
    p = np.asarray(model.parameters(main), float)
    d = _discretization(scene, main)
    try:
        xg, zg, _ = shooting_nodes(scene, d)
    except SolverError as shooting:       # outside the shooting's reach: the chain's energy NLP, or both reasons
        try:
            eq0 = solve_equilibrium(scene, n_elements=d.n_elements)
        except SolverError as nlp:
            raise SolverError(f"{nlp} (and {shooting})") from None
        xg, zg = np.interp(d.s, eq0.s, eq0.x), np.interp(d.s, eq0.s, eq0.z)    # onto the span's nodes
    guess = np.column_stack([xg[1:-1], -zg[1:-1], np.zeros(len(xg) - 2)]).ravel()
    q, _ = span_equilibrium(model, p, guess=guess)
    nodes = q.reshape(-1, 3)
    x = np.concatenate([[0.0], nodes[:, 0], [scene.span]])
    z = np.concatenate([[0.0], -nodes[:, 1], [scene.rise]])
    tension = scene.cable.ae * (np.hypot(np.diff(x), np.diff(z)) - d.L0) / d.L0      # elastic law, T_r = 0
    eq = Equilibrium(scene=scene, s=d.s, x=x, z=z, tension=tension, discretization=d, method="node model",
                     iterations=KINSOL_SOLVES, seconds=time.perf_counter() - t0, node_state=(model, q, p))
    return eq


def modes(eq: Equilibrium, n_modes: int | None = None, *, solver: str = "auto") -> ModeSet:
    """The ``n_modes`` lowest modes of the node model about ``eq`` (an :func:`equilibrium`): M and K of
    :func:`cablesys.statics.span.span_matrices`, in-plane and out-of-plane, eq. 25 normalisation."""
    node = eq.node_state
    if node is None:
        raise ParameterError("eq", eq.method, "must be an Equilibrium of cablesys.slack.shared.equilibrium")
    n_modes = eq.scene.n_modes if n_modes is None else n_modes
    if isinstance(n_modes, bool) or int(n_modes) != n_modes or n_modes < 1:
        raise ParameterError("n_modes", n_modes, "must be an integer >= 1")
    t0 = time.perf_counter()
    mats = span_matrices(*node)
    w_in, V_in, used = _eig(mats["K_in"], mats["M_in"], n_modes, solver)
    w_out, V_out, _ = _eig(mats["K_out"], mats["M_out"], n_modes, solver)
    nn = len(eq.x)
    rows = []
    for j in range(len(w_in)):
        shape = np.zeros((nn, 3))
        shape[1:-1, 0] = V_in[0::2, j]
        shape[1:-1, 2] = -V_in[1::2, j]          # z up = -y
        rows.append((w_in[j], None, np.nan, shape))
    for j in range(len(w_out)):
        shape = np.zeros((nn, 3))
        shape[1:-1, 1] = V_out[:, j]
        rows.append((w_out[j], "O", np.nan, shape))
    return classify_rows(eq, rows, n_modes, n_elements=eq.discretization.n_elements, solver=used,
                         seconds=time.perf_counter() - t0)


@timed
def analyze(scene: SlackScene, n_modes: int | None = None, *, n_elements: int | None = None, segments=None,
            solver: str = "auto", cache: FunctionCache | None = None) -> SlackAnalysis:
    """Equilibrium and modes of a slack scene on the node model, as one :class:`SlackAnalysis`."""
    eq = equilibrium(scene, n_elements=n_elements, segments=segments, cache=cache)
    return SlackAnalysis(equilibrium=eq, modes=modes(eq, n_modes, solver=solver))


__all__ = ["analyze", "equilibrium", "modes", "section_segments", "span_form", "span_model", "to_scene"]
