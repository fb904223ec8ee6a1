"""Linearization about the steady state: labelled second-order and state-space models.

Everything comes from the model's own CasADi functions by automatic differentiation.
Write the equations of motion (Wang 1971 eq. 47-48, M q'' = f) as the residual

    r(xi) = f(q, q', e, p) - M(q) q'' = 0,   xi = (q, q', q'', z, z', z'', w),

with z = (x_s, y_s) the top displacement (it enters only through e = (t, z, z', z''))
and w the amplitudes of the scene's waves (Wang 1971 eq. 26, parameters of the model).
Its Jacobian dr/dxi, evaluated at one point (exact linearization) or averaged over a
response (equivalent linearization, :mod:`.equivalent`), gives

    M dq'' + C dq' + K dq = F0 z + F1 z' + F2 z'' + Fw w,       M = -dr/dq'', C = -dr/dq', K = -dr/dq,

and the outputs y = Cq dq + Cv dq' + D0 z + D1 z' (x_b, y_b, phi, u, tension, ...).
The state-space form x = (dq, dq') is x' = A x + B0 z + B1 z' + B2 z''.
"""

from __future__ import annotations

import dataclasses
from typing import ClassVar

import casadi as ca
import numpy as np

from ..model import CableModel
from ..results import ResultBase, timed
from .steady import SteadyState, steady_state

TOP_INPUTS = ("x_s", "y_s")
TOP_INPUTS_3D = TOP_INPUTS + ("z_s",)     # Wang's cable in 3-D: the sway z_s too


def top_inputs(model: CableModel) -> tuple:
    """The top-displacement inputs of ``model``: (x_s, y_s), and z_s for the 3-D equations (e = (t, z, z', z'')), then
    a vessel's rotation where it moves several prescribed points (``rot_z_s`` ..., rad; model/system.py), whose
    entries e appends after the translation's (model/top_motion.py)."""
    vessel = getattr(model, "vessel_inputs", ())
    n = model.top.size1_out(0) - 3 * len(vessel)
    return (TOP_INPUTS_3D if n == 1 + 3 * len(TOP_INPUTS_3D) else TOP_INPUTS) + tuple(vessel)


def wave_amplitude_indices(model: CableModel) -> list[int]:
    """Positions in p of the wave amplitudes (Wang 1971 eq. 26 'a'), in wave order."""
    return model.layout.wave_amplitude_indices()


def xi_blocks(model: CableModel) -> dict:
    """Slices of xi = (q, q', q'', z, z', z'', w) by name."""
    nq, nw = model.nq, len(wave_amplitude_indices(model))
    nz = len(top_inputs(model))
    sizes = [("q", nq), ("qd", nq), ("qdd", nq), ("z", nz), ("zd", nz), ("zdd", nz), ("w", nw)]
    out, k = {}, 0
    for name, n in sizes:
        out[name] = slice(k, k + n)
        k += n
    out["n"] = k
    return out


def functions(model: CableModel) -> dict:
    """CasADi functions of xi (built once per model and cached).

    ``residual(xi, p) -> r``, ``jac(xi, p) -> dr/dxi`` and ``out_jac(xi, p) -> (y, dy/dxi)``;
    the time in e is 0 and the wave amplitudes of p are replaced by the w block of xi.
    """
    return model.cache.get("linearize", lambda: _build_functions(model))


def _build_functions(model: CableModel) -> dict:
    b = xi_blocks(model)
    xi = ca.SX.sym("xi", b["n"])
    p = ca.SX.sym("p", len(model.layout))
    widx = wave_amplitude_indices(model)
    p_w = ca.vertcat(*[xi[b["w"]][widx.index(i)] if i in widx else p[i] for i in range(len(model.layout))])
    nt = len(top_inputs(model)) - len(getattr(model, "vessel_inputs", ()))      # the translation, then the rotation
    z, zd, zdd = xi[b["z"]], xi[b["zd"]], xi[b["zdd"]]
    e = ca.vertcat(0.0, z[:nt], zd[:nt], zdd[:nt], z[nt:], zd[nt:], zdd[nt:])   # EXO_LABELS order (top_motion.py)
    assert e.shape[0] == model.top.size1_out(0)
    q, qd, qdd = xi[b["q"]], xi[b["qd"]], xi[b["qdd"]]
    M, f = model.dynamics(q, qd, e, p_w)
    r = f - ca.mtimes(M, qdd)
    y = model.outputs(ca.vertcat(q, qd), e, p_w)
    fns = {
        "residual": ca.Function("lin_residual", [xi, p], [r], ["xi", "p"], ["r"]),
        "jac": ca.Function("lin_jac", [xi, p], [ca.jacobian(r, xi)], ["xi", "p"], ["J"]),
        "out_jac": ca.Function("lin_out_jac", [xi, p], [y, ca.jacobian(y, xi)], ["xi", "p"], ["y", "Jy"]),
    }
    return fns


