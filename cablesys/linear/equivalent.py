"""Equivalent linearization of the drag: harmonic (describing function) and Gaussian (stochastic).

Quadratic drag 1/2 rho C A |v| v has zero slope at v = 0 (Wang 1971 eq. 32-45), so the exact
Jacobian about still water gives an undamped model. Both methods here replace the Jacobian
dr/dxi of the model's residual (:mod:`.linearize`) by an average over the response the linear
model itself predicts, and iterate until that response is self-consistent. No drag law is
re-derived: the averages are taken of the model's own CasADi Jacobian, so every drag element
(sphere, cylinder, cable segments, current, waves) is linearized the same way.

Harmonic (Krylov-Bogoliubov describing function). For xi(theta) = xi_0 + Re(Xi e^{i theta}),
integrating the first Fourier harmonic by parts gives exactly
    F1 = (1/pi) int r(xi(theta)) e^{-i theta} d theta = J0 Xi - J2 conj(Xi),
    J0 = <J>, J2 = <J e^{-2 i theta}>  (averages over one cycle),
so the describing-function matrix reproducing F1 on the response is N = J0 - J2 conj(Xi) Xi^H / Xi^H Xi.
For one scalar element |v| v with v = V sin theta this is N = 8 |V| / (3 pi), the classical
equivalent-damping result (e.g. Roberts & Spanos, "Random Vibration and Statistical
Linearization", ch. 5; Borgman 1967 for Morison drag). Self-consistency, N(Xi) Xi = 0 with the
mean balanced as well, is the one-harmonic balance; we solve it by Newton's method with the
exact Jacobian, assembled by the chain rule from the per-phase Jacobians of one mapped, compiled
function (:func:`hb1_residual`), with continuation in frequency, because fixed-point
substitution oscillates at resonance where the damping is entirely drag. An orbit that goes
slack (a tension at its floor, eq. 54) is outside the method's domain and is marked so.

Stochastic (Gaussian). For xi ~ N(xi_0, Sigma) the mean-square optimal linear matrix is the
expected Jacobian, N = E[dr/dxi] (Atalik & Utku 1976; Roberts & Spanos ch. 5). For one scalar
element |v| v with v ~ N(U, s^2): 2 E|v|, i.e. sqrt(8/pi) s at U = 0 and 2 |U| (the exact slope
about the steady relative flow) as s -> 0. Sigma follows from the response spectrum of the
current linear model; the expectation is a scrambled-Sobol quadrature with antithetic pairs.
"""

from __future__ import annotations

import dataclasses
from typing import ClassVar

import casadi as ca
import numpy as np

from ..compiled import compile_functions
from ..errors import ParameterError
from ..model import CableModel
from ..results import ResultBase, timed
from ..statics.problem import residual_scales
from .frequency_response import RAO
from .linearization import (
    from_jacobian,
    functions,
    operating_xi,
    taut_parameters,
    top_inputs,
    xi_blocks,
)
from .steady import steady_state


