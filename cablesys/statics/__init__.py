"""Statics: equilibria of every model (the layer below both :mod:`cablesys.time_domain` and :mod:`cablesys.linear`).

- :func:`steady_state` the equilibrium of any model (2-DOF: KINSOL on (phi, u); segmented:
  the elastic catenary of :mod:`.catenary`; a system of lines joined at points: :mod:`.system`);
- :func:`elastic_catenary` the closed-form elastic catenary used to check it.
"""

from .catenary import hanging_guess, segmented_equilibrium
from .closed_forms import elastic_catenary
from .problem import SteadyState, static_residual
from .steady import steady_state

__all__ = ["SteadyState", "elastic_catenary", "hanging_guess", "segmented_equilibrium", "static_residual",
           "steady_state"]
