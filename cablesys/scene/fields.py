"""Field metadata for scene dataclasses: unit, physical dimension and meaning.

Each scene field carries ``metadata={"dim": ..., "doc": ...}`` so that one table
converts a scene written in the report's ft/lb/slug to SI (Wang 1971 works in
ft-lb-slug) and documents every field in ``cablesys scene --example``.
"""

from __future__ import annotations

import dataclasses
import math

from .. import units as U
from ..errors import ParameterError, require_finite

# SI unit shown to users, per physical dimension
SI_UNIT = {
    "length": "m", "force": "N", "mass": "kg", "mass_per_length": "kg/m",
    "force_per_length": "N/m", "density": "kg/m^3", "velocity": "m/s",
    "acceleration": "m/s^2", "area": "m^2", "force_time": "N s", "angle": "rad",
    "angle_deg": "deg", "frequency": "rad/s", "time": "s", "none": "-",
    "stiffness_per_area": "Pa/m", "damping_per_area": "Pa s/m",     # seabed contact (scene Seabed)
    "angle_deg_per_length": "deg/m",                                   # a vessel's rotation RAO (scene/vessel.py)
    "inertia": "kg m^2", "moment_time": "N m s", "moment_time2": "N m s^2",   # a rigid body's pitch (scene Body)
}

# factor from the report's foot-pound-second (slug) system to SI, per dimension
FPS_TO_SI = {
    "length": U.FT, "force": U.LBF, "mass": U.SLUG, "mass_per_length": U.SLUG / U.FT,
    "force_per_length": U.LBF / U.FT, "density": U.SLUG / U.FT**3, "velocity": U.FT,
    "acceleration": U.FT, "area": U.FT**2, "force_time": U.LBF, "angle": 1.0,
    "angle_deg": 1.0, "frequency": 1.0, "time": 1.0, "none": 1.0,
    "stiffness_per_area": U.LBF / U.FT**3, "damping_per_area": U.LBF / U.FT**3,
    "angle_deg_per_length": 1.0 / U.FT,
    "inertia": U.SLUG * U.FT**2, "moment_time": U.LBF * U.FT, "moment_time2": U.LBF * U.FT,
}

UNIT_SYSTEMS = ("SI", "fps")


def spec(dim: str, doc: str, default=dataclasses.MISSING, *, default_factory=dataclasses.MISSING,
         symbol: str | None = None, quantity: str | None = None):
    """A dataclass field with unit metadata.

    Parameters
    ----------
    dim : str
        Physical dimension, a key of :data:`SI_UNIT` (``"force"``, ``"length"``...).
    doc : str
        Meaning of the field (with the report's notation and equation).
    default, default_factory : optional
        As for :func:`dataclasses.field`.
    symbol : str, optional
        The quantity's symbol (``"EA"``); stored as ``metadata["symbol"]``.
    quantity : str, optional
        Name of the entry of :data:`QUANTITIES` the field stands for (set by :func:`quantity`).

    Returns
    -------
    dataclasses.Field
        With ``metadata`` ``dim``, ``unit`` (SI), ``doc`` and, when given, ``symbol`` and ``quantity``.
    """
    meta = {"dim": dim, "unit": SI_UNIT[dim], "doc": doc}
    if symbol is not None:
        meta["symbol"] = symbol
    if quantity is not None:
        meta["quantity"] = quantity
    kw = {"metadata": meta}
    if default is not dataclasses.MISSING:
        kw["default"] = default
    if default_factory is not dataclasses.MISSING:
        kw["default_factory"] = default_factory
    return dataclasses.field(**kw)


# One name per physical quantity shared by the models (Wang's scene, the slack and the towed
# cable): name -> (dimension, symbol). A model that has one of these quantities declares it
# with ``quantity(name, doc)``, so the name, unit and symbol are the same everywhere
# (tests/test_vocabulary.py checks the three models against this table).
QUANTITIES = {
    "length": ("length", "L"),                     # cable length (unstretched or at the reference tension)
    "diameter": ("length", "d"),
    "mass_per_length": ("mass_per_length", "m"),   # in air
    "weight_per_length": ("force_per_length", "w"),  # weight in water per unit length
    "ae": ("force", "EA"),                         # axial stiffness (Wang's (AE)_r)
    "added_mass_factor": ("none", "C_a"),          # added mass = C_a x displaced fluid mass
    "cd_normal": ("none", "C_D"),                  # quadratic normal drag, referred to d
    "ct_tangential": ("none", "C_t"),              # quadratic tangential friction, referred to d
    "specific_gravity": ("none", "S"),
    "gravity": ("acceleration", "g"),
    "density": ("density", "rho"),
}


def quantity(name: str, doc: str, default=dataclasses.MISSING, *, default_factory=dataclasses.MISSING):
    """A dataclass field for the shared quantity ``name`` of :data:`QUANTITIES` (its unit and symbol).

    Parameters
    ----------
    name : str
        A key of :data:`QUANTITIES`; the field must have this name.
    doc : str
        Meaning in the model at hand (its report's notation and equation).
    default, default_factory : optional
        As for :func:`dataclasses.field`.

    Returns
    -------
    dataclasses.Field
        See :func:`spec`; ``metadata["quantity"]`` is ``name``.
    """
    dim, symbol = QUANTITIES[name]
    return spec(dim, doc, default, default_factory=default_factory, symbol=symbol, quantity=name)


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


def check_all_finite(obj, prefix: str) -> None:
    for f in dataclasses.fields(obj):
        v = getattr(obj, f.name)
        if isinstance(v, (int, float)) and not isinstance(v, bool):
            if f.name == "tension_floor" and v == -math.inf:
                continue  # -inf: the cable never goes slack (a rod)
            require_finite(f"{prefix}.{f.name}", v)
            if abs(v) > MAX_MAGNITUDE:
                raise ParameterError(f"{prefix}.{f.name}", v, f"must be within +-{MAX_MAGNITUDE:g} (SI units); larger "
                                     "values overflow the squares and products of the equations of motion")


# no cable or body number in SI comes near this (AE of the largest steel ropes ~1e10 N); a cable
# 1e300 m long passed the range checks and overflowed the steady-state solve (found by fuzzing)
MAX_MAGNITUDE = 1e15
