"""Exact gradient of a time-domain design objective by forward sensitivities of a fixed-step roll-out.

For any cable model of the ladder (:func:`cablesys.model.build_model`: Wang's 2-DOF straight cable or
the segmented cable), the objective

    J(theta) = (1 / N) sum_{k=0}^{N-1} (y_b(x_k) - y_b(x_0))^2        (mean square body heave, m^2)

of the classical RK4 roll-out x_{k+1} = F(x_k, t_k; p(theta)) with step h from the time domain's start
state x_0 (:func:`cablesys.time_domain.initial.initial_state` of the nominal scene, held for every
theta) and parameters theta = (AE N, C_I N s) of the (single) section's cable. The sensitivities
S_k = dx_k / dtheta (nx, 2) are propagated with the state in one sweep, S_{k+1} = F_x S_k + F_theta
(the variational equation of the discrete map, Hairer, Norsett & Wanner, *Solving ODEs I*, 2nd ed.,
sec. I.14), both columns as CasADi forward directional derivatives of the step, and dJ/dtheta
accumulates 2 (y_b - y_b0) dy_b/dx S_k / N the same way: the derivative of the computed J, exact to
rounding. The step takes the scene's numbers as inputs, so its compiled form
(:func:`cablesys.compiled.compile_functions`) depends on the model's structure only.
"""

from __future__ import annotations

import dataclasses

import casadi as ca
import numpy as np

from ..compiled import compile_functions, compiles
from ..disk_cache import digest
from ..errors import ParameterError, require_positive
from ..model import build_model
from ..time_domain.initial import initial_state
from .kernels import keep_recent

PARAMETERS = ("cable.ae", "cable.internal_damping")


@dataclasses.dataclass(frozen=True)
class RolloutGradient:
    """``objective(theta) -> J`` (m^2) and ``gradient(theta) -> (J, dJ/dtheta (1, 2))`` of the module's
    roll-out; ``theta0`` the scene's (AE, C_I); ``compiled`` whether the step kernels are compiled."""

    objective: ca.Function
    gradient: ca.Function
    theta0: np.ndarray
    steps: int
    h: float
    kind: str
    compiled: bool


_KERNELS: dict = {}
KERNELS_KEPT = 4


def compiled_kernels(step: ca.Function, sens: ca.Function):
    """(step, sens, compiled): a roll-out's step and sensitivity step compiled once per structure
    (:func:`cablesys.compiled.compile_functions`, keyed by the serialized step, whose scene numbers are
    inputs; no Jacobians: the sensitivity step is the derivative), else as given."""
    if not compiles():
        return step, sens, False
    key = digest(step.serialize())
    k = _KERNELS.get(key)
    if k is None:
        k = compile_functions([step, sens], jacobians=False, optimization="-O1")
        if not k.compiled:
            return step, sens, False
        keep_recent(_KERNELS, key, k, KERNELS_KEPT)
    return k.functions[step.name()], k.functions[sens.name()], True


