"""The time-domain design's roll-out, its exact sensitivities and the NLP's functions of the design (:mod:`.design`).

One RK4 step of the design's winch model at zero payout (:func:`cablesys.control.kernels.substep_functions`) and the
series (:attr:`.design_problem.TimeDesignProblem.series`) at its start, with the design theta (its n variables,
:mod:`.design_problem`) an input (p = p0 + B theta), is one
kernel; the roll-out maps it over the ``substeps`` steps of every interval (``mapaccum``) and keeps the series at
the interval starts. Its forward sensitivities S = dx/dtheta (nx, n) follow the variational equation of the
discrete map, S_{k+1} = F_x S_k + F_theta (Hairer, Norsett & Wanner, *Solving ODEs I*, sec. I.14), its n columns as
forward directional derivatives of the step in one sweep; the rest state's by the implicit-function theorem
(``rootfinder``). The step and its sensitivity step take the scene's numbers as inputs, so they are compiled once
per model structure (:func:`cablesys.control.gradient.compiled_kernels`). The objective and the constraints of
:mod:`.design`'s module docstring are then cheap functions of the series, differentiated forward, seeded by the
sensitivities: the gradient is the derivative of the computed roll-out, exact to rounding.
"""

from __future__ import annotations

import dataclasses
import math

import casadi as ca
import numpy as np

from ..model.params import section_prefix
from .design_problem import TimeDesignProblem, selection
from .gradient import compiled_kernels
from .kernels import output_labels


def ks_max(v, rho: float):
    """Kreisselmeier-Steinhauser envelope of the entries of ``v`` (:mod:`.design`'s module docstring): >= max v."""
    m = ca.mmax(v)
    return m + ca.log(ca.sum2(ca.exp(rho * (v - m)))) / rho


def _series_rows(problem: TimeDesignProblem) -> list:
    """The model's output rows of the problem's series (``tension_floor``: the model's floor output)."""
    oi = output_labels(problem.model).index
    return [oi(problem.floor_output if name == "tension_floor" else name) for name in problem.series]


def rest_state(problem: TimeDesignProblem, theta):
    """(x_0, static strains u_0 / l_0 per section) of the design theta (MX): the coordinates solving q'' = 0 at rest
    with the first section's zero-tension length L = l_0 = l_r - T_r l_r / AE (Wang 1971 eq. 1: the design keeps
    the length at the reference tension; a chain's lower sections the same, in the model) by Newton's method
    (``rootfinder``, from the nominal design's rest state; its derivative by the implicit-function theorem); each
    section's strain is the model's elongation output (the chord's, or the elements' elongations summed: ``stretch``,
    ``stretch_2``, ...) over its l_0."""
    hp = problem.heave
    model, lay = hp.model, hp.model.layout
    nq, k = model.nq, problem.sections
    base, B = selection(problem)
    qs, ts = ca.SX.sym("q", nq), ca.SX.sym("theta", len(problem.variables))
    ps = ca.DM(base) + ca.mtimes(ca.DM(B), ts)
    num = lambda i, name: ps[lay.index(section_prefix(k, i) + name)]
    l0 = [num(i, "cable.length") * (1 - num(i, "cable.tension_ref") / num(i, "cable.ae")) for i in range(k)]
    wz = ca.vertcat(l0[0], 0, 0, 0)
    res = model.accel(qs, ca.DM.zeros(nq), ca.DM.zeros(7), wz, ps, ca.DM(hp.c))
    solve = ca.rootfinder("rest_design", "newton", ca.Function("r", [qs, ts], [res]), {"abstol": 1e-10})
    oi = output_labels(model).index
    y = model.outputs_e(qs, ca.DM.zeros(nq), ca.DM.zeros(7), wz, ps, ca.DM(hp.c))
    stretch = [y[oi("stretch" if i == 0 else f"stretch_{i + 1}")] / l0[i] for i in range(k)]
    strain = ca.Function("strain", [qs, ts], [ca.vertcat(*stretch)])
    q0 = solve(ca.DM(hp.x_rest[:nq]), theta)
    L0 = ca.Function("L0", [ts], [l0[0]])(theta)
    return ca.vertcat(q0, ca.MX.zeros(nq), L0, 0), strain(q0, theta)


