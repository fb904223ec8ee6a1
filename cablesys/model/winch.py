"""Wang's 2-DOF cable + body model with a winch at the top: a variable unstretched length.

The winch pays out the cable at the rate w(t) = L'(t), L the unstretched (zero-tension) length
in the water; its acceleration alpha = w' is the control. Optionally the sheave sits on a heave
compensator: a piston of moving mass m_p with stroke s (m, down positive) between the crane
tip and the sheave, a spring k_p and damper c_p about a pre-charge force that carries the
static load, and an actuated force F_a (N, down positive): ``k_p = c_p = 0`` with F_a = 0 is
a free-floating sheave, k_p > 0 with F_a = 0 the passive heave compensator (PHC).

Derivation (the same route as :mod:`.build` for Wang 1971 eq. 8-9, 15-25, 37-46):

- Coordinates q = (phi, l) with l the chord length (the body sits at top + l e_t, eq. 10b, 10d),
  plus s with a compensator. L is a *prescribed* coordinate like the top motion: it enters
  Lagrange's equations with L' = w and L'' = alpha (:func:`.lagrange.lagrange_equations`).
- The stretch is u = l - L (eq. 1 with l_0 -> L). The material point at unstretched distance
  sigma from the body (0 <= sigma <= L) sits at l (1 - sigma / L) below the top: the uniform
  stretch of Wang's model. Its velocity along the cable is a + f (l' - a) with f = 1 - sigma/L
  the fraction of the chord from the top and a = w l / L the speed at which paid-out cable
  leaves the sheave. Wang's fixed-length field is f u' (eq. 38): the winch field is Wang's with
  the top velocity v_s + a e_t and the stretch rate l' - a = L d/dt(l / L). So one section of
  :func:`.section.section_terms` with those two substitutions gives the kinetic energy (eq. 22,
  24 with this field), the drag on the moving cable (eq. 41-45), the Voigt damping on the true
  strain rate (eq. 46) and the cable momentum.
- A varying L changes the cable: mass M_c = m_0 L and weight W_c = w_0 L with m_0 = M_c / l_0
  and w_0 = W_c / l_0 of the reference cable (eq. 5, 7, 12), and the spring constant
  k(L) = k_r l_0 / L (strain u / L at the same EA; eq. 1 gives k_r = (AE)_r / l_r at L = l_0).
  At w = 0 and L = l_0 the model is Wang's model exactly.
- Neglected: the momentum carried in or out with the paid-out cable (a mass flux m_0 w at the
  sheave velocity, terms of order m_0 w v: for 30 mm wire at 1 m/s a few N against 10^4 N of
  tension) and Lagrange's variable-mass correction of the same order.

Winch power P = T_top w (W; positive while paying out under tension: the drum is braked; the
motor supplies -P while hauling in). Only one section (a 2-DOF model): a chain or segmented
cable raises :class:`~cablesys.errors.ParameterError`.
"""

from __future__ import annotations

import dataclasses

import casadi as ca
import numpy as np

from ..errors import ParameterError
from ..scene import Scene
from .build import _end_forces
from .lagrange import lagrange_equations, virtual_work
from .params import ParameterLayout, environment_symbols
from .section import SectionParameters, section_terms
from .top_motion import top_motion_function

# the compensator parameters c = (m_p, k_p, c_p, F_pre) in that order
COMPENSATOR_PARAMETERS = ("mass", "stiffness", "damping", "precharge")
WINCH_OUTPUTS = ("heave", "heave_rate", "x_b", "tension_mid", "tension_top", "tension_bottom",
                 "stretch", "length", "speed", "acceleration", "power", "stroke")


@dataclasses.dataclass(frozen=True)
class _VariableLength(SectionParameters):
    """Section parameters (eq. 1-7) with the unstretched length L in place of l_0."""

    length: ca.SX = None

    @property
    def _k_r(self):
        return self.ae / self.l_r                               # eq. 1

    @property
    def _l0_r(self):
        return self.l_r - self.T_r / self._k_r                  # eq. 1

    @property
    def k(self):
        """k(L) = k_r l_0 / L: the same AE over the length in the water."""
        return self._k_r * self._l0_r / self.length

    @property
    def l_0(self):
        return self.length

    @property
    def d_0(self):
        return self.d_r * (1 - self.thinning * self.T_r / (self._k_r * self.l_r))   # eq. 4

    @property
    def m_c(self):
        return self.m_r * self.l_r * self.mass_on * self.length / self._l0_r        # eq. 5, 7

    @property
    def w_c(self):
        return self.w_r * self.l_r * self.length / self._l0_r                       # eq. 12


