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
mean balanced as well, is the one-harmonic balance; we solve it by Newton's method (CasADi
KINSOL) with continuation in frequency, because fixed-point substitution oscillates at
resonance where the damping is entirely drag.

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
from ..messages import casadi_warnings_captured
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
def _hb1_rootfinder(model: CableModel, n_theta: int) -> tuple[ca.Function, ca.Function]:
    """KINSOL on (mean residual, first harmonic) = 0 for unknowns (q0, Re Q, Im Q), and that residual."""
    return model.cache.get(f"hb1_{n_theta}", lambda: _build_hb1(model, n_theta))


def _build_hb1(model: CableModel, n_theta: int) -> tuple[ca.Function, ca.Function]:
    fns = functions(model)
    nq, b = model.nq, xi_blocks(model)
    nu = 2 + (b["w"].stop - b["w"].start)
    v = ca.SX.sym("v", 3 * nq)
    w = ca.SX.sym("omega")
    Zr, Zi = ca.SX.sym("Zr", nu), ca.SX.sym("Zi", nu)
    p = ca.SX.sym("p", len(model.layout))
    q0, Qr, Qi = v[:nq], v[nq:2 * nq], v[2 * nq:]
    theta = 2 * np.pi * np.arange(n_theta) / n_theta
    cols = []
    for th in theta:
        c, s = np.cos(th), np.sin(th)
        q = Qr * c - Qi * s                      # Re(Q e^{i th})
        qd = -w * (Qi * c + Qr * s)              # Re(i w Q e^{i th})
        z = Zr * c - Zi * s
        zd = -w * (Zi * c + Zr * s)
        cols.append(ca.vertcat(q0 + q, qd, -w**2 * q, z[:2], zd[:2], -w**2 * z[:2], z[2:]))
    # each row over its scale (the submerged weight; x length for moments; at least 1): KINSOL's tolerance and the 1e-8 test
    # are then relative, reachable in double precision by a 300 m steel wire as by the Dale model
    R = fns["residual"].map(n_theta)(ca.horzcat(*cols), p) / ca.repmat(ca.fmax(residual_scales(model, p), 1.0), 1, n_theta)
    g = ca.vertcat(ca.mtimes(R, np.full(n_theta, 1.0 / n_theta)),
                   ca.mtimes(R, 2.0 / n_theta * np.cos(theta)),
                   ca.mtimes(R, -2.0 / n_theta * np.sin(theta)))
    G = ca.Function(f"hb1_{n_theta}", [v, ca.vertcat(w, Zr, Zi, p)], [g], ["v", "par"], ["g"])
    # compiled with its v-Jacobian (C, cached on disk): in CasADi's VM KINSOL's residual and Jacobian
    # evaluations were nearly all of a solve (Dale, 16 phases); the VM without a compiler
    G = compile_functions([G], jacobians=("v",)).functions[G.name()]
    rf = ca.rootfinder("hb1_solve", "kinsol", G, {"strategy": "linesearch", "abstol": 1e-13,
                                                  "error_on_fail": False, "print_level": 0,
                                                  "disable_internal_warnings": True})
    return rf, G


def _orbit_jacobians(model: CableModel, n_theta: int) -> tuple[ca.Function, ca.Function, ca.Function]:
    """dr/dxi and (y, dy/dxi) at ``n_theta`` columns of xi, and dr/dxi at one: the linearization's functions
    mapped once and compiled (cached on disk), not mapped anew on every call (in the VM a map per call
    costs more than the describing function's solve)."""
    def build():
        fns = functions(model)
        xi, p = fns["jac"].mx_in()
        maps = [fns["jac"].map(f"orbit_jac_{n_theta}", "serial", n_theta, [1], []),
                fns["out_jac"].map(f"orbit_out_jac_{n_theta}", "serial", n_theta, [1], []),
                ca.Function(f"static_jac_{n_theta}", [xi, p], fns["jac"].call([xi, p]))]
        out = compile_functions(maps, jacobians=False).functions
        return tuple(out[m.name()] for m in maps)
    return model.cache.get(f"orbit_jacobians_{n_theta}", build)