def step_functions(problem: TimeDesignProblem):
    """(step, sens): one RK4 step of h s at zero payout, ``step(x, E_j, theta, p0, c, h) -> (x_next, y)`` with y the
    :data:`SERIES` at the step's start and E_j the top at its 3 stage times (21 rows), and ``sens(x, S, E_j, theta,
    p0, c, h) -> (x_next, S_next, y, dy)`` with the sensitivities S = dx/dtheta (nx, n) (module docstring). The
    scene's numbers are inputs (p0 the parameters with AE and C_I zeroed, p = p0 + B theta, B from the layout; c
    the compensator's): the functions depend on the model's structure only."""
    hp = problem.heave
    model = hp.model
    nq = model.nq
    _, B = selection(problem)
    nv = len(problem.variables)
    x, e, th = ca.SX.sym("x", model.nx), ca.SX.sym("E", 21), ca.SX.sym("theta", nv)
    p0, c, h = ca.SX.sym("p0", len(hp.p)), ca.SX.sym("c", len(hp.c)), ca.SX.sym("h")
    S = ca.SX.sym("S", model.nx, nv)
    p = p0 + ca.mtimes(ca.DM(B), th)
    xn = hp.substep(x, 0.0, e, p, c, h)
    y = model.outputs_e(x[:nq], x[nq:2 * nq], e[:7], ca.vertcat(x[2 * nq], x[2 * nq + 1], 0, 0), p, c)
    ys = ca.vertcat(*(y[i] for i in _series_rows(problem)))
    z, seeds = ca.vertcat(x, th), ca.vertcat(S, ca.DM.eye(nv))
    names = ["x", "E", "theta", "p0", "c", "h"]
    step = ca.Function("design_step", [x, e, th, p0, c, h], [xn, ys], names, ["xn", "y"])
    sens = ca.Function("design_sens", [x, S, e, th, p0, c, h],
                       [xn, ca.jtimes(xn, z, seeds), ys, ca.jtimes(ys, z, seeds)],
                       names[:1] + ["S"] + names[1:], ["xn", "Sn", "y", "dy"])
    return step, sens


def design_kernels(problem: TimeDesignProblem):
    """(step, sens, compiled): :func:`step_functions` compiled once per model structure
    (:func:`cablesys.control.gradient.compiled_kernels`), or the SX functions in CasADi's virtual machine
    (``CABLESYS_COMPILE=0``, no compiler, a failed build)."""
    return compiled_kernels(*step_functions(problem))


def step_table(problem: TimeDesignProblem, E: np.ndarray) -> np.ndarray:
    """The per-step table (21, N substeps) of an interval table E (N, 7 (2 substeps + 1)): step j of interval k reads
    the top at the stage times 2j, 2j + 1, 2j + 2 of its interval."""
    m = problem.heave.substeps
    rows = [E[:, 14 * j: 14 * j + 21] for j in range(m)]
    return np.stack(rows, axis=1).reshape(-1, 21).T


def series_functions(problem: TimeDesignProblem):
    """(series, sensitivities) of the roll-out from the design's rest state, each a function of theta (n) and the
    step table E (21, N substeps, :func:`step_table`): ``series -> (Y, strain)`` with Y (len(series), N) at the
    interval starts and the static strains (sections, 1), ``sensitivities -> (Y, dY (len(series) n, N): the rows
    dY/dtheta_1, then dY/dtheta_2, ..., strain, dstrain/dtheta (sections, n))``."""
    hp = problem.heave
    step, sens, _ = design_kernels(problem)
    base, _ = selection(problem)
    m, N = hp.substeps, problem.N
    nums = (ca.DM(base), ca.DM(hp.c), hp.dt / m)
    nv = len(problem.variables)
    theta, E = ca.MX.sym("theta", nv), ca.MX.sym("E", 21, N * m)
    starts = list(range(0, N * m, m))                   # the steps that start an interval
    x0, strain = rest_state(problem, theta)
    _, Y = step.mapaccum("design_roll", N * m, [0], [0])(x0, E, theta, *nums)
    series = ca.Function("design_series", [theta, E], [Y[:, starts], strain], ["theta", "E"], ["Y", "strain"])
    S0 = ca.jacobian(x0, theta)                        # the rest state's own dependence (implicit function)
    _, _, Y2, dY = sens.mapaccum("design_roll_sens", N * m, [0, 1], [0, 1])(x0, S0, E, theta, *nums)
    n = Y2.size1()
    dY = ca.reshape(dY, n * nv, N * m)[:, starts]      # columns [dy/dtheta_1; dy/dtheta_2; ...] per interval
    sensitivities = ca.Function("design_sensitivities", [theta, E],
                                [Y2[:, starts], dY, strain, ca.jacobian(strain, theta)],
                                ["theta", "E"], ["Y", "dY", "strain", "dstrain"])
    return series, sensitivities


def section_row(name: str, i: int) -> str:
    """A constraint row's name for section ``i`` (0 at the top): ``name`` for the first, ``name_2`` ... below."""
    return name if i == 0 else f"{name}_{i + 1}"


