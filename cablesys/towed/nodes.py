r"""The towed cable as the 3-D segmented node model: the nonlinear counterpart of Kennedy & Strahan (1981).

The scene (:func:`tow_scene`): the node model (:mod:`cablesys.model.segmented`, nodes (x, y, z), z the
sway) of a neutrally buoyant cable (weight in water 0, mass ``m = M (1 - beta) / beta``, added mass
``M = rho pi d^2 / 4``, gamma = 1, Wang 1971 eq. 23) lying along +x from a fixed tow point in a uniform
current ``U`` along +x (the ship's frame: the tow point at rest, the water moving past it; a uniform steady
current has no acceleration, so this is the tow point moving at -U through still water). The drogue is the
report's "lengthened cable" (p. 10): the cable continues past x = L for ``d_c c_t' / c_t`` with nothing at
its free end, so the tension at x = L is the drogue's drag ``2 c_t' M U^2``. Two sections, [0, L] and
[L, L*], so a node sits at the far pinger (xi = 1). The tow point moves sideways, ``z_s = a sin(omega t)``.

Tangential friction ``(rho/2) C_t d |v_t| v_t`` along the element (Wang eq. 44, ``C_t = pi c_t``);
normal drag by the cross-flow principle ``(rho/2) C_n d |v_n| v_n`` (Wang eq. 42, the report's eq. 33-35
with ``C_n = c_n``). Linearized about the straight tow (:func:`frequency_response`) the quadratic normal
drag has zero slope; the theory's equivalent linear law replaces it (Kennedy & Strahan eq. 38-39):
``F_n = (rho/2) d c_n* U v_n``, ``c_n* = A C_n``, added here to the node model's AD Jacobian element by
element with the node model's own drag points and virtual-work shares. The quadratic drag itself, at the
amplitude of a run, is linearized harmonically (:func:`describing_function_response`: first harmonic of
``|v| v``, ``8 / (3 pi) |V| v``, per element, iterated; Caughey 1963), the frequency-domain route to what the
time domain (``studies/towed_nonlinear.py``) integrates.

What the node model's physics is, as eq. 3 (:func:`node_coefficients`), differs from the report's eq. 1 in
two terms, both of the model and not of its discretization:

* the tangential friction acts along the element (cross-flow principle), so its cross-track part
  ``F_t y_x`` cancels the ``-T' y_x`` of ``-(T y_x)_x``: ``c = d`` instead of ``c = b + d`` (the report's
  friction acts along the stream; p = c/b - 1 becomes ``c_n/(pi c_t) - 1``);
* the added mass acts on the node's own normal acceleration (Wang eq. 23-24), not on the convected
  relative flow (Paidoussis 1966): no ``2 beta eta_xt`` and no ``beta`` in ``a``.
"""

from __future__ import annotations

import dataclasses
import math

import casadi as ca
import numpy as np

from ..errors import ParameterError
from ..model import build_model
from ..model.segmented import drag_points
from ..model.segmented_element import normal_part
from ..scene import Body, Cable, Environment, Numerics, Scene, Section, Sinusoid, TopMotion
from .equation import Coefficients, TowedCable, added_fluid_mass

__all__ = ["NodeResponse", "tow_scene", "node_coefficients", "straight_tow", "frequency_response",
           "describing_function_response", "describing_function_scan",
           "harmonic", "phase_lag_along", "DEFAULT_AE"]

#: Axial stiffness EA (N) of the node model's cable: 2e7 N, a 16 mm steel wire rope (the theory is
#: inextensible; the strain at the tow point is then < 0.1 % at the sea trials' tensions).
DEFAULT_AE = 2.0e7
#: The least beta the theory's Coefficients accept: the node model's eq. 3 has no 2 beta eta_xt term.
_NO_CONVECTIVE_INERTIA = 1e-300


def _lengthened(cable: TowedCable) -> float:
    """Length d_c c_t' / c_t of cable that replaces the drogue (Kennedy & Strahan p. 10), m."""
    return cable.diameter * cable.c_t_drogue / cable.c_t