@dataclasses.dataclass(frozen=True)
class WinchModel:
    """CasADi functions of the winch model of one scene structure (SX, SI units).

    State x = (phi, l[, s], phi', l'[, s'], L, w); control v = (alpha, F_a); ``p`` the scene's
    parameter vector (:class:`.params.ParameterLayout`, slack switch 0: the spring law), ``c``
    the compensator parameters (:data:`COMPENSATOR_PARAMETERS`; ignored without compensator).

    ``ode(x, v, t, p, c) -> x'``; ``outputs(x, v, t, p, c) -> y`` (labels :data:`WINCH_OUTPUTS`:
    body heave y_b (m, down, from the top's mean depth) and its rate, x_b, ``tension_mid`` the spring
    force F_bc = k(L) u + (C_I / l_r)(l' - a) (N, eq. 54: the tension of the uniform stretch, at rest the
    mid-length tension W_b + W_c / 2 as in :data:`.signals.OUTPUT_NAMES`), the cable's pull on the sheave and on the
    body (N, momentum balances as in :func:`.build._end_forces`), u, L, w, alpha, the winch
    power T_top w (W) and the stroke s); ``accel(q, qd, e, winch, p, c) -> q''`` with an explicit
    exogenous vector e (:data:`.signals.EXO_LABELS`) and winch = (L, w, alpha, F_a);
    ``outputs_e(q, qd, e, winch, p, c) -> y`` the outputs with that explicit e (a transcription that
    tabulates the top motion once, outside its NLP, calls ``accel`` and ``outputs_e``).
    """

    layout: ParameterLayout
    compensator: bool
    q_labels: tuple
    ode: ca.Function
    outputs: ca.Function
    accel: ca.Function
    top: ca.Function
    outputs_e: ca.Function

    @property
    def nq(self) -> int:
        return len(self.q_labels)

    @property
    def nx(self) -> int:
        return 2 * self.nq + 2

    @property
    def state_labels(self) -> tuple:
        return self.q_labels + tuple(f"{q}_rate" for q in self.q_labels) + ("length", "speed")

    def parameters(self, scene: Scene) -> np.ndarray:
        """The scene's parameter vector with the slack switch off (the spring law holds)."""
        p = self.layout.values(scene)
        p[self.layout.index("slack")] = 0.0
        return p

    def output_index(self, name: str) -> int:
        return WINCH_OUTPUTS.index(name)


