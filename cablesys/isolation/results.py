"""The result of an isolation design: optimal values, margins, active set, solver statistics."""

from __future__ import annotations

import dataclasses
from typing import ClassVar

import numpy as np

from ..results import ResultBase

_TEXT = {
    "slack": "mean tension minus n_sigma standard deviations above the tension floor TENS of section {i} (no slack)",
    "peak_tension": "mean tension plus n_sigma standard deviations below the working load of section {i}",
    "static_strain": "static stretch u_0 / l_0 of section {i} within its strain limit",
}


def describe_constraint(name: str, settings=None) -> str:
    """Human text of a constraint name such as ``static_strain_2``."""
    kind, i = name.rsplit("_", 1)
    text = _TEXT[kind].format(i=i)
    if settings is not None:
        k = int(i) - 1
        if kind == "peak_tension":
            text += f" ({settings.working_load[k]:.6g} N, n_sigma = {settings.n_sigma:g})"
        elif kind == "static_strain":
            text += f" ({settings.strain_limit[k]:.4g})"
        else:
            text += f" (n_sigma = {settings.n_sigma:g})"
    return text


@dataclasses.dataclass(frozen=True, eq=False)
class DesignResult(ResultBase):
    """Optimal design. ``constraint_values`` are g <= 0 (normalized); the margin is -g.

    ``success``: IPOPT succeeded and the outer drag fixed point settled (objective change <= outer_tol;
    with ``outer_iterations = 1`` only the NLP for the first held dJ is solved); ``message`` says
    which did not. ``stats``: ``wall_time_s``, ``iterations`` (IPOPT, all solves), ``nlp_wall_s``."""

    variable_names: tuple
    values: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    objective: float
    objective_kind: str
    constraint_names: tuple
    constraint_values: np.ndarray
    active: tuple
    sigma_y_b: float
    sigma_tension: np.ndarray
    mean_tension: np.ndarray
    static_strain: np.ndarray
    q0: np.ndarray
    parameters: np.ndarray
    jacobian_shift: np.ndarray       # dJ held in the last solve (see objective.py)
    status: str
    success: bool
    runs: tuple
    outer_history: tuple
    nlp_iterations: int
    nlp_wall_s: float
    total_wall_s: float
    stochastic_sig_y_b: float
    message: str = ""
    stats: dict = dataclasses.field(default_factory=dict)

    VARIABLES: ClassVar[dict] = {"value": ("SI", "optimal value of the design variable"), "lower": ("SI", "lower bound"),
                                  "upper": ("SI", "upper bound"), "variable": ("1", "design variable"),
                                  "constraint": ("1", "constraint"), "margin": ("1", "normalized constraint margin -g (>= 0 met)")}

    @property
    def converged(self) -> bool:
        """Alias of :attr:`success`."""
        return self.success

    def summary(self) -> dict:
        """The JSON document of :meth:`to_dict` with ``success``, ``message`` and ``stats``.

        Returns
        -------
        dict
            JSON-able.
        """
        return {**super().summary(), **self.to_dict()}

    def to_xarray(self):
        """Variables with bounds (dim ``variable``) and constraint margins (dim ``constraint``).

        Returns
        -------
        xarray.Dataset
        """
        import xarray as xr
        return xr.Dataset({"value": ("variable", self.values), "lower": ("variable", self.lower),
                           "upper": ("variable", self.upper), "margin": ("constraint", -self.constraint_values)},
                          coords={"variable": list(self.variable_names), "constraint": list(self.constraint_names)},
                          attrs={"objective": self.objective, "objective_kind": self.objective_kind})

    @property
    def margins(self) -> dict:
        """Constraint margins (>= 0 means met), by name."""
        return {n: float(-g) for n, g in zip(self.constraint_names, self.constraint_values)}

    def value(self, name: str) -> float:
        return float(self.values[self.variable_names.index(name)])

    def to_dict(self) -> dict:
        return {
            "converged": self.success, "status": self.status, "message": self.message,
            "objective": self.objective, "objective_kind": self.objective_kind,
            "variables": {n: {"value": float(v), "lower": float(lo), "upper": float(hi)}
                          for n, v, lo, hi in zip(self.variable_names, self.values, self.lower, self.upper)},
            "constraint_margins": self.margins, "active": list(self.active),
            "significant_y_b_m": 2 * self.sigma_y_b, "significant_y_b_stochastic_m": self.stochastic_sig_y_b,
            "mean_tension_N": [float(a) for a in self.mean_tension],
            "std_tension_N": [float(a) for a in self.sigma_tension],
            "static_strain": [float(a) for a in self.static_strain],
            "nlp_iterations": self.nlp_iterations, "nlp_wall_s": self.nlp_wall_s, "total_wall_s": self.total_wall_s,
            "outer_history": list(self.outer_history), "runs": list(self.runs),
        }
