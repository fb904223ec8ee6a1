"""Inputs of a slack-cable analysis: frozen, keyword-only, SI, validated on creation.

A scene is one extensible cable hung between support A (the origin) and
support B at (``span``, ``rise``), with point masses attached at unstretched
arc-length positions measured from A, in air or in water. The TOML format
read by :func:`load_slack_scene` is documented in :data:`EXAMPLE_TOML`.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from pathlib import Path

from ..errors import ParameterError, require_finite, require_nonnegative, require_positive
from ..reader import build, located, read_toml, typed_fields
from ..scene.fields import quantity, spec
from ..scene.limits import Limits, static_limits
from ..units import G_STANDARD

MEDIA = ("air", "water")
MAX_ELEMENTS = 5000      # lumped-mass elements: 3 N unknowns, a few seconds of sparse shift-invert at the limit
MAX_MODES = 200          # modes reported by a scene file


def _buoyancy_and_added(mass: float, S: float | None, c_am: float, medium: str, g: float,
                        field_name: str) -> tuple[float, float]:
    """Submerged weight and added mass of a body of mass ``mass`` and specific gravity S.

    Griffin & Rosenthal (1985) eq. 26: added mass = C_am m / S (the displaced
    fluid mass times C_am); the buoyancy is m g / S.
    """
    if medium == "air":
        return mass * g, 0.0
    if S is None:
        raise ParameterError(f"{field_name}.specific_gravity", None,
                             "must be given (> 1) for a scene in water")
    return mass * g * (1.0 - 1.0 / S), c_am * mass / S


@dataclass(frozen=True, kw_only=True)
class SlackCable:
    """A uniform extensible cable of a slack scene (Griffin & Rosenthal 1985), in the vocabulary of the Wang scene.

    Named apart from :class:`cablesys.scene.Cable` (the Wang cable) so that both can be imported together.

    The quantities it shares with :class:`cablesys.scene.Cable` (length, mass_per_length, ae,
    weight_per_length, added_mass_factor, specific_gravity) have the same names, units and
    symbols (:data:`cablesys.scene.fields.QUANTITIES`); the slack model adds the specific
    gravity that derives the weight in water and added mass (eq. 26), an explicit added mass
    and the largest strain. ``weight_per_length`` and ``added_mass_per_length`` override the
    values derived from S and C_a (water only); ``max_strain`` fixes how far the cable can
    reach (chord < length * (1 + max_strain)).
    """

    length: float = quantity("length", "unstretched length L")
    mass_per_length: float = quantity("mass_per_length", "mass per unit length in air m")
    ae: float = quantity("ae", "axial stiffness EA (Wang's (AE))")
    specific_gravity: float | None = quantity("specific_gravity", "specific gravity S of the cable, needed in water "
                                              "(buoyancy m g / S and added mass, eq. 26)", None)
    added_mass_factor: float = quantity("added_mass_factor", "C_am of eq. 26: added mass = C_am m / S (water only; "
                                        "Wang's added-mass factor gamma)", 1.0)
    weight_per_length: float | None = quantity("weight_per_length", "weight in water per unit length; overrides "
                                               "m g (1 - 1/S) (water only)", None)
    added_mass_per_length: float | None = spec("mass_per_length", "transverse added mass per unit length; overrides "
                                               "C_am m / S (water only)", None, symbol="m_a")
    max_strain: float = spec("none", "largest strain the cable may take (linear elastic up to it)", 0.02,
                             symbol="epsilon_max")

    def __post_init__(self):
        require_positive("cable.length", self.length, "m")
        require_positive("cable.mass_per_length", self.mass_per_length, "kg/m")
        require_positive("cable.ae", self.ae, "N")
        if self.specific_gravity is not None and require_positive(
                "cable.specific_gravity", self.specific_gravity) <= 1.0:
            raise ParameterError("cable.specific_gravity", self.specific_gravity,
                                 "must be > 1 (a cable that floats cannot hang as a catenary)")
        require_nonnegative("cable.added_mass_factor", self.added_mass_factor)
        if self.weight_per_length is not None:
            require_positive("cable.weight_per_length", self.weight_per_length, "N/m")
        if self.added_mass_per_length is not None:
            require_nonnegative("cable.added_mass_per_length", self.added_mass_per_length, "kg/m")
        v = require_positive("cable.max_strain", self.max_strain)
        if v >= 0.5:
            raise ParameterError("cable.max_strain", v, "must be in (0, 0.5)")

    def weight_and_added_mass(self, medium: str, g: float) -> tuple[float, float]:
        """(weight per length N/m, transverse added mass per length kg/m) in ``medium``."""
        if medium == "water" and self.weight_per_length is not None \
                and self.added_mass_per_length is not None:
            return self.weight_per_length, self.added_mass_per_length
        w, ma = _buoyancy_and_added(self.mass_per_length, self.specific_gravity,
                                    self.added_mass_factor, medium, g, "cable")
        if medium == "water":
            w = self.weight_per_length if self.weight_per_length is not None else w
            ma = self.added_mass_per_length if self.added_mass_per_length is not None else ma
        return w, ma


@dataclass(frozen=True, kw_only=True)
class PointMass:
    """A point mass at unstretched arc length ``position`` (m) from support A.

    mass in air (kg); specific_gravity S and added_mass_factor C_am as
    for the cable (eq. 26; added mass is taken isotropic for a compact body);
    name is a label for outputs.
    """

    position: float = spec("length", "unstretched arc length from support A", symbol="s")
    mass: float = spec("mass", "mass in air", symbol="M")
    specific_gravity: float | None = quantity("specific_gravity", "specific gravity S, needed in water", None)
    added_mass_factor: float = quantity("added_mass_factor", "C_am: added mass = C_am M / S (isotropic, eq. 26)", 1.0)
    name: str = spec("none", "label for outputs", "", symbol="")

    def __post_init__(self):
        require_finite("mass.position", self.position)
        require_positive("mass.mass", self.mass, "kg")
        if self.specific_gravity is not None:
            require_positive("mass.specific_gravity", self.specific_gravity)
        require_nonnegative("mass.added_mass_factor", self.added_mass_factor)


@dataclass(frozen=True, kw_only=True)
class SlackScene:
    """A cable between support A at (0, 0) and support B at (span, rise), z up.

    span: horizontal distance (m, > 0); rise: height of B above A (m);
    masses: attached point masses; medium: 'air' or 'water';
    gravity (m/s^2); n_elements: lumped-mass elements (mass positions are
    added as nodes); n_modes: number of natural modes an analysis reports
    (:func:`~cablesys.slack.analyze` and :func:`~cablesys.slack.converge` use it
    when not given one); limits: the working load and least tension the
    equilibrium's element tensions are judged against (:func:`cablesys.verdict.judge`).
    """

    cable: SlackCable = spec("none", "the cable", symbol="")
    span: float = spec("length", "horizontal distance from A to B", symbol="x_B")
    rise: float = spec("length", "height of B above A", 0.0, symbol="z_B")
    masses: tuple[PointMass, ...] = spec("none", "attached point masses", default_factory=tuple, symbol="")
    medium: str = spec("none", f"surrounding fluid, one of {MEDIA}", "air", symbol="")
    gravity: float = quantity("gravity", "gravitational acceleration", G_STANDARD)
    n_elements: int = spec("none", "lumped-mass elements (mass positions are added as nodes)", 120, symbol="N")
    n_modes: int = spec("none", "natural modes an analysis reports", 12, symbol="")
    limits: Limits | None = spec("none", "what the span's static tensions are checked against (cablesys.verdict): "
                                 "working load and least_tension", None, symbol="")

    def __post_init__(self):
        require_positive("scene.span", self.span, "m")
        static_limits(self.limits)          # the criteria a static analysis can judge, or a named error
        require_finite("scene.rise", self.rise)
        require_positive("scene.gravity", self.gravity, "m/s^2")
        if self.medium not in MEDIA:
            raise ParameterError("scene.medium", self.medium, f"must be one of {MEDIA}")
        if (not isinstance(self.n_elements, int) or isinstance(self.n_elements, bool)
                or not 4 <= self.n_elements <= MAX_ELEMENTS):
            raise ParameterError("scene.n_elements", self.n_elements,
                                 f"must be an integer in [4, {MAX_ELEMENTS}] (the limit keeps the eigenproblem "
                                 "within seconds and memory)")
        if (not isinstance(self.n_modes, int) or isinstance(self.n_modes, bool)
                or not 1 <= self.n_modes <= MAX_MODES):
            raise ParameterError("scene.n_modes", self.n_modes, f"must be an integer in [1, {MAX_MODES}]")
        object.__setattr__(self, "masses", tuple(self.masses))
        L = self.cable.length
        for i, pm in enumerate(self.masses):
            if not isinstance(pm, PointMass):
                raise ParameterError(f"masses[{i}]", pm, "must be a PointMass")
            if not (0.0 < pm.position < L):
                raise ParameterError(f"masses[{i}].position", pm.position,
                                     f"must be in (0, {L:g}) m: on the cable, between the supports")
            if self.medium == "water" and pm.specific_gravity is None:
                raise ParameterError(f"masses[{i}].specific_gravity", None,
                                     "must be given for a scene in water")
        reach = L * (1.0 + self.cable.max_strain)
        if self.chord >= reach:
            raise ParameterError("scene.chord", round(self.chord, 6),
                                 f"must be < {reach:.6g} m = cable.length * (1 + cable.max_strain): "
                                 "the cable cannot reach that far",
                                 hint="shorten span/rise or lengthen the cable")
        self.cable.weight_and_added_mass(self.medium, self.gravity)  # checks water data

    @property
    def chord(self) -> float:
        """Distance between the supports (m)."""
        return math.hypot(self.span, self.rise)

    @property
    def inclination(self) -> float:
        """Chord angle above the horizontal (rad)."""
        return math.atan2(self.rise, self.span)

    @classmethod
    def from_chord(cls, *, cable: SlackCable, chord: float, theta_deg: float = 0.0, **kw) -> "SlackScene":
        """A scene from the chord length (m) and its inclination (degrees)."""
        chord = require_positive("chord", chord, "m")
        th = math.radians(require_finite("theta_deg", theta_deg))
        if not (-90.0 < theta_deg < 90.0):
            raise ParameterError("theta_deg", theta_deg, "must be in (-90, 90) deg")
        return cls(cable=cable, span=chord * math.cos(th), rise=chord * math.sin(th), **kw)

    def replace(self, **changes) -> "SlackScene":
        """A copy with some fields changed (validated again)."""
        import dataclasses
        return dataclasses.replace(self, **changes)


EXAMPLE_TOML = """\
# cablesys slack scene: SI units throughout (m, kg, N, s).
# Support A is at (0, 0); support B at (span, rise), z up.
[scene]
span = 22.9           # horizontal distance between supports, m (> 0)
rise = 0.0            # height of B above A, m
medium = "air"        # "air" or "water"
n_elements = 120      # lumped-mass elements (>= 4)
# gravity = 9.80665   # m/s^2
n_modes = 12          # modes to report

