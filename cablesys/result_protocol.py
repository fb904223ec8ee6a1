"""The result protocol every analysis of every model satisfies (a leaf module: numpy only; re-exported by
:mod:`cablesys.results` together with the time-domain result).

An analysis (a time run, a steady state, a linearization, modes, RAOs, a design, a slack
equilibrium, a towed-cable transfer grid...) returns one immutable object with

``success``  bool: False when the numerics did not reach the answer (nothing is raised:
             exceptions are only for bad input, :class:`~cablesys.errors.ParameterError`,
             or an unrecoverable numerical failure, :class:`~cablesys.errors.SolverError`);
``message``  str: why not, and what to try ("" on success);
``stats``    dict: ``wall_time_s`` (s) and ``iterations`` or ``steps`` where they apply;
labelled data (fields named by the physical quantity, labels for outputs and coordinates);
``to_xarray()``  an ``xarray.Dataset`` (or ``DataArray``) whose variables and coordinates carry
             ``units`` and ``long_name`` attributes;
``summary()``    a JSON-able dict of the headline numbers;
a short ``repr`` (shapes, not arrays: safe to display in Jupyter).

A static analysis whose scene carries ``limits`` (a slack span, a towed cable) also offers
``static_tensions()`` -> {tension label: array of N}: what :func:`cablesys.verdict.judge` reads.

To add an analysis: write a frozen dataclass deriving from :class:`ResultBase` with the fields
``success``, ``message`` and ``stats`` (or properties of those names), a ``to_xarray`` that
builds the dataset (units and long names of well-known labels are filled in from
:data:`QUANTITIES`; give others in the class attribute ``VARIABLES``), and decorate the
function that computes it with :func:`timed`. :class:`cablesys.linear.Modes` is a short example.
"""

from __future__ import annotations

import dataclasses
import functools
import json
import re
import time as _time
from typing import Any, ClassVar, Protocol, runtime_checkable

import numpy as np

# label -> (SI unit, long name): the one table of units and names of labelled quantities.
QUANTITIES = {
    "time": ("s", "time"), "omega": ("rad/s", "angular frequency"),
    "phi": ("rad", "chord (top end to body) angle from the vertical"), "phi_rate": ("rad/s", "cable angular rate"),
    "u": ("m", "cable stretch beyond its zero-tension length"), "u_rate": ("m/s", "cable stretch rate"),
    "chord_stretch": ("m", "chord (top to body) minus the cable's zero-tension length"),
    "chord_stretch_rate": ("m/s", "rate of the chord length"),
    "x_b": ("m", "body horizontal position"), "x_b_rate": ("m/s", "body horizontal velocity"),
    "y_b": ("m", "body vertical position"), "y_b_rate": ("m/s", "body vertical velocity"),
    "tension_mid": ("N", "cable tension at mid-length"), "x_s": ("m", "top (ship) horizontal motion"),
    "tension_top": ("N", "cable tension at the top end"), "tension_bottom": ("N", "cable tension at the body end"),
    "y_s": ("m", "top (ship) vertical motion"),
    "phi_z": ("rad", "cable angle out of the x-y plane"), "phi_z_rate": ("rad/s", "out-of-plane angular rate"),
    "z_b": ("m", "body sway position"), "z_b_rate": ("m/s", "body sway velocity"),
    "z_s": ("m", "top (ship) sway motion"),
    # a vessel's small rotation about the node axes, moving several prescribed points (model/top_motion.py)
    "rot_x_s": ("rad", "vessel rotation about x"), "rot_y_s": ("rad", "vessel rotation about y (down)"),
    "rot_z_s": ("rad", "vessel rotation about z (x towards y)"),
    # a rigid, pitching body (model/rigid_body.py): x_b, y_b are its attachment point
    "theta_b": ("rad", "body pitch (x towards y) from its body axes along x, y"),
    "theta_b_rate": ("rad/s", "body pitch rate"),
    "x_cg": ("m", "body centre of gravity, horizontal position"), "x_cg_rate": ("m/s", "body centre of gravity, horizontal velocity"),
    "y_cg": ("m", "body centre of gravity, vertical position"), "y_cg_rate": ("m/s", "body centre of gravity, vertical velocity"),
    # a rigid body in space: R = R_y(yaw) R_z(pitch) R_x(roll) (model/rigid_body.attitude), theta_b its pitch
    "roll_b": ("rad", "body roll about its x axis"), "roll_b_rate": ("rad/s", "body roll rate"),
    "yaw_b": ("rad", "body yaw about the vertical"), "yaw_b_rate": ("rad/s", "body yaw rate"),
    "z_cg": ("m", "body centre of gravity, sway position"), "z_cg_rate": ("m/s", "body centre of gravity, sway velocity"),
    "omega_x_b": ("rad/s", "body angular velocity about its x axis"),
    "omega_y_b": ("rad/s", "body angular velocity about its y axis"),
    "omega_z_b": ("rad/s", "body angular velocity about its z axis"),
    "quat_w_b": ("1", "body orientation quaternion, scalar part"), "quat_x_b": ("1", "body orientation quaternion, x"),
    "quat_y_b": ("1", "body orientation quaternion, y"), "quat_z_b": ("1", "body orientation quaternion, z"),
    # the winch at the top of the first section (model/segmented_winch.py)
    "winch_length": ("m", "zero-tension length of the first section (paid out by the winch)"),
    "winch_speed": ("m/s", "winch payout speed (+ pays out)"),
    "winch_acceleration": ("m/s^2", "winch payout acceleration"),
    "winch_power": ("W", "winch power, top tension times payout speed (+ while paying out under tension)"),
}
UNITS = {k: v[0] for k, v in QUANTITIES.items()}