def tow_scene(cable: TowedCable, *, segments: int, density: float = 1025.0, ae: float = DEFAULT_AE,
              amplitude: float = 0.0, omega: float | None = None, cd_normal: float | None = None,
              duration: float = 60.0, output_step: float = 1.0, rtol: float = 1e-7, atol: float = 1e-9) -> Scene:
    """The 3-D node-model scene of ``cable`` towed at ``cable.speed`` (see the module docstring).

    Parameters
    ----------
    cable : TowedCable
        Length L (m, tow point to the far pinger), speed U (m/s), diameter (m), c_t, c_n, c_t', beta.
    segments : int
        Elements N over [0, L]; the lengthened part gets ``max(2, round(N dL / L))``.
    density : float
        Water density rho (kg/m^3).
    ae : float
        Axial stiffness EA (N).
    amplitude, omega : float
        Sway of the tow point, z_s = amplitude sin(omega t) (m, rad/s); amplitude 0 for none.
    cd_normal : float, optional
        Quadratic normal drag coefficient C_n of the cable (Wang eq. 42); default the theory's ``c_n``.
    duration, output_step, rtol, atol : float
        Numerics of a time-domain run (s, s, -, -).
    """
    if isinstance(segments, bool) or not isinstance(segments, int) or not 2 <= segments <= 400:
        raise ParameterError("segments", segments, "must be an integer in [2, 400]")
    if amplitude and (omega is None or not omega > 0):
        raise ParameterError("omega", omega, "must be > 0 (rad/s) when the tow point sways")
    d, U = cable.diameter, cable.speed
    M = added_fluid_mass(density, d)
    m = M * (1.0 - cable.beta) / cable.beta
    dL = _lengthened(cable)
    n2 = max(2, round(segments * dL / cable.length))
    cn = cable.c_n if cd_normal is None else cd_normal

    def wire(length, n):
        return Cable(length=length, ae=ae, diameter=d, mass_per_length=m, weight_per_length=0.0,
                     added_mass_factor=1.0, cd_normal=cn, ct_tangential=cable.ct_tangential, segments=n)

    # no drogue body: the free end and the pinger node carry a point of 1 mg weighing 1 uN in water (a scene
    # needs a body per section and a positive hanging tension; against the ~1e2 N of friction on the last element)
    point = Body(weight=1e-6, mass_x=1e-6, mass_y=1e-6, mass_z=1e-6)
    env = Environment(density=density, current_speeds=(U,))
    top = TopMotion(z=(Sinusoid(amplitude=amplitude, frequency=omega),)) if amplitude else TopMotion()
    num = Numerics(model="as-built", dimensions=3, duration=duration, output_step=output_step, rtol=rtol, atol=atol)
    return Scene(sections=(Section(cable=wire(cable.length, segments), body=point), Section(cable=wire(dL, n2), body=point)),
                 environment=env, top_motion=top, numerics=num, name="towed_nodes")


def node_coefficients(cable: TowedCable) -> Coefficients:
    """Eq. 3's coefficients of the node model's physics (module docstring): ``a = -2 beta (c_t eps + c_t')``,
    ``b = 2 beta c_t eps``, ``c = d = (2/pi) beta c_n eps``; no convective fluid inertia (the ``beta`` of
    the ``2 i beta omega`` term is set to the least value :class:`Coefficients` takes)."""
    ref = cable.coefficients()
    return Coefficients(a=ref.a - cable.beta, b=ref.b, c=ref.d, d=ref.d, beta=_NO_CONVECTIVE_INERTIA)


def straight_tow(model, p, scene: Scene, tol: float = 1e-12, max_iter: int = 30) -> np.ndarray:
    """Node positions q (x, y, z per free node) of the straight tow at rest: on the line y = z = 0 (the cable
    weighs nothing in water), each element stretched by its tension (the friction and drogue drag downstream
    of it, Wang eq. 44), by Newton's method on the x-accelerations (AD Jacobian). Off the line the quadratic
    normal drag has no stiffness about the straight tow (a rigid turn of the cable meets drag ~ angle^2), so
    y and z are not iterated; the 1 uN points of :func:`tow_scene` leave a y-acceleration below 1e-6 m/s^2."""
    rho, U = scene.environment.density, scene.environment.current_speeds[0]
    edges = [0.0]
    for sec in scene.sections:
        c = sec.cable
        edges += [edges[-1] + (k + 1) * c.length / c.segments for k in range(c.segments)][: c.segments]
    edges = np.array(edges)
    # the tension at an element's mid-point: the tangential friction (rho/2) C_t d U^2 downstream of it (eq. 44)
    c = scene.sections[0].cable
    f_t = 0.5 * rho * c.ct_tangential * c.diameter * U**2
    mid = 0.5 * (edges[1:] + edges[:-1])
    stretched = np.diff(edges) * (1.0 + f_t * (edges[-1] - mid) / c.ae)
    q0 = np.zeros(3 * len(stretched))
    q0[0::3] = np.cumsum(stretched)
    nq = q0.size
    qs = ca.SX.sym("q", nq)
    e0 = np.array(model.top(0.0, p)).ravel() * 0.0
    acc = model.accel(qs, ca.DM.zeros(nq), e0, p)
    ix = list(range(0, nq, 3))
    F = ca.Function("F", [qs], [acc[ix], ca.jacobian(acc[ix], qs[ix])])
    q, dq = q0, np.inf
    for _ in range(max_iter):
        r, J = (np.array(v) for v in F(q))
        dq = np.linalg.solve(J, r.ravel())
        q = q.copy()
        q[ix] -= dq
        if np.max(np.abs(dq)) <= tol * edges[-1]:
            return q
    raise ParameterError("straight tow", float(np.max(np.abs(dq))), "Newton's method on the straight tow did not converge")


