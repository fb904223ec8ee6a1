"""The per-interval functions of the heave-compensation NLP (:mod:`.payout`) and their compiled kernels.

One control interval of ``dt`` seconds is ``substeps`` classical RK4 steps (Hairer, Norsett & Wanner, *Solving
ODEs I*, sec. II.1, Table 1.2) of the winch ODE with alpha constant and the top motion read from the tabulated
exogenous vector E, plus the stage cost and the path outputs at the interval start (the objective and
constraints of :mod:`.payout`'s module docstring). The functions take the scene's numbers as inputs (p, c and
w = (heave at rest, T_0, c_T, c_a, dt)), so each depends on the model's structure only and one compiled library
serves every scene value (:func:`interval_kernels`, :func:`substep_kernels`, :func:`gauss_newton_kernel`;
libraries by :func:`cablesys.compiled.compile_functions`, derivatives restricted to (x, u) by
:func:`cablesys.derivatives.state_derivatives`). Without a compiler (``CABLESYS_COMPILE=0``) the NLP keeps the
SX functions with the numbers inlined, in CasADi's virtual machine.
"""

from __future__ import annotations

import casadi as ca

from ..compiled import compile_functions, compiles
from ..derivatives import state_derivatives
from ..disk_cache import digest
from ..model.winch import WINCH_OUTPUTS


# rows of the stage function's path outputs g: the power, the tension the no-slack floor bounds (the model's
# ``floor_output``: Wang's F_bc "tension_mid", the node model's least element tension), the top tension
G_ROWS = ("power", "tension_floor", "tension_top")

# optimization flag of the kernels (see interval_kernels)
KERNEL_OPTIMIZATION = "-O1"
# compiled kernels by the serialized interval function (its structure: the scene numbers are its inputs),
# the KERNELS_KEPT most recent (a loaded library is not checked and opened again on every MPC step)
_KERNELS: dict = {}
KERNELS_KEPT = 8

# more RK4 steps per interval than this: the NLP calls one compiled step kernel per step (nlp_functions)
# instead of one kernel of the whole interval, whose C grows with the steps
SUBSTEP_KERNELS_FROM = 4


def output_labels(model) -> tuple:
    """The rows of ``model.outputs``: :data:`WINCH_OUTPUTS` (the node model adds ``tension_least``)."""
    return getattr(model, "output_labels", WINCH_OUTPUTS)


def floor_output(model) -> str:
    """The output the no-slack floor bounds: the 2-DOF model's spring force F_bc (``tension_mid``, Wang 1971 eq.
    54), the node model's least element tension (``tension_least``)."""
    return getattr(model, "floor_output", "tension_mid")


def interval_functions(model, dt, substeps, p, c, y_rest, tension_weight, control_weight):
    """(step, stage, interval, substep, start) of one control interval; step and stage are SX functions of
    (x, alpha, E_k) with the numbers inlined; substep and start those of :func:`substep_functions`.

    ``interval(x, u, E, p, c, w) -> (x_next, cost, g)``: ``substeps`` classical RK4 steps of the
    winch ODE with alpha = u constant and the top motion read from E (:meth:`.payout.HeaveProblem.exogenous`:
    e at the 2 substeps + 1 stage times), the stage cost at the interval start and the path outputs
    (:data:`G_ROWS`); w = (heave at rest, T_0, c_T, c_a, dt).
    """
    ne = 7
    substep, start = substep_functions(model, len(p), len(c))
    xs, uk = ca.SX.sym("x", model.nx), ca.SX.sym("u")
    Es = ca.SX.sym("E", ne * (2 * substeps + 1))
    ps, cs, ws = ca.SX.sym("p", len(p)), ca.SX.sym("c", len(c)), ca.SX.sym("w", 5)
    h = ws[4] / substeps
    x = xs
    for i in range(substeps):                       # classical RK4, the top at its stage times 2i, 2i+1, 2i+2
        x = substep(x, uk, Es[ne * 2 * i: ne * (2 * i + 3)], ps, cs, h)
    cost, g = start(xs, uk, Es[:ne], ps, cs, ws)
    interval = ca.Function("interval", [xs, uk, Es, ps, cs, ws], [x, cost, g],
                           ["x", "u", "E", "p", "c", "w"], ["xn", "cost", "g"])
    w = ca.DM([y_rest["heave"], y_rest["tension_top"], tension_weight, control_weight, dt])
    xa, ua, ra = ca.SX.sym("x", model.nx), ca.SX.sym("u"), ca.SX.sym("E", Es.numel())
    xn, cost, g = interval(xa, ua, ra, ca.DM(p), ca.DM(c), w)
    step = ca.Function("step", [xa, ua, ra], [xn])
    stage = ca.Function("stage", [xa, ua, ra], [cost, g])
    return step, stage, interval, substep, start


