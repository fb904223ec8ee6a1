"""Inputs of a towed-cable analysis from a scene file: the cable in the Wang scene's vocabulary, SI.

A towed scene is a neutrally buoyant-ish cable of length L and diameter d towed at speed U,
with the drag coefficients a user has in hand (``ct_tangential`` C_t and ``cd_normal`` C_n,
referred to d as in :class:`cablesys.scene.Cable`) and the drogue as a drag area. The theory's
coefficients c_t, c_n, c_t' and beta follow from
:func:`cablesys.towed.equation.theory_coefficients` (the one conversion, with its sources).
The TOML format read by :func:`load_towed_scene` is documented in :data:`EXAMPLE_TOML`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import ParameterError, require_positive, require_range
from ..reader import build, located, read_toml, typed_fields
from ..scene.fields import quantity, spec
from ..scene.limits import Limits, static_limits
from .equation import TowedCable, theory_coefficients
from .runs import MAX_LENGTH_M
from .transfer import MAX_OMEGA_ND

__all__ = ["EXAMPLE_TOML", "MAX_FREQUENCIES", "TowedScene", "TowedSceneCable", "load_towed_scene",
           "towed_scene_from_dict"]

MAX_FREQUENCIES = 2000      # frequencies of one analysis (each is one 0F1 evaluation per xi)
MAX_POSITIONS = 200         # positions xi along the cable


@dataclass(frozen=True, kw_only=True)
class TowedSceneCable:
    """The towed cable of a scene file, named as the Wang scene's cable (:class:`cablesys.scene.Cable`)."""

    length: float = quantity("length", "cable length L from the tow point to the drogue")
    diameter: float = quantity("diameter", "cable diameter d_c")
    mass_per_length: float = quantity("mass_per_length", "cable mass per unit length in air m (beta = M/(M+m))")
    ct_tangential: float = quantity("ct_tangential", "tangential friction coefficient C_t, referred to d (Wang "
                                    "eq. 44); the theory's c_t = C_t / pi")
    cd_normal: float = quantity("cd_normal", "quadratic normal drag coefficient C_n, referred to d (Wang eq. 42); "
                                "the theory's c_n* = A C_n (Kennedy & Strahan eq. 39)")

    def __post_init__(self):
        require_range("cable.length", self.length, 0.0, MAX_LENGTH_M, "m", lo_open=True)
        require_positive("cable.diameter", self.diameter, "m")
        require_positive("cable.mass_per_length", self.mass_per_length, "kg/m")
        require_range("cable.ct_tangential", self.ct_tangential, 0.0, 3.0, lo_open=True)
        require_range("cable.cd_normal", self.cd_normal, 0.0, 10.0, lo_open=True)