def _equivalent_drag_force(scene: Scene, q, qd, top_r, top_v, c_n_star):
    """Generalized forces (per free node, 3 each) of the equivalent linear normal drag
    ``(rho/2) d c_n* U v_n`` per length (Kennedy & Strahan eq. 39), v_n the part of the relative velocity
    normal to the element, at the node model's drag points with its virtual-work shares; ``c_n_star`` one
    coefficient per element (elements top to bottom over the sections)."""
    rho, U = scene.environment.density, scene.environment.current_speeds[0]
    n = q.shape[0] // 3
    c_n_star = ca.vertcat(c_n_star) if not isinstance(c_n_star, (int, float)) else ca.DM.ones(n) * c_n_star
    r = [top_r] + [q[3 * j:3 * j + 3] for j in range(n)]
    v = [top_v] + [qd[3 * j:3 * j + 3] for j in range(n)]
    Q = [ca.SX.zeros(3) for _ in range(n + 1)]
    j = 0
    flow = ca.vertcat(U, 0.0, 0.0)
    for sec in scene.sections:
        n_el, c = sec.cable.segments, sec.cable
        npts = drag_points(scene, n_el)
        for _ in range(n_el):
            dr = r[j + 1] - r[j]
            length = ca.norm_2(dr)
            et = dr / length
            for k in range(npts):
                s = (k + 0.5) / npts
                vq = flow - (v[j] + s * (v[j + 1] - v[j]))
                vn = ca.vertcat(*normal_part([vq[i] for i in range(3)], [et[i] for i in range(3)]))
                F = 0.5 * rho * c.diameter * c_n_star[j] * U * (length / npts) * vn
                Q[j] += (1 - s) * F
                Q[j + 1] += s * F
            j += 1
    return ca.vertcat(*Q[1:])


@dataclasses.dataclass(frozen=True, kw_only=True)
class NodeResponse:
    """Sway response of the node model along the cable at one angular frequency.

    ``xi``: node positions x/L (0 the tow point); ``H``: complex sway amplitude per unit tow-point sway
    (Kennedy & Strahan eq. 26, ``e^{i omega t}``: arg H = -psi); ``psi``: phase lag unwrapped along the
    nodes (rad); ``omega_nd`` = omega L / U; ``H1``, ``c_star1``: at the far pinger xi = 1 (c* in units of
    U, eq. 27b).
    """

    xi: np.ndarray
    H: np.ndarray
    psi: np.ndarray
    omega_nd: float
    H1: complex
    c_star1: float


def phase_lag_along(xi, H, omega_nd: float, pinger: int) -> NodeResponse:
    """``psi = -arg H`` unwrapped from the tow point along the nodes, and |H|, c* = omega xi / psi at node
    ``pinger`` (eq. 26-27b)."""
    psi = -np.unwrap(np.angle(H))
    psi = psi - psi[0]
    return NodeResponse(xi=np.asarray(xi), H=np.asarray(H), psi=psi, omega_nd=omega_nd, H1=complex(H[pinger]),
                        c_star1=float(omega_nd * xi[pinger] / psi[pinger]))