[cable]
length = 23.80        # unstretched length L, m (chord < L (1 + max_strain))
mass_per_length = 1.14    # kg/m, in air
ae = 8.9e5                # axial stiffness EA, N
# specific_gravity = 7.8        # needed in water: buoyancy and added mass (eq. 26)
# added_mass_factor = 1.0       # C_am
# weight_per_length = 47.6     # N/m, weight in water, overrides m g (1 - 1/S)
# added_mass_per_length = 0.71         # kg/m, overrides C_am m / S
# max_strain = 0.02

# optional: what the verdict checks the static element tensions against (N)
# [limits]
# safe_working_load = 5000.0   # or minimum_breaking_load with safety_factor
# least_tension = 100.0

# one [[masses]] table per attached point mass
[[masses]]
name = "heavy-1"
position = 7.933      # unstretched arc length from A, m, in (0, L)
mass = 4.5            # kg
# specific_gravity = 2.0   # needed in water

[[masses]]
name = "heavy-2"
position = 15.867
mass = 4.5
"""

def scene_from_dict(doc: dict, source=None) -> SlackScene:
    """The scene of a parsed TOML document (see :data:`EXAMPLE_TOML`).

    Parameters
    ----------
    doc : dict
        The parsed document: ``[scene]`` (with ``n_modes``), ``[cable]``, ``[[masses]]``.
    source : cablesys.reader.SourceMap or str, optional
        Where the document came from; errors then name the file and line.

    Returns
    -------
    SlackScene
        The validated scene (SI); ``scene.n_modes`` is the number of modes to report, in
        [1, MAX_MODES] and below the degrees of freedom of its ``n_elements``.

    Raises
    ------
    ParameterError
        Naming the field, its value and the allowed range (and the file and line).
    """
    try:
        return _scene_from_dict(doc)
    except ParameterError as err:
        raise located(err, source) from None


# keys renamed to the Wang scene's vocabulary (one name per quantity); the old ones still load
DEPRECATED_KEYS = {"axial_stiffness": "ae", "added_mass_coefficient": "added_mass_factor",
                   "submerged_weight_per_length": "weight_per_length"}


def _renamed(table, where: str):
    """``table`` with deprecated keys renamed (a DeprecationWarning names each); both spellings is an error."""
    if not isinstance(table, dict):
        return table
    out = dict(table)
    for old, new in DEPRECATED_KEYS.items():
        if old in out:
            if new in out:
                raise ParameterError(f"{where}.{old}", out[old], f"is the old name of {where}.{new}; give one of them")
            warnings.warn(f"{where}.{old} is deprecated: write {new}", DeprecationWarning, stacklevel=4)
            out[new] = out.pop(old)
    return out


def _scene_from_dict(doc: dict) -> SlackScene:
    if not isinstance(doc, dict):
        raise ParameterError("document", doc, "must be a TOML document (a table)")
    for k in doc:
        if k not in ("scene", "cable", "masses", "limits"):
            raise ParameterError(k, doc[k], "unknown table; allowed: scene, cable, masses, limits")
    if "cable" not in doc:
        raise ParameterError("cable", None, "a [cable] table is required")
    cable = build(SlackCable, _renamed(doc["cable"], "cable"), "cable")
    masses = doc.get("masses", [])
    if isinstance(masses, dict):
        raise ParameterError("masses", "one table", "must be an array of tables: write [[masses]] per point mass")
    if not isinstance(masses, list) or not all(isinstance(m, dict) for m in masses):
        raise ParameterError("masses", masses, "must be an array of tables [[masses]]")
    masses = tuple(build(PointMass, _renamed(m, f"masses[{i}]"), f"masses[{i}]") for i, m in enumerate(masses))
    kw = typed_fields(SlackScene, doc.get("scene", {}), "scene", skip=("cable", "masses", "limits"))
    limits = build(Limits, doc["limits"], "limits") if "limits" in doc else None
    scene = SlackScene(cable=cable, masses=masses, limits=limits, **kw)
    if scene.n_modes > 3 * (scene.n_elements - 1) - 1:
        raise ParameterError("scene.n_modes", scene.n_modes, f"must be < 3 (n_elements - 1) = {3 * (scene.n_elements - 1)}, "
                             "the number of degrees of freedom")
    return scene


def load_slack_scene(path: str | Path) -> SlackScene:
    """Read a slack-cable scene TOML file (UTF-8, a byte-order mark accepted).

    Parameters
    ----------
    path : str or Path
        The TOML file (format: :data:`EXAMPLE_TOML`).

    Returns
    -------
    SlackScene
        The validated scene; ``scene.n_modes`` is the number of modes to report.

    Raises
    ------
    ParameterError
        Unreadable, undecodable or invalid file, or a value out of range (file, line, field).
    """
    doc, source = read_toml(path, "scene file")
    return scene_from_dict(doc, source)
