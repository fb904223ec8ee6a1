"""A vessel's six-degree-of-freedom motion RAO, carried to a crane tip or fairlead at a lever arm.

A ship's motion RAOs (surge, sway, heave, roll, pitch, yaw per unit wave amplitude, per wave
frequency and relative heading, as a seakeeping code or a model test gives them) become the
motion of the point where the cable leaves the vessel, in cablesys' axes, for the realised sea of
:mod:`cablesys.scene.sea`.

Conventions (the usual seakeeping ones, Faltinsen 1990, *Sea Loads on Ships and Offshore
Structures*, ch. 3):

* vessel axes: x forward, y to port, z up, origin at the RAO's reference point; the motions
  eta_1..eta_6 (surge, sway, heave in m; roll, pitch, yaw in rad, right-handed about x, y, z) are
  small;
* relative wave heading beta: the direction the waves travel, measured from the bow counter-
  clockwise seen from above (180 deg: head seas, 90 deg: waves from starboard, 0: following);
  beta = ``spectrum.heading_deg`` - ``vessel_heading_deg``;
* phases are leads over the wave elevation at the reference point (as :class:`MotionRAO`);
* a point r = (x, y, z) of the vessel moves, to first order in the motions, by
  s = (eta_1, eta_2, eta_3) + (eta_4, eta_5, eta_6) x r (Faltinsen 1990 ch. 3, the motion of a
  point of the body under a small rotation)::

      s_1 = eta_1 + z eta_5 - y eta_6
      s_2 = eta_2 - z eta_4 + x eta_6
      s_3 = eta_3 + y eta_4 - x eta_5

* the vessel's bow points ``vessel_heading_deg`` from cablesys' +x, counter-clockwise seen from
  above (towards +z); cablesys' axes are x horizontal, y down, z horizontal with (x, y, z)
  right-handed, so x = cos(psi) s_1 - sin(psi) s_2, z = sin(psi) s_1 + cos(psi) s_2, y = -s_3:
  a vessel vector v becomes R v in the node frame with::

      R = [[c, -s, 0], [0, 0, -1], [s, c, 0]],   c = cos(psi), s = sin(psi),  det R = c^2 + s^2 = +1

  (:meth:`VesselRAO.to_node`).

Several points of one vessel (the prescribed points of a system, :mod:`cablesys.scene.system`; Faltinsen 1990
ch. 3, the rigid-body displacement above). R is a proper rotation (both frames right-handed), so it carries cross
products: R (a x b) = (R a) x (R b). A point whose mean position is Delta (node frame) from the first prescribed
point, itself at ``lever_arm`` r_0, is at r = r_0 + R^T Delta in vessel axes (:meth:`VesselRAO.arm_of`)::

      r = r_0 + (c Delta_x + s Delta_z, -s Delta_x + c Delta_z, -Delta_y)

(at psi = 0: forward = node x, port = node z, up = -node y), and its displacement in the node frame is

      R s(r) = R (eta_t + eta_r x r_0) + (R eta_r) x (R R^T Delta) = s_0 + theta x Delta,

s_0 the first point's displacement (:meth:`VesselRAO.transfer`) and theta = R eta_r the vessel's small rotation in
the node frame (:meth:`VesselRAO.rotation_transfer`): theta_x = c eta_4 - s eta_5, theta_y = -eta_6,
theta_z = s eta_4 + c eta_5. Every point's motion is the same fixed linear map of the vessel's motion (s_0, theta),
so the model takes (s_0, theta) as its input (:func:`cablesys.model.top_motion.top_motion_function`).

Between table headings the RAO is linear in amplitude and phase; a table that goes more than half
way round (its last heading within 180 deg of its first, through 360) is interpolated across 360
deg. A table for headings 0..180 deg only serves 180..360 deg by the port-starboard symmetry of a
hull (beta -> 360 - beta with sway, roll and yaw reversed). Any other heading outside the table is
an error naming the field.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..errors import ParameterError, require_finite, require_nonnegative
from .fields import spec
from .sea import interpolate_rao, read_csv_rows

DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")
ANTISYMMETRIC = ("sway", "roll", "yaw")     # reversed by the port-starboard mirror beta -> 360 - beta
_ROTATIONS = ("roll", "pitch", "yaw")


def _unit(dof: str) -> str:
    return "deg/m" if dof in _ROTATIONS else "m/m"


@dataclasses.dataclass(frozen=True, kw_only=True)
class HeadingRAO:
    """The six motion RAOs of a vessel at one relative wave heading, per frequency of the table."""

    heading_deg: float = spec("angle_deg", "relative wave heading beta: the waves' direction of travel from the bow, "
                                           "counter-clockwise seen from above (180: head seas)")
    surge_amplitude: tuple = spec("none", "surge amplitude per unit wave amplitude [m/m]", ())
    surge_phase_deg: tuple = spec("none", "surge phase lead over the wave elevation [deg]", ())
    sway_amplitude: tuple = spec("none", "sway (+ to port) amplitude per unit wave amplitude [m/m]", ())
    sway_phase_deg: tuple = spec("none", "sway phase lead [deg]", ())
    heave_amplitude: tuple = spec("none", "heave (+ up) amplitude per unit wave amplitude [m/m]", ())
    heave_phase_deg: tuple = spec("none", "heave phase lead [deg]", ())
    roll_amplitude: tuple = spec("angle_deg_per_length", "roll (+ starboard down) amplitude per unit wave amplitude", ())
    roll_phase_deg: tuple = spec("none", "roll phase lead [deg]", ())
    pitch_amplitude: tuple = spec("angle_deg_per_length", "pitch (+ bow down) amplitude per unit wave amplitude", ())
    pitch_phase_deg: tuple = spec("none", "pitch phase lead [deg]", ())
    yaw_amplitude: tuple = spec("angle_deg_per_length", "yaw (+ bow to port) amplitude per unit wave amplitude", ())
    yaw_phase_deg: tuple = spec("none", "yaw phase lead [deg]", ())

    def __post_init__(self):
        require_finite("heading_deg", self.heading_deg)
        for dof in DOFS:
            for part in ("amplitude", "phase_deg"):
                name = f"{dof}_{part}"
                v = tuple(float(x) for x in getattr(self, name))
                for i, x in enumerate(v):
                    require_finite(f"{name}[{i}]", x)
                    if part == "amplitude":
                        require_nonnegative(f"{name}[{i}]", x, _unit(dof))
                object.__setattr__(self, name, v)

    def complex_table(self, n: int, where: str) -> dict:
        """{dof: complex RAO per table frequency} (rotations in rad per m); an unset DOF is zero."""
        out = {}
        for dof in DOFS:
            amp, ph = getattr(self, f"{dof}_amplitude"), getattr(self, f"{dof}_phase_deg")
            if not amp and ph:
                raise ParameterError(f"{where}.{dof}_amplitude", "missing", f"is needed with {dof}_phase_deg")
            amp = amp or (0.0,) * n
            ph = ph or (0.0,) * n
            for name, v in ((f"{dof}_amplitude", amp), (f"{dof}_phase_deg", ph)):
                if len(v) != n:
                    raise ParameterError(f"{where}.{name}", f"{len(v)} values", f"needs one per frequency ({n})")
            scale = math.pi / 180.0 if dof in _ROTATIONS else 1.0
            out[dof] = (np.asarray(amp) * scale, np.radians(ph))
        return out


@dataclasses.dataclass(frozen=True, kw_only=True)
class VesselRAO:
    """A vessel's 6-DOF motion RAO table and the point of the vessel the cable hangs from.

    Inline (``omega`` and one ``[[top_motion.vessel.headings]]`` table per relative heading) or
    ``file``: a CSV with one row per (heading, frequency) and the columns ``heading_deg, omega`` and
    ``<dof>_amplitude, <dof>_phase_deg`` for any of surge, sway, heave, roll, pitch, yaw, in SI (m/m and
    deg/m whatever the scene's ``units``; read at load time and kept inline, so a dumped scene
    reproduces the run)."""

    omega: tuple = spec("frequency", "table frequencies, strictly increasing (linear interpolation, end values "
                                     "held outside)", ())
    headings: tuple[HeadingRAO, ...] = spec("none", "one RAO table per relative wave heading", ())
    lever_arm: tuple = spec("length", "the cable's point on the vessel (crane tip, fairlead) from the RAO reference "
                                      "point, in vessel axes (x forward, y to port, z up)", (0.0, 0.0, 0.0))
    vessel_heading_deg: float = spec("angle_deg", "direction the bow points, deg from +x, counter-clockwise seen from "
                                                  "above (towards +z)", 0.0)
    file: str = spec("none", "CSV file with the table instead of the arrays (path relative to the working directory)", "")

    def __post_init__(self):
        w = "top_motion.vessel"
        if self.file:
            if self.omega or self.headings:
                raise ParameterError(f"{w}.file", self.file, "give either the file or the inline tables")
            omega, headings = _read_vessel_csv(self.file)
            object.__setattr__(self, "omega", omega)
            object.__setattr__(self, "headings", headings)
            object.__setattr__(self, "file", "")
        om = tuple(float(v) for v in self.omega)
        if not om:
            raise ParameterError(f"{w}.omega", self.omega, "needs at least one frequency")
        for i, v in enumerate(om):
            if not (math.isfinite(v) and v > 0.0):
                raise ParameterError(f"{w}.omega[{i}]", v, "must be a finite frequency > 0 rad/s")
            if i and not v > om[i - 1]:
                raise ParameterError(f"{w}.omega", om, f"must be strictly increasing (entry {i})")
        object.__setattr__(self, "omega", om)
        hs = tuple(self.headings)
        if not hs:
            raise ParameterError(f"{w}.headings", "none", "needs at least one [[top_motion.vessel.headings]] table")
        object.__setattr__(self, "headings", hs)
        betas = [h.heading_deg % 360.0 for h in hs]
        for i in range(1, len(betas)):
            if not betas[i] > betas[i - 1]:
                raise ParameterError(f"{w}.headings[{i}].heading_deg", hs[i].heading_deg,
                                     "must increase from table to table within [0, 360) deg")
        tables = [h.complex_table(len(om), f"{w}.headings[{i}]") for i, h in enumerate(hs)]
        object.__setattr__(self, "_tables", tables)
        object.__setattr__(self, "_betas", np.asarray(betas))
        arm = tuple(float(v) for v in self.lever_arm)
        if len(arm) != 3:
            raise ParameterError(f"{w}.lever_arm", self.lever_arm, "needs three values (x forward, y to port, z up) in m")
        for i, v in enumerate(arm):
            require_finite(f"{w}.lever_arm[{i}]", v)
        object.__setattr__(self, "lever_arm", arm)
        require_finite(f"{w}.vessel_heading_deg", self.vessel_heading_deg)

    # ---------------------------------------------------------------- the RAOs
    def _at_table(self, k: int, omega: np.ndarray) -> dict:
        """{dof: (|R|, unwrapped phase) at ``omega``} of table heading k (:func:`.sea.interpolate_rao`)."""
        return {dof: interpolate_rao(self.omega, amp, ph, omega) for dof, (amp, ph) in self._tables[k].items()}

    def _bracket(self, beta: float):
        """(k0, k1, weight, mirrored) of the table headings around ``beta`` (deg in [0, 360))."""
        b = self._betas
        for mirrored, x in ((False, beta), (True, (360.0 - beta) % 360.0)):
            hit = np.flatnonzero(np.isclose(b, x, atol=1e-9))
            if hit.size:
                return int(hit[0]), int(hit[0]), 0.0, mirrored
            spans = [(k, k + 1, b[k], b[k + 1]) for k in range(len(b) - 1)]
            if len(b) > 1 and b[0] + 360.0 - b[-1] < 180.0 - 1e-9:    # the table spans more than half the circle: it wraps
                spans.append((len(b) - 1, 0, b[-1], b[0] + 360.0))
            for k0, k1, lo, hi in spans:
                xx = x if x >= lo else x + 360.0
                if lo <= xx <= hi:
                    return k0, k1, (xx - lo) / (hi - lo), mirrored
        raise ParameterError("top_motion.vessel.headings", [float(v) for v in b],
                             f"must cover the relative wave heading {beta:.6g} deg (spectrum.heading_deg - "
                             f"vessel_heading_deg), directly or by port-starboard symmetry (360 - beta)")

    def motions(self, omega, wave_heading_deg: float) -> dict:
        """{dof: complex RAO at ``omega``} for waves travelling ``wave_heading_deg`` from cablesys' +x
        (rotations in rad per m of wave amplitude); linear in amplitude and unwrapped phase between
        table frequencies and between the two neighbouring table headings."""
        omega = np.asarray(omega, float)
        beta = (float(wave_heading_deg) - self.vessel_heading_deg) % 360.0
        k0, k1, s, mirrored = self._bracket(beta)
        a, b = self._at_table(k0, omega), self._at_table(k1, omega)
        out = {}
        for dof in DOFS:
            amp = (1 - s) * a[dof][0] + s * b[dof][0]
            dph = (b[dof][1] - a[dof][1] + math.pi) % (2 * math.pi) - math.pi
            r = amp * np.exp(1j * (a[dof][1] + s * dph))
            out[dof] = -r if (mirrored and dof in ANTISYMMETRIC) else r
        return out

    def _heading(self) -> tuple[float, float]:
        """(cos psi, sin psi) of ``vessel_heading_deg``; a whole quadrant exactly (0, +-1)."""
        psi = math.radians(self.vessel_heading_deg)
        c, s = (0.0 if abs(v) < 1e-12 else v for v in (math.cos(psi), math.sin(psi)))
        return c, s

    def to_node(self, v1, v2, v3) -> tuple:
        """R v: a vector (v1 forward, v2 to port, v3 up) of the vessel in cablesys axes (x, y down, z), R of the
        module docstring."""
        c, s = self._heading()
        return c * v1 - s * v2, -v3, s * v1 + c * v2

    def arm_of(self, offset) -> tuple:
        """The lever arm (m, vessel axes) of a point of the vessel whose mean position is ``offset`` (dx, dy, dz; m,
        node frame: x, y down, z) from the ``lever_arm`` point: r_0 + R^T Delta (module docstring)."""
        c, s = self._heading()
        dx, dy, dz = (float(v) for v in offset)
        x, y, z = self.lever_arm
        return (x + c * dx + s * dz, y - s * dx + c * dz, z - dy)

    def transfer(self, omega, wave_heading_deg: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Complex amplitudes (X, Y, Z) of the lever-arm point's motion per unit wave amplitude, in
        cablesys axes (x, y down, z), from the rigid-body displacement of the module docstring."""
        m = self.motions(omega, wave_heading_deg)
        x, y, z = self.lever_arm
        s1 = m["surge"] + z * m["pitch"] - y * m["yaw"]
        s2 = m["sway"] - z * m["roll"] + x * m["yaw"]
        s3 = m["heave"] + y * m["roll"] - x * m["pitch"]
        return self.to_node(s1, s2, s3)

    def rotation_transfer(self, omega, wave_heading_deg: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Complex amplitudes (theta_x, theta_y, theta_z) of the vessel's small rotation about cablesys' axes (rad per
        m of wave amplitude): theta = R (roll, pitch, yaw) (module docstring)."""
        m = self.motions(omega, wave_heading_deg)
        return self.to_node(m["roll"], m["pitch"], m["yaw"])


def _read_vessel_csv(path) -> tuple[tuple, tuple]:
    field = "top_motion.vessel.file"
    rows = read_csv_rows(path, field)
    if not rows or any(c not in rows[0] for c in ("heading_deg", "omega")):
        raise ParameterError(field, str(path), "needs a header with heading_deg, omega and <dof>_amplitude, "
                             f"<dof>_phase_deg columns for any of {', '.join(DOFS)}")
    cols = [c for c in rows[0] if c not in ("heading_deg", "omega")]
    known = {f"{d}_{p}" for d in DOFS for p in ("amplitude", "phase_deg")}
    for c in cols:
        if c not in known:
            raise ParameterError(field, str(path), f"unknown column {c!r}; allowed: heading_deg, omega, {', '.join(sorted(known))}")
    try:
        table = [{k: float(v) for k, v in r.items()} for r in rows]
    except (TypeError, ValueError):
        raise ParameterError(field, str(path), "every table entry must be a number") from None
    headings = sorted({r["heading_deg"] for r in table})
    omega = sorted({r["omega"] for r in table})
    out = []
    for h in headings:
        rs = sorted((r for r in table if r["heading_deg"] == h), key=lambda r: r["omega"])
        if [r["omega"] for r in rs] != omega:
            raise ParameterError(field, str(path), f"heading {h:g} deg needs a row for every frequency of the table "
                                 f"({len(omega)}), has {len(rs)}")
        out.append(HeadingRAO(heading_deg=h, **{c: tuple(r[c] for r in rs) for c in cols}))
    return tuple(omega), tuple(out)
