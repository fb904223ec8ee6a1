"""The parameter vector: every number of a scene as one labelled entry of a CasADi vector.

The model is built once per scene *structure* (number of sections, angle mode, body drag
shapes, drag segments, current points, waves, sinusoids, time-series grid); every value is
an entry of ``p``, so changing a value never rebuilds or recompiles a function. Labels
follow the scene's field paths (``cable.ae``, ``sections[1].body.weight``,
``top_motion.x[0].amplitude``) so sweeps and sensitivities can name what they vary.
"""

from __future__ import annotations

import dataclasses
import math

import casadi as ca
import numpy as np

from ..errors import ParameterError
from ..scene import Scene
from ..scene.labels import section_prefix, section_suffix  # noqa: F401 (re-exported for the model modules)
from ..scene.body import RIGID_FIELDS, RIGID_FIELDS_3D

_CABLE = ("length", "tension_ref", "ae", "diameter", "mass_per_length", "weight_per_length",
          "thinning_ratio", "added_mass_factor", "cd_normal", "ct_tangential", "internal_damping",
          "tension_floor", "cable_mass_switch")
_BODY = ("weight", "mass_x", "mass_y", "drag_area_normal", "drag_area_tangential", "axis_angle")
_ENV = ("density", "gravity", "system_speed", "top_depth")
_SINE = ("amplitude", "frequency", "phase")
_WAVE = ("amplitude", "length", "phase")
TENSION_FLOOR_NONE = -1e300   # stands for -inf (a rod that never goes slack)


def structure_of(scene: Scene) -> tuple:
    """What fixes the shape of the CasADi functions (everything else is a parameter value).

    Parameters
    ----------
    scene : Scene
        The scene.

    Returns
    -------
    tuple
        Hashable structure key: two scenes with equal keys share one compiled model.
    """
    env, top = scene.environment, scene.top_motion
    if getattr(scene, "system", None) is not None:     # a graph of lines (model/system.py): its own last entry
        return (0, "per_section", (), scene.numerics.drag_segments, len(env.current_depths), len(env.waves),
                len(top.x), len(top.y), None if top.series is None else (top.series.times, top.series.x, top.series.y),
                ()) + _ends_structure(scene) + ((("3d", len(top.z)),) if scene.three_d else ()) + (
                scene.system.structure(),) + _vessel_structure(scene)
    return (len(scene.sections), scene.angles, tuple(s.body.is_sphere for s in scene.sections),
            scene.numerics.drag_segments, len(env.current_depths), len(env.waves),
            len(top.x), len(top.y),
            # the series' samples are constants of the top-motion function (top_motion.py)
            None if top.series is None else (top.series.times, top.series.x, top.series.y),
            tuple(s.cable.segments for s in scene.sections)) + _ends_structure(scene) + (
            # Wang's cable in 3-D (stretch and two angles): one more entry, only then, so that a
            # planar scene keeps its structure key
            (("3d", len(top.z)),) if scene.three_d else ()) + (
            # rigid (pitching) bodies add a coordinate each: only then an entry (model/rigid_body.py)
            (("rigid", tuple(s.body.is_rigid for s in scene.sections)),)
            if any(s.body.is_rigid for s in scene.sections) else ())


def _vessel_structure(scene: Scene) -> tuple:
    """A vessel's rotation moving several prescribed points (model/top_motion.py): its axes and terms per axis, only
    then (a scene without it keeps today's key)."""
    axes = scene.vessel_rotation_axes
    return (("vessel rotation", tuple((a, len(scene.top_motion.vessel_rotation[a])) for a in axes)),) if axes else ()


def vessel_rotation_items(scene: Scene) -> list:
    """(label, value) of the vessel's rotation sinusoids (rad; ``top_motion.vessel.rotation_z[k].amplitude``, ...)
    on the axes the model takes (:attr:`cablesys.scene.Scene.vessel_rotation_axes`)."""
    axes = getattr(scene, "vessel_rotation_axes", ())
    rot = scene.top_motion.vessel_rotation if axes else {}
    return [(f"top_motion.vessel.rotation_{axis}[{k}].{a}", float(getattr(s, a)))
            for axis in axes for k, s in enumerate(rot[axis]) for a in _SINE]