def build_winch_model(scene: Scene, *, compensator: bool = False) -> WinchModel:
    """Build the winch (and compensator) model of a one-section, 2-DOF scene.

    Parameters
    ----------
    scene : Scene
        One section, ``segments = 1`` (Wang's straight cable).
    compensator : bool
        Add the sheave stroke s as a coordinate (module docstring).

    Returns
    -------
    WinchModel
    """
    if len(scene.sections) != 1:
        raise ParameterError("sections", len(scene.sections), "the winch model has one section (Wang's 2-DOF model)")
    if scene.sections[0].cable.segments != 1:
        raise ParameterError("cable.segments", scene.sections[0].cable.segments,
                             "must be 1: the winch model is Wang's straight cable")
    layout = ParameterLayout.from_scene(scene)
    p = layout.symbol
    c = ca.SX.sym("c", len(COMPENSATOR_PARAMETERS))
    m_p, k_p, c_p, f_pre = (c[i] for i in range(len(COMPENSATOR_PARAMETERS)))
    q_labels = ("phi", "l", "s") if compensator else ("phi", "l")
    q, qd = ca.SX.sym("q", len(q_labels)), ca.SX.sym("qd", len(q_labels))
    e = ca.SX.sym("e", 7)
    winch = ca.SX.sym("winch", 4)                       # L, w, alpha, F_a
    L, w, alpha, f_act = winch[0], winch[1], winch[2], winch[3]
    t = e[0]
    env = environment_symbols(layout, scene)
    rho, depth0 = env["density"], env["top_depth"]
    phi, l, phid, ld = q[0], q[1], qd[0], qd[1]
    s, sd = (q[2], qd[2]) if compensator else (0.0, 0.0)

    P0 = SectionParameters.from_layout(layout, "", scene.sections[0].body.is_sphere)
    P = _VariableLength(**{f.name: getattr(P0, f.name) for f in dataclasses.fields(SectionParameters)}, length=L)
    e_t = (-ca.sin(phi), ca.cos(phi))
    a = w * l / L                                       # speed of the cable leaving the sheave
    top_r = (e[1], depth0 + e[2] + s)
    top_v = (e[3] + a * e_t[0], e[4] + sd + a * e_t[1])
    T = section_terms(P, top_r, top_v, phi, l - L, phid, ld - a, t=t, env=env, rho=rho,
                      n_segments=scene.numerics.drag_segments)
    K, V = T["K"], T["V"]
    Q = virtual_work(T["point_forces"], qd) + ca.jacobian(l - L, q).T * T["Q_u"]
    if compensator:                                     # the piston: its mass, spring, damper, force
        K = K + 0.5 * m_p * (e[4] + sd) ** 2
        Q = Q + ca.jacobian(s, q).T * (f_pre + f_act - k_p * s - c_p * sd)
    z = ca.vertcat(e[1], e[2], L)
    zd = ca.vertcat(e[3], e[4], w)
    zdd = ca.vertcat(e[5], e[6], alpha)
    M, f = lagrange_equations(K - V, Q, q, qd, z, zd, zdd)
    qdd = ca.solve(M, f)
    ((bottom, top_force),) = _end_forces([(T["momentum"], T["body_momentum"])],
                                         [(T["external_force"], T["body_external_force"])],
                                         M, f, q, qd, z, zd, zdd)
    pull_body = -(bottom[0] * e_t[0] + bottom[1] * e_t[1])
    pull_top = top_force[0] * e_t[0] + top_force[1] * e_t[1]
    t_top = ca.sign(pull_top) * ca.sqrt(top_force[0] ** 2 + top_force[1] ** 2)
    t_bottom = ca.sign(pull_body) * ca.sqrt(bottom[0] ** 2 + bottom[1] ** 2)
    y = ca.vertcat(T["r_b"][1] - depth0, T["v_b"][1], T["r_b"][0], T["tension"], t_top, t_bottom,
                   l - L, L, w, alpha, t_top * w, s)
    accel = ca.Function("accel", [q, qd, e, winch, p, c], [qdd], ["q", "qd", "e", "winch", "p", "c"], ["qdd"])
    out_e = ca.Function("winch_outputs_e", [q, qd, e, winch, p, c], [y], ["q", "qd", "e", "winch", "p", "c"], ["y"])

    top = top_motion_function(scene, layout)
    nq = len(q_labels)
    xs, vs, ts = ca.SX.sym("x", 2 * nq + 2), ca.SX.sym("v", 2), ca.SX.sym("t")
    ex = top(ts, p)
    wx = ca.vertcat(xs[2 * nq], xs[2 * nq + 1], vs[0], vs[1])
    xdot = ca.vertcat(xs[nq:2 * nq], accel(xs[:nq], xs[nq:2 * nq], ex, wx, p, c), xs[2 * nq + 1], vs[0])
    ode = ca.Function("winch_ode", [xs, vs, ts, p, c], [xdot], ["x", "v", "t", "p", "c"], ["xdot"])
    outputs = ca.Function("winch_outputs", [xs, vs, ts, p, c],
                          [out_e(xs[:nq], xs[nq:2 * nq], ex, wx, p, c)], ["x", "v", "t", "p", "c"], ["y"])
    return WinchModel(layout=layout, compensator=compensator, q_labels=q_labels, ode=ode,
                      outputs=outputs, accel=accel, top=top, outputs_e=out_e)


def rest_state(model: WinchModel, p, c=None, length: float | None = None) -> np.ndarray:
    """The state at rest: top still (e = 0 but t), w = 0, unstretched length ``length`` (default
    l_0 of eq. 1), (phi, l[, s]) solving q'' = 0 by Newton's method (CasADi ``rootfinder``).

    Parameters
    ----------
    model : WinchModel
    p : array
        ``model.parameters(scene)``.
    c : array, optional
        Compensator parameters (:data:`COMPENSATOR_PARAMETERS`).
    length : float, optional
        Unstretched length L (m).

    Returns
    -------
    numpy.ndarray
        x at rest (``model.state_labels``).
    """
    p = np.asarray(p, float)
    c = np.zeros(len(COMPENSATOR_PARAMETERS)) if c is None else np.asarray(c, float)
    lay = model.layout
    l_r, t_r, ae = (p[lay.index(f"cable.{n}")] for n in ("length", "tension_ref", "ae"))
    L = l_r - t_r * l_r / ae if length is None else float(length)
    qs = ca.SX.sym("q", model.nq)
    res = model.accel(qs, ca.DM.zeros(model.nq), ca.DM.zeros(7), ca.DM([L, 0, 0, 0]), p, c)
    solve = ca.rootfinder("rest", "newton", ca.Function("r", [qs], [res]), {"abstol": 1e-10})
    guess = [0.0, l_r] + ([0.0] if model.compensator else [])
    qr = np.array(solve(guess)).ravel()
    if not np.all(np.isfinite(qr)) or np.max(np.abs(np.array(model.accel(qr, np.zeros(model.nq), np.zeros(7),
                                                               [L, 0, 0, 0], p, c)))) > 1e-6:
        raise ParameterError("scene", "rest state", "the winch model found no static equilibrium")
    return np.concatenate([qr, np.zeros(model.nq), [L, 0.0]])