def describing_matrices(J: np.ndarray, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """J0 = <J>, J2 = <J e^{-2 i theta}> over uniformly spaced ``theta`` (first axis of ``J``)."""
    w = np.exp(-2j * theta)
    return J.mean(axis=0), np.tensordot(w, J, axes=(0, 0)) / len(theta)


def describing_function(J0: np.ndarray, J2: np.ndarray, Xi: np.ndarray) -> np.ndarray:
    """N = J0 - J2 conj(Xi) Xi^H / (Xi^H Xi): the complex matrix with N Xi = first harmonic."""
    Xi = np.asarray(Xi, complex)
    return J0 - np.outer(J2 @ np.conj(Xi), np.conj(Xi)) / np.vdot(Xi, Xi).real


def orbit(model: CableModel, xi0, Q, Z, omega, theta):
    """xi(theta) = xi0 + Re(Xi e^{i theta}) and the complex Xi, for q amplitude Q and input Z."""
    Xi = complex_xi(model, Q, Z, omega)
    return xi0[:, None] + np.real(Xi[:, None] * np.exp(1j * theta)[None, :]), Xi


def complex_xi(model: CableModel, Q, Z, omega) -> np.ndarray:
    """Complex amplitude of xi = (q, q', q'', z, z', z'', w) for dq = Q, inputs Z = (x_s, y_s, w...)."""
    b = xi_blocks(model)
    s = 1j * omega
    Xi = np.zeros(b["n"], complex)
    Xi[b["q"]], Xi[b["qd"]], Xi[b["qdd"]] = Q, s * Q, s**2 * Q
    nz = len(top_inputs(model))               # x_s, y_s (and z_s in 3-D), then the wave inputs
    Xi[b["z"]], Xi[b["zd"]], Xi[b["zdd"]] = Z[:nz], s * Z[:nz], s**2 * Z[:nz]
    Xi[b["w"]] = Z[nz:]
    return Xi


# --------------------------------------------------------------------------------------------
# harmonic
# --------------------------------------------------------------------------------------------
def _hb1_matrices(n_theta: int, omega: float) -> tuple[np.ndarray, np.ndarray]:
    """The one-harmonic balance as matrices over the phases theta_j = 2 pi j / n.

    ``W`` (3, n): the rows that take a phase-sampled residual R_j to its balance, (mean, 2 <R cos>, -2 <R sin>),
    i.e. (R_0, Re R_1, Im R_1) of R(theta) ~ R_0 + Re(R_1 e^{i theta}); ``C`` (3 unknown blocks, 3 xi blocks, n):
    d(q, q', q'')_j / d(q0, Re Q, Im Q) for q(theta) = q0 + Re(Q e^{i theta}), q' = Re(i omega Q e^{i theta}),
    q'' = Re(-omega^2 Q e^{i theta}) (Krylov-Bogoliubov; Roberts & Spanos ch. 5)."""
    theta = 2 * np.pi * np.arange(n_theta) / n_theta
    c, s = np.cos(theta), np.sin(theta)
    W = np.stack([np.full(n_theta, 1.0 / n_theta), 2.0 / n_theta * c, -2.0 / n_theta * s])
    one, zero = np.ones(n_theta), np.zeros(n_theta)
    C = np.array([[one, zero, zero],
                  [c, -omega * s, -omega**2 * c],
                  [-s, -omega * c, omega**2 * s]])
    return W, C


def hb1_residual(model: CableModel, p, omega: float, v, Z, n_theta: int, *, jacobian: bool = True):
    """The one-harmonic balance g(v) of the equations of motion for v = (q0, Re Q, Im Q) at ``omega``, the top input
    Re(Z e^{i omega t}), and, with ``jacobian``, dg/dv (exact: the chain rule through the phase samples).

    g = W R with R_j = r(xi(theta_j)) / s the model's residual (:func:`.linearization.functions`, Wang 1971
    eq. 47-48) at the orbit's phase samples, each row over its scale s (the submerged weight; x length for
    moments; at least 1: :func:`cablesys.statics.problem.residual_scales`), so tolerances are relative; W and the
    orbit's derivatives from :func:`_hb1_matrices`. dg/dv = sum_j W_rj (dr/dxi)_j d xi_j/dv from the per-phase
    Jacobians of one mapped, compiled function (:func:`_orbit_jacobians`): its C is one phase's code in a loop,
    whatever ``n_theta`` (the whole balance written out as one expression and differentiated is ~150 MB of C
    for the node model of the 300 m heave wire at N = 16, 64 phases: past the compiler limit, VM-slow).

    Returns
    -------
    (ndarray, ndarray or None)
        g (3 nq) and dg/dv (3 nq, 3 nq).
    """
    nq, b = model.nq, xi_blocks(model)
    fo = _orbit_jacobians(model, n_theta)
    scale = _residual_scale(model, p)
    theta = 2 * np.pi * np.arange(n_theta) / n_theta
    v = np.asarray(v, float)
    xi0 = operating_xi(model, v[:nq])
    X, _ = orbit(model, xi0, v[nq:2 * nq] + 1j * v[2 * nq:], np.asarray(Z, complex), omega, theta)
    W, C = _hb1_matrices(n_theta, omega)
    if not jacobian:
        R = _numpy(fo["res"](X, p)) / scale[:, None]                          # (nq, n)
        return (W @ R.T).ravel(), None
    R, J = (_numpy(a) for a in fo["res_jac"](X, p))
    R = R / scale[:, None]
    J = J.reshape(nq, n_theta, -1) / scale[:, None, None]                  # (nq, n, n_xi)
    # G[r a, c b] = sum_{k, j} W[r, j] C[c, k, j] (dr_a/dxi_kb)_j: one (9, 3 n) x (3 n, nq^2) product
    Jk = np.stack([J[:, :, b[k]] for k in ("q", "qd", "qdd")]).transpose(0, 2, 1, 3)   # (3, n, nq, nq)
    WC = (W[:, None, None, :] * C[None, :, :, :]).reshape(9, 3 * n_theta)
    G = (WC @ Jk.reshape(3 * n_theta, nq * nq)).reshape(3, 3, nq, nq).transpose(0, 2, 1, 3).reshape(3 * nq, 3 * nq)
    return (W @ R.T).ravel(), G


def _numpy(dm: ca.DM) -> np.ndarray:
    """``dm`` as a dense array from its nonzeros (``DM.full`` builds a Python list of every entry: ~25x slower
    for the per-phase Jacobians, most of a describing-function sweep)."""
    nz = np.array(dm.nonzeros(), float)
    if dm.is_dense():
        return nz.reshape(dm.shape, order="F")
    out = np.zeros(dm.shape)
    r, c = dm.sparsity().get_triplet()
    out[r, c] = nz
    return out


def _residual_scale(model: CableModel, p) -> np.ndarray:
    """:func:`cablesys.statics.problem.residual_scales` at ``p``, at least 1 (per equation)."""
    return np.maximum(np.array(ca.DM(residual_scales(model, ca.DM(np.asarray(p, float))))).ravel(), 1.0)


HB_TOLERANCE = 1e-8       # max |g| of a converged balance (relative: rows over their scales)
HB_MAX_ITER = 25
HB_HALVINGS = 8           # step halvings per Newton step before the step counts as failed


def _hb1_newton(model: CableModel, p, omega: float, v, Z, n_theta: int) -> tuple[np.ndarray, float, int]:
    """Newton's method with step halving on :func:`hb1_residual` from ``v``: (v, max |g|, iterations).

    Stops at max |g| below 1e-3 HB_TOLERANCE, when no halved step decreases max |g| (below HB_TOLERANCE: the
    round-off floor, ~2e-11 on the 300 m heave wire), or after HB_MAX_ITER steps. Semi-smooth where the model
    has kinks (the tension floor, eq. 54): the Jacobian is the one of the side each phase sample is on."""
    g, G = hb1_residual(model, p, omega, v, Z, n_theta)
    res = float(np.max(np.abs(g)))
    it = 0
    while res > 1e-3 * HB_TOLERANCE and it < HB_MAX_ITER and np.isfinite(res):
        it += 1
        try:
            step = np.linalg.solve(G, g)
        except np.linalg.LinAlgError:
            break
        for k in range(HB_HALVINGS + 1):
            vn = v - 0.5**k * step
            gn, _ = hb1_residual(model, p, omega, vn, Z, n_theta, jacobian=False)
            rn = float(np.max(np.abs(gn)))
            if np.isfinite(rn) and rn < res:
                break
            if res < HB_TOLERANCE:
                return v, res, it                        # converged to round-off: nothing decreases any more
        else:
            break                                        # no decrease along the Newton direction: stuck
        v, res = vn, rn
        g, G = hb1_residual(model, p, omega, v, Z, n_theta)
    return v, res, it


REFINE_STEPS = 4          # intermediate frequencies of a continuation step whose Newton did not converge
FOLD_STEPS = (0.05, 0.1, 0.2)   # relative steps above a fold at the top of the band where the branch above is sought


def _refined(model: CableModel, p, w_from: float, w: float, v, Z, n_theta: int, failed: tuple) -> tuple:
    """(v, max |g|, iterations) at ``w`` by continuation in REFINE_STEPS smaller steps from the converged balance ``v``
    at ``w_from`` (natural-parameter continuation with a shorter step: near a lightly damped mode the orbit changes
    fast with the frequency and Newton from the last frequency's orbit can stall); ``failed`` (the direct attempt)
    when a step does not converge either."""
    its = 0
    for w_k in np.linspace(w_from, w, REFINE_STEPS + 1)[1:]:
        v_k, r, it = _hb1_newton(model, p, float(w_k), v, Z, n_theta)
        its += it
        if not (np.all(np.isfinite(v_k)) and r < HB_TOLERANCE):
            return failed
        v = v_k
    return v, r, its


def _orbit_jacobians(model: CableModel, n_theta: int) -> dict:
    """The linearization's functions (:func:`.linearization.functions`) at ``n_theta`` columns of xi: ``res`` r,
    ``res_jac`` (r, dr/dxi), and ``out`` y and ``static_jac`` dr/dxi at one (these two not compiled); mapped once
    and compiled (cached on disk), not mapped anew on every call (in the VM a map per call costs more than the
    describing function's solve). A serial map is one phase's code in a loop: the C does not grow with
    ``n_theta``."""
    def build():
        fns = functions(model)
        xi, p = fns["jac"].mx_in()
        res_jac = ca.Function("lin_res_jac", [xi, p], [fns["residual"](xi, p), fns["jac"](xi, p)], ["xi", "p"], ["r", "J"])
        maps = {"res": fns["residual"].map(f"orbit_res_{n_theta}", "serial", n_theta, [1], []),
                "res_jac": res_jac.map(f"orbit_res_jac_{n_theta}", "serial", n_theta, [1], [])}
        out = compile_functions(list(maps.values()), jacobians=False).functions
        # the outputs y alone (SX: the Jacobian's part of out_jac dropped), in the VM: evaluated twice per
        # frequency, not per Newton step, and compiled they would double this library's C (and gcc's time)
        xs, ps = ca.SX.sym("xi", xi.shape[0]), ca.SX.sym("p", p.shape[0])
        y = ca.Function("lin_out", [xs, ps], [fns["out_jac"](xs, ps)[0]], ["xi", "p"], ["y"])
        # dr/dxi at the steady state, evaluated once per sweep: in the VM too
        return {"static_jac": fns["jac"], "out": y.map(f"orbit_out_{n_theta}", "serial", n_theta, [1], []),
                "gap": model.cable_force.map(f"orbit_gap_{n_theta}", "serial", n_theta, [1], []),
                **{k: out[m.name()] for k, m in maps.items()}}
    return model.cache.get(f"orbit_jacobians_{n_theta}", build)


def _orbit_output_jacobian(model: CableModel, n_theta: int) -> ca.Function:
    """(y, dy/dxi) at ``n_theta`` columns of xi, mapped and compiled (a library of its own: only the equivalent
    linear models need it)."""
    def build():
        f = functions(model)["out_jac"].map(f"orbit_out_jac_{n_theta}", "serial", n_theta, [1], [])
        return compile_functions([f], jacobians=False).functions[f.name()]
    return model.cache.get(f"orbit_out_jacobian_{n_theta}", build)


def orbit_slack(model: CableModel, X: np.ndarray, p) -> tuple[bool, float]:
    """Whether the cable goes slack somewhere on the orbit xi(theta_j) (columns of ``X``), and the least
    tension on it (N). Slack: an element's tension law at its floor (the segmented cable's ``element_slack``,
    eq. 54 per element), or Wang's F_bc below TENS (``cable_force`` < 0, eq. 54). A one-harmonic orbit that
    goes slack is outside the describing function's domain: the response has snap loads, whose harmonics the
    balance drops."""
    n = X.shape[1]
    lab = model.output_labels
    y = _numpy(_orbit_jacobians(model, n)["out"](X, p))
    tens = [k for k, lb in enumerate(lab) if lb.startswith(("element_tension[", "tension_"))
            and "rate" not in lb]
    least = float(np.min(y[tens])) if tens else float("nan")
    flags = [k for k, lb in enumerate(lab) if lb.startswith("element_slack[")]
    if flags:
        return bool(np.any(y[flags] > 0.5)), least
    b = xi_blocks(model)
    x = np.vstack([X[b["q"]], X[b["qd"]]])
    gap = _numpy(_orbit_jacobians(model, n)["gap"](x, p))
    return bool(gap.size and np.min(gap) < 0.0), least


@dataclasses.dataclass(frozen=True, eq=False)
class HarmonicResponse(ResultBase):
    """One-harmonic (describing-function) response to a regular input of complex amplitude ``input``.

    ``q_amplitude[k]`` complex dq at ``omega[k]``; ``output_amplitude[k]`` the exact first
    harmonic of every output along that orbit; ``output_mean`` its mean; ``linear[k]`` the
    equivalent (complex) linear model at omega[k] (None where not solved; empty unless asked for). ``slack[k]``: the orbit
    goes slack (outside the describing function's domain); ``solved[k]``: a balance was solved;
    ``least_tension[k]`` the least tension on the orbit (N).
    """

    omega: np.ndarray
    input: np.ndarray
    input_labels: tuple
    output_labels: tuple
    q_amplitude: np.ndarray
    q_mean: np.ndarray
    output_amplitude: np.ndarray
    output_mean: np.ndarray
    residual: np.ndarray
    linear: tuple
    success: bool = True
    message: str = ""
    slack: np.ndarray | None = None
    solved: np.ndarray | None = None
    least_tension: np.ndarray | None = None
    stats: dict = dataclasses.field(default_factory=dict)

    VARIABLES: ClassVar[dict] = {"output_amplitude": ("SI", "complex first-harmonic amplitude of each output"),
                                  "output_mean": ("SI", "mean of each output over the orbit"),
                                  "residual": ("1", "harmonic-balance residual"), "output": ("1", "output")}

    @property
    def converged(self) -> bool:
        """Alias of :attr:`success` (every frequency's residual below 1e-8)."""
        return self.success

    def amplitude(self, output: str) -> np.ndarray:
        return np.abs(self.output_amplitude[:, self.output_labels.index(output)])

    def rao(self, scale: float | None = None, label: str = "input") -> RAO:
        """Output amplitudes per unit input (``scale`` defaults to the largest |input| entry)."""
        scale = scale or float(np.max(np.abs(self.input)))
        return RAO(omega=self.omega, output_labels=self.output_labels, input_labels=(label,),
                   values=self.output_amplitude[:, :, None] / scale, kind="harmonic")

    def to_xarray(self):
        import xarray as xr
        return xr.Dataset({"output_amplitude": (("omega", "output"), self.output_amplitude),
                           "output_mean": (("omega", "output"), self.output_mean),
                           "residual": ("omega", self.residual)},
                          coords={"omega": self.omega, "output": list(self.output_labels)},
                          attrs={"kind": "harmonic", "input": str(self.input)})


@timed
def harmonic_response(model: CableModel, p, omega, input_amplitude, *, n_theta: int = 64,
                      ladder: int = 6, slack_stop: int | None = None, linear_models: bool = True) -> HarmonicResponse:
    """Describing-function equivalent linearization at each ``omega`` for the regular input
    Re(Z e^{i omega t}), Z = ``input_amplitude`` = (x_s, y_s, wave amplitudes...) complex.

    Solved by continuation from ``omega.min()/4`` (where the exact linear response is a good
    guess) up through the requested frequencies.

    Parameters
    ----------
    model : CableModel
        The Wang (1971) model (:func:`cablesys.build_model`).
    p : array_like
        Parameter vector (``scene.parameters()``); slack switches are cleared.
    omega : array_like
        Angular frequencies (rad/s).
    input_amplitude : array_like of complex
        Z: top x_s, y_s (m) and wave amplitudes (m), one per input of the linear model.
    n_theta : int, optional
        Phase samples per cycle of the harmonic balance.
    ladder : int, optional
        Continuation steps below ``omega.min()``.
    slack_stop : int, optional
        After this many consecutive frequencies (ascending) whose orbit goes slack, the higher ones are not
        solved (``solved`` False, NaN values); None solves every frequency.
    linear_models : bool, optional
        Also the equivalent linear model at each frequency (``linear``; the describing matrices of dr/dxi and
        dy/dxi along the orbit); False leaves ``linear`` empty (the amplitudes alone).

    Returns
    -------
    HarmonicResponse
        ``success`` is False when a frequency's harmonic-balance residual stays above 1e-8 (or it was not
        solved); ``slack`` marks the frequencies whose orbit goes slack (:func:`orbit_slack`).
    """
    p = taut_parameters(model, p)
    st = steady_state(model, p)
    fo = _orbit_jacobians(model, n_theta)
    jac_map, jac_static = fo["res_jac"], fo["static_jac"]
    xi0 = operating_xi(model, st.q)
    # the exact linearization's dq response (the continuation's start); its outputs are not needed
    ny = len(model.output_labels)
    lin0 = from_jacobian(model, jac_static(xi0, p).full(), np.zeros((ny, xi0.size)), st.q, np.zeros(ny), kind="exact")
    omega = np.atleast_1d(np.asarray(omega, float))
    Z = np.asarray(input_amplitude, complex)
    if Z.shape != (len(lin0.input_labels),):
        raise ParameterError("input_amplitude", f"shape {Z.shape}",
                             f"needs {len(lin0.input_labels)} entries {lin0.input_labels}")
    order = np.argsort(omega)
    pre = np.geomspace(omega[order[0]] / 4.0, omega[order[0]], ladder + 1)[:-1]
    nq = model.nq
    Q0, _ = lin0.transfer(pre[:1])
    v = np.concatenate([st.q, (Q0[0] @ Z).real, (Q0[0] @ Z).imag])
    theta = 2 * np.pi * np.arange(n_theta) / n_theta
    n_w = len(omega)
    res, iters, slack, least = {}, np.zeros(n_w, int), np.zeros(n_w, bool), np.full(n_w, np.nan)
    run = 0                      # consecutive slack orbits among the requested frequencies
    w_last = None                # the last frequency whose balance converged (the continuation's start)

    def record(i, v_i, r_i, it_i):
        """Keep the balance ``v_i`` of requested frequency i, its residual, iterations and whether its orbit is slack."""
        xi0[xi_blocks(model)["q"]] = v_i[:nq]
        X, _ = orbit(model, xi0, v_i[nq:2 * nq] + 1j * v_i[2 * nq:], Z, omega[i], theta)
        slack[i], least[i] = orbit_slack(model, X, p)
        iters[i] = it_i
        res[i] = (np.array(v_i, float).copy(), r_i)

    for k, w in enumerate(list(pre) + list(omega[order])):
        j = k - len(pre)         # index into the sorted requested frequencies (< 0: a continuation step)
        if j >= 0 and slack_stop is not None and run >= slack_stop:
            break                # the rest are not solved (reported: residual NaN, ``solved`` False)
        v_new, r, it = _hb1_newton(model, p, float(w), v, Z, n_theta)
        if not r < HB_TOLERANCE and w_last is not None:
            v_new, r, it = _refined(model, p, w_last, float(w), v, Z, n_theta, (v_new, r, it))
        ok = np.all(np.isfinite(v_new))
        if j >= 0:               # the residual of the requested frequencies (the continuation's are not reported)
            i = int(order[j])
            record(i, v_new if ok else v, r, it)
            run = run + 1 if slack[i] else 0
        if ok and r < HB_TOLERANCE:
            v, w_last = v_new, float(w)      # continuation: the next frequency starts from the last converged balance
    # a taut balance that did not converge from below is continued from the nearest converged one above: near a
    # lightly damped mode the one-harmonic response can fold (the jump phenomenon: Nayfeh & Mook, *Nonlinear
    # Oscillations*, 1979, sec. 4.1), the branch followed from below ends there, and the one from above goes on;
    # with none above (the fold at the top of the band) the branch above is sought at FOLD_STEPS above the frequency,
    # from the converged balance below (Newton's jump), and followed back down
    for i in sorted((i for i in res if not res[i][1] < HB_TOLERANCE and not slack[i]), key=lambda i: -omega[i]):
        good = [k for k in res if res[k][1] < HB_TOLERANCE]
        above = [k for k in good if omega[k] > omega[i]]
        below = [k for k in good if omega[k] < omega[i]]
        if above:
            k = min(above, key=lambda k: omega[k])
            w_hi, v_hi = float(omega[k]), res[k][0]
        elif below:
            v_lo = res[max(below, key=lambda k: omega[k])][0]
            for step in FOLD_STEPS:
                w_hi = float(omega[i]) * (1.0 + step)
                v_hi, r_hi, _ = _hb1_newton(model, p, w_hi, v_lo, Z, n_theta)
                if r_hi < HB_TOLERANCE:
                    break
            else:
                continue
        else:
            continue
        v_new, r, it = _refined(model, p, w_hi, float(omega[i]), v_hi, Z, n_theta, (None, np.inf, 0))
        if r < HB_TOLERANCE:
            record(i, v_new, r, it)
    nan = np.full(nq, np.nan)
    Qa, Qm, Ya, Ym, R, lins = [], [], [], [], [], []
    for j in range(n_w):
        w = omega[j]
        if j not in res:
            ny = len(model.output_labels)
            Qa.append(nan + 0j); Qm.append(nan); R.append(np.nan)
            if linear_models:
                lins.append(None)
            Ya.append(np.full(ny, np.nan + 0j)); Ym.append(np.full(ny, np.nan))
            continue
        v, r = res[j]
        Q = v[nq:2 * nq] + 1j * v[2 * nq:]
        xi0[xi_blocks(model)["q"]] = v[:nq]
        X, Xi = orbit(model, xi0, Q, Z, w, theta)
        if linear_models:
            J = _numpy(jac_map(X, p)[1]).reshape(model.nq, n_theta, -1).transpose(1, 0, 2)
            y, Jy = (_numpy(a) for a in _orbit_output_jacobian(model, n_theta)(X, p))
            J0, J2 = describing_matrices(J, theta)
            N = describing_function(J0, J2, Xi)
            Jy = Jy.reshape(y.shape[0], n_theta, -1).transpose(1, 0, 2)
            Jy0, Jy2 = describing_matrices(Jy, theta)
            lins.append(from_jacobian(model, N, describing_function(Jy0, Jy2, Xi), v[:nq], y.mean(axis=1),
                                      kind="harmonic", omega=float(w)))
        else:
            y = _numpy(fo["out"](X, p))
        Qa.append(Q); Qm.append(v[:nq]); R.append(r)
        Ya.append(2.0 / n_theta * (y @ np.exp(-1j * theta))); Ym.append(y.mean(axis=1))
    R = np.array(R)
    solved = np.array([j in res for j in range(n_w)])
    return HarmonicResponse(omega=omega, input=Z, input_labels=lin0.input_labels, output_labels=model.output_labels,
                            q_amplitude=np.array(Qa), q_mean=np.array(Qm), output_amplitude=np.array(Ya),
                            output_mean=np.array(Ym), residual=R, linear=tuple(lins),
                            success=bool(np.all(R < HB_TOLERANCE)), message=_harmonic_message(omega, R, slack, solved),
                            slack=slack, solved=solved, least_tension=least,
                            stats={"n_theta": n_theta, "continuation_steps": ladder, "newton_iterations": iters.tolist()})


def harmonic_model(scene, model: CableModel) -> CableModel:
    """The model whose one-harmonic balance :func:`harmonic_response` should solve for ``model`` of ``scene``: the node
    model (segmented cable) in its element coordinates (phi_k, u_k), (phi_k, phi_z_k, u_k) in 3-D
    (:func:`cablesys.model.element_coordinates.build_element_model`: the same physics, the same outputs), any other
    model itself.

    Why: a node swinging on a stiff element moves on an arc, which a one-harmonic orbit of its Cartesian position
    cannot follow: its chord shortens by ~W^2 / 4h at the mean and the second harmonic (W the transverse amplitude
    across an element of length h), which the axial stiffness AE / h turns into spurious tension, so the balance in
    node coordinates overstates the response by O(W^2 AE / (h^2 T)). One harmonic of the angles follows the arc, as
    in Wang's straight cable. Measured (the 60 m wire of a 6 kN sphere in a 0.5 m/s current, N = 3, 0.4 m of sway
    at 0.6 rad/s, against the first harmonic of the time domain; tests/test_rao_describing_3d.py): the body's sway
    6.5 % high in node coordinates, 0.16 % in element coordinates. An anchored line, a winch, a rigid body or a system
    of lines joined at points (``scene.system``: a graph has no chain of element angles from one top) has no element
    coordinates (:func:`~cablesys.model.element_coordinates.build_element_model` refuses them): its own model."""
    if not getattr(model, "segments", None) or getattr(model, "anchored", False) or getattr(model, "n_rotations", 0) \
            or getattr(scene, "winch", None) is not None or getattr(scene, "system", None) is not None:
        return model
    from ..model.element_coordinates import build_element_model
    return build_element_model(scene, model)


def _harmonic_message(omega, residual, slack, solved) -> str:
    """What did not converge (taut orbits: a solver failure), which orbits go slack and what was not solved."""
    parts = []
    bad = [f"{w:.4g}" for w, r, s, d in zip(omega, residual, slack, solved) if d and not s and not r < HB_TOLERANCE]
    if bad:
        parts.append(f"harmonic balance did not converge at omega = {', '.join(bad)} rad/s "
                     f"(residual > {HB_TOLERANCE:g}): refine the grid near those frequencies or use simulate()")
    sl = np.asarray(omega)[np.asarray(slack)]
    if sl.size:
        parts.append(f"the one-harmonic orbit goes slack at {sl.size} frequencies in {sl.min():.4g} .. {sl.max():.4g} "
                     "rad/s (the describing function does not hold there: snap loads; use simulate())")
    skipped = np.asarray(omega)[~np.asarray(solved)]
    if skipped.size:
        parts.append(f"{skipped.size} frequencies from {skipped.min():.4g} rad/s up not solved "
                     "(above consecutive slack orbits)")
    return "; ".join(parts)