def rollout_gradient(scene, duration: float, h: float, *, model=None) -> RolloutGradient:
    """The objective and its forward-sensitivity gradient (module docstring) for ``scene``.

    Parameters
    ----------
    scene : Scene
        One section (any ``segments``).
    duration, h : float
        Roll-out length and RK4 step (s); N = round(duration / h) steps.
    model : CableModel, optional
        Built before for the scene's structure.
    """
    require_positive("duration", duration, "s")
    require_positive("h", h, "s")
    if len(scene.sections) != 1:
        raise ParameterError("sections", len(scene.sections), "one section: theta is its cable's (AE, C_I)")
    N = int(round(duration / h))
    if N < 1:
        raise ParameterError("duration", duration, f"must span at least one step of {h:g} s")
    model = model or build_model(scene)
    lay = model.layout
    idx = [lay.index(n) for n in PARAMETERS]
    p_nom = lay.values(scene)
    x0 = np.asarray(initial_state(scene, model, p_nom), float)
    base = np.array(p_nom, float)
    base[idx] = 0.0
    B = np.zeros((len(base), 2))
    B[idx[0], 0] = B[idx[1], 1] = 1.0
    heave = [i for i, n in enumerate(model.output_labels) if n.startswith("y_b")][-1]   # the lowest body
    nx = len(x0)
    x, t, th = ca.SX.sym("x", nx), ca.SX.sym("t"), ca.SX.sym("theta", 2)
    p0, hs, ref = ca.SX.sym("p0", len(base)), ca.SX.sym("h"), ca.SX.sym("y0")
    S = ca.SX.sym("S", nx, 2)
    p = p0 + ca.mtimes(ca.DM(B), th)
    f = lambda xx, tt: model.ode(xx, tt, p)
    k1 = f(x, t)
    k2 = f(x + hs / 2 * k1, t + hs / 2)
    k3 = f(x + hs / 2 * k2, t + hs / 2)
    k4 = f(x + hs * k3, t + hs)
    xn = x + hs / 6 * (k1 + 2 * k2 + 2 * k3 + k4)                    # classical RK4
    sq = (model.outputs(x, model.top(t, p), p)[heave] - ref) ** 2
    z, seeds = ca.vertcat(x, th), ca.vertcat(S, ca.DM.eye(2))
    step = ca.Function(f"grad_step_{model.kind.replace('-', '_')}", [x, t, th, p0, hs, ref], [xn, sq])
    sens = ca.Function(f"grad_sens_{model.kind.replace('-', '_')}", [x, S, t, th, p0, hs, ref],
                       [xn, ca.jtimes(xn, z, seeds), sq, ca.jtimes(sq, z, seeds)])
    step, sens, compiled = compiled_kernels(step, sens)
    y0 = float(np.array(model.outputs(x0, model.top(0.0, p_nom), p_nom)).ravel()[heave])
    times = ca.DM(h * np.arange(N)).T
    theta = ca.MX.sym("theta", 2)
    _, sq_k = step.mapaccum("grad_roll", N, [0], [0])(ca.DM(x0), times, theta, ca.DM(base), h, y0)
    J = ca.sum2(sq_k) / N
    _, _, sq2, dsq = sens.mapaccum("grad_roll_sens", N, [0, 1], [0, 1])(ca.DM(x0), ca.DM.zeros(nx, 2), times, theta,
                                                                        ca.DM(base), h, y0)
    G = ca.sum2(ca.reshape(dsq, 2, N)).T / N
    return RolloutGradient(objective=ca.Function("J", [theta], [J]),
                           gradient=ca.Function("G", [theta], [ca.sum2(sq2) / N, G]),
                           theta0=p_nom[idx].copy(), steps=N, h=float(h), kind=model.kind, compiled=compiled)


def central_differences(objective, theta0, rel_steps=(1e-4, 1e-5)) -> np.ndarray:
    """(len(rel_steps), 2): per relative step d / theta_i, the central difference D(d) =
    (J(theta + d e_i) - J(theta - d e_i)) / (2 d) extrapolated by Richardson, (4 D(d / 2) - D(d)) / 3
    (truncation O(d^4) instead of O(d^2); e.g. Dahlquist & Bjorck, *Numerical Methods*, sec. 7.2):
    the independent route to the gradient. The start state is held, so a change of AE starts an axial
    transient whose J grows with the square of the change: a large second derivative, which the
    plain O(d^2) difference resolves only to ~1e-5 at d = 1e-5 theta."""
    th0 = np.asarray(theta0, float)
    out = np.zeros((len(rel_steps), len(th0)))

    def D(i, d):
        e = np.zeros(len(th0))
        e[i] = d
        return float((objective(th0 + e) - objective(th0 - e)) / (2 * d))
    for j, rel in enumerate(rel_steps):
        for i in range(len(th0)):
            d = rel * th0[i]
            out[j, i] = (4 * D(i, d / 2) - D(i, d)) / 3
    return out