@dataclass(frozen=True, kw_only=True)
class TowedScene:
    """A cable towed at ``speed`` in a fluid of ``density``, and the grid to report on.

    ``xi``: positions x/L along the cable (0 at the tow point, 1 at the drogue); the angular
    frequencies of the tow-point motion are ``n_omega`` log-spaced in [``omega_min``,
    ``omega_max``] (rad/s; default 0.1 to 30 U/L, the report's Figs. 6-7); ``n_modes`` mode
    pairs of the complementary solution (eq. 18-20); ``limits`` the working load and least tension
    the steady tensions are judged against (:func:`cablesys.verdict.judge`).
    """

    cable: TowedSceneCable = spec("none", "the towed cable", symbol="")
    speed: float = spec("velocity", "tow speed U", symbol="U")
    density: float = quantity("density", "fluid density rho", 1025.0)
    drogue_drag_area: float = spec("area", "drag area (C_D A) of the drogue: drag (rho/2) (C_D A) U^2; 0 for none",
                                   0.0, symbol="(C_D A)_d")
    amplification: float = spec("none", "A of Kennedy & Strahan eq. 38-39, c_n* = A C_n (1 for a level cable)", 1.0,
                                symbol="A")
    xi: tuple[float, ...] = spec("none", "positions x/L along the cable to report", (0.5, 1.0), symbol="xi")
    omega_min: float | None = spec("frequency", "lowest angular frequency (default 0.1 U/L)", None,
                                   symbol="omega_min")
    omega_max: float | None = spec("frequency", "highest angular frequency (default 30 U/L)", None,
                                   symbol="omega_max")
    n_omega: int = spec("none", "number of log-spaced angular frequencies", 120, symbol="")
    n_modes: int = spec("none", "mode pairs of the complementary solution (eq. 18-20)", 5, symbol="")
    limits: Limits | None = spec("none", "what the steady tensions at the tow point and the drogue are checked "
                                 "against (cablesys.verdict): working load and least_tension", None, symbol="")

    def __post_init__(self):
        static_limits(self.limits)          # the criteria a static analysis can judge, or a named error
        require_positive("towed.speed", self.speed, "m/s")
        require_positive("environment.density", self.density, "kg/m^3")
        require_positive("towed.amplification", self.amplification)
        if not math.isfinite(self.drogue_drag_area) or self.drogue_drag_area < 0:
            raise ParameterError("towed.drogue_drag_area", self.drogue_drag_area, "must be a finite number >= 0 (m^2)")
        xi = tuple(float(x) for x in np.atleast_1d(self.xi))
        if not 1 <= len(xi) <= MAX_POSITIONS or not all(math.isfinite(x) and 0.0 <= x <= 1.0 for x in xi):
            raise ParameterError("towed.xi", list(self.xi), f"must be 1 to {MAX_POSITIONS} positions x/L in [0, 1]")
        object.__setattr__(self, "xi", xi)
        for name in ("n_omega", "n_modes"):
            v = getattr(self, name)
            hi = MAX_FREQUENCIES if name == "n_omega" else 50
            if isinstance(v, bool) or not isinstance(v, int) or not 1 <= v <= hi:
                raise ParameterError(f"towed.{name}", v, f"must be an integer in [1, {hi}]")
        lo, hi = self.omega_range
        if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo <= hi):
            raise ParameterError("towed.omega_min", self.omega_min,
                                 f"must satisfy 0 < omega_min <= omega_max (rad/s); got [{lo:.6g}, {hi:.6g}]")
        if not hi * self.cable.length / self.speed <= MAX_OMEGA_ND:     # bounds the xi grid fine_xi allocates
            raise ParameterError("towed.omega_max", hi,
                                 f"must be <= {MAX_OMEGA_ND * self.speed / self.cable.length:.6g} rad/s, i.e. "
                                 f"omega L/U <= {MAX_OMEGA_ND:.6g} (L = {self.cable.length:g} m, U = {self.speed:g} "
                                 "m/s): the phase lag is unwrapped on 8 points per radian along the cable")
        # the conversion checks its inputs once more, naming them
        self.coefficients()

    @property
    def omega_range(self) -> tuple[float, float]:
        """[omega_min, omega_max] in rad/s, defaults from the time scale L/U."""
        scale = self.speed / self.cable.length
        lo = self.omega_min if self.omega_min is not None else 0.1 * scale
        hi = self.omega_max if self.omega_max is not None else 30.0 * scale
        return float(lo), float(hi)

    def omega(self) -> np.ndarray:
        """The analysis' angular frequencies (rad/s), log-spaced."""
        lo, hi = self.omega_range
        return np.geomspace(lo, hi, self.n_omega)

    def coefficients(self) -> dict:
        """The theory's c_t, c_n, c_t_drogue and beta (:func:`~cablesys.towed.equation.theory_coefficients`)."""
        c = self.cable
        return theory_coefficients(diameter=c.diameter, mass_per_length=c.mass_per_length,
                                   ct_tangential=c.ct_tangential, cd_normal=c.cd_normal, density=self.density,
                                   amplification=self.amplification, drogue_drag_area=self.drogue_drag_area)

    def towed_cable(self) -> TowedCable:
        """The cable in the theory's terms (:class:`TowedCable`)."""
        return TowedCable(length=self.cable.length, speed=self.speed, diameter=self.cable.diameter,
                          **self.coefficients())


