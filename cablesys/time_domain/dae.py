"""The model's equations of motion in relative time, in the signature of ``casadi.integrator``.

Every integrator of :mod:`.integrators` (CVODES, IDAS, collocation, the RK4 loop) and the compiled
explicit driver of :mod:`.explicit_rk` integrate this one function: physical time t = t_0 + h s,
the parameter vector extended by (t_0, h), and optionally the scaled states x / S(p) of
:mod:`cablesys.model.scales`. It lives apart from both so that neither imports the other.
"""

from __future__ import annotations

import casadi as ca

from ..model import CableModel
from ..model.scales import state_scales

__all__ = ["relative_time_dae"]


def relative_time_dae(model: CableModel, implicit: bool, scaled: bool = False, kernel: bool = False) -> ca.Function:
    """The DAE in relative time s as a CasADi function with the integrator's signature
    (``ca.dyn_in()`` -> ``ca.dyn_out()``): x' = h * ode(x, t0 + h s), parameters (p, t0, h);
    implicit form: x' = h (q', q''), 0 = M(q) q'' - f.

    ``scaled``: the same DAE in the states x~ = x / S(p) (S = :func:`~cablesys.model.scales.state_scales`,
    computed from p inside the function, so one compiled DAE serves every parameter value):
    x~' = h ode(S x~) / S; implicit: z~ = q'' / S_rate, x~' = h (q' / S_q, z~), 0 = M(q) (S_rate z~) - f.

    ``kernel`` (explicit form only): the ODE is the model's ``loop_ode``, the segmented cable's element kernel
    mapped over its elements (:mod:`cablesys.model.segmented_kernel`), and the function is MX, so that its C and
    its Jacobian's stay loops over the elements instead of growing into straight-line code with N.
    """
    if kernel and implicit:
        raise ValueError("the element kernel gives the explicit form x' = f(x) only")
    X = ca.MX if kernel else ca.SX
    x = X.sym("x", 2 * model.nq)
    s = X.sym("t")
    p = X.sym("p", len(model.layout) + 2)
    pm, t0, h = p[:-2], p[-2], p[-1]
    t = t0 + h * s
    S = state_scales(model)(pm) if scaled else X.ones(2 * model.nq)
    xs = S * x if scaled else x
    q, qd = xs[: model.nq], xs[model.nq:]
    u = X.sym("u", 0)
    empty = X(0, 1)
    if not implicit:
        z = X.sym("z", 0)
        ode, alg = h * (model.loop_ode if kernel else model.ode)(xs, t, pm), empty
        if scaled:
            ode = ode / S
    else:
        z = ca.SX.sym("z", model.nq)
        zs = S[model.nq:] * z if scaled else z
        M, f = model.dynamics(q, qd, model.top(t, pm), pm)
        ode, alg = h * ca.vertcat(qd, zs), ca.mtimes(M, zs) - f
        if scaled:
            ode = ode / S
    name = ("cablesys_dae_implicit" if implicit else "cablesys_dae") + ("_scaled" if scaled else "")
    return ca.Function(name, [s, x, z, p, u], [ode, alg, empty, empty], ca.dyn_in(), ca.dyn_out())
