"""Time series out in the user's units (CSV) and self-describing netCDF (SI, conventions, the scene).

A scene written in ft/lb/slug gets its CSV in those units; every column name carries its
unit. The netCDF file stays SI (CF-style ``units`` and ``long_name`` on every variable) and
stores the sign conventions and the whole scene as TOML text, so a run can be reproduced
from its file alone (``cablesys.scene.scene_from_dict(tomllib.loads(ds.attrs["scene_toml"]))``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .results import long_name_of, unit_of
from .units import output_unit

CONVENTIONS = {
    "axes": "x horizontal, + to the right (the direction of +current and of wave travel); "
            "y vertical, + downwards from the still surface (Wang 1971, Fig. 1)",
    "phi": "angle from the vertical of the section's chord, the straight line from its top end to its body (rad); "
           "the chord's unit vector is (-sin phi, cos phi), so a positive phi puts the lower end at -x of the top",
    "u": "stretch of the cable beyond its zero-tension length (m)",
    "tension": "cable tension, + in tension (N), always named by where it is: tension_top at the top end, "
               "tension_bottom at the body, tension_mid at mid-length (unstretched arc length), element_tension[k] "
               "per element of a segmented cable",
    "top_motion": "x_s, y_s: prescribed top (ship / crane-tip) motion in the same axes",
}

LONG_NAMES = {"tension_top": "cable tension at the top (ship) end of the section",
              "tension_bottom": "cable tension at the body end of the section",
              "tension_mid": "cable tension at mid-length of the section"}


def si_unit(label: str) -> str:
    """The SI unit of a series label ("" when unknown); tension outputs in N."""
    return unit_of(label) or ("N" if label.startswith("tension") else "")


def series_table(result, system: str = "SI") -> tuple[list[str], np.ndarray]:
    """(header, rows) of time and every series, converted to ``system``, ``name [unit]`` columns."""
    head, cols = ["time [s]"], [np.asarray(result.time, float)]
    for lbl in result.labels:
        f, u = output_unit(si_unit(lbl), system)
        head.append(f"{lbl} [{u or '-'}]")
        cols.append(np.asarray(result[lbl], float) * f)
    return head, np.column_stack(cols)


def write_csv(result, path, system: str = "SI") -> Path:
    """Write the series as CSV in ``system`` ("SI" or "fps"), the unit in every column name."""
    head, rows = series_table(result, system)
    np.savetxt(path, rows, delimiter=",", header=",".join(head), comments="", fmt="%.10g")
    return Path(path)


def to_dataset(result, *, scene_toml: str = "", scene_units: str = "SI"):
    """The run as an ``xarray.Dataset`` (SI) with units, long names, conventions and the scene."""
    ds = result.to_xarray()
    for lbl in ds.data_vars:
        ds[lbl].attrs.setdefault("units", si_unit(lbl))
        if not ds[lbl].attrs.get("units"):
            ds[lbl].attrs["units"] = si_unit(lbl) or "1"
        ds[lbl].attrs["long_name"] = LONG_NAMES.get(lbl.rstrip("_0123456789"), None) or ds[lbl].attrs.get(
            "long_name") or long_name_of(lbl)
    ds.attrs.update({f"convention_{k}": v for k, v in CONVENTIONS.items()})
    if scene_toml:
        ds.attrs["scene_toml"] = scene_toml
        ds.attrs["scene_units_of_input"] = scene_units
    return ds


def write_netcdf(result, path, *, scene_toml: str = "", scene_units: str = "SI") -> Path:
    """Write :func:`to_dataset` as netCDF3 (scipy backend: no netCDF C library needed)."""
    to_dataset(result, scene_toml=scene_toml, scene_units=scene_units).to_netcdf(path, engine="scipy")
    return Path(path)


def units_of_file(path) -> str:
    """The ``units`` a scene file is written in ("SI" when absent or unreadable)."""
    import tomllib
    try:
        units = tomllib.loads(Path(path).read_text(encoding="utf-8-sig")).get("units", "SI")
    except (OSError, ValueError):
        return "SI"
    return units if units in ("SI", "fps") else "SI"


def convert_rao_table(head: list[str], rows: np.ndarray, system: str = "SI") -> tuple[list[str], np.ndarray]:
    """An RAO table (columns ``name [unit/m]`` per unit top motion or ``[unit/rad]`` per unit rotation, ``[deg]``,
    ``[rad/s]``) in ``system``."""
    from .units import per_input_unit
    if system == "SI":
        return head, rows
    rows = np.array(rows, float, copy=True)
    out = []
    for k, h in enumerate(head):
        name, _, unit = h.partition(" [")
        unit = unit.rstrip("]")
        if unit.endswith(("/m", "/rad")):
            out_unit, _, per = unit.rpartition("/")
            f, unit = per_input_unit(out_unit, system, per)
            rows[:, k] *= f
        out.append(f"{name} [{unit}]")
    return out, rows