EXAMPLE_TOML = """\
# cablesys towed scene: SI units throughout (m, kg, N, s, rad/s).
# The cable's keys are those of the Wang scene's [cable] (`cablesys scene --example`).
[cable]
length = 1190.0          # L, tow point to drogue, m
diameter = 0.016         # d_c, m
mass_per_length = 0.206  # m, kg/m in air (beta = M / (M + m), M = rho pi d^2 / 4)
ct_tangential = 0.0317   # C_t referred to d (Wang eq. 44): c_t = C_t / pi = 0.0101
cd_normal = 0.16         # C_n referred to d (Wang eq. 42): c_n* = A C_n

[environment]
density = 1025.0         # rho, kg/m^3

[towed]
speed = 5.0              # tow speed U, m/s
drogue_drag_area = 0.1834   # (C_D A) of the drogue, m^2: c_t' = (C_D A) / (pi d^2) = 228
amplification = 1.0      # A of eq. 38-39 (1: level cable)
xi = [0.5, 1.0]          # positions x/L to report
# omega_min = 4.2e-4     # rad/s (default 0.1 U/L)
# omega_max = 0.126      # rad/s (default 30 U/L)
n_omega = 120
n_modes = 5

# optional: what the verdict checks the steady tensions (tow point, drogue) against, N
# [limits]
# safe_working_load = 20000.0   # or minimum_breaking_load with safety_factor
# least_tension = 100.0
"""


def towed_scene_from_dict(doc: dict, source=None) -> TowedScene:
    """The towed scene of a parsed TOML document (see :data:`EXAMPLE_TOML`).

    Parameters
    ----------
    doc : dict
        The parsed document: ``[cable]``, ``[environment]`` (density), ``[towed]``.
    source : cablesys.reader.SourceMap or str, optional
        Where the document came from; errors then name the file and line.

    Returns
    -------
    TowedScene
        The validated scene (SI).

    Raises
    ------
    ParameterError
        Naming the field, its value and the allowed range (and the file and line).
    """
    try:
        return _scene_from_dict(doc)
    except ParameterError as err:
        raise located(err, source) from None


def _scene_from_dict(doc) -> TowedScene:
    if not isinstance(doc, dict):
        raise ParameterError("document", doc, "must be a TOML document (a table)")
    for k in doc:
        if k not in ("cable", "environment", "towed", "limits"):
            raise ParameterError(k, doc[k], "unknown table; allowed: cable, environment, towed, limits")
    for k in ("cable", "towed"):
        if k not in doc:
            raise ParameterError(k, None, f"a [{k}] table is required")
    cable = build(TowedSceneCable, doc["cable"], "cable")
    env = doc.get("environment", {})
    if not isinstance(env, dict) or set(env) - {"density"}:
        raise ParameterError("environment", env, "must be a table with at most the key density (kg/m^3)")
    kw = typed_fields(TowedScene, doc["towed"], "towed", skip=("cable", "density", "limits"))
    if "limits" in doc:
        kw["limits"] = build(Limits, doc["limits"], "limits")
    if "density" in env:
        kw["density"] = typed_fields(TowedScene, {"density": env["density"]}, "environment",
                                     skip=tuple(f for f in TowedScene.__dataclass_fields__ if f != "density"))["density"]
    return TowedScene(cable=cable, **kw)


def load_towed_scene(path: str | Path) -> TowedScene:
    """Read a towed-cable scene TOML file (UTF-8, a byte-order mark accepted).

    Parameters
    ----------
    path : str or Path
        The TOML file (format: :data:`EXAMPLE_TOML`).

    Returns
    -------
    TowedScene
        The validated scene (SI).

    Raises
    ------
    ParameterError
        Unreadable, undecodable or invalid file, or a value out of range (file, line, field).
    """
    doc, source = read_toml(path, "towed scene file")
    return towed_scene_from_dict(doc, source)