def _base(label: str) -> tuple[str, str]:
    """('phi', '2') for 'phi_2'; ('tension_mid', '') for 'tension_mid'."""
    head, _, tail = label.rpartition("_")
    return (head, tail) if tail.isdigit() and head else (label, "")


# a system of lines joined at points (model/system.py): ``point.NAME.x`` .. ``point.NAME.z_rate`` of every point,
# ``line.NAME.tension_from`` / ``tension_to`` of every line
_SYSTEM = re.compile(r"^(point|line)\.([A-Za-z][A-Za-z0-9_\-]*)\.(x|y|z|x_rate|y_rate|z_rate|tension_from|tension_to)$")
_SYSTEM_NAMES = {"x": ("m", "horizontal position of point {}"), "y": ("m", "depth of point {} (y down)"),
                 "z": ("m", "sway position of point {}"), "x_rate": ("m/s", "horizontal velocity of point {}"),
                 "y_rate": ("m/s", "vertical velocity of point {} (y down)"),
                 "z_rate": ("m/s", "sway velocity of point {}"),
                 "tension_from": ("N", "tension of line {} at its from end (its pull on that point)"),
                 "tension_to": ("N", "tension of line {} at its to end (its pull on that point)")}


# a rigid body at a system's point: ``point.NAME.theta_b``, ``point.NAME.x_cg``, ... (the chain's body quantities)
_SYSTEM_BODY = re.compile(r"^point\.([A-Za-z][A-Za-z0-9_\-]*)\.([a-z_]+)$")


def system_quantity(label: str):
    """(``"point"`` or ``"line"``, its name, quantity) of a system's output label (``point.buoy.x``,
    ``line.riser.tension_to``), or None for any other label."""
    m = _SYSTEM.match(label)
    return (m.group(1), m.group(2), m.group(3)) if m else None


def _system_body(label: str):
    """(point name, quantity) of a rigid body's quantity at a system's point, or None."""
    m = _SYSTEM_BODY.match(label)
    return (m.group(1), m.group(2)) if m and m.group(2) in QUANTITIES else None


def unit_of(label: str) -> str:
    """SI unit of a labelled quantity (``phi_2`` -> ``rad``, ``point.buoy.x`` -> ``m``); "" when unknown."""
    m = _SYSTEM.match(label)
    if m:
        return _SYSTEM_NAMES[m.group(3)][0]
    body = _system_body(label)
    if body:
        return UNITS[body[1]]
    return UNITS.get(_base(label)[0], "")


def long_name_of(label: str) -> str:
    """Long name of a labelled quantity (``phi_2`` -> ``cable angle ... (section 2)``)."""
    m = _SYSTEM.match(label)
    if m:
        return _SYSTEM_NAMES[m.group(3)][1].format(m.group(2))
    body = _system_body(label)
    if body:
        return f"{QUANTITIES[body[1]][1]} (point {body[0]})"
    base, k = _base(label)
    name = QUANTITIES.get(base, ("", label.replace("_", " ")))[1]
    return f"{name} (section {k})" if k and base in QUANTITIES else name


@runtime_checkable
class AnalysisResult(Protocol):
    """What every analysis result offers (see the module docstring)."""

    success: bool
    message: str
    stats: dict

    def to_xarray(self) -> Any: ...

    def summary(self) -> dict: ...