@dataclasses.dataclass(frozen=True, eq=False)
class _LinearTow:
    """The node model linearized about the straight tow: accelerations' Jacobians (AD) and the equivalent
    drag's Jacobian as a function of one coefficient c_n* per element (it is linear in them)."""

    scene: Scene
    q0: np.ndarray
    J: np.ndarray                 # d acc / d (q, qd, e) of the node model
    drag: ca.Function             # c (one per element) -> M^-1 d F_lin / d (q, qd, e)

    @property
    def n_elements(self) -> int:
        return sum(s.cable.segments for s in self.scene.sections)

    def solve(self, cable: TowedCable, w: float, c_el) -> np.ndarray:
        """Complex sway amplitudes Z of the free nodes (3 per node: x, y, z) per unit tow-point sway at
        angular frequency w (rad/s)."""
        nq = self.q0.size
        J = self.J + np.array(self.drag(np.asarray(c_el, float)))
        Jq, Jv, Je = J[:, :nq], J[:, nq:2 * nq], J[:, 2 * nq:]
        iz, izd, izdd = 3, 6, 9        # e = (t, top x, y, z, rates, accelerations): the sway's columns
        A = -w**2 * np.eye(nq) - 1j * w * Jv - Jq
        return np.linalg.solve(A, Je[:, iz] + 1j * w * Je[:, izd] - w**2 * Je[:, izdd])


def _linear_tow(cable: TowedCable, segments: int, density: float, ae: float) -> _LinearTow:
    scene = tow_scene(cable, segments=segments, density=density, ae=ae)
    model = build_model(scene)
    p = model.parameters(scene)
    q0 = straight_tow(model, p, scene)
    nq = q0.size
    q, qd, e = ca.SX.sym("q", nq), ca.SX.sym("qd", nq), ca.SX.sym("e", model.top.size1_out(0))
    n_el = sum(s.cable.segments for s in scene.sections)
    c = ca.SX.sym("c", n_el)
    acc = model.accel(q, qd, e, p)
    Mblk, _ = model.dynamics(q, qd, e, p)
    Fl = _equivalent_drag_force(scene, q, qd, e[1:4], e[4:7], c)
    x = ca.vertcat(q, qd, e)
    jac = ca.Function("tow_jacobians", [q, qd, e], [ca.jacobian(acc, x), Mblk])
    zero = (q0, np.zeros(nq), np.zeros(e.shape[0]))
    Ja, Mm = (np.array(v) for v in jac(*zero))
    Jf = ca.substitute(ca.jacobian(Fl, x), ca.vertcat(q, qd, e), ca.vertcat(*[ca.DM(v) for v in zero]))
    drag = ca.Function("tow_drag_jacobian", [c], [ca.solve(ca.DM(Mm), Jf)])
    return _LinearTow(scene=scene, q0=q0, J=Ja, drag=drag)


def _along(lin: _LinearTow, cable: TowedCable, Z, w_nd: float) -> NodeResponse:
    n1 = lin.scene.sections[0].cable.segments
    xi = np.r_[0.0, lin.q0[0::3][:n1] / cable.length]
    return phase_lag_along(xi, np.r_[1.0, Z[2::3][:n1]], float(w_nd), n1)


def _check_omega_nd(omega_nd) -> np.ndarray:
    omega_nd = np.atleast_1d(np.asarray(omega_nd, dtype=float))
    if omega_nd.size == 0 or np.any(~np.isfinite(omega_nd)) or np.any(omega_nd <= 0):
        raise ParameterError("omega_nd", omega_nd.tolist(), "must be finite and > 0")
    return omega_nd


def frequency_response(cable: TowedCable, omega_nd, *, segments: int, c_n_star: float | None = None,
                       density: float = 1025.0, ae: float = DEFAULT_AE) -> list:
    """The linearized node model's sway transfer function along the cable, solved directly per frequency.

    The Jacobian of the node model's accelerations with respect to the node positions, velocities and the
    tow point's sway (position, velocity, acceleration) by CasADi AD at the straight tow, plus the
    equivalent linear normal drag ``(rho/2) d c_n* U v_n`` (Kennedy & Strahan eq. 38-39) through the
    node mass blocks; ``(-omega^2 I - i omega J_v - J_q) Q = (J_z + i omega J_zd - omega^2 J_zdd) Z``.

    Parameters
    ----------
    cable : TowedCable
        The cable and tow (SI), as :func:`tow_scene` takes it.
    omega_nd : array_like
        Nondimensional angular frequencies omega L / U (> 0).
    segments : int
        Elements over [0, L].
    c_n_star : float, optional
        Coefficient of the equivalent linear normal drag (default the theory's ``cable.c_n``).

    Returns
    -------
    list of NodeResponse
        One per frequency.
    """
    omega_nd = _check_omega_nd(omega_nd)
    cns = cable.c_n if c_n_star is None else float(c_n_star)
    if not (math.isfinite(cns) and cns >= 0):
        raise ParameterError("c_n_star", c_n_star, "must be finite and >= 0")
    lin = _linear_tow(cable, segments, density, ae)
    c_el = np.full(lin.n_elements, cns)
    return [_along(lin, cable, lin.solve(cable, w_nd * cable.speed / cable.length, c_el), w_nd) for w_nd in omega_nd]


