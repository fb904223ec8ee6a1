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

__all__ = ["relative_time_dae", "relative_time_jacobian"]


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


def relative_time_jacobian(model: CableModel, dae: ca.Function, scaled: bool = False) -> ca.Function:
    """``jac_<name>`` of the element-kernel DAE ``dae`` (:func:`relative_time_dae` with ``kernel``), in the signature
    of ``dae.jacobian()`` (what ``casadi.external`` finds beside the DAE in a compiled library, and an integrator asks
    of it), with the state block from the model's ``kernel_jacobian`` (the chain rule over the elements' AD,
    :func:`cablesys.model.segmented_kernel.kernel_jacobian`) instead of AD of the whole mapped function:
    d x~'/d x~ = h diag(1 / S) J(S x~) diag(S) (S = 1 unscaled). Every other block is structurally zero, as in
    :func:`cablesys.derivatives.state_jacobian` (the explicit form has no z): a library built with it serves the
    integrators, never parameter sensitivities."""
    jac = model.kernel_jacobian
    if jac is None or model.loop_ode is not model.kernel_ode:
        raise ValueError("the model has no element-kernel Jacobian for its loop_ode")
    ins = [ca.MX.sym(n, dae.sparsity_in(i)) for i, n in enumerate(dae.name_in())]
    # the nominal outputs the signature passes in, unused (no nonzeros, as CasADi declares them)
    ins += [ca.MX.sym(f"out_{n}", ca.Sparsity(*dae.size_out(i))) for i, n in enumerate(dae.name_out())]
    s, x, p = ins[dae.name_in().index("t")], ins[dae.name_in().index("x")], ins[dae.name_in().index("p")]
    pm, t0, h = p[:-2], p[-2], p[-1]
    S = state_scales(model)(pm) if scaled else ca.MX.ones(x.shape[0])
    J = jac(S * x, t0 + h * s, pm)
    sp = J.sparsity()
    rows, cols = sp.get_triplet()
    # J's nonzeros times h / S_row * S_col, in J's own (column-major) order
    block = ca.MX(sp, J.nz[:] * h * S[list(cols)] / S[list(rows)]) if scaled else h * J
    outs, names = [], []
    for o in range(dae.n_out()):
        for i in range(dae.n_in()):
            names.append(f"jac_{dae.name_out(o)}_{dae.name_in(i)}")
            stateful = dae.name_out(o) == "ode" and dae.name_in(i) == "x"
            outs.append(block if stateful else ca.MX(dae.numel_out(o), dae.numel_in(i)))
    return ca.Function(f"jac_{dae.name()}", ins, outs, dae.name_in() + [f"out_{n}" for n in dae.name_out()], names)