@dataclasses.dataclass(frozen=True, eq=False)
class LinearModel(ResultBase):
    """M dq'' + C dq' + K dq = F0 u + F1 u' + F2 u'';  y = Cq dq + Cv dq' + D0 u + D1 u' + D2 u''.

    ``u`` are the inputs (``input_labels``: x_s, y_s and one per wave amplitude). Matrices may
    be complex when they come from a harmonic equivalent linearization (valid at ``omega``).
    ``q0``/``y0`` is the operating point; ``kind`` says how the drag was linearized.
    """

    q_labels: tuple
    input_labels: tuple
    output_labels: tuple
    M: np.ndarray
    C: np.ndarray
    K: np.ndarray
    F0: np.ndarray
    F1: np.ndarray
    F2: np.ndarray
    Cq: np.ndarray
    Cv: np.ndarray
    D0: np.ndarray
    D1: np.ndarray
    D2: np.ndarray
    q0: np.ndarray
    y0: np.ndarray
    kind: str = "exact"
    omega: float | None = None
    success: bool = True
    message: str = ""
    stats: dict = dataclasses.field(default_factory=dict)

    VARIABLES: ClassVar[dict] = {"q": ("1", "generalized coordinate (row)"), "q_col": ("1", "generalized coordinate (column)"),
                                  "input": ("1", "input"), "output": ("1", "output"),
                                  "M": ("SI", "mass matrix"), "C": ("SI", "damping matrix"), "K": ("SI", "stiffness matrix"),
                                  "F0": ("SI", "input force matrix"), "F1": ("SI", "input-rate force matrix"),
                                  "F2": ("SI", "input-acceleration force matrix"), "Cq": ("SI", "output matrix of dq"),
                                  "Cv": ("SI", "output matrix of dq'"), "D0": ("SI", "feedthrough of u"),
                                  "D1": ("SI", "feedthrough of u'"), "D2": ("SI", "feedthrough of u''"),
                                  "q0": ("SI", "operating point"), "y0": ("SI", "outputs at the operating point")}

    @property
    def nq(self) -> int:
        return len(self.q_labels)

    # -- state-space form, x = (dq, dq') ----------------------------------------------------
    @property
    def A(self) -> np.ndarray:
        nq = self.nq
        Minv = np.linalg.inv(self.M)
        return np.block([[np.zeros((nq, nq)), np.eye(nq)], [-Minv @ self.K, -Minv @ self.C]])

    def B(self, order: int) -> np.ndarray:
        """B0, B1, B2: input matrices of u, u', u'' in x' = A x + B0 u + B1 u' + B2 u''."""
        F = (self.F0, self.F1, self.F2)[order]
        return np.vstack([np.zeros_like(F), np.linalg.solve(self.M, F)])

    @property
    def C_out(self) -> np.ndarray:
        """Output matrix of the state x = (dq, dq')."""
        return np.hstack([self.Cq, self.Cv])

    def transfer_state_space(self, omega) -> np.ndarray:
        """C (iwI - A)^-1 (B0 + iw B1 + (iw)^2 B2) + D0 + iw D1 + (iw)^2 D2, shape (n_omega, ny, nu).

        The textbook form, kept as a cross-check of :meth:`transfer` (which solves the
        smaller second-order system)."""
        s = 1j * np.atleast_1d(np.asarray(omega, float))[:, None, None]
        n = 2 * self.nq
        lhs = s * np.eye(n) - self.A
        rhs = self.B(0) + s * self.B(1) + s**2 * self.B(2)
        return self.C_out @ np.linalg.solve(lhs, rhs) + self.D0 + s * self.D1 + s**2 * self.D2

    def transfer(self, omega) -> tuple[np.ndarray, np.ndarray]:
        """(Q, Y): complex amplitudes of dq and y per unit input, shapes (n_omega, nq, nu), (n_omega, ny, nu).

        One batched ``numpy.linalg.solve`` of (K + iw C - w^2 M) Q = F0 + iw F1 - w^2 F2 over all w.
        """
        s = 1j * np.atleast_1d(np.asarray(omega, float))[:, None, None]
        Z = self.K + s * self.C + s**2 * self.M
        Q = np.linalg.solve(Z, self.F0 + s * self.F1 + s**2 * self.F2)
        Y = (self.Cq + s * self.Cv) @ Q + self.D0 + s * self.D1 + s**2 * self.D2
        return Q, Y

    def to_xarray(self):
        """An ``xarray.Dataset`` of the matrices with labelled dimensions."""
        import xarray as xr
        dq, du, dy = ("q", self.q_labels), ("input", self.input_labels), ("output", self.output_labels)
        dq2 = ("q_col", self.q_labels)
        def da(a, dims):
            return xr.DataArray(np.asarray(a), dims=[d[0] for d in dims], coords={d[0]: list(d[1]) for d in dims})
        return xr.Dataset({"M": da(self.M, (dq, dq2)), "C": da(self.C, (dq, dq2)), "K": da(self.K, (dq, dq2)),
                           "F0": da(self.F0, (dq, du)), "F1": da(self.F1, (dq, du)), "F2": da(self.F2, (dq, du)),
                           "Cq": da(self.Cq, (dy, dq2)), "Cv": da(self.Cv, (dy, dq2)),
                           "D0": da(self.D0, (dy, du)), "D1": da(self.D1, (dy, du)), "D2": da(self.D2, (dy, du)),
                           "q0": da(self.q0, (dq,)), "y0": da(self.y0, (dy,))},
                          attrs={"kind": self.kind, "omega": float("nan") if self.omega is None else self.omega})