_ANCHOR = ("x", "y")
_SEABED = ("depth", "slope_deg", "stiffness", "damping", "friction_axial", "friction_lateral", "friction_speed")


def _ends_structure(scene: Scene) -> tuple:
    """An anchor and a seabed change the model's coordinates and forces, a winch the first section, a track's path
    the top motion: part of the structure when present (a scene without them keeps today's key)."""
    extra = (scene.winch.structure(),) if getattr(scene, "winch", None) is not None else ()   # a varying first section
    track = scene.top_motion.track
    if track is not None and track.structure() is not None:    # a path's pieces (model/track_path.py)
        extra = extra + (track.structure(),)
    if scene.anchor is None and scene.seabed is None:
        return extra
    return (("ends", scene.anchor is not None, scene.seabed is not None),) + extra


def parameter_items(scene: Scene) -> list[tuple[str, float]]:
    """(label, SI value) for every scene number, in vector order.

    Parameters
    ----------
    scene : Scene
        The scene.

    Returns
    -------
    list of (str, float)
        Labels (``sections[i].cable.ae``, ...) and values of the parameter vector p.
    """
    items = _system_items(scene) if getattr(scene, "system", None) is not None else _section_items(scene)
    return items + _scene_items(scene)


def _cable_items(prefix: str, cable) -> list:
    """(label, SI value) of a cable's numbers (:data:`_CABLE`), labels ``{prefix}{name}``."""
    out = []
    for name in _CABLE:
        v = getattr(cable, name)
        if name == "tension_floor" and v == -math.inf:
            v = TENSION_FLOOR_NONE
        out.append((f"{prefix}{name}", float(v)))
    return out


def _body_items(prefix: str, body, three_d: bool) -> list:
    """(label, SI value) of a point body's numbers (:data:`_BODY`; the axis angle in rad), and M_bvz in 3-D."""
    out = [(f"{prefix}{name}", float(math.radians(body.axis_angle_deg) if name == "axis_angle" else getattr(body, name)))
           for name in _BODY]
    return out + ([(f"{prefix}mass_z", float(body.virtual_mass_z))] if three_d else [])


def _system_items(scene: Scene) -> list:
    """A system's numbers (model/system.py): every line section's cable (``system.line[k].section[s].ae``), every
    fixed point's position and every prescribed point's mean position but the first's (the origin)
    (``system.point[i].x``, ``.y``, ``.z``) and every body's or junction's numbers
    (``system.point[i].body.weight``), the labels being the scene's field paths."""
    items = []
    for k, line in enumerate(scene.system.line):
        for s, cable in enumerate(line.section):
            items += _cable_items(f"system.line[{k}].section[{s}].", cable)
    origin = scene.system.prescribed
    for i, pt in enumerate(scene.system.point):
        if pt.kind == "fixed" or (pt.kind == "prescribed" and pt is not origin):   # a held point's (mean) position
            items += [(f"system.point[{i}].{c}", float(v)) for c, v in zip("xyz", pt.position)]
        if pt.body is not None:
            items += _body_items(f"system.point[{i}].body.", pt.body, scene.three_d)
            items += _rigid_items(f"system.point[{i}].body.", pt.body, scene.three_d)
    return items


def _rigid_items(prefix: str, body, three_d: bool) -> list:
    """(label, SI value) of a rigid body's inertia, offsets, buoyancy and damping (model/rigid_body.py), in space also
    its inertia tensor, added inertias per axis and offsets' z; none for a point body."""
    if not body.is_rigid:
        return []
    return [(f"{prefix}{name}", body.rigid(name)) for name in RIGID_FIELDS + (RIGID_FIELDS_3D if three_d else ())]