def substep_functions(model, n_p: int, n_c: int):
    """(substep, start): one classical RK4 step ``(x, u, E_j, p, c, h) -> x_next`` of the winch ODE with alpha
    = u and the top at the step's 3 stage times (E_j, 21 rows), and the stage cost and path outputs at the
    interval start ``(x, u, e, p, c, w) -> (cost, g)``, as in :func:`interval_functions`."""
    nq, ne = model.nq, 7
    x, u, E = ca.SX.sym("x", model.nx), ca.SX.sym("u"), ca.SX.sym("E", 3 * ne)
    p, c, h, w = ca.SX.sym("p", n_p), ca.SX.sym("c", n_c), ca.SX.sym("h"), ca.SX.sym("w", 5)

    def f(xx, j):
        qdd = model.accel(xx[:nq], xx[nq:2 * nq], E[ne * j: ne * (j + 1)],
                          ca.vertcat(xx[2 * nq], xx[2 * nq + 1], u, 0.0), p, c)
        return ca.vertcat(xx[nq:2 * nq], qdd, xx[2 * nq + 1], u)
    k1 = f(x, 0)
    k2 = f(x + h / 2 * k1, 1)
    k3 = f(x + h / 2 * k2, 1)
    k4 = f(x + h * k3, 2)
    names = ["x", "u", "E", "p", "c"]
    substep = ca.Function("ocp_rk4", [x, u, E, p, c, h], [x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)], names + ["h"], ["xn"])
    e0 = ca.SX.sym("e", ne)
    y = model.outputs_e(x[:nq], x[nq:2 * nq], e0, ca.vertcat(x[2 * nq], x[2 * nq + 1], u, 0.0), p, c)
    oi = output_labels(model).index
    cost = w[4] * ((y[oi("heave")] - w[0]) ** 2 + w[2] * ((y[oi("tension_top")] - w[1]) / w[1]) ** 2 + w[3] * u ** 2)
    g = ca.vertcat(*(y[oi(floor_output(model) if name == "tension_floor" else name)] for name in G_ROWS))
    start = ca.Function("ocp_start", [x, u, e0, p, c, w], [cost, g], ["x", "u", "e", "p", "c", "w"], ["cost", "g"])
    return substep, start



def interval_kernels(interval: ca.Function):
    """The compiled per-interval kernels of ``interval`` (:func:`interval_functions`), a
    :class:`cablesys.compiled.Compiled` with ``ocp_step`` (x, u, E, p, c, w) -> x_{k+1} and ``ocp_stage``
    -> (cost, g), each with its forward, adjoint and forward-over-adjoint derivatives with respect to
    (x, u) (:func:`cablesys.derivatives.state_derivatives`) in the same library, where ``casadi.external``
    finds them. The NLP maps them over its intervals (``Function.map`` in :class:`.shooting.ShootingNLP`),
    so one small kernel serves every interval. None when nothing is compiled (``CABLESYS_COMPILE=0``, no
    compiler), and a ``Compiled`` with ``compiled`` False when compilation failed: the callers then keep
    the inlined SX functions."""
    if not compiles():
        return None
    key = digest(interval.serialize())
    kernels = _KERNELS.get(key)
    if kernels is None:
        x, u, e, p, c, w = (ca.SX.sym(n, interval.sparsity_in(i)) for i, n in enumerate(interval.name_in()))
        xn, cost, g = interval(x, u, e, p, c, w)
        names = ["x", "u", "E", "p", "c", "w"]
        step = ca.Function("ocp_step", [x, u, e, p, c, w], [xn], names, ["xn"])
        stage = ca.Function("ocp_stage", [x, u, e, p, c, w], [cost, g], names, ["cost", "g"])
        functions = state_derivatives(step, ("x", "u")) + state_derivatives(stage, ("x", "u"))
        # -O1: Hessians as fast as at -O2 for a fraction of its compile; -O0 compiles sooner with slower Hessians
        kernels = _compiled_kernels(key, functions)
    return kernels



