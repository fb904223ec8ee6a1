"""Response amplitude operators: complex output amplitudes per unit input, on labelled arrays.

As in Capytaine's ``post_pro/rao.py``, an RAO is a complex array with dimensions
(omega, output, input); amplitude and phase are two small pure functions of it. The
phase convention: output = Re(RAO * A e^{i omega t}) for input Re(A e^{i omega t}).
"""

from __future__ import annotations

import dataclasses
from typing import ClassVar

import numpy as np

from ..result_protocol import system_quantity
from ..results import ResultBase, timed, unit_of
from .linearization import LinearModel

def response_outputs(labels, scene=None) -> list:
    """The outputs an RAO table or a sea response reports unless told: the body's motion (``x_b``, ``y_b``, ``z_b`` of
    each section) and the tensions (``tension_*``), rates left out; for a system of lines (``scene.system``) every
    point's coordinates (``point.NAME.x`` ...) but those of its held points (prescribed: the input itself; fixed:
    zero) and every line's end tensions (:func:`cablesys.result_protocol.system_quantity`)."""
    held = {p.name for p in scene.system.point if p.held} if getattr(scene, "system", None) is not None else set()
    out = []
    for o in labels:
        q = system_quantity(o)
        if (o.startswith(("x_b", "y_b", "z_b", "tension")) and not o.endswith("rate")) or (q is not None and (
                q[0] == "line" or (q[2] in ("x", "y", "z") and q[1] not in held))):
            out.append(o)
    return out


def is_tension(label: str) -> bool:
    """Whether ``label`` is a tension (N): a chain's ``tension_*`` or a system's ``line.NAME.tension_from`` / ``_to``."""
    return unit_of(label) == "N"


@dataclasses.dataclass(frozen=True, eq=False)
class RAO(ResultBase):
    """Complex RAO ``values[k, j, i]``: output j per unit input i at ``omega[k]``."""

    omega: np.ndarray
    output_labels: tuple
    input_labels: tuple
    values: np.ndarray
    kind: str = "exact"
    info: dict = dataclasses.field(default_factory=dict)
    success: bool = True
    message: str = ""
    stats: dict = dataclasses.field(default_factory=dict)

    VARIABLES: ClassVar[dict] = {"rao": ("output unit per input unit", "response amplitude operator (complex)"),
                                  "output_units": ("1", "SI unit of each output"), "output": ("1", "output"), "input": ("1", "input")}

    def __call__(self, output: str, input: str) -> np.ndarray:
        """The complex RAO curve of one output for one input."""
        return self.values[:, self.output_labels.index(output), self.input_labels.index(input)]

    def amplitude(self, output: str, input: str) -> np.ndarray:
        return np.abs(self(output, input))

    def phase(self, output: str, input: str) -> np.ndarray:
        """Phase in rad, unwrapped along omega."""
        return np.unwrap(np.angle(self(output, input)))

    def peak(self, output: str, input: str) -> tuple[float, float]:
        """(omega, amplitude) of the largest amplitude on the grid."""
        a = self.amplitude(output, input)
        k = int(np.argmax(a))
        return float(self.omega[k]), float(a[k])

    def to_xarray(self):
        """``xarray.DataArray`` (complex) with dims omega, output, input."""
        import xarray as xr
        return xr.DataArray(self.values, dims=("omega", "output", "input"),
                            coords={"omega": ("omega", self.omega, {"units": "rad/s"}),
                                    "output": list(self.output_labels), "input": list(self.input_labels),
                                    "output_units": ("output", [unit_of(o) for o in self.output_labels])},
                            name="rao", attrs={"kind": self.kind})

    def table(self, input: str) -> tuple[list[str], np.ndarray]:
        """(header, rows) for CSV: omega, then amplitude (per m of top motion; per rad of a vessel's rotation
        ``rot_*_s``) and phase (deg) of every output."""
        head = ["omega [rad/s]"]
        cols = [self.omega]
        per = unit_of(input) or "m"
        for o in self.output_labels:
            u = unit_of(o) or "-"
            head += [f"{o}_amp [{u}/{per}]", f"{o}_phase [deg]"]
            cols += [self.amplitude(o, input), np.degrees(self.phase(o, input))]
        return head, np.column_stack(cols)


def amplitude(rao_values: np.ndarray) -> np.ndarray:
    """|RAO|."""
    return np.abs(rao_values)


def phase(rao_values: np.ndarray) -> np.ndarray:
    """arg RAO in rad."""
    return np.angle(rao_values)


@timed
def rao(lin: LinearModel, omega) -> RAO:
    """RAOs of every output of ``lin`` for every input, one batched complex solve over ``omega``.

    Y(omega) = (Cq + i omega Cv) Q + D0 + i omega D1 - omega^2 D2 with
    (K + i omega C - omega^2 M) Q = F0 + i omega F1 - omega^2 F2.

    Parameters
    ----------
    lin : LinearModel
        The linear model (:func:`linearize`, or an equivalent linearization).
    omega : array_like
        Angular frequencies (rad/s).

    Returns
    -------
    RAO
        Complex output amplitude per unit input amplitude, dims (omega, output, input).
    """
    omega = np.atleast_1d(np.asarray(omega, float))
    _, Y = lin.transfer(omega)
    return RAO(omega=omega, output_labels=lin.output_labels, input_labels=lin.input_labels, values=Y, kind=lin.kind)
