"""The time-integration methods: one registry by name, and the protocol a user method follows.

A method is an :class:`IntegratorMethod`: which ``casadi.integrator`` plugin runs it, its fixed
plugin options, whether it controls its error (``rtol``, ``atol`` and the step budget apply) or
takes fixed steps (``steps_per_output``), and whether it integrates the implicit residual
M(q) q'' - f = 0 with q'' algebraic (a DAE plugin such as IDAS) instead of the explicit ODE.

The built-in methods are :data:`METHODS`, by the names a scene file uses
(``[numerics] integrator``). A user method is an instance passed where a name is accepted
(``IntegratorSettings(method=...)``, ``simulate(method=...)``), as
``scipy.integrate.solve_ivp`` accepts an ``OdeSolver`` subclass: no registration, no global
state. For example CVODES with a looser Newton convergence test::

    my_bdf = IntegratorMethod(name="cvodes-loose", plugin="cvodes",
                              options={"linear_multistep_method": "bdf", "nonlin_conv_coeff": 0.5})

This module is a leaf (no CasADi import): the scene validates names against it and
:mod:`cablesys.time_domain` builds the integrators.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

from .errors import ParameterError


@dataclasses.dataclass(frozen=True, kw_only=True)
class IntegratorMethod:
    """How to integrate a cablesys model in time.

    Parameters
    ----------
    name : str
        Label used in results, statistics and messages.
    plugin : str
        The ``casadi.integrator`` plugin (``cvodes``, ``idas``, ``collocation``, ``rk``, ...).
    options : Mapping
        Fixed plugin options (kept as sorted ``(key, value)`` pairs: hashable and picklable;
        :meth:`plugin_options` gives the dict); tolerances and step counts are added from
        the settings.
    adaptive : bool
        True: error-controlled steps (``rtol``, ``atol``, ``max_num_steps`` apply); False:
        ``steps_per_output`` fixed steps per output interval.
    implicit : bool
        True: integrate the residual M(q) q'' - f = 0 with q'' algebraic (a DAE plugin).
    """

    name: str
    plugin: str
    options: Mapping | tuple = ()
    adaptive: bool = True
    implicit: bool = False

    def __post_init__(self):
        if not isinstance(self.name, str) or not self.name:
            raise ParameterError("method.name", self.name, "must be a non-empty string")
        if not isinstance(self.plugin, str) or not self.plugin:
            raise ParameterError("method.plugin", self.plugin, "must name a casadi.integrator plugin")
        object.__setattr__(self, "options", tuple(sorted(dict(self.options).items())))

    def plugin_options(self) -> dict:
        """A fresh dict of the fixed plugin options.

        Returns
        -------
        dict
            Options for ``casadi.integrator``.
        """
        return dict(self.options)

    def __str__(self) -> str:
        return self.name


METHODS = {m.name: m for m in (
    # CVODES, BDF (variable order 1-5), Newton iterations: stiff-safe default
    IntegratorMethod(name="cvodes", plugin="cvodes",
                     options={"linear_multistep_method": "bdf", "nonlinear_solver_iteration": "newton"}),
    # CVODES, BDF of order <= 2 (A-stable): steps over undamped stiff oscillatory modes (the stretch
    # mode when C_I = 0) that orders 3-5 must resolve; cheapest at engineering tolerances (rtol >= 1e-5)
    IntegratorMethod(name="cvodes-bdf2", plugin="cvodes",
                     options={"linear_multistep_method": "bdf", "nonlinear_solver_iteration": "newton",
                              "max_order": 2}),
    # CVODES, Adams-Moulton: cheaper per step on non-stiff scenes
    IntegratorMethod(name="cvodes-adams", plugin="cvodes",
                     options={"linear_multistep_method": "adams", "nonlinear_solver_iteration": "newton"}),
    # IDAS on the implicit residual (q'' algebraic; M never inverted)
    IntegratorMethod(name="idas", plugin="idas", implicit=True),
    # classical fixed-step Runge-Kutta 4 (cablesys compiles it as one loop)
    IntegratorMethod(name="rk", plugin="rk", adaptive=False),
    # Runge-Kutta-Chebyshev, second order, fixed step with IntegratorSettings.stages stages: stable along the
    # negative real axis to ~0.65 stages^2 (the segmented cable's overdamped element modes; time_domain/rkc.py)
    IntegratorMethod(name="rkc", plugin="rk", adaptive=False),
    # Dormand-Prince 5(4), explicit, error-controlled: cablesys's own compiled C driver (not a
    # casadi.integrator plugin; time_domain/explicit_rk.py); CVODES when nothing is compiled
    IntegratorMethod(name="dopri5", plugin="dopri5"),
    # Bogacki-Shampine 3(2) (SciPy's RK23, MATLAB's ode23), explicit, error-controlled, in the same
    # compiled driver: 3 evaluations a step and stable on the imaginary axis to |h lambda| = sqrt(3)
    IntegratorMethod(name="rk23", plugin="rk23"),
    # fixed-step Radau collocation (implicit), for comparison
    IntegratorMethod(name="collocation", plugin="collocation", adaptive=False,
                     options={"collocation_scheme": "radau", "interpolation_order": 3}),
)}


def resolve(method, field: str = "method") -> IntegratorMethod:
    """The :class:`IntegratorMethod` of a name in :data:`METHODS`, or ``method`` itself.

    Parameters
    ----------
    method : str or IntegratorMethod
        A built-in name or a user method.
    field : str, optional
        Name of the input, for the error message.

    Returns
    -------
    IntegratorMethod
        The method.

    Raises
    ------
    ParameterError
        For an unknown name or another type.
    """
    if isinstance(method, IntegratorMethod):
        return method
    try:
        return METHODS[method]
    except (KeyError, TypeError):
        raise ParameterError(field, method, f"must be one of {tuple(METHODS)} or an IntegratorMethod") from None
