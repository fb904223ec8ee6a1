"""A cable system: lines joined at points (the ``[[point]]`` and ``[[line]]`` tables of a scene).

Every point is one of four kinds:

- ``prescribed``: the top (a ship, a crane tip, a fairlead); its motion is the scene's ``[top_motion]`` and its
  mean position is the origin of the node frame (x right, y down from the top's mean depth, z the sway). More
  prescribed points are more points of the same vessel (a second fairlead, a second lift wire): each at its mean
  position (x, y, z) in the node frame, every one moved by the one ``[top_motion]``'s translation (the first
  prescribed point stays the origin, its position unset); with ``[top_motion.vessel]`` (a 6-DOF RAO) the first is
  at its ``lever_arm`` and every other one at its own lever arm, moved by the vessel's rotation there too
  (s_0 + theta x Delta, :mod:`.vessel`);
- ``fixed``: an anchor or a support at rest at (x, y, z);
- ``body``: a free body (Wang's body, :class:`~.body.Body`: weight in water, virtual masses, drag; rigid with
  ``pitch_inertia``);
- ``junction``: a connector, a clump weight or a buoyancy module: a point mass with a weight in water, virtual
  masses (mass plus added mass) and drag, the fields of Wang's intermediate body (Wang 1971 p. 33).

Every line runs from one point to another (``from``, ``to``) and is a sequence of sections (``[[line.section]]``,
:class:`~.components.Cable`: chain-wire-chain, a soft insert), listed from its ``from`` end. There are no free
points: every point ends a line, and every line names two points. A system held by nothing (no prescribed and no
fixed point) has no equilibrium; a line shorter than the distance between the held points it joins cannot reach.

A system whose lines make one path from the prescribed point down through bodies and junctions to a free body or
a fixed point (the chain's ``[anchor]``, in the plane or off it), one section per line, is today's chain of sections
(:meth:`System.as_chain`), and the scene is that chain, exactly: the same model, parameters and outputs
(:class:`~.scene.Scene`). Any other system is built by the node model of a graph of lines
(:mod:`cablesys.model.system`).
"""

from __future__ import annotations

import dataclasses
import heapq
import math
import re

from ..errors import ParameterError, require_finite
from .body import Body
from .components import Cable
from .fields import spec

__all__ = ["KINDS", "Line", "Point", "System"]

KINDS = ("prescribed", "fixed", "body", "junction")
_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_\-]*$")
_POSITION = ("x", "y", "z")


def _check_name(field: str, name) -> None:
    if not isinstance(name, str) or not _NAME.match(name):
        raise ParameterError(field, name, "must be a name of letters, digits, '_' and '-' starting with a letter "
                                          "(outputs are named by it: point.NAME.x, line.NAME.tension_from)")