def substep_kernels(substep: ca.Function, start: ca.Function):
    """The compiled ``ocp_rk4`` and ``ocp_start`` of :func:`substep_functions`, each with its forward, adjoint
    and forward-over-adjoint derivatives with respect to (x, u), as :func:`interval_kernels`; None when nothing
    is compiled."""
    if not compiles():
        return None
    key = digest(substep.serialize() + start.serialize())
    return _KERNELS.get(key) or _compiled_kernels(
        key, state_derivatives(substep, ("x", "u")) + state_derivatives(start, ("x", "u")))


def _compiled_kernels(key, functions):
    """``functions`` compiled (:data:`KERNEL_OPTIMIZATION`) and kept under ``key`` in the KERNELS_KEPT cache."""
    kernels = compile_functions(functions, jacobians=False, optimization=KERNEL_OPTIMIZATION)
    if kernels.compiled:
        keep_recent(_KERNELS, key, kernels)
    return kernels


def keep_recent(cache: dict, key, value, kept: int = KERNELS_KEPT) -> None:
    """``cache[key] = value``, the oldest entries dropped first (dicts keep insertion order) to keep ``kept``: the
    in-memory caches of loaded kernel libraries (a library is not checked and opened again on every call)."""
    while len(cache) >= kept:
        cache.pop(next(iter(cache)))
    cache[key] = value



def nlp_functions(problem):
    """(step, stage, compiled) of a :class:`.payout.HeaveProblem`: the NLP's (x, alpha, E_k) -> x_{k+1} and
    -> (cost, g).

    Compiled (:func:`interval_kernels`): MX functions that call the compiled per-interval kernels with
    the problem's numbers (p, c and w = (heave at rest, T_0, c_T, c_a, dt)) as inputs, so one
    library per model structure serves every scene value, and the NLP's derivatives are the kernels'
    compiled forward, adjoint and forward-over-adjoint derivatives with respect to (x, alpha) only.
    More RK4 steps per interval than :data:`SUBSTEP_KERNELS_FROM`: one compiled RK4 step called ``substeps``
    times (:func:`substep_kernels`); the C of a whole interval of the node model's stiff steps is too large to
    compile (54 MB at N = 4 with 11 steps), one step's is a substeps-th of it.
    In CasADi's virtual machine: the problem's ``step`` and ``stage`` (the numbers inlined, SX)."""
    pr = problem
    many = pr.substeps > SUBSTEP_KERNELS_FROM
    kernels = substep_kernels(pr.substep, pr.start) if many else interval_kernels(pr.interval)
    if kernels is None or not kernels.compiled:
        return pr.step, pr.stage, False
    f = kernels.functions
    x, u, e = ca.MX.sym("x", pr.model.nx), ca.MX.sym("u"), ca.MX.sym("E", pr.step.size1_in(2))
    p, c = ca.DM(pr.p), ca.DM(pr.c)
    w = ca.DM([pr.heave_rest, pr.static_tension, pr.tension_weight, pr.control_weight, pr.dt])
    if not many:
        step = ca.Function("step", [x, u, e], [f["ocp_step"](x, u, e, p, c, w)])
        return step, ca.Function("stage", [x, u, e], f["ocp_stage"](x, u, e, p, c, w)), True
    xn, h = x, pr.dt / pr.substeps
    for i in range(pr.substeps):
        xn = f["ocp_rk4"](xn, u, e[7 * 2 * i: 7 * (2 * i + 3)], p, c, h)
    step = ca.Function("step", [x, u, e], [xn])
    return step, ca.Function("stage", [x, u, e], f["ocp_start"](x, u, e[:7], p, c, w)), True


# the Gauss-Newton linearization kernels by the serialized kernel (structure only; see gauss_newton_kernel)
_GN_KERNELS: dict = {}


