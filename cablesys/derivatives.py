"""Derivative functions restricted to some inputs, under the names CasADi gives them, for code generation.

A compiled library serves a solver what it asks of a function: an integrator or a Newton solver its Jacobian with
respect to the states (``jac_<out>_<in>``), an NLP loaded through ``casadi.external`` its forward, adjoint and
forward-over-adjoint derivatives (``fwd1_``, ``adj1_``, ``fwd1_adj1_``). CasADi's own derivatives are with respect
to every input, whose count grows with the scene's parameters; these are the same signatures with only the
blocks of the inputs named (the others structurally zero), so the generated C stays small (:mod:`cablesys.compiled`).
A library built from them must not be used for sensitivities to the other inputs: those read as zero.
"""

from __future__ import annotations

import casadi as ca

__all__ = ["state_derivatives", "state_forward", "state_jacobian", "state_reverse"]


def state_jacobian(f: ca.Function, wrt) -> ca.Function:
    """``f.jacobian()``'s signature with only the blocks with respect to the inputs ``wrt``;
    every other block is declared structurally zero.

    What an integrator or a Newton solver asks of its residual is the state blocks (d/dx,
    d/dz); the full Jacobian also carries d/dp, whose size grows with the number of scene
    parameters (a 305-sample series: 610 columns, most of 1.6 MB of C, and every Jacobian
    evaluation paying for them). A library built this way must not be used for parameter
    sensitivities: those blocks read as zero.
    """
    J = f.jacobian()
    X = ca.MX if f.is_a("MXFunction") else ca.SX     # an MX function (mapped kernels) keeps its loops
    ins = _symbols_like(J, X)
    vals = f.call(ins[: f.n_in()])
    outs = []
    for k, name in enumerate(J.name_out()):          # jac_<output>_<input>
        o = next(o for o in f.name_out() if name.startswith(f"jac_{o}_"))
        i = name[len(f"jac_{o}_"):]
        if i in wrt:
            outs.append(ca.jacobian(vals[f.name_out().index(o)], ins[f.name_in().index(i)]))
        else:
            outs.append(X(J.sparsity_out(k).size1(), J.sparsity_out(k).size2()))
    return ca.Function(J.name(), ins, outs, J.name_in(), J.name_out())


def _symbols_like(F: ca.Function, X=ca.SX) -> list:
    """Symbols (``X``: SX or MX) with the names and sparsities of ``F``'s inputs."""
    return [X.sym(name, F.sparsity_in(i)) for i, name in enumerate(F.name_in())]


def state_forward(f: ca.Function, wrt) -> ca.Function:
    """``f.forward(1)``'s signature (``fwd1_<name>``, CasADi's name for the forward derivative an external
    function looks up in its library) with the seeds of the inputs ``wrt`` only; the seeds of every
    other input are ignored (read as zero). ``f`` must be an SX function.

    The directional derivative is J_wrt s_wrt (CasADi's ``jtimes``, forward mode). As with
    :func:`state_jacobian`, a library built this way serves derivatives with respect to ``wrt`` (the
    decision variables of an NLP) and must not be used for sensitivities to the other inputs."""
    F = f.forward(1)
    ins = _symbols_like(F)
    n, m = f.n_in(), f.n_out()
    nominal, seeds = ins[:n], ins[n + m:]
    keep = [i for i in range(n) if f.name_in(i) in wrt]
    z = ca.vertcat(*(ca.vec(nominal[i]) for i in keep))
    s = ca.vertcat(*(ca.vec(seeds[i]) for i in keep))
    outs = [ca.reshape(ca.jtimes(ca.vec(o), z, s), o.shape) for o in f.call(nominal)]
    return ca.Function(F.name(), ins, outs, F.name_in(), F.name_out())


def state_reverse(f: ca.Function, wrt) -> ca.Function:
    """``f.reverse(1)``'s signature (``adj1_<name>``) with the adjoint sensitivities of the inputs ``wrt``
    (J_wrt^T a, reverse mode) and structurally zero ones for every other input (see :func:`state_forward`)."""
    R = f.reverse(1)
    ins = _symbols_like(R)
    n, m = f.n_in(), f.n_out()
    nominal, seeds = ins[:n], ins[n + m:]
    o = ca.vertcat(*(ca.vec(v) for v in f.call(nominal)))
    a = ca.vertcat(*(ca.vec(v) for v in seeds))
    outs = [ca.reshape(ca.jtimes(o, ca.vec(nominal[i]), a, True), nominal[i].shape) if f.name_in(i) in wrt
            else ca.SX(*R.size_out(i)) for i in range(n)]
    return ca.Function(R.name(), ins, outs, R.name_in(), R.name_out())


def state_derivatives(f: ca.Function, wrt) -> list:
    """``[f, fwd1_f, adj1_f, fwd1_adj1_f]``: what an NLP's exact first and second derivatives with respect
    to the inputs ``wrt`` need of ``f`` once it is compiled and loaded with ``casadi.external`` (which finds
    its derivatives in the same library by these names): the forward and adjoint derivatives
    (:func:`state_forward`, :func:`state_reverse`) and the forward derivative of the adjoint
    (forward-over-reverse, the Hessian-vector products of the Lagrangian; Griewank & Walther,
    *Evaluating Derivatives*, 2nd ed., sec. 5.2), all restricted to ``wrt``. Far smaller than the
    Jacobians with respect to every input and their Jacobians (third derivatives)."""
    adj = state_reverse(f, wrt)
    seeds = tuple(adj.name_in()[f.n_in() + f.n_out():])      # adj_<output>: the multipliers
    return [f, state_forward(f, wrt), adj, state_forward(adj, tuple(wrt) + seeds)]