@dataclasses.dataclass(frozen=True, kw_only=True)
class Point:
    """One point of a cable system (module docstring): prescribed, fixed, a free body or a junction.

    A fixed point's ``x``, ``y`` (and ``z``, unset: 0) are its position in the node frame (m: x from the prescribed
    point's mean position, y down from its mean depth, z the sway). A body's or junction's position, when given, is
    the statics' starting guess for it. The (first) prescribed point is the origin: its position is unset (its
    motion is the scene's ``[top_motion]``); a further prescribed point's ``x``, ``y`` (``z``) are its mean position,
    about which the same ``[top_motion]`` translates it. In a TOML file a body's or junction's fields (``weight``, ``mass_x``, ...) are written
    in the ``[[point]]`` table itself.
    """

    name: str = spec("none", "the point's name (letters, digits, '_', '-'); lines name their ends by it")
    kind: str = spec("none", "prescribed (the top, moved by [top_motion]) | fixed (an anchor, a support) | body (a free "
                             "body) | junction (a connector, clump weight or buoyancy module)")
    x: float | None = spec("length", "fixed: horizontal position from the prescribed point's mean position (+x right); "
                                     "body or junction: the statics' starting guess (unset: from the lines)", None)
    y: float | None = spec("length", "fixed: depth below the prescribed point's mean depth (y down); body or junction: "
                                     "the statics' guess", None)
    z: float | None = spec("length", "fixed: sway position (out of the x-y plane; unset: 0; any other value makes the "
                                     "scene 3-D); body or junction: the statics' guess", None)
    body: Body | None = spec("none", "a body's or junction's weight in water, virtual masses and drag (Wang's body, "
                                     "scene.body.Body); unset for prescribed and fixed points", None)

    def __post_init__(self):
        _check_name("point.name", self.name)
        if self.kind not in KINDS:
            raise ParameterError("point.kind", self.kind, f"must be one of {KINDS}")
        for c in _POSITION:
            if getattr(self, c) is not None:
                object.__setattr__(self, c, require_finite(f"point.{c}", getattr(self, c)))
        if self.kind == "fixed" or (self.kind == "prescribed" and any(getattr(self, c) not in (None, 0.0)
                                                                       for c in _POSITION)):
            for c in ("x", "y"):
                if getattr(self, c) is None:
                    raise ParameterError(f"point.{c}", "missing", f"is required for a {self.kind} point given a "
                                         "position (its mean position in the node frame, m)" if self.kind ==
                                         "prescribed" else "is required for a fixed point (its position, m)")
        if self.kind in ("prescribed", "fixed"):
            if self.body is not None:
                raise ParameterError("point.weight", self.body.weight, f"must be unset for a {self.kind} point: it "
                                     "does not move, so a weight or drag there would load only the support")
            return
        if not isinstance(self.body, Body):
            raise ParameterError("point.weight", "missing", f"a {self.kind} needs its body fields (weight, mass_x, "
                                 "mass_y; drag_area_normal, ...): Wang's body")
        if self.kind == "junction" and self.body.is_rigid:
            raise ParameterError("point.pitch_inertia", self.body.pitch_inertia, "must be unset for a junction (a "
                                 "point mass): a rigid body is kind = \"body\"")

    @property
    def free(self) -> bool:
        """A body or a junction: its position is a coordinate of the model."""
        return self.kind in ("body", "junction")

    @property
    def held(self) -> bool:
        """A prescribed or fixed point: its position is known (the prescribed point's mean position is the origin)."""
        return not self.free

    @property
    def position(self) -> tuple:
        """(x, y, z) (m): a fixed point's position, a prescribed point's mean position (unset: the origin), a free
        point's guess (None entries unset)."""
        if self.kind == "prescribed":
            return (self.x or 0.0, self.y or 0.0, self.z or 0.0)
        if self.kind == "fixed":
            return (self.x, self.y, self.z or 0.0)
        return (self.x, self.y, self.z)


@dataclasses.dataclass(frozen=True, kw_only=True)
class Line:
    """A line from point ``start`` to point ``end`` (``from`` and ``to`` in a TOML file), a sequence of sections
    (``[[line.section]]``: :class:`~.components.Cable`, each with its own ``segments``) listed from ``start``."""

    name: str = spec("none", "the line's name (letters, digits, '_', '-')")
    start: str = spec("none", "the point the line starts from (TOML key: from); its first section begins there")
    end: str = spec("none", "the point the line ends at (TOML key: to)")
    section: tuple[Cable, ...] = spec("none", "the line's sections from its start to its end (chain-wire-chain, a soft "
                                              "insert), each a [cable] table")

    def __post_init__(self):
        _check_name("line.name", self.name)
        _check_name("line.from", self.start)
        _check_name("line.to", self.end)
        if self.start == self.end:
            raise ParameterError("line.to", self.end, "must differ from line.from: a line joins two points")
        secs = tuple(self.section)
        if not secs:
            raise ParameterError("line.section", "none", "a line needs at least one [[line.section]] (a [cable] table)")
        for k, c in enumerate(secs):
            if not isinstance(c, Cable):
                raise ParameterError(f"line.section[{k}]", type(c).__name__, "must be a Cable")
        object.__setattr__(self, "section", secs)

    @property
    def length(self) -> float:
        """The line's length at its sections' reference tensions, sum of ``cable.length`` (m)."""
        return sum(c.length for c in self.section)


def _unique(kind: str, items) -> dict:
    """{name: index} of the points or lines ``items``; a name given twice is an error naming the second."""
    seen = {}
    for i, item in enumerate(items):
        if item.name in seen:
            raise ParameterError(f"{kind}[{i}].name", item.name, f"is the name of {kind}[{seen[item.name]}] too: "
                                 f"{kind} names must be unique")
        seen[item.name] = i
    return seen


