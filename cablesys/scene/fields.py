"""Field metadata for scene dataclasses: unit, physical dimension and meaning.

Each scene field carries ``metadata={"dim": ..., "doc": ...}`` so that one table
converts a scene written in the report's ft/lb/slug to SI (Wang 1971 works in
ft-lb-slug) and documents every field in ``cablesys scene --example``.
"""

from __future__ import annotations

import dataclasses

from .. import units as U

# SI unit shown to users, per physical dimension
SI_UNIT = {
    "length": "m", "force": "N", "mass": "kg", "mass_per_length": "kg/m",
    "force_per_length": "N/m", "density": "kg/m^3", "velocity": "m/s",
    "acceleration": "m/s^2", "area": "m^2", "force_time": "N s", "angle": "rad",
    "angle_deg": "deg", "frequency": "rad/s", "time": "s", "none": "-",
}

# factor from the report's foot-pound-second (slug) system to SI, per dimension
FPS_TO_SI = {
    "length": U.FT, "force": U.LBF, "mass": U.SLUG, "mass_per_length": U.SLUG / U.FT,
    "force_per_length": U.LBF / U.FT, "density": U.SLUG / U.FT**3, "velocity": U.FT,
    "acceleration": U.FT, "area": U.FT**2, "force_time": U.LBF, "angle": 1.0,
    "angle_deg": 1.0, "frequency": 1.0, "time": 1.0, "none": 1.0,
}

UNIT_SYSTEMS = ("SI", "fps")


def spec(dim: str, doc: str, default=dataclasses.MISSING, *, default_factory=dataclasses.MISSING):
    """A dataclass field with unit metadata."""
    kw = {"metadata": {"dim": dim, "doc": doc}}
    if default is not dataclasses.MISSING:
        kw["default"] = default
    if default_factory is not dataclasses.MISSING:
        kw["default_factory"] = default_factory
    return dataclasses.field(**kw)


def to_si(value, dim: str, system: str):
    """Convert a number (or a list of numbers) given in ``system`` to SI."""
    f = FPS_TO_SI[dim] if system == "fps" else 1.0
    if isinstance(value, (list, tuple)):
        return tuple(float(v) * f for v in value)
    return float(value) * f


def from_si(value, dim: str, system: str):
    """Convert an SI number (or tuple) to ``system``."""
    f = FPS_TO_SI[dim] if system == "fps" else 1.0
    if isinstance(value, (list, tuple)):
        return [float(v) / f for v in value]
    return float(value) / f