def operating_xi(model: CableModel, q0) -> np.ndarray:
    """xi at the steady state: q = q0, every rate, input and wave amplitude zero."""
    xi = np.zeros(xi_blocks(model)["n"])
    xi[xi_blocks(model)["q"]] = q0
    return xi


def from_jacobian(model: CableModel, J, Jy, q0, y0, *, kind: str, omega=None) -> LinearModel:
    """Assemble a :class:`LinearModel` from dr/dxi (``J``) and dy/dxi (``Jy``)."""
    b = xi_blocks(model)
    J, Jy = np.asarray(J), np.asarray(Jy)
    wl = tuple(f"wave[{k}]" for k in range(b["w"].stop - b["w"].start))
    nw = len(wl)
    def inp(block, extra):    # top columns plus wave columns (waves enter without derivatives)
        return np.hstack([block, extra])
    zw = np.zeros((J.shape[0], nw), dtype=J.dtype)
    zwy = np.zeros((Jy.shape[0], nw), dtype=Jy.dtype)
    return LinearModel(
        q_labels=model.q_labels, input_labels=top_inputs(model) + wl, output_labels=model.output_labels,
        M=-J[:, b["qdd"]], C=-J[:, b["qd"]], K=-J[:, b["q"]],
        F0=inp(J[:, b["z"]], J[:, b["w"]]), F1=inp(J[:, b["zd"]], zw), F2=inp(J[:, b["zdd"]], zw),
        Cq=Jy[:, b["q"]], Cv=Jy[:, b["qd"]],
        D0=inp(Jy[:, b["z"]], Jy[:, b["w"]]), D1=inp(Jy[:, b["zd"]], zwy), D2=inp(Jy[:, b["zdd"]], zwy),
        q0=np.asarray(q0, float), y0=np.asarray(y0, float), kind=kind, omega=omega)


def residual_jacobian(lin: LinearModel) -> np.ndarray:
    """dr/dxi of a linear model, xi = (q, q', q'', z, z', z'', w): the inverse of :func:`from_jacobian`.

    Parameters
    ----------
    lin : LinearModel
        A linear model (exact, harmonic or stochastic).

    Returns
    -------
    ndarray
        (nq, len(xi)) with blocks -K, -C, -M, F0, F1, F2 of the top inputs and F0 of the waves.
    """
    nz = sum(1 for lbl in lin.input_labels if not lbl.startswith("wave["))
    return np.hstack([-lin.K, -lin.C, -lin.M, lin.F0[:, :nz], lin.F1[:, :nz], lin.F2[:, :nz], lin.F0[:, nz:]])


def taut_parameters(model: CableModel, p) -> np.ndarray:
    """p with the slack switches cleared (a linear model is about a taut state); waves stay.

    Not the statics' parameters (:mod:`cablesys.statics.steady` also zeroes the wave
    amplitudes: a steady state has no waves), hence the different name.
    """
    p = np.array(p, dtype=float)
    p[list(model.slack_index)] = 0.0
    return p


@timed
def linearize(model: CableModel, p, *, steady: SteadyState | None = None) -> LinearModel:
    """Exact first-order linearization about the steady state (Jacobians by CasADi AD).

    With a current or tow speed this is the exact linearization about the steady relative
    flow (the drag slope 2 * 1/2 rho C A |U| per element). Without flow the quadratic drag has
    zero slope and this model is undamped: use :mod:`.equivalent` for amplitudes near resonance.

    Parameters
    ----------
    model : CableModel
        The Wang (1971) model (:func:`cablesys.build_model`).
    p : array_like
        Parameter vector (``scene.parameters()``); slack switches are cleared.
    steady : SteadyState, optional
        The operating point; solved with :func:`steady_state` when omitted.

    Returns
    -------
    LinearModel
        M, C, K, input and output matrices about the steady state (SI units of the labels).
    """
    p = taut_parameters(model, p)
    steady = steady or steady_state(model, p)
    fns = functions(model)
    xi0 = operating_xi(model, steady.q)
    J = np.array(fns["jac"](xi0, p))
    y0, Jy = (np.array(v) for v in fns["out_jac"](xi0, p))
    return from_jacobian(model, J, Jy, steady.q, y0.ravel(), kind="exact")