@dataclasses.dataclass(frozen=True, kw_only=True)
class System:
    """Points joined by lines (module docstring): ``point`` and ``line`` are the ``[[point]]`` and ``[[line]]``
    tables in file order. Checked when made: unique names, every line's ends name points, every point ends a line,
    a prescribed or fixed point holds the system, the first prescribed point at the origin and every other one at a
    given mean position (the scene's one top motion translates them all, a vessel's RAO turns them about its
    lever arm too), every path of lines between two held points
    at least as long as their distance."""

    point: tuple[Point, ...] = spec("none", "the points ([[point]] tables)")
    line: tuple[Line, ...] = spec("none", "the lines ([[line]] tables)")

    def __post_init__(self):
        pts, lns = tuple(self.point), tuple(self.line)
        object.__setattr__(self, "point", pts)
        object.__setattr__(self, "line", lns)
        if not lns:
            raise ParameterError("line", "none", "a system needs at least one [[line]]")
        for i, p in enumerate(pts):
            if not isinstance(p, Point):
                raise ParameterError(f"point[{i}]", type(p).__name__, "must be a Point")
        for k, ln in enumerate(lns):
            if not isinstance(ln, Line):
                raise ParameterError(f"line[{k}]", type(ln).__name__, "must be a Line")
        seen = _unique("point", pts)
        _unique("line", lns)
        for k, ln in enumerate(lns):
            for key, end in (("from", ln.start), ("to", ln.end)):
                if end not in seen:
                    raise ParameterError(f"line[{k}].{key}", end, f"names no point; the points are {list(seen)}")
        used = {name for ln in lns for name in (ln.start, ln.end)}
        for i, p in enumerate(pts):
            if p.name not in used:
                raise ParameterError(f"point[{i}].name", p.name, "is connected to nothing: every point must be the "
                                     "from or to end of a [[line]] (a system has no free points)")
        if not any(p.held for p in pts):
            raise ParameterError("point", f"{len(pts)} points of kinds {sorted({p.kind for p in pts})}",
                                 "nothing holds the system: it needs a prescribed point (the top) or a fixed point "
                                 "(an anchor, a support)")
        self._check_held_parts()
        top = [i for i, p in enumerate(pts) if p.kind == "prescribed"]
        if top:
            first = pts[top[0]]
            for c in _POSITION:
                if getattr(first, c) not in (None, 0.0):
                    raise ParameterError(f"point[{top[0]}].{c}", getattr(first, c), "must be unset (or 0) for the "
                                         "first prescribed point: it is the origin of the node frame, moved by "
                                         "[top_motion] (a further prescribed point's x, y, z are its mean position)")
        for i in top[1:]:
            if pts[i].x is None:
                raise ParameterError(f"point[{i}].x", "missing", f"is required for a second prescribed point (its "
                                     f"mean position in the node frame, m, x and y; point[{top[0]}] "
                                     f"{pts[top[0]].name!r} is the origin): the one [top_motion] translates every "
                                     "prescribed point about its mean position")
        self._check_reach()

    def _check_held_parts(self) -> None:
        """Every connected part of the system holds a prescribed or a fixed point (a part of free points only would
        fall or float away): the error names the first point of a part that nothing holds."""
        part = {p.name: p.name for p in self.point}

        def root(a):
            while part[a] != a:
                part[a] = part[part[a]]
                a = part[a]
            return a
        for ln in self.line:
            part[root(ln.start)] = root(ln.end)
        held = {root(p.name) for p in self.point if p.held}
        for i, p in enumerate(self.point):
            if root(p.name) not in held:
                names = [q.name for q in self.point if root(q.name) == root(p.name)]
                raise ParameterError(f"point[{i}].name", p.name, f"is in a part of the system that nothing holds "
                                     f"(points {names}, joined to no prescribed or fixed point)")

    def _check_reach(self) -> None:
        """Every path of lines between two held points is at least as long as their distance: for each pair, the
        shortest path through the graph (Dijkstra, line lengths at their reference tension) against the straight
        distance (m). The error names the last section's length of the last line on that path."""
        held = [p for p in self.point if p.held]
        adj = {p.name: [] for p in self.point}
        for k, ln in enumerate(self.line):
            adj[ln.start].append((ln.end, k))
            adj[ln.end].append((ln.start, k))
        for a_i, a in enumerate(held):
            dist, prev, heap = {a.name: 0.0}, {}, [(0.0, a.name)]
            while heap:
                d, u = heapq.heappop(heap)
                if d > dist[u]:
                    continue
                for v, k in adj[u]:
                    nd = d + self.line[k].length
                    if nd < dist.get(v, math.inf):
                        dist[v], prev[v] = nd, (u, k)
                        heapq.heappush(heap, (nd, v))
            for b in held[a_i + 1:]:
                if b.name not in dist:
                    continue
                chord = math.dist(a.position, b.position)
                if dist[b.name] < chord:
                    path, v = [], b.name
                    while v != a.name:
                        v, k = prev[v]
                        path.append(k)
                    k = path[0]
                    s = len(self.line[k].section) - 1
                    names = " + ".join(self.line[j].name for j in reversed(path))
                    raise ParameterError(f"line[{k}].section[{s}].length", self.line[k].section[s].length,
                                         f"makes the lines {names} from {a.name!r} to {b.name!r} {dist[b.name]:.6g} m "
                                         f"long (at their reference tensions), shorter than the {chord:.6g} m between "
                                         "those held points")

    # -- queries --------------------------------------------------------------------------------
    def index(self, name: str) -> int:
        """Position of the point ``name`` in :attr:`point`."""
        return next(i for i, p in enumerate(self.point) if p.name == name)

    def by_name(self, name: str) -> Point:
        """The point ``name``."""
        return self.point[self.index(name)]

    @property
    def prescribed(self) -> Point | None:
        """The (first) prescribed point, the node frame's origin (None: the system hangs between fixed points)."""
        return next((p for p in self.point if p.kind == "prescribed"), None)

    @property
    def n_prescribed(self) -> int:
        """How many prescribed points the system has (each moved by the one [top_motion]; by a vessel's RAO at its own
        lever arm)."""
        return sum(p.kind == "prescribed" for p in self.point)

    def degree(self, name: str) -> int:
        """How many line ends meet at point ``name``."""
        return sum((ln.start == name) + (ln.end == name) for ln in self.line)

    def as_chain(self) -> tuple | None:
        """The system as today's chain of sections, or None when it is not one.

        A chain: one prescribed point ending one line; from it a path of lines, each with one section, through
        bodies and junctions each ending two lines, to a free body or a fixed point (the chain's ``[anchor]``, at its
        x, y and z) ending one line. Returns ``(steps, end)``: steps ((line index, reversed), ...) in order from the top
        (reversed when the line is written from its lower end) and the last point.
        """
        top = self.prescribed
        if top is None or self.degree(top.name) != 1 or any(len(ln.section) != 1 for ln in self.line):
            return None
        steps, here, used = [], top.name, set()
        while True:
            nxt = [(k, ln) for k, ln in enumerate(self.line) if k not in used and here in (ln.start, ln.end)]
            if not nxt:
                break
            if len(nxt) > 1:
                return None
            k, ln = nxt[0]
            used.add(k)
            rev = ln.end == here
            steps.append((k, rev))
            here = ln.start if rev else ln.end
            p = self.by_name(here)
            if p.held or self.degree(here) == 1:
                break
        end = self.by_name(here)
        if len(used) != len(self.line) or self.degree(end.name) != 1 or end.kind == "prescribed":
            return None
        return tuple(steps), end

    def with_segments(self, n: int) -> "System":
        """The same system with every section of every line divided into ``n`` elements (``cable.segments``)."""
        return dataclasses.replace(self, line=tuple(dataclasses.replace(ln, section=tuple(
            dataclasses.replace(c, segments=int(n)) for c in ln.section)) for ln in self.line))

    def structure(self) -> tuple:
        """What fixes the shape of the system's model: its graph (kinds, line ends and sections' element counts),
        which points' bodies take sphere drag, fixed points off the plane."""
        pts = tuple((p.kind, p.body.is_sphere if p.body is not None else None,
                     p.body.is_rigid if p.body is not None else None) for p in self.point)
        lns = tuple((self.index(ln.start), self.index(ln.end), tuple(c.segments for c in ln.section)) for ln in self.line)
        return ("system", pts, lns)