def describing_function_response(cable: TowedCable, omega_nd: float, amplitude: float, *, segments: int,
                                 cd_normal: float | None = None, density: float = 1025.0, ae: float = DEFAULT_AE,
                                 tol: float = 1e-6, max_iter: int = 200):
    """The sway response of the nonlinear node model by harmonic equivalent linearization (describing
    function) of its quadratic normal drag, a route independent of the time domain.

    A normal relative velocity ``v(t) = |V| sin(omega t + phase)`` meets the drag ``(rho/2) C_n d |v| v``,
    whose first harmonic is ``(rho/2) C_n d (8 / (3 pi)) |V| v`` (Krylov & Bogoliubov; Caughey 1963,
    "Equivalent linearization techniques", J. Acoust. Soc. Am. 35; K&S Appendix B takes the Gaussian
    average instead). So each element gets ``c_n* = C_n (8 / (3 pi)) |V_e| / U`` with ``V_e`` its
    mid-point's normal relative velocity amplitude ``-(i omega Z + U dZ/dx)`` (the sway Z in m for the
    tow-point amplitude ``amplitude``), iterated to a fixed point.

    Returns
    -------
    (NodeResponse, dict)
        The response along the cable and ``{"iterations", "c_n_star_range"}``.
    """
    w_nd = float(_check_omega_nd(omega_nd)[0])
    if not (math.isfinite(amplitude) and amplitude > 0):
        raise ParameterError("amplitude", amplitude, "must be finite and > 0 (m)")
    cn = cable.c_n if cd_normal is None else float(cd_normal)
    if not (math.isfinite(cn) and cn > 0):
        raise ParameterError("cd_normal", cd_normal, "must be finite and > 0")
    return _describing(_linear_tow(cable, segments, density, ae), cable, w_nd, amplitude, cn, tol, max_iter)


def describing_function_scan(cable: TowedCable, omega_nd: float, amplitude: float, cd_normals, *, segments: int,
                             density: float = 1025.0, ae: float = DEFAULT_AE) -> list:
    """:func:`describing_function_response` for several quadratic coefficients C_n (one linearization)."""
    w_nd = float(_check_omega_nd(omega_nd)[0])
    lin = _linear_tow(cable, segments, density, ae)
    return [_describing(lin, cable, w_nd, amplitude, float(cn), 1e-6, 200)[0] for cn in cd_normals]


def _describing(lin: _LinearTow, cable: TowedCable, w_nd: float, amplitude: float, cn: float, tol: float,
                max_iter: int):
    U, w = cable.speed, w_nd * cable.speed / cable.length
    h = np.diff(np.r_[0.0, lin.q0[0::3]])
    c_el = np.full(lin.n_elements, cn * 0.05)
    for k in range(max_iter):
        Z = amplitude * np.r_[1.0, lin.solve(cable, w, c_el)[2::3]]
        V = -(1j * w * 0.5 * (Z[1:] + Z[:-1]) + U * np.diff(Z) / h)
        new = cn * 8.0 / (3.0 * math.pi) * np.abs(V) / U
        if np.max(np.abs(new - c_el)) <= tol * cn:
            c_el = new
            break
        c_el = 0.5 * (c_el + new)            # damped fixed-point step
    Z = lin.solve(cable, w, c_el)
    return _along(lin, cable, Z, w_nd), {"iterations": k + 1, "c_n_star_range": [float(c_el.min()), float(c_el.max())]}


def harmonic(t, y, omega: float) -> complex:
    """Complex amplitude Y of y(t) ~ Re(Y e^{i omega t}) + mean, least squares over the samples."""
    t, y = np.asarray(t, float), np.asarray(y, float)
    A = np.column_stack([np.cos(omega * t), -np.sin(omega * t), np.ones_like(t)])
    c, *_ = np.linalg.lstsq(A, y, rcond=None)
    return complex(c[0], c[1])
