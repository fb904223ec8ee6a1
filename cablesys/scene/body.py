"""The body at the lower end of a cable section: Wang's point body or a rigid body (SI units inside).

Validation runs in ``__post_init__`` and raises :class:`~cablesys.errors.ParameterError` naming the field, its value
and the allowed range, before any model is built. A rigid body's inertia tensor about its centre of gravity must be
a mass distribution's: symmetric (given by its six entries), positive semi-definite with principal moments that
satisfy the triangle inequality I_1 <= I_2 + I_3 (Goldstein, Classical Mechanics, 3rd ed., sec. 5.3-5.4: I_1 + ... =
2 sum m (r^2 - x_1^2) >= ...), and with the added inertia positive definite (the rotational kinetic energy).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..errors import ParameterError, require_nonnegative, require_positive, require_range
from .fields import check_all_finite, spec

#: The rigid body's fields of :class:`Body` (all at their defaults: Wang's point body).
RIGID_FIELDS = ("pitch_inertia", "pitch_added_inertia", "attachment_x", "attachment_y", "buoyancy", "buoyancy_x",
                "buoyancy_y", "pitch_damping", "pitch_drag", "drag_centre_x", "drag_centre_y", "drag_area_x",
                "drag_area_y")
#: The rigid body's fields that only the 3-D equations take (any of them set makes the scene 3-D).
RIGID_FIELDS_3D = ("inertia_xx", "inertia_yy", "inertia_xy", "inertia_xz", "inertia_yz", "added_inertia_x",
                   "added_inertia_y", "attachment_z", "buoyancy_z", "drag_centre_z", "drag_area_z")
#: The rigid body's attitude at the start of a run, R = R_y(yaw) R_z(pitch) R_x(roll) (the outputs' named angles,
#: :func:`cablesys.model.rigid_body.attitude`): initial conditions, not parameters of the model; roll and yaw only in
#: space (either set makes the scene 3-D).
INITIAL_ATTITUDE = ("initial_roll_deg", "initial_pitch_deg", "initial_yaw_deg")
# unset, a 3-D field takes the planar one (a body symmetric about its pitch axis), else 0
_DEFAULT_3D = {"inertia_xx": "pitch_inertia", "inertia_yy": "pitch_inertia", "added_inertia_x": "pitch_added_inertia",
               "added_inertia_y": "pitch_added_inertia"}


@dataclasses.dataclass(frozen=True, kw_only=True)
class Body:
    """The body at the lower end of a cable section: a point (Wang 1971 eq. 16, 32-35) or, with ``pitch_inertia``
    set, a rigid body on an attachment point off its centre of gravity that pitches in the x-y plane, or turns with
    three degrees of freedom in a 3-D scene (Wang 1971 p. 32, "Extensions"; equations in
    :mod:`cablesys.model.rigid_body`). A rigid body's virtual masses ``mass_x``, ``mass_y``, ``mass_z`` (mass plus
    added mass per body axis) and its drag axis ``axis_angle_deg`` are along its body axes, which are the scene's
    x, y, z at the level attitude; its drag acts at its centre of pressure (``drag_centre_x/y/z``; unset: the centre
    of gravity). In space ``pitch_inertia`` is I_zz (about the plane's normal z), ``inertia_xx`` (roll, about x) and
    ``inertia_yy`` (yaw, about the vertical y) default to it, the products of inertia to 0."""

    weight: float = spec("force", "weight in water W_b (negative: buoyant)")
    mass_x: float = spec("mass", "virtual mass (mass plus added mass) for motion in x, M_bvx")
    mass_y: float = spec("mass", "virtual mass (mass plus added mass) for motion in y, M_bvy")
    drag_area_normal: float = spec("area", "CDABN: (C_D A_b)_n, or C_D A_b of a sphere (eq. 32-33)", 0.0)
    drag_area_tangential: float = spec("area", "CDABT: (C_D A_b)_t; equal to CDABN for a sphere (eq. 33b)", 0.0)
    axis_angle_deg: float = spec("angle_deg", "PHIBD: angle phi_b of the body's tangential axis with the vertical in degrees; |PHIBD| > 180 selects sphere drag (eq. 32)", 999.0)
    mass_z: float | None = spec("mass", "virtual mass for motion in z (out of the x-y plane), M_bvz; used by the 3-D "
                                "equations only; unset: mass_x (a body symmetric about the vertical)", None)
    # the body's footprint on a [seabed] (MoorDyn's kBot, cBot per unit area act on it: model/segmented_seabed.py)
    bed_area: float | None = spec("area", "footprint of the body on a [seabed]: the area the bed's stiffness, damping "
                                  "and friction per unit area act on when the body rests on it, beside its cable's "
                                  "contact at that node (unset: 0, a point body, held on the bed by its cable's half "
                                  "element alone, whose contact area d l / 2 falls with the element length)", None)
    # a rigid body that pitches in the x-y plane (Wang 1971 p. 32, "Extensions": "where the body is fairly large
    # and the cable is not attached to the center of mass"); body axes coincide with the scene's x, y (y down)
    # at theta_b = 0, theta_b turning +x towards +y (about +z); unset pitch_inertia: Wang's point body
    pitch_inertia: float | None = spec("inertia", "moment of inertia I of the body's mass about its centre of gravity for "
                                       "rotation in the x-y plane (pitch); set: the body is rigid and pitches (one more "
                                       "coordinate theta_b, segmented cable only); unset: a point body", None)
    pitch_added_inertia: float | None = spec("inertia", "added moment of inertia I_a of the fluid for pitch "
                                             "(rigid body; unset: 0)", None)
    attachment_x: float | None = spec("length", "x of the cable's attachment point from the centre of gravity, body "
                                      "axes (rigid body; unset: 0)", None)
    attachment_y: float | None = spec("length", "y (down) of the cable's attachment point from the centre of gravity, body "
                                      "axes; negative: above the CG (rigid body; unset: 0)", None)
    buoyancy: float | None = spec("force", "buoyant force B acting up at the centre of buoyancy (rigid body; unset: 0); the "
                                  "weight W_b + B acts down at the CG, so the weight in water stays W_b", None)
    buoyancy_x: float | None = spec("length", "x of the centre of buoyancy from the centre of gravity, body axes "
                                    "(rigid body; unset: 0)", None)
    buoyancy_y: float | None = spec("length", "y (down) of the centre of buoyancy from the centre of gravity, body axes "
                                    "(rigid body; unset: 0)", None)
    pitch_damping: float | None = spec("moment_time", "linear pitch damping c: moment -c theta_b' (rigid body; unset: 0)",
                                       None)
    pitch_drag: float | None = spec("moment_time2", "quadratic pitch drag d: moment -d |theta_b'| theta_b' (rigid body; "
                                    "unset: 0)", None)
    drag_centre_x: float | None = spec("length", "x of the point where the body's drag acts (centre of pressure) from the "
                                       "centre of gravity, body axes (rigid body; unset: 0, at the CG)", None)
    drag_centre_y: float | None = spec("length", "y (down) of the body's centre of pressure from the centre of gravity, "
                                       "body axes (rigid body; unset: 0)", None)
    # drag per body axis at the centre of pressure (added to Wang's law of drag_area_normal/tangential)
    drag_area_x: float | None = spec("area", "(C_D A)_x: quadratic drag 1/2 rho (C_D A)_x |u_x| u_x along the body's x "
                                     "axis at the centre of pressure, u the relative flow in body axes (rigid body; "
                                     "unset: 0; added to the drag of drag_area_normal/tangential)", None)
    drag_area_y: float | None = spec("area", "(C_D A)_y: the same along the body's y axis (rigid body; unset: 0)", None)
    # a rigid body in space (3-D equations only; model/rigid_body.py): the inertia tensor about the CG in body axes,
    # the added inertia per body axis and the offsets' z
    inertia_xx: float | None = spec("inertia", "inertia tensor entry I_xx (roll, about the body's x) about the centre of "
                                    "gravity (rigid body, 3-D; unset: pitch_inertia)", None)
    inertia_yy: float | None = spec("inertia", "inertia tensor entry I_yy (yaw, about the body's vertical y) about the "
                                    "centre of gravity (rigid body, 3-D; unset: pitch_inertia)", None)
    inertia_xy: float | None = spec("inertia", "inertia tensor entry I_xy = -sum m x y (product of inertia), body axes "
                                    "(rigid body, 3-D; unset: 0)", None)
    inertia_xz: float | None = spec("inertia", "inertia tensor entry I_xz = -sum m x z, body axes (rigid body, 3-D; "
                                    "unset: 0)", None)
    inertia_yz: float | None = spec("inertia", "inertia tensor entry I_yz = -sum m y z, body axes (rigid body, 3-D; "
                                    "unset: 0)", None)
    added_inertia_x: float | None = spec("inertia", "added moment of inertia of the fluid about the body's x (roll; "
                                         "rigid body, 3-D; unset: pitch_added_inertia)", None)
    added_inertia_y: float | None = spec("inertia", "added moment of inertia of the fluid about the body's y (yaw; "
                                         "rigid body, 3-D; unset: pitch_added_inertia)", None)
    attachment_z: float | None = spec("length", "z of the cable's attachment point from the centre of gravity, body axes "
                                      "(rigid body, 3-D; unset: 0)", None)
    buoyancy_z: float | None = spec("length", "z of the centre of buoyancy from the centre of gravity, body axes (rigid "
                                    "body, 3-D; unset: 0)", None)
    drag_centre_z: float | None = spec("length", "z of the body's centre of pressure from the centre of gravity, body "
                                       "axes (rigid body, 3-D; unset: 0)", None)
    drag_area_z: float | None = spec("area", "(C_D A)_z: the per-axis drag along the body's z axis (rigid body, 3-D; "
                                     "unset: 0)", None)
    # a rigid body's attitude at the start of a run (not a parameter of the model: the statics do not see it)
    initial_roll_deg: float | None = spec("angle_deg", "roll of the body at the start of a run (degrees, about its x; rigid "
                                          "body, 3-D): the run starts from the static equilibrium with the body turned "
                                          "about its attachment point to this attitude and released at rest; unset: "
                                          "the static roll", None)
    initial_pitch_deg: float | None = spec("angle_deg", "pitch of the body at the start of a run (degrees, theta_b; rigid "
                                           "body): as initial_roll_deg; unset: the static pitch", None)
    initial_yaw_deg: float | None = spec("angle_deg", "yaw of the body at the start of a run (degrees, about the vertical "
                                         "y; rigid body, 3-D): as initial_roll_deg; unset: the static yaw", None)

    def __post_init__(self):
        check_all_finite(self, "body")
        require_positive("body.mass_x", self.mass_x, "kg")
        require_positive("body.mass_y", self.mass_y, "kg")
        if self.mass_z is not None:
            require_positive("body.mass_z", self.mass_z, "kg")
        if self.bed_area is not None:
            require_nonnegative("body.bed_area", self.bed_area, "m^2")
        self._check_rigid()
        require_nonnegative("body.drag_area_normal", self.drag_area_normal, "m^2")
        require_nonnegative("body.drag_area_tangential", self.drag_area_tangential, "m^2")
        if self.is_sphere and not math.isclose(self.drag_area_normal, self.drag_area_tangential, rel_tol=1e-12, abs_tol=0.0):
            raise ParameterError("body.drag_area_tangential", self.drag_area_tangential,
                                 f"must equal body.drag_area_normal = {self.drag_area_normal} for sphere drag "
                                 "(|axis_angle_deg| > 180, the report's PHIBD rule)")

    def _check_rigid(self) -> None:
        """A rigid body's fields: non-negative inertias, damping and buoyancy; on a point body every rigid field
        must be unset or 0 (an offset or inertia given without ``pitch_inertia`` would be dropped)."""
        if self.pitch_inertia is None:
            for name in RIGID_FIELDS[1:] + RIGID_FIELDS_3D + INITIAL_ATTITUDE:
                if getattr(self, name) not in (None, 0.0):
                    raise ParameterError(f"body.{name}", getattr(self, name), "needs body.pitch_inertia (a rigid body); "
                                         "a point body has no attachment offset, buoyancy centre or pitch")
            return
        for name in ("pitch_inertia", "pitch_added_inertia", "buoyancy", "pitch_damping", "pitch_drag"):
            require_nonnegative(f"body.{name}", self.rigid(name))
        if not self.pitch_inertia + self.rigid("pitch_added_inertia") > 0.0:
            raise ParameterError("body.pitch_inertia", self.pitch_inertia, "must make pitch_inertia + pitch_added_inertia "
                                 "> 0 kg m^2 (a rigid body without rotary inertia has no pitch equation)")
        for name in ("inertia_xx", "inertia_yy", "added_inertia_x", "added_inertia_y", "drag_area_x", "drag_area_y",
                     "drag_area_z"):
            require_nonnegative(f"body.{name}", self.rigid(name))
        for name, bound in zip(INITIAL_ATTITUDE, (180.0, 90.0, 180.0)):    # the named angles' ranges
            if getattr(self, name) is not None:
                require_range(f"body.{name}", getattr(self, name), -bound, bound, "deg")
        self._check_inertia_tensor()

    def inertia_tensor(self) -> np.ndarray:
        """The 3 x 3 inertia tensor about the CG in body axes (kg m^2), symmetric by construction."""
        g = self.rigid
        return np.array([[g("inertia_xx"), g("inertia_xy"), g("inertia_xz")],
                         [g("inertia_xy"), g("inertia_yy"), g("inertia_yz")],
                         [g("inertia_xz"), g("inertia_yz"), g("pitch_inertia")]])

    def _check_inertia_tensor(self) -> None:
        """A mass distribution's tensor (module docstring): principal moments >= 0 and I_1 <= I_2 + I_3; with the
        added inertia positive definite. The error names the diagonal entry of the offending axis for a diagonal
        tensor, the products of inertia otherwise."""
        tensor = self.inertia_tensor()
        diagonal = not np.any(tensor - np.diag(np.diag(tensor)))
        names = ("inertia_xx", "inertia_yy", "pitch_inertia")
        moments = np.linalg.eigvalsh(tensor)
        scale = max(float(np.max(np.abs(moments))), 1e-300)
        tol = 1e-12 * scale
        products = "inertia_xy" if self.inertia_xy else "inertia_xz" if self.inertia_xz else "inertia_yz"
        if moments[0] < -tol:
            raise ParameterError(f"body.{products}", self.rigid(products), "must keep the inertia tensor positive "
                                 f"semi-definite (principal moments {moments.tolist()} kg m^2)")
        d = np.diag(tensor) if diagonal else moments
        for k in range(3):
            if d[k] > d[(k + 1) % 3] + d[(k + 2) % 3] + tol:
                name = names[k] if diagonal else products
                raise ParameterError(f"body.{name}", self.rigid(name), "must keep the principal moments of inertia "
                                     f"within the triangle inequality I_1 <= I_2 + I_3 (principal moments "
                                     f"{np.sort(d).tolist()} kg m^2): no mass distribution has them")
        added = np.diag([self.rigid("added_inertia_x"), self.rigid("added_inertia_y"), self.rigid("pitch_added_inertia")])
        if not np.linalg.eigvalsh(tensor + added)[0] > 0.0:
            raise ParameterError("body.inertia_xx", self.rigid("inertia_xx"), "must make the inertia tensor plus the "
                                 "added inertias positive definite (a rigid body without rotary inertia about an axis has "
                                 "no equation for that rotation)")

    def rigid(self, name: str) -> float:
        """The rigid-body field ``name`` (one of :data:`RIGID_FIELDS`, :data:`RIGID_FIELDS_3D`) in SI; unset, the
        3-D roll and yaw inertias take the pitch ones, every other field 0."""
        v = getattr(self, name)
        if v is None and name in _DEFAULT_3D:
            return self.rigid(_DEFAULT_3D[name])
        return 0.0 if v is None else float(v)

    def three_d_fields(self) -> tuple:
        """The rigid body's 3-D fields this body sets (:data:`RIGID_FIELDS_3D`, an initial roll or yaw)."""
        return tuple(name for name in RIGID_FIELDS_3D + ("initial_roll_deg", "initial_yaw_deg")
                     if getattr(self, name) is not None)

    @property
    def initial_attitude_deg(self) -> tuple:
        """(roll, pitch, yaw) of the body at the start of a run (degrees; None where unset: the static angle)."""
        return tuple(getattr(self, name) for name in INITIAL_ATTITUDE)

    @property
    def is_rigid(self) -> bool:
        """A rigid body (``pitch_inertia`` set): its orientation is a coordinate of the segmented cable (theta_b in the
        plane, a quaternion in space)."""
        return self.pitch_inertia is not None

    @property
    def virtual_mass_z(self) -> float:
        """M_bvz (kg): ``mass_z``, or ``mass_x`` when unset."""
        return self.mass_x if self.mass_z is None else self.mass_z

    @property
    def is_sphere(self) -> bool:
        """The report's PHIBD rule: |PHIBD| > 180 means sphere drag, eq. 32."""
        return abs(self.axis_angle_deg) > 180.0
