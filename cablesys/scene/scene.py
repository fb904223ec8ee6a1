"""The scene: everything that defines one cable-system problem, immutable and in SI."""

from __future__ import annotations

import dataclasses

import numpy as np

from ..errors import ParameterError
from .components import Body, Cable, Environment, Initial, Numerics, Section, TopMotion
from .ends import Anchor, Seabed, Winch
from .labels import section_prefix
from .limits import Limits
from .sea import append_once, sea_waves, user_count
from .system import System

#: The body of a chain's last section when the chain ends at a fixed point (an [anchor]): it sits at the anchor and
#: loads nothing (weight 0; its mass is no coordinate's).
ANCHOR_BODY = Body(weight=0.0, mass_x=1.0, mass_y=1.0)

ANGLE_MODES = ("per_section", "shared")


@dataclasses.dataclass(frozen=True, kw_only=True)
class Scene:
    """A chain of cable sections hanging from a moving top (Wang 1971, Fig. 1 and p. 33), or a system of lines
    joined at points (:class:`~.system.System`).

    One section is Wang's 2-DOF model (angle phi, stretch u). Several sections are the
    report's extensions: ``angles="shared"`` is the dual-isolation model (one swing angle,
    one stretch per section); ``angles="per_section"`` the general segmented cable.

    ``system`` (the ``[[point]]`` and ``[[line]]`` tables) describes any cable system instead of ``sections``: a
    system that is a chain (:meth:`.system.System.as_chain`) becomes that chain of sections here (with an
    ``anchor`` when it ends at a fixed point), so it is today's scene exactly and ``system`` is None; any other
    system keeps ``system`` and has no sections (the node model of a graph of lines builds it).
    """

    name: str = "scene"
    sections: tuple = ()
    angles: str = "per_section"
    environment: Environment = dataclasses.field(default_factory=Environment)
    top_motion: TopMotion = dataclasses.field(default_factory=TopMotion)
    initial: Initial = dataclasses.field(default_factory=Initial)
    numerics: Numerics = dataclasses.field(default_factory=Numerics)
    limits: Limits | None = None      # what a run is checked against (cablesys.verdict); optional
    design: dict | None = dataclasses.field(default=None, compare=False)   # the [design] table, read by cablesys.isolation
    anchor: Anchor | None = None      # the last section's lower end fixed (segmented cable only)
    seabed: Seabed | None = None      # a seabed acting on the nodes (segmented cable only)
    winch: Winch | None = None        # the first section's length changes in time (segmented cable only)
    system: System | None = None      # points joined by lines ([[point]], [[line]]); a chain becomes sections

    def __post_init__(self):
        secs = tuple(self.sections)
        if self.system is not None:
            secs = self._from_system(secs)
        if self.system is not None:       # not a chain: the node model of a graph of lines
            self._check_system()
            self._check_dimensions()
            self._finish_sea()
            return
        if not secs:
            raise ParameterError("sections", secs, "needs at least one cable section")
        for i, s in enumerate(secs):
            if not isinstance(s, Section):
                raise ParameterError(f"sections[{i}]", type(s).__name__, "must be a Section(cable=..., body=...)")
        object.__setattr__(self, "sections", secs)
        if self.angles not in ANGLE_MODES:
            raise ParameterError("angles", self.angles, f"must be one of {ANGLE_MODES}")
        self._check_hanging_tension()
        self._check_initial_lengths()
        self._check_ends()
        self._check_dimensions()
        self._check_rigid_bodies()
        self._check_track()
        self._check_winch()
        self._finish_sea()

    def _finish_sea(self) -> None:
        """The irregular sea's waves at the cable too (Wang 1971 eq. 26-28; scene/sea.py), when asked."""
        sea = self.top_motion.spectrum
        if sea is not None and sea.waves_at_cable:   # the same sea at the cable (Wang 1971 eq. 26-28; scene/sea.py)
            env = self.environment
            object.__setattr__(self, "environment", dataclasses.replace(
                env, waves=append_once(env.waves, sea_waves(sea, env.gravity))))

    def _from_system(self, secs: tuple) -> tuple:
        """Check the system against the rest of the scene and, when it is a chain (:meth:`.system.System.as_chain`),
        make it that chain: sections top to bottom, each with the body at its lower end (:data:`ANCHOR_BODY` at a
        fixed end, which becomes the ``[anchor]``); returns the sections."""
        sys_ = self.system
        if not isinstance(sys_, System):
            raise ParameterError("system", type(sys_).__name__, "must be a System of [[point]] and [[line]] tables")
        if secs:
            raise ParameterError("sections", f"{len(secs)} sections", "must be unset with [[point]] and [[line]]: "
                                 "describe the cable either as sections ([cable]/[body] or [[sections]]) or as a "
                                 "system of points and lines")
        if self.anchor is not None:
            raise ParameterError("anchor", "set", "must be unset with [[point]] and [[line]]: a fixed point is the "
                                 "anchor")
        bed, depth0 = self.seabed, self.environment.top_depth
        for i, p in enumerate(sys_.point):
            if p.held and bed is not None:
                px, py, pz = p.position
                y_bed = bed.bed_y(px, depth0, pz)
                if py > y_bed + 1e-9 * max(1.0, abs(y_bed)):
                    where = f"x = {px:.6g} m" + (f", z = {pz:.6g} m" if pz else "")
                    raise ParameterError(f"point[{i}].y", py, f"puts the {p.kind} point {p.name!r} below the seabed "
                                         f"(the bed is at y = {y_bed:.6g} m under {where}, seabed.depth = "
                                         f"{bed.depth:.6g} m): a fixed or prescribed point must lie on or above the bed")
        chain = sys_.as_chain()
        if chain is None:
            return secs
        steps, end = chain
        out = []
        for k, rev in steps:
            line = sys_.line[k]
            lower = sys_.by_name(line.start if rev else line.end)
            out.append(Section(cable=line.section[0], body=lower.body if lower.free else ANCHOR_BODY))
        object.__setattr__(self, "sections", tuple(out))
        object.__setattr__(self, "system", None)
        if end.kind == "fixed":
            object.__setattr__(self, "anchor", Anchor(x=end.x, y=end.y, z=end.z or None))   # z = 0: in the plane
        return tuple(out)

    def _check_system(self) -> None:
        """What the node model of a graph of lines (:mod:`cablesys.model.system`) does not take yet, each refused by
        name: a rigid body with a seabed (as the chain's), an initial angle or stretch (it starts from its
        statics), top motion without a prescribed point; a winch whose line is not the prescribed point's one line; a
        track as a chain's (:meth:`_check_track`). A vessel's 6-DOF RAO moves several prescribed points each by its
        own lever arm (:attr:`vessel_rotation_axes`)."""
        self._check_system_winch()
        top = self.top_motion
        if self.system.prescribed is None:
            moved = [f"top_motion.{a}" for a in ("x", "y", "z") if getattr(top, a)] + [
                f"top_motion.{a}" for a in ("series", "spectrum", "track") if getattr(top, a) is not None]
            if moved:
                raise ParameterError(moved[0], "set", "must be unset: [top_motion] moves the prescribed point, and "
                                     "this system has none (its points are fixed or free)")
        for name in ("phi", "u"):
            if getattr(self.initial, name) is not None:
                raise ParameterError(f"initial.{name}", getattr(self.initial, name), "must be unset for a system of "
                                     "lines: it starts from its static state")
        for i, p in enumerate(self.system.point):
            if p.body is not None and p.body.is_rigid and self.seabed is not None:
                raise ParameterError(f"point[{i}].pitch_inertia", p.body.pitch_inertia, "must be unset for a scene "
                                     "with a [seabed]: a rigid, pitching body is built by the node model without "
                                     "seabed so far (its footprint's contact does not turn it)")
        self._check_track()

    def _check_system_winch(self) -> None:
        """A ``[winch]`` on a system pays out the one line that starts at the (first) prescribed point (its first section, as
        the chain's first section: :mod:`cablesys.model.segmented_winch`), keeping its zero-tension length in
        (0, max_length] (:meth:`.ends.Winch.check_length`)."""
        if self.winch is None:
            return
        top = self.system.prescribed
        if top is None:
            raise ParameterError("winch", "set", "must be unset: a winch pays out the line that starts at the "
                                 "prescribed point, and this system has none (its points are fixed or free)")
        starts = [k for k, ln in enumerate(self.system.line) if ln.start == top.name]
        if len(starts) != 1:
            names = [self.system.line[k].name for k in starts]
            raise ParameterError("winch", f"{len(starts)} lines from the prescribed point {top.name!r}"
                                 + (f" ({', '.join(names)})" if names else ""),
                                 "must pay out one line: exactly one [[line]] must start (from) at the prescribed "
                                 "point, the line the winch pays out (write the others from their other end)")
        k = starts[0]
        c = self.system.line[k].section[0]
        self.winch.check_length(c.length * (1.0 - c.tension_ref / c.ae), f"line[{k}].section[0].length")

    def _check_ends(self) -> None:
        """An anchor or a seabed acts on the nodes of the segmented cable; the anchor lies on or above
        the bed; the line reaches from the top's mean position to its anchor (length l_r >= chord)."""
        if self.anchor is None and self.seabed is None:
            return
        what = "[anchor]" if self.seabed is None else "[seabed]"
        if all(s.cable.segments == 1 for s in self.sections):
            raise ParameterError(f"{section_prefix(self, 0)}cable.segments", 1, f"must be >= 2 in some section: {what} "
                                 "acts on the nodes of the segmented cable (Wang's 2-DOF straight cable has none)")
        a, bed, depth0 = self.anchor, self.seabed, self.environment.top_depth
        if a is None:
            return
        if self.initial.phi is not None or self.initial.u is not None:
            raise ParameterError("initial.phi" if self.initial.phi is not None else "initial.u",
                                 self.initial.phi if self.initial.phi is not None else self.initial.u,
                                 "must be unset for an anchored line: it starts from its static state")
        ax, ay, az = a.position
        if bed is not None:
            y_bed = bed.bed_y(ax, depth0, az)
            if ay > y_bed + 1e-9 * max(1.0, abs(y_bed)):
                where = f"anchor.x = {ax:.6g} m" + (f", anchor.z = {az:.6g} m" if a.z is not None else "")
                raise ParameterError("seabed.depth", bed.depth,
                                     f"puts the bed at y = {y_bed:.6g} m under the anchor ({where}), "
                                     f"above anchor.y = {ay:.6g} m: the anchor must lie on or above the seabed")
        length = sum(s.cable.length for s in self.sections)
        chord = float(np.linalg.norm(a.position))
        if length < chord:
            raise ParameterError(f"{section_prefix(self, len(self.sections) - 1)}cable.length",
                                 self.sections[-1].cable.length,
                                 f"makes the line {length:.6g} m long (all sections, at their reference tension), "
                                 f"shorter than the {chord:.6g} m from the top's mean position to the anchor")
    def _check_rigid_bodies(self) -> None:
        """A rigid body is built by the segmented cable (model/rigid_body.py: pitch in the plane, three rotations in
        space): it needs a section with ``cable.segments`` > 1, no seabed, and not to sit at an anchor."""
        for i, s in enumerate(self.sections):
            if not s.body.is_rigid:
                continue
            name = f"{section_prefix(self, i)}body.pitch_inertia"
            why = ("Wang's 2-DOF straight cable (every cable.segments = 1; the model ladder runs such a scene "
                   "with the node model)" if all(c.cable.segments == 1 for c in self.sections)
                   else "a scene with a [seabed]" if self.seabed is not None
                   else "the body at the [anchor]" if self.anchor is not None and i == len(self.sections) - 1 else None)
            if why is not None:
                raise ParameterError(name, s.body.pitch_inertia, f"must be unset for {why}: a rigid, pitching body is "
                                     "built by the segmented cable without seabed so far")

    def _check_winch(self) -> None:
        """The winch keeps the first section's zero-tension length L(t) = l_0 + Delta L(t) in (0, max_length]
        (:meth:`.ends.Winch.check_length`, l_0 of Wang 1971 eq. 1); it acts on the node model in the plane and in space,
        with a free body or an anchor at the lower end (no track so far: the steady turn has a fixed length)."""
        w = self.winch
        if w is None:
            return
        if self.top_motion.track is not None:
            raise ParameterError("top_motion.track", "set", "must be unset with [winch]: the node model with a winch "
                                 "starts from rest under a still top so far")
        c = self.sections[0].cable
        w.check_length(c.length * (1.0 - c.tension_ref / c.ae), f"{section_prefix(self, 0)}cable.length")

    def three_d_fields(self) -> tuple:
        """The 3-D fields this scene sets (``top_motion.z``, a track that leaves the x axis, a current or wave heading,
        ``body.mass_z``, a rigid body's 3-D fields: its inertia tensor's other entries, added inertias about x and y,
        offsets' z, drag along z, its initial roll or yaw; ``anchor.z``, ``seabed.heading_deg``)."""
        env, out = self.environment, []
        track = self.top_motion.track
        if track is not None and not track.in_plane:
            out.append("top_motion.track")
        if self.top_motion.z and user_count(self.top_motion, "z"):
            out.append("top_motion.z")
        elif self.top_motion.z and track is None:
            out.append("top_motion.vessel (the lever arm's motion has sway)")
        if env.current_headings_deg:
            out.append("environment.current_headings_deg")
        out += [f"environment.waves[{k}].heading_deg" for k, w in enumerate(env.waves) if w.heading_deg is not None]
        out += [f"{section_prefix(self, i)}body.mass_z" for i, s in enumerate(self.sections) if s.body.mass_z is not None]
        out += [f"{section_prefix(self, i)}body.{name}" for i, s in enumerate(self.sections) for name in s.body.three_d_fields()]
        if self.anchor is not None and self.anchor.z is not None:
            out.append("anchor.z")
        if self.seabed is not None and self.seabed.heading_deg is not None:
            out.append("seabed.heading_deg")
        if self.system is not None:      # a fixed point off the x-y plane, a body's M_bvz
            out += [f"point[{i}].z" for i, p in enumerate(self.system.point) if p.held and p.z]
            out += [f"point[{i}].mass_z" for i, p in enumerate(self.system.point)
                    if p.body is not None and p.body.mass_z is not None]
            out += [f"point[{i}].{name}" for i, p in enumerate(self.system.point) if p.body is not None
                    for name in p.body.three_d_fields()]      # a rigid body's 3-D fields
            rot = self.top_motion.vessel_rotation       # a further point of the vessel swayed by its roll or yaw:
            out += [f"top_motion.vessel (point[{i}]'s motion has sway: the vessel's roll or yaw at its lever arm)"
                    for i, p in enumerate(self.system.point)      # z_k = z_0 + theta_x dy - theta_y dx (scene/vessel.py)
                    if p.kind == "prescribed" and ((rot.get("x") and p.y) or (rot.get("y") and p.x))][:1]
        return tuple(out)

    @property
    def vessel_rotation_axes(self) -> tuple:
        """The axes of the vessel's rotation that the model takes as input (:mod:`cablesys.model.top_motion`): with
        [top_motion.vessel] and several prescribed points, each moved by its own lever arm (s_0 + theta x Delta,
        :mod:`.vessel`), ("z",) in the plane (only theta_z moves a point in the x-y plane) and ("x", "y", "z") in
        space; () otherwise (one point: the lever arm's motion is the top motion)."""
        if self.system is None or not self.top_motion.vessel_rotation or self.system.n_prescribed < 2:
            return ()
        return ("x", "y", "z") if self.three_d else ("z",)

    @property
    def three_d(self) -> bool:
        """True when Wang's 3-D equations run: ``numerics.dimensions = 3``, or unset and a 3-D field is set."""
        dims = self.numerics.dimensions
        return dims == 3 or (dims is None and bool(self.three_d_fields()))

    def _check_dimensions(self) -> None:
        """A 3-D field needs the 3-D equations; the node model's anchor and seabed are then in space
        ((anchor.x, anchor.y, anchor.z), a bed sloping towards seabed.heading_deg)."""
        fields = self.three_d_fields()
        if self.numerics.dimensions == 2 and fields:
            raise ParameterError("numerics.dimensions", 2, f"must be 3 or unset: the scene sets {fields[0]}, "
                                 "which only the 3-D equations take")
        if self.three_d:
            # the time domain's initial state sets every angle from initial.phi / phi_rate: it does not
            # know the out-of-plane angle yet, so a 3-D run starts from its steady state (or an x0 given)
            for name, unset in (("phi", None), ("phi_rate", 0.0)):
                v = getattr(self.initial, name)
                if v != unset:
                    raise ParameterError(f"initial.{name}", v, "must be unset in a 3-D scene: the 3-D run starts "
                                         "from its steady state so far (the Python API takes any state as x0)")

    def _check_track(self) -> None:
        """A track starts on a steady state of still water: towing in a circle on the steady turn, every other path on
        the steady straight tow (in the frame turning or moving with the tow point a current or a wave would not be
        steady, or is not modelled so far): no current, waves or system speed, no anchor, and the initial state is
        the steady one (``initial.u``, ``initial.phi`` unset). A system's several prescribed points (points of one
        ship) only on a course whose heading holds (:attr:`~.track.Track.keeps_heading`), where they keep their places
        about the first, which the track moves, or on a circle, where they swing round with the ship's heading
        (:func:`cablesys.model.ship_points.turned`)."""
        track = self.top_motion.track
        if track is None:
            return
        start = "steady turn" if track.is_circle else "steady straight tow"
        if self.anchor is not None:
            raise ParameterError("anchor", "set", "must be unset with top_motion.track: an anchored line cannot be towed "
                                 "along with the tow point")
        points = self.system.point if self.system is not None else ()
        if self.system is not None and self.system.n_prescribed > 1 and not (track.keeps_heading or track.is_circle):
            raise ParameterError("top_motion.track", track.kind, f"must be a straight course or a circle with "
                                 f"{self.system.n_prescribed} prescribed points: points of one ship keep their places "
                                 "about the first while its heading holds and swing round with it on a circle (a "
                                 "constant turn rate); a changing turn rate is not modelled for them so far")
        for i, pt in enumerate(points):
            if pt.kind == "fixed":
                raise ParameterError(f"point[{i}].kind", "fixed", "must not be fixed with top_motion.track: a system "
                                     f"held at {pt.name!r} cannot be towed along with the tow point (make it a body "
                                     "or a junction)")
            if track.is_circle and pt.body is not None and pt.body.is_rigid:
                raise ParameterError(f"point[{i}].pitch_inertia", pt.body.pitch_inertia, "must be unset with a "
                                     "circular top_motion.track: the steady turn's statics hold the nodes alone so far")
        env = self.environment
        for i, v in enumerate(env.current_speeds):
            if v != 0.0:
                raise ParameterError(f"environment.current_speeds[{i}]", v, f"must be 0 with top_motion.track: the "
                                     f"{start} the run starts on is found in still water")
        if env.waves:
            raise ParameterError("environment.waves", f"{len(env.waves)} waves", "must be empty with top_motion.track "
                                 f"(the {start} the run starts on is an equilibrium only in still water)")
        if env.system_speed != 0.0:
            raise ParameterError("environment.system_speed", env.system_speed, "must be 0 with top_motion.track: the "
                                 "track is the tow point's motion over the ground (a straight track at the speed U is "
                                 "the tow of system_speed = U seen from the ground)")
        for name in ("u", "phi"):
            if getattr(self.initial, name) is not None:
                raise ParameterError(f"initial.{name}", getattr(self.initial, name), "must be unset with "
                                     f"top_motion.track: the run starts on the {start}")
        if track.is_circle:
            for i, s in enumerate(self.sections):
                if s.body.is_rigid:
                    raise ParameterError(f"{section_prefix(self, i)}body.pitch_inertia", s.body.pitch_inertia,
                                         "must be unset with a circular top_motion.track: the steady turn's statics "
                                         "hold the nodes alone so far (a path's straight tow takes a rigid body)")

    def _check_initial_lengths(self) -> None:
        """An initial stretch u must leave every section a positive length l_0 + u (Wang 1971 eq. 10)."""
        u = self.initial.u
        if u is None:
            return
        shortest = min(s.cable.length_zero for s in self.sections)
        if not u > -shortest:
            raise ParameterError("initial.u", u, f"must be > -{shortest:.6g} m: the shortest section's zero-tension "
                                 "length l_0, so that every section keeps a positive length l_0 + u")

    def _check_hanging_tension(self) -> None:
        """Each section must be taut when hanging still: k u = weights below + W_c/2 > TENS (eq. 49b, 54)."""
        below = 0.0
        for i in reversed(range(len(self.sections))):
            c, b = self.sections[i].cable, self.sections[i].body
            tension = below + b.weight + 0.5 * c.total_weight
            if tension <= c.tension_floor:
                field = f"{section_prefix(self, i)}body.weight"
                raise ParameterError(
                    field, b.weight,
                    f"the hanging cable force W_b + W_c/2 + (weight below) = {tension:.6g} N must exceed "
                    f"tension_floor = {c.tension_floor:.6g} N; a body lighter than water with TENS = 0 has no taut "
                    "equilibrium (make the body heavier or lower cable.tension_floor)")
            below += b.weight + c.total_weight

    # single-section shortcuts
    @property
    def cable(self) -> Cable:
        """The cable of a one-section scene."""
        self._require_single("cable")
        return self.sections[0].cable

    @property
    def body(self) -> Body:
        """The (lower) body of a one-section scene."""
        self._require_single("body")
        return self.sections[0].body

    def _require_single(self, what: str) -> None:
        if len(self.sections) != 1:
            raise ParameterError("sections", f"{len(self.sections)} sections",
                                 f"scene.{what} is defined for one section only; use scene.sections[i].{what}")

    @property
    def n_sections(self) -> int:
        return len(self.sections)

    @property
    def output_times(self) -> np.ndarray:
        """0, dt, 2 dt, ... up to the duration (inclusive when it divides evenly)."""
        n = self.numerics
        k = int(np.floor(n.duration / n.output_step + 1e-9))
        return np.arange(k + 1) * n.output_step

    def replace(self, **changes) -> "Scene":
        """A copy with top-level fields replaced (validated again)."""
        return dataclasses.replace(self, **changes)

    def replace_section(self, index: int = 0, *, cable: dict | None = None, body: dict | None = None) -> "Scene":
        """A copy with fields of one section's cable and/or body replaced, e.g. ``cable={"ae": 1e4}``."""
        secs = list(self.sections)
        s = secs[index]
        secs[index] = Section(cable=dataclasses.replace(s.cable, **(cable or {})),
                              body=dataclasses.replace(s.body, **(body or {})))
        return dataclasses.replace(self, sections=tuple(secs))

    def with_numerics(self, **changes) -> "Scene":
        return dataclasses.replace(self, numerics=dataclasses.replace(self.numerics, **changes))

    def with_environment(self, **changes) -> "Scene":
        return dataclasses.replace(self, environment=dataclasses.replace(self.environment, **changes))


def single_section_scene(*, cable: Cable, body: Body, **kw) -> Scene:
    """Convenience: Wang's 2-DOF scene from one cable and one body.

    Parameters
    ----------
    cable : Cable
        The cable (SI).
    body : Body
        The body at its lower end.
    **kw
        Other :class:`Scene` fields (environment, top_motion, numerics, name...).

    Returns
    -------
    Scene
        A one-section scene.
    """
    return Scene(sections=(Section(cable=cable, body=body),), **kw)