def _section_items(scene: Scene) -> list:
    """A chain's numbers per section (``sections[i].cable.ae``, ``body.weight``, its slack switch)."""
    items: list[tuple[str, float]] = []
    n = len(scene.sections)
    for i, s in enumerate(scene.sections):
        pre = section_prefix(n, i)
        items += _cable_items(f"{pre}cable.", s.cable) + _body_items(f"{pre}body.", s.body, scene.three_d)
        items += _rigid_items(f"{pre}body.", s.body, scene.three_d)    # a pitching body (model/rigid_body.py)
        items.append((f"{pre}slack", 0.0))          # 1 while the section is slack (set by the simulator)
    return items


def _scene_items(scene: Scene) -> list:
    """The numbers every scene has: environment, top motion, ends and winch."""
    items = []
    env = scene.environment
    items += [(f"environment.{k}", float(getattr(env, k))) for k in _ENV]
    for k, (d, c) in enumerate(zip(env.current_depths, env.current_speeds)):
        items += [(f"environment.current_depths[{k}]", d), (f"environment.current_speeds[{k}]", c)]
    if scene.three_d:     # the current's heading (rad from +x towards +z) at every current depth
        items += [(f"environment.current_headings[{k}]", math.radians(h))
                  for k, h in enumerate(env.headings_per_depth_deg)]
    for k, w in enumerate(env.waves):
        items += [(f"environment.waves[{k}].{a}", float(getattr(w, a))) for a in _WAVE]
        if scene.three_d:
            items.append((f"environment.waves[{k}].heading", math.radians(w.heading_deg or 0.0)))
    top = scene.top_motion
    for axis in ("x", "y", "z"):
        for k, s in enumerate(getattr(top, axis)):
            items += [(f"top_motion.{axis}[{k}].{a}", float(getattr(s, a))) for a in _SINE]
    # a sampled series is not in p: its samples are constants of the model (structure_of,
    # model/top_motion.py): 2n dead entries cost a copy in every integrator step
    items += vessel_rotation_items(scene)   # the vessel's rotation moving several prescribed points (scene/vessel.py)
    items.append(("top_motion.ramp_s", top.effective_ramp_s))  # smooth start (model/top_motion.py; unset: 3 periods)
    if top.track is not None:              # a path's speed, heading and pieces (model/track_path.py); a circle: sinusoids
        items += top.track.parameter_items()
    if scene.anchor is not None:           # the fixed lower end and the seabed (model/segmented.py)
        items += [(f"anchor.{a}", float(getattr(scene.anchor, a))) for a in _ANCHOR]
        if scene.three_d:                  # in space its sway z (0 unset)
            items.append(("anchor.z", float(scene.anchor.position[2])))
    if scene.seabed is not None:
        items += [(f"seabed.{a}", float(getattr(scene.seabed, a))) for a in _SEABED]
        if scene.three_d:                  # in space the heading of its slope (deg from +x towards +z; 0 unset)
            items.append(("seabed.heading_deg", float(scene.seabed.heading_deg or 0.0)))
        items += [(f"{section_prefix(len(scene.sections), i)}body.bed_area", float(s.body.bed_area or 0.0))
                  for i, s in enumerate(scene.sections)]                   # footprints on the bed
        if getattr(scene, "system", None) is not None:                      # a system's bodies' and junctions'
            items += [(f"system.point[{i}].body.bed_area", float(pt.body.bed_area or 0.0))
                      for i, pt in enumerate(scene.system.point) if pt.free]
    if getattr(scene, "winch", None) is not None:    # the first section's payout (model/segmented_winch.py)
        items += scene.winch.parameter_items()     # its profile's numbers (scene.ends.Winch)
    return items


