"""Re-simulation of a payout by an adaptive integrator, between and on the transcription's grid.

CVODES (CasADi ``integrator``, relative tolerance 1e-8) integrates the winch model with the
payout acceleration held on each control interval, output ``per_interval`` times per interval,
and every constraint of the problem is evaluated on that finer grid. Violations are relative
to the limit (speed, power, working load) or to the static tension (the floor).
"""

from __future__ import annotations

import casadi as ca
import numpy as np



class Plant:
    """CVODES on a winch model over one control interval of ``dt`` s with alpha (and F_a) held,
    outputs at ``per_interval`` equal steps: ``advance(x, alpha, t_k) -> states (per_interval, nx)``."""

    def __init__(self, model, p, c, dt: float, per_interval: int = 1, *, reltol: float = 1e-8):
        x, tau, par = ca.SX.sym("x", model.nx), ca.SX.sym("tau"), ca.SX.sym("par", 3)   # (alpha, F_a, t_k)
        ode = model.ode(x, par[:2], par[2] + tau, p, c)
        self.grid = np.linspace(0.0, dt, per_interval + 1)
        self.F = ca.integrator("plant", "cvodes", {"x": x, "p": par, "t": tau, "ode": ode}, 0.0, self.grid[1:],
                               {"reltol": reltol, "abstol": reltol * 1e-2})

    def advance(self, x, alpha: float, t: float, force: float = 0.0) -> np.ndarray:
        return np.array(self.F(x0=x, p=[alpha, force, t])["xf"]).T


def simulate_payout(problem, U, *, x0=None, t0: float = 0.0, per_interval: int = 4):
    """(times, states, outputs) of CVODES on the winch model under the piecewise-constant ``U``."""
    plant = Plant(problem.model, problem.p, problem.c, problem.dt, per_interval)
    xk = np.asarray(problem.x_rest if x0 is None else x0, float)
    X, T, A = [xk], [t0], [U[0] if len(U) else 0.0]
    for k, a in enumerate(np.ravel(U)):
        tk = t0 + k * problem.dt
        xf = plant.advance(xk, a, tk)
        X += list(xf)
        T += list(tk + plant.grid[1:])
        A += [a] * per_interval
        xk = xf[-1]
    X, T = np.array(X), np.array(T)
    return T, X, problem.outputs(X, np.array(A), T)


def resimulate(problem, result, *, per_interval: int = 4) -> dict:
    """Constraint check of ``result``'s payout by CVODES (module docstring).

    Returns
    -------
    dict
        ``max_relative_violation`` and one entry per constraint (relative, 0 when met),
        ``heave_rms_m`` over the result's statistics window, and ``state_deviation`` (largest
        |x_cvodes - x_grid| at the grid points, in the problem's state scales).
    """
    T, X, Y = simulate_payout(problem, result.acceleration, per_interval=per_interval)
    oi = problem.output_labels.index
    lim = problem.limits
    rel = lambda excess, scale: float(max(np.max(excess), 0.0) / scale)
    viol = {"speed": rel(np.abs(Y[:, oi("speed")]) - lim.speed, lim.speed) if np.isfinite(lim.speed) else 0.0,
            "power": rel(np.abs(Y[:, oi("power")]) - lim.power, lim.power) if np.isfinite(lim.power) else 0.0,
            "working load": rel(Y[:, oi("tension_top")] - problem.working_load, problem.working_load),
            "tension floor (no slack)": rel(problem.floor - Y[:, oi(problem.floor_output)], problem.static_tension)}
    start = result.times[-1] * 0.2
    h = Y[:, oi("heave")] - problem.heave_rest
    dev = np.max(np.abs(X[::per_interval] - result.states) / problem.scales())
    return {"max_relative_violation": max(viol.values()), **viol,
            "heave_rms_m": float(np.sqrt(np.mean(h[T >= start] ** 2))), "state_deviation": float(dev)}
