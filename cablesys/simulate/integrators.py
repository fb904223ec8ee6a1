"""Integrator registry: one name per method, all behind ``casadi.integrator``.

- ``cvodes``        CVODES, BDF (variable order 1-5), Newton iterations: stiff-safe default;
- ``cvodes-adams``  CVODES, Adams-Moulton: cheaper per step on non-stiff scenes;
- ``idas``          IDAS on the implicit residual M(q) q'' - f = 0 (q'' algebraic; M never inverted);
- ``rk``            classical fixed-step Runge-Kutta 4, for comparison;
- ``collocation``   fixed-step Radau collocation (implicit), for comparison.

Every integrator runs in relative time s with the parameter vector extended by (t_0, h):
physical time t = t_0 + h s. With h = 1 the grid is in seconds from t_0 (one call over all
output times); with the grid (0, 1) the same integrator steps one interval of any length h,
which the slack-event location and the failure fallback use.
"""

from __future__ import annotations

import dataclasses

import casadi as ca
import numpy as np

from ..errors import ParameterError
from ..model import CableModel

METHODS = {
    "cvodes": ("cvodes", {"linear_multistep_method": "bdf", "nonlinear_solver_iteration": "newton"}),
    "cvodes-adams": ("cvodes", {"linear_multistep_method": "adams", "nonlinear_solver_iteration": "newton"}),
    "idas": ("idas", {}),
    "rk": ("rk", {}),
    "collocation": ("collocation", {"collocation_scheme": "radau", "interpolation_order": 3}),
}
ADAPTIVE = ("cvodes", "cvodes-adams", "idas")


@dataclasses.dataclass(frozen=True)
class IntegratorSettings:
    """Method and accuracy settings (immutable)."""

    method: str = "cvodes"
    rtol: float = 1e-8
    atol: float = 1e-10
    steps_per_output: int = 10        # fixed-step methods only
    max_num_steps: int = 100000
    jit: bool = False                 # compile the DAE with the C compiler (about 3x faster, ~1 s build each)

    def __post_init__(self):
        if self.method not in METHODS:
            raise ParameterError("method", self.method, f"must be one of {tuple(METHODS)}")


def _dae(model: CableModel, implicit: bool):
    """The DAE in relative time s: x' = h * ode(x, t0 + h s), parameters (p, t0, h)."""
    x = model.sym("x", 2 * model.nq)
    s = model.sym("s")
    p = model.sym("p", len(model.layout))
    t0, h = model.sym("t0"), model.sym("h")
    t = t0 + h * s
    q, qd = x[: model.nq], x[model.nq:]
    pa = ca.vertcat(p, t0, h)
    if not implicit:
        return {"x": x, "t": s, "p": pa, "ode": h * model.ode(x, t, p)}
    z = model.sym("qdd", model.nq)
    M, f = model.dynamics(q, qd, model.top(t, p), p)
    return {"x": x, "z": z, "t": s, "p": pa, "ode": h * ca.vertcat(qd, z), "alg": ca.mtimes(M, z) - f}


def make_integrator(model: CableModel, settings: IntegratorSettings, grid, name: str = "F") -> ca.Function:
    """A CasADi integrator over the relative ``grid`` (first entry 0 excluded from outputs)."""
    plugin, opts = METHODS[settings.method]
    opts = dict(opts)
    grid = np.asarray(grid, dtype=float)
    if settings.method in ADAPTIVE:
        opts.update(reltol=settings.rtol, abstol=settings.atol, max_num_steps=settings.max_num_steps)
        if settings.method == "idas":
            # q'' is algebraic (index 1): its accuracy follows from q', so keep it out of the error test
            opts.update(calc_ic=True, suppress_algebraic=True)
    else:
        opts["number_of_finite_elements"] = int(settings.steps_per_output * (len(grid) - 1))
        if settings.method == "collocation":
            opts["rootfinder"] = "newton"   # the q'' system is small and dense
    opts["print_stats"] = False
    if settings.jit:
        opts.update(jit=True, compiler="shell", jit_options={"flags": ["-O2"], "verbose": False})
    dae = _dae(model, settings.method == "idas")
    return ca.integrator(name, plugin, dae, float(grid[0]), list(grid[1:]), opts)