def residuals(model, x, u, e, p, c, w):
    """The stage cost's residuals r at the interval start (SX): cost = r^T r with r = sqrt(dt) (y_b - y_b0,
    sqrt(c_T) (T_top - T_0) / T_0, sqrt(c_a) alpha), the objective of :mod:`.payout`'s module docstring as a sum
    of squares; e the top's exogenous vector there, w = (heave at rest, T_0, c_T, c_a, dt)."""
    nq = model.nq
    y = model.outputs_e(x[:nq], x[nq:2 * nq], e, ca.vertcat(x[2 * nq], x[2 * nq + 1], u, 0.0), p, c)
    oi = output_labels(model).index
    return ca.sqrt(w[4]) * ca.vertcat(y[oi("heave")] - w[0], ca.sqrt(w[2]) * (y[oi("tension_top")] - w[1]) / w[1],
                                      ca.sqrt(w[3]) * u)


def residual_function(problem) -> ca.Function:
    """``(x, alpha, E_k) -> r`` of a :class:`.payout.HeaveProblem`: :func:`residuals` at the interval start (the
    first 7 rows of E_k) with the problem's numbers inlined (SX; cheap, the outputs only: no dynamics), whose
    r^T r is the stage cost. The Gauss-Newton Hessian of the objective is 2 J^T J with J = dr/d(x, alpha)
    (:class:`.shooting.ShootingNLP`'s ``hessian="gauss-newton"``)."""
    model = problem.model
    x, u, E = ca.SX.sym("x", model.nx), ca.SX.sym("u"), ca.SX.sym("E", problem.step.size1_in(2))
    w = ca.DM([problem.heave_rest, problem.static_tension, problem.tension_weight, problem.control_weight, problem.dt])
    r = residuals(model, x, u, E[:7], ca.DM(problem.p), ca.DM(problem.c), w)
    return ca.Function("residual", [x, u, E], [r], ["x", "u", "E"], ["r"])


def gauss_newton_function(problem) -> ca.Function:
    """The interval's linearization of a :class:`.payout.HeaveProblem` for a Gauss-Newton method, an SX function
    of (x, u, E, p, c, w):

    ``(xn, A, B, r, Rx, Ru, g, Gx, Gu)`` with xn the interval's end state (the RK4 steps of
    :func:`interval_functions`), A = dxn/dx, B = dxn/du; r the stage cost's residuals at the interval start,
    cost = r^T r with r = sqrt(dt) (y_b - y_b0, sqrt(c_T) (T_top - T_0) / T_0, sqrt(c_a) alpha) (the
    objective of :mod:`.payout`'s module docstring is a sum of squares), Rx, Ru their Jacobians; g the path outputs
    (:data:`G_ROWS`) and Gx, Gu theirs (:func:`residuals`). w = (heave at rest, T_0, c_T, c_a, dt) as for ``interval``. The
    Gauss-Newton Hessian of the objective is J_r^T J_r (Bock 1983, "Recent advances in parameter
    identification techniques for ODE", in Numerical Treatment of Inverse Problems, Birkhaeuser, p. 95-121):
    no second derivatives of the dynamics."""
    model, interval = problem.model, problem.interval
    x, u, e, p, c, w = (ca.SX.sym(n, interval.sparsity_in(i)) for i, n in enumerate(interval.name_in()))
    xn, _, g = interval(x, u, e, p, c, w)
    r = residuals(model, x, u, e[:7], p, c, w)
    jac = lambda f, v: ca.jacobian(f, v)
    return ca.Function("gn_interval", [x, u, e, p, c, w],
                       [xn, jac(xn, x), jac(xn, u), r, jac(r, x), jac(r, u), g, jac(g, x), jac(g, u)],
                       ["x", "u", "E", "p", "c", "w"], ["xn", "A", "B", "r", "Rx", "Ru", "g", "Gx", "Gu"])


def gauss_newton_kernel(problem) -> ca.Function:
    """:func:`gauss_newton_function` compiled (one library per model structure: the scene's numbers are its
    inputs p, c, w; the cache is keyed by the function's serialization), or the SX function itself in
    CasADi's virtual machine (``CABLESYS_COMPILE=0``, no compiler, a failed build)."""
    f = gauss_newton_function(problem)
    if not compiles():
        return f
    key = digest(f.serialize())
    kernel = _GN_KERNELS.get(key)
    if kernel is None:
        built = compile_functions([f], jacobians=False, optimization=KERNEL_OPTIMIZATION)
        kernel = built.functions["gn_interval"]
        if built.compiled:
            keep_recent(_GN_KERNELS, key, kernel)
    return kernel