def _short(value) -> str:
    if isinstance(value, np.ndarray):
        return f"array{list(value.shape)} {value.dtype}"
    if isinstance(value, (tuple, list)):
        return f"{type(value).__name__}[{len(value)}]" if len(value) > 4 or any(
            isinstance(v, (np.ndarray, dict, tuple, list)) or dataclasses.is_dataclass(v) for v in value) else repr(value)
    if isinstance(value, dict):
        return f"dict[{len(value)}]"
    if dataclasses.is_dataclass(value):
        return f"<{type(value).__name__}>"
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def _jsonable(value):
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(value)
    if isinstance(value, (complex, np.complexfloating)):
        return {"real": float(value.real), "imag": float(value.imag)}
    if isinstance(value, str) or value is None:
        return value
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, (tuple, list)):
        return [_jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return _jsonable(value.tolist())
    return str(value)


def annotate(ds, variables: dict | None = None, result=None):
    """Fill ``units`` and ``long_name`` of every variable and coordinate of an xarray object.

    ``variables`` maps names to (unit, long name) and wins over :data:`QUANTITIES`; unknown
    names keep their name as long name and unit "1" (dimensionless). With ``result`` the
    attributes ``success``, ``message`` and ``stats`` (JSON) are added.

    Parameters
    ----------
    ds : xarray.Dataset or xarray.DataArray
        Modified in place.
    variables : dict, optional
        ``{name: (unit, long_name)}``.
    result : AnalysisResult, optional
        The result whose flag, message and statistics go into the attributes.

    Returns
    -------
    xarray.Dataset or xarray.DataArray
        ``ds`` itself.
    """
    table = {**{k: v for k, v in QUANTITIES.items()}, **(variables or {})}
    items = list(ds.coords.items())
    items += list(ds.data_vars.items()) if hasattr(ds, "data_vars") else [(ds.name, ds)]
    for name, var in items:
        unit, long = table.get(str(name), (unit_of(str(name)) or None, None))
        var.attrs.setdefault("units", unit or "1")
        var.attrs.setdefault("long_name", long or long_name_of(str(name)))
    if result is not None:
        ds.attrs.update(success=int(bool(result.success)), message=str(result.message),
                        stats=json.dumps(_jsonable(dict(result.stats))))
    return ds


class ResultBase:
    """Shared behaviour of the result dataclasses: short repr, ``summary()``, annotated ``to_xarray()``.

    A subclass's own ``to_xarray`` is wrapped so that its output is passed through
    :func:`annotate` with the class's ``VARIABLES``; its own ``summary`` (if any) replaces the
    default, which reports ``success``, ``message``, ``stats`` and the scalar fields.
    """

    VARIABLES: ClassVar[dict] = {}
    SUMMARY_EXCLUDE: ClassVar[tuple] = ()

    def __init_subclass__(cls, **kw):
        super().__init_subclass__(**kw)
        # dataclass(repr=True) keeps a __repr__ already in the class body: put the short one there
        if "__repr__" not in cls.__dict__:
            cls.__repr__ = ResultBase.__repr__
        own = cls.__dict__.get("to_xarray")
        if own is not None and not getattr(own, "_annotated", False):
            @functools.wraps(own)
            def to_xarray(self, *a, **k):
                return annotate(own(self, *a, **k), type(self).VARIABLES, self)
            to_xarray._annotated = True
            cls.to_xarray = to_xarray

    def __repr__(self) -> str:
        names = [f.name for f in dataclasses.fields(self)] if dataclasses.is_dataclass(self) else []
        head = [f"success={getattr(self, 'success', True)!r}"]
        msg = getattr(self, "message", "")
        if msg:
            head.append(f"message={_short(msg)}")
        body = [f"{n}={_short(getattr(self, n))}" for n in names if n not in ("success", "message", "stats")]
        return f"{type(self).__name__}({', '.join(head + body)})"

    def _repr_pretty_(self, printer, cycle):   # IPython / Jupyter
        printer.text(repr(self))

    def summary(self) -> dict:
        """JSON-able headline numbers: ``success``, ``message``, ``stats`` and the scalar fields.

        Returns
        -------
        dict
            Plain Python values (``json.dumps`` accepts it).
        """
        out = {"result": type(self).__name__, "success": bool(self.success), "message": str(self.message),
               "stats": _jsonable(dict(self.stats))}
        for f in dataclasses.fields(self):
            v = getattr(self, f.name)
            if f.name not in out and f.name not in self.SUMMARY_EXCLUDE and (
                    isinstance(v, (bool, int, float, str, np.generic)) and not isinstance(v, np.ndarray)):
                out[f.name] = _jsonable(v)
        return out


def timed(func):
    """Decorator for analysis functions: add ``stats['wall_time_s']`` (s) to the returned result.

    Parameters
    ----------
    func : callable
        Returns a frozen dataclass with a ``stats`` dict field.

    Returns
    -------
    callable
        The same function; its result is a copy with the wall time in ``stats``.
    """
    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        t0 = _time.perf_counter()
        res = func(*args, **kwargs)
        return dataclasses.replace(res, stats={**res.stats, "wall_time_s": _time.perf_counter() - t0})
    return wrapper
