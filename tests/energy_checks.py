"""A conservative run's energy history, shared by the energy-conservation tests of the node model's bodies."""

import numpy as np

from cablesys.time_domain import simulate
from cablesys.time_domain.integrators import IntegratorSettings
from cablesys.time_domain.run import Simulator


def energy_history(scene, model, p, x0, x_static):
    """Run ``scene`` from ``x0`` with CVODES Adams at rtol 1e-11 (the VM) and return (result, E, swing): the total
    energy K + V (J) at every output time, through the model's own ``energy`` with the top at its t = 0 position, and
    the swing energy E(0) - E(x_static) (J) that a drift is measured against."""
    sim = Simulator(model, scene.output_times, IntegratorSettings(method="cvodes-adams", rtol=1e-11, atol=1e-13,
                                                                  compiled=False))
    r = simulate(scene, model=model, x0=x0, simulator=sim)
    assert r.success
    e0 = np.array(model.top(0.0, p)).ravel()
    E = np.array([sum(float(v) for v in model.energy(x, e0, p)) for x in r.states.T])
    return r, E, E[0] - sum(float(v) for v in model.energy(x_static, e0, p))