@dataclasses.dataclass(frozen=True, eq=False)
class HarmonicResponse(ResultBase):
    """One-harmonic (describing-function) response to a regular input of complex amplitude ``input``.

    ``q_amplitude[k]`` complex dq at ``omega[k]``; ``output_amplitude[k]`` the exact first
    harmonic of every output along that orbit; ``output_mean`` its mean; ``linear[k]`` the
    equivalent (complex) linear model at omega[k].
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
                      ladder: int = 6) -> HarmonicResponse:
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

    Returns
    -------
    HarmonicResponse
        ``success`` is False when a frequency's harmonic-balance residual stays above 1e-8.
    """
    p = taut_parameters(model, p)
    st = steady_state(model, p)
    jac_map, out_map, jac_static = _orbit_jacobians(model, n_theta)
    xi0 = operating_xi(model, st.q)
    # the exact linearization's dq response (the continuation's start); its outputs are not needed
    ny = len(model.output_labels)
    lin0 = from_jacobian(model, jac_static(xi0, p).full(), np.zeros((ny, xi0.size)), st.q, np.zeros(ny), kind="exact")
    omega = np.atleast_1d(np.asarray(omega, float))
    Z = np.asarray(input_amplitude, complex)
    if Z.shape != (len(lin0.input_labels),):
        raise ParameterError("input_amplitude", f"shape {Z.shape}",
                             f"needs {len(lin0.input_labels)} entries {lin0.input_labels}")
    rf, G = _hb1_rootfinder(model, n_theta)
    order = np.argsort(omega)
    pre = np.geomspace(omega[order[0]] / 4.0, omega[order[0]], ladder + 1)[:-1]
    nq = model.nq
    Q0, _ = lin0.transfer(pre[:1])
    v = np.concatenate([st.q, (Q0[0] @ Z).real, (Q0[0] @ Z).imag])
    theta = 2 * np.pi * np.arange(n_theta) / n_theta
    res = {}
    for k, w in enumerate(list(pre) + list(omega[order])):
        par = np.concatenate([[w], Z.real, Z.imag, p])
        with casadi_warnings_captured():      # KINSOL's flag of a failed step: the residual below reports the outcome
            v_new = np.array(rf(v, par)).ravel()
        v = v_new if np.all(np.isfinite(v_new)) else v
        if k >= len(pre):           # the residual of the requested frequencies (the continuation's are not reported)
            res[k - len(pre)] = (v.copy(), float(np.max(np.abs(np.array(G(v_new, par))))))
    Qa, Qm, Ya, Ym, R, lins = [], [], [], [], [], []
    for j in range(len(omega)):
        v, r = res[int(np.where(order == j)[0][0])]
        w = omega[j]
        Q = v[nq:2 * nq] + 1j * v[2 * nq:]
        xi0[xi_blocks(model)["q"]] = v[:nq]
        X, Xi = orbit(model, xi0, Q, Z, w, theta)
        J = np.array(jac_map(X, p)).reshape(model.nq, n_theta, -1).transpose(1, 0, 2)
        y, Jy = (np.array(a) for a in out_map(X, p))
        J0, J2 = describing_matrices(J, theta)
        N = describing_function(J0, J2, Xi)
        Jy = Jy.reshape(y.shape[0], n_theta, -1).transpose(1, 0, 2)
        Jy0, Jy2 = describing_matrices(Jy, theta)
        lins.append(from_jacobian(model, N, describing_function(Jy0, Jy2, Xi), v[:nq], y.mean(axis=1),
                                  kind="harmonic", omega=float(w)))
        Qa.append(Q); Qm.append(v[:nq]); R.append(r)
        Ya.append(2.0 / n_theta * (y @ np.exp(-1j * theta))); Ym.append(y.mean(axis=1))
    return HarmonicResponse(omega=omega, input=Z, input_labels=lin0.input_labels, output_labels=model.output_labels,
                            q_amplitude=np.array(Qa), q_mean=np.array(Qm), output_amplitude=np.array(Ya),
                            output_mean=np.array(Ym), residual=np.array(R), linear=tuple(lins),
                            success=bool(np.all(np.array(R) < 1e-8)), message=_harmonic_message(omega, R),
                            stats={"n_theta": n_theta, "continuation_steps": ladder})


def _harmonic_message(omega, residual) -> str:
    bad = [f"{w:.4g}" for w, r in zip(omega, residual) if not r < 1e-8]
    return "" if not bad else (f"harmonic balance did not converge at omega = {', '.join(bad)} rad/s "
                               "(residual > 1e-8): refine the grid near those frequencies or use simulate()")