def _seed_terms(problem: TimeDesignProblem, Y):
    """(variance of y_b, [(constraint, value, bound)]) of one seed's series Y (MX; rows ``problem.series``)."""
    k0, rho = problem.window_start, problem.rho
    W = Y[:, k0:]
    n = W.size2()
    mean = ca.sum2(W) / n
    h = W[0, :] - mean[0]
    var = ca.sum2(h ** 2) / n
    g = []
    for i, wl in enumerate(problem.working_load):       # each section's top tension: rows 3, 4, ... of the series
        if math.isfinite(wl):
            g.append((section_row("peak_tension", i), ks_max(W[3 + i, :] / wl, rho), 1.0))
    if problem.slack_fraction is not None:
        g.append(("slack", ks_max(-W[2, :] / mean[2], rho), -problem.slack_fraction))
    if problem.max_excursion is not None:
        dev = ca.horzcat(h, -h, W[1, :] - mean[1], mean[1] - W[1, :]) / problem.max_excursion
        g.append(("excursion", ks_max(dev, rho), 1.0))
    return var, g


@dataclasses.dataclass(frozen=True)
class DesignFunctions:
    """The NLP's functions of the normalized design z: ``fg(z) -> (f, g)`` the objective (mean heave
    variance over the seeds, m^2) and the constraints (rows ``rows``, upper bounds ``ub``), and
    ``jac(z) -> (df/dz, dg/dz)`` by the forward sensitivities (exact, no AD through the roll-out's graph);
    ``series(theta, E)`` the roll-out of one seed's step table ``tables[i]`` (:func:`series_functions`)."""

    fg: ca.Function
    jac: ca.Function
    rows: tuple
    ub: np.ndarray
    theta: ca.Function
    series: ca.Function
    tables: tuple


def design_functions(problem: TimeDesignProblem) -> DesignFunctions:
    """The objective and constraints of ``problem`` as CasADi functions of z (:mod:`.design`'s module docstring)."""
    nv, k, ns = len(problem.variables), problem.sections, len(problem.series)
    z = ca.MX.sym("z", nv)
    lo = np.log([v.lower for v in problem.variables])
    hi = np.log([v.upper for v in problem.variables])
    theta = ca.exp(ca.DM(lo) + z * ca.DM(hi - lo))
    dtheta_dz = theta * ca.DM(hi - lo)                  # diagonal
    series, sens = series_functions(problem)
    tables = tuple(step_table(problem, E) for E in problem.exogenous)
    # post-processing of the series (cheap): (f, g) of the per-seed Y and the strains
    Ys = [ca.MX.sym(f"Y{s}", ns, problem.N) for s in problem.seeds]
    strain = ca.MX.sym("strain", k)
    total, rows, gs, ub = 0, [], [], []
    for s, Y in zip(problem.seeds, Ys):
        var, g = _seed_terms(problem, Y)
        total = total + var
        for name, expr, bound in g:
            rows.append(f"{name} (seed {s})")
            gs.append(expr)
            ub.append(bound)
    for i, limit in enumerate(problem.strain_limit or ()):
        rows.append(section_row("static_strain", i))
        gs.append(strain[i])
        ub.append(limit)
    fo, go = total / len(problem.seeds), ca.vertcat(*gs) if gs else ca.MX(0, 1)
    post = ca.Function("design_post", [*Ys, strain], [fo, go])
    # forward mode of the post-processing, seeded by the sensitivities of each theta direction
    dYs = [ca.MX.sym(f"dY{s}", ns, problem.N) for s in problem.seeds]
    dstrain = ca.MX.sym("dstrain", k)
    vars_, seeds_ = ca.vertcat(*[ca.vec(Y) for Y in Ys], strain), ca.vertcat(*[ca.vec(d) for d in dYs], dstrain)
    post_fwd = ca.Function("design_post_fwd", [*Ys, strain, *dYs, dstrain],
                           [ca.jtimes(fo, vars_, seeds_), ca.jtimes(go, vars_, seeds_)])
    outs = [series(theta, ca.DM(T)) for T in tables]
    fg = ca.Function("design_fg", [z], post(*[o[0] for o in outs], outs[0][1]))
    sol = [sens(theta, ca.DM(T)) for T in tables]
    Yv, st, dst = [o[0] for o in sol], sol[0][2], sol[0][3]
    cols_f, cols_g = [], []
    for j in range(nv):
        df, dg = post_fwd(*Yv, st, *[o[1][j * ns:(j + 1) * ns, :] for o in sol], dst[:, j])
        cols_f.append(df * dtheta_dz[j])
        cols_g.append(dg * dtheta_dz[j])
    jac = ca.Function("design_jac", [z], [ca.horzcat(*cols_f), ca.horzcat(*cols_g)])
    return DesignFunctions(fg=fg, jac=jac, rows=tuple(rows), ub=np.array(ub, float),
                           theta=ca.Function("theta", [z], [theta]), series=series, tables=tables)