@dataclasses.dataclass(frozen=True)
class ParameterLayout:
    """Labels of the parameter vector and the symbolic vector itself."""

    labels: tuple
    structure: tuple
    symbol: ca.SX = dataclasses.field(repr=False, compare=False)

    @classmethod
    def from_scene(cls, scene: Scene) -> "ParameterLayout":
        labels = tuple(lbl for lbl, _ in parameter_items(scene))
        return cls(labels=labels, structure=structure_of(scene), symbol=ca.SX.sym("p", len(labels)))

    def __len__(self) -> int:
        return len(self.labels)

    def index(self, label: str) -> int:
        """Position of ``label`` in the vector (clear error for an unknown label)."""
        try:
            return self.labels.index(label)
        except ValueError:
            close = [lb for lb in self.labels if label.split(".")[-1] in lb][:6]
            raise ParameterError("parameter", label, f"is not a model parameter; similar: {close}") from None

    def sym(self, label: str) -> ca.SX:
        return self.symbol[self.index(label)]

    @property
    def series_samples(self) -> tuple | None:
        """The sampled top-motion series as (times, x, y) tuples of numbers, None without one:
        part of the structure (the top-motion function holds them as constants)."""
        return self.structure[8]

    # -- the one owner of label arithmetic: sections, waves, tension floors --------------------
    @property
    def n_sections(self) -> int:
        """Number of sections of the scene structure."""
        return self.structure[0]

    def section_index(self, i: int, name: str) -> int:
        """Position of section ``i``'s entry ``name`` (``cable.ae``, ``body.weight``, ``slack``)."""
        return self.index(f"{section_prefix(self.n_sections, i)}{name}")

    def section_indices(self, name: str) -> list[int]:
        """Positions of ``name`` for every section, top first (e.g. ``cable.tension_floor``)."""
        return [self.section_index(i, name) for i in range(self.n_sections)]

    def wave_amplitude_indices(self) -> list[int]:
        """Positions of the wave amplitudes (Wang 1971 eq. 26 'a'), in wave order."""
        return [k for k, lbl in enumerate(self.labels)
                if lbl.startswith("environment.waves[") and lbl.endswith(".amplitude")]

    def values(self, scene: Scene) -> np.ndarray:
        """The numeric vector of ``scene``; the scene must have this layout's structure."""
        if structure_of(scene) != self.structure:
            raise ParameterError("scene", scene.name,
                                 "has a different structure (sections, drag shapes, segments, current points, "
                                 "waves, sinusoids or series samples) than the model; build a model for it")
        return np.array([v for _, v in parameter_items(scene)], dtype=float)


def environment_symbols(layout: "ParameterLayout", scene: Scene) -> dict:
    """The environment's entries of ``p`` as the dict the fluid laws take (Wang 1971 eq. 26-28):
    ``current_depths``/``current_speeds`` (the CUR profile), ``system_speed``, ``gravity``,
    ``waves`` [(a, lambda, phase)], and ``density`` and ``top_depth``.

    Parameters
    ----------
    layout : ParameterLayout
        The model's parameter layout (its symbol vector).
    scene : Scene
        A scene of the layout's structure (how many current points and waves).

    Returns
    -------
    dict
        SX entries of ``layout.symbol`` by name; a 3-D scene (``scene.three_d``) adds
        ``current_headings`` (rad, one per current point) and a heading (rad) to every wave tuple.
    """
    env = scene.environment
    sym = layout.sym
    if scene.three_d:     # 3-D: the headings of the current points (rad) and a heading per wave
        return {**_planar_environment(layout, env),
                "current_headings": [sym(f"environment.current_headings[{k}]") for k in range(len(env.current_depths))],
                "waves": [tuple(sym(f"environment.waves[{k}].{a}") for a in _WAVE + ("heading",))
                          for k in range(len(env.waves))]}
    return _planar_environment(layout, env)


def _planar_environment(layout: "ParameterLayout", env) -> dict:
    """The environment symbols of a planar scene (:func:`environment_symbols`)."""
    return {
        "current_depths": [layout.sym(f"environment.current_depths[{k}]") for k in range(len(env.current_depths))],
        "current_speeds": [layout.sym(f"environment.current_speeds[{k}]") for k in range(len(env.current_depths))],
        "system_speed": layout.sym("environment.system_speed"),
        "gravity": layout.sym("environment.gravity"),
        "waves": [tuple(layout.sym(f"environment.waves[{k}].{a}") for a in _WAVE) for k in range(len(env.waves))],
        "density": layout.sym("environment.density"),
        "top_depth": layout.sym("environment.top_depth"),
    }
