"""Whether an explicit pair may step a quasi-static rung: its stability step against its accuracy step.

The quasi-static rungs have no stretch modes left, so their fastest dynamics are the swing and string
modes of the elements and, in motion, the drag on light elements, which gives fast real eigenvalues
(Dale, quasi-static N = 4: -52 1/s with every angle rate at its natural scale, against a 1.3 rad/s
forcing; -33 1/s at most along the run). An explicit pair is stable while h lambda lies in its
stability region |R(h lambda)| <= 1 (Hairer & Wanner, *Solving ODEs II*, sec. IV.2), R the pair's
stability polynomial:

- ``rk23`` (Bogacki-Shampine 3(2), 3 stages of order 3): R(z) = 1 + z + z^2/2 + z^3/6, the real-axis
  limit 2.51, the imaginary-axis limit sqrt(3);
- ``dopri5`` (Dormand-Prince 5(4), 6 stages of order 5): R(z) = sum_k<=5 z^k/k! + z^6/600 (Hairer &
  Wanner II, sec. IV.2), real-axis limit 3.31; it only touches the imaginary axis (|R(iy)| - 1 < 1e-6
  for y <= 1), so GROWTH allows that much.

Its accuracy step at rtol is set by the forcing: the error estimate of a p(p-1) pair is O((h omega)^p)
per step relative to the motion, so h_acc ~ rtol^(1/p) / omega (rk23 at rtol 1e-4 on Dale: predicted
0.035 s, measured mean step 0.042 s; dopri5 predicted 0.12 s, measured 0.065 s). Where
h_stab = min over the eigenvalues of r(arg lambda) / |lambda| is below h_acc, stability sets the step
and the pair crawls at its limit (Dale quasi-static N = 8: string modes at 56.5 rad/s, rk23 takes
1.73 / 56.5 = 0.031 s steps whatever rtol, 1950 steps from 1e-3 to 1e-4): the guard refuses and the
rung runs CVODES (BDF, whose step does not depend on the fast modes' stability). The eigenvalues are
taken of the rung's ODE Jacobian at its initial (static) state and there with every rate at its
natural scale (:mod:`cablesys.model.scales`: the forcing frequency times the angle scale, the size of
the motion the tolerances are relative to) times ``motion`` (the linear response's amplification of
the body motion over the top's, at least 1): the drag slope grows with the speed. Along the Dale run the
largest |lambda| was 33 1/s (rates up to 0.85 of their scales) against the probe's 52 1/s: the guard errs
on the side of refusing.

Why the ladder uses rk23 and not dopri5 (both guarded alike): at rest, without current, the string modes lie
on the imaginary axis (Dale N = 4: 11-27 rad/s), which rk23's region contains up to sqrt(3) but DOPRI5's
only touches, so DOPRI5's stability step there is 1.0 / 26.6 s and the guard refuses it, although in motion
the drag damps those modes and DOPRI5 ran Dale in 926 steps (mean 0.065 s). Their run times are close
(``studies/work_precision.py``); dopri5 is 5-15x more accurate at equal rtol, which the ladder gets
instead by tightening rtol where the stated error is small (:data:`cablesys.ladder.auto.STATED_ROOM`).

Counted (Dale 60 s, quasi-static N = 4, rtol 1e-4, compiled): rk23 1438 steps, 4.7k right-hand sides; dopri5
926 steps, 5.7k; CVODES (variable-order BDF) 1762 steps, with fewer operations per step for the explicit pairs
(their run times: ``studies/work_precision.py``). Body / tension error
against the rung's own rtol 1e-10 run: rk23 8.7e-6 / 3.6e-7, CVODES 6.7e-7 / 4.2e-7, dopri5 8.7e-7 / 2.8e-8,
against the stated model error 4.0e-3 / 1.0e-4. (The variable-order BDF had replaced BDF2 there: straight
1748 -> 592 steps, body error 1e-3 -> 1.5e-4; N = 3: 2623 -> 1363 steps, 5e-4 -> 4e-6.)

Accuracy: at rtol 1e-4 the body error of rk23 against its own tight run was 0.09 rtol on Dale (stated 4e-3),
0.75 rtol on the random scene short-3 (tests/test_ladder_random.py; N = 1, stated 1.26e-4 at the floor: 59 %
of it, CVODES 1.08 rtol, 86 %) and up to 7 rtol when forced at a lightly damped swing resonance (short-2 run
quasi-static; auto runs Wang's model there); the tension's is 10-10^4 times smaller. So the ladder's rtol for
these rungs is at most the stated body error / 20 (``auto.STATED_ROOM``), rounded down to a decade: short-3
at rtol 1e-6 has 4.7e-8 (589 steps), Dale keeps 1e-4, and the random stiff scenes (heavy-2, current-3 with AE
x 300, N = 3) showed 0.5 % and 0.3 % of their stated errors.
"""

from __future__ import annotations

import cmath
import dataclasses
import functools
import math

import numpy as np

# stability polynomials: coefficients of z^0, z^1, ... (module docstring)
STABILITY_POLYNOMIALS = {"rk23": (1.0, 1.0, 1 / 2, 1 / 6),
                         "dopri5": (1.0, 1.0, 1 / 2, 1 / 6, 1 / 24, 1 / 120, 1 / 600)}
ERROR_ORDER = {"rk23": 3, "dopri5": 5}    # the pair's error estimate is O(h^p) per step
# past 8 elements the string modes set an explicit pair's step (Dale N = 8: refused) and the guard's dense probe
# Jacobian grows as N^3 (heavy1000 quasi-static N = 20: 404 MB serialized, 120 MB of C, the compiler out of memory)
EXPLICIT_MAX_ELEMENTS = 8
GROWTH = 1e-6          # |R| up to 1 + GROWTH counts as stable (DOPRI5 on the imaginary axis)
ACCURACY_MARGIN = 1.0  # accept when h_stab >= ACCURACY_MARGIN x h_acc


def amplification(method: str, z):
    """|R(z)| of the pair ``method``'s stability polynomial (``z`` a number or an array)."""
    return np.abs(np.polyval(STABILITY_POLYNOMIALS[method][::-1], z))


@functools.lru_cache(maxsize=4096)
def stability_radius(method: str, angle: float) -> float:
    """Largest r with |R(t e^{i angle})| <= 1 + GROWTH for all 0 < t <= r (the stability boundary
    along the ray at ``angle`` from the positive real axis, rad; 0 where the ray leaves at once)."""
    d = cmath.exp(1j * angle)
    ts = np.linspace(1e-3, 8.0, 8000)
    bad = np.nonzero(amplification(method, ts * d) > 1.0 + GROWTH)[0]
    if bad.size == 0:
        return float(ts[-1])
    if bad[0] == 0:
        return 0.0
    lo, hi = ts[bad[0] - 1], ts[bad[0]]
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if amplification(method, mid * d) <= 1.0 + GROWTH else (lo, mid)
    return float(lo)


def stability_step(method: str, eigenvalues) -> float:
    """Largest step h with h lambda in the stability region for every eigenvalue (s; inf without
    any nonzero one). A growing mode (Re lambda >= 0) is taken on the imaginary axis: its growth is
    physical and resolved for accuracy; the pair must only not add its own."""
    lam = np.atleast_1d(np.asarray(eigenvalues, dtype=complex))
    lam = lam[np.abs(lam) > 0.0]
    angles = np.where(lam.real >= 0.0, math.pi / 2, np.arctan2(np.abs(lam.imag), lam.real))
    radii = [stability_radius(method, a) for a in np.round(angles, 4).tolist()]
    return float(np.min(np.array(radii) / np.abs(lam))) if lam.size else math.inf


def accuracy_step(method: str, rtol: float, omega: float) -> float:
    """h_acc = rtol^(1/p) / omega: the step at which the pair's O((h omega)^p) error estimate per
    step reaches rtol on a motion of frequency ``omega`` (rad/s)."""
    return rtol ** (1.0 / ERROR_ORDER[method]) / max(omega, 1e-12)


@dataclasses.dataclass(frozen=True)
class ExplicitFit:
    """The guard's decision and its numbers: ``accepted`` when the stability step is at least
    ACCURACY_MARGIN x the accuracy step."""

    method: str
    accepted: bool
    stability_step: float     # s
    accuracy_step: float      # s
    lambda_max: float         # 1/s, largest |eigenvalue| of the states probed
    omega: float              # rad/s, the frequency the accuracy step resolves

    @property
    def reason(self) -> str:
        verdict = "accepted" if self.accepted else "refused (stability sets the step): CVODES"
        return (f"{self.method} {verdict}: stability step {self.stability_step:.3g} s (|lambda|_max "
                f"{self.lambda_max:.3g} 1/s) vs accuracy step {self.accuracy_step:.3g} s at omega {self.omega:.3g} rad/s")


# the probe's dense Jacobian grows as N^3: Dale quasi-static N = 4 / 8 / 12 / 16 serialize to 1.2 / 4.7 / 15 / 38 MB
# (0.3 / 1.3 / 4.0 / 10 MB of C in one function; 6 s to compile at N = 12). It is evaluated once per run: past
# this size the VM costs less than the compiler (which compiled.MAX_C_BYTES also keeps within memory)
PROBE_COMPILE_MAX = 2_000_000


def probe_function(model):
    """``(x0, p, motion) -> (J(x0), J(x0 + motion S_rates), S)``: the rung's ODE Jacobian at its start and
    moving at ``motion`` x the rate scales, and the state scales S (:mod:`cablesys.model.scales`), one
    function built once per model and compiled up to PROBE_COMPILE_MAX serialized bytes (cached on disk; CasADi's
    VM without a compiler or past that size)."""
    def build():
        import casadi as ca

        from ..compiled import compile_functions
        from ..model.scales import state_scales
        nx = 2 * model.nq
        x, p, k = model.sym("x", nx), model.sym("p", len(model.layout)), model.sym("motion")
        jac = ca.Function("explicit_probe_jac", [x, p], [ca.jacobian(model.ode(x, 0.0, p), x)])
        S = state_scales(model)(p)
        shift = ca.vertcat(ca.DM.zeros(model.nq), k * S[model.nq:])
        F = ca.Function("explicit_probe", [x, p, k], [jac(x, p), jac(x + shift, p), S], ["x", "p", "motion"],
                        ["J0", "J1", "S"])
        if len(F.serialize()) > PROBE_COMPILE_MAX:    # one evaluation per run: the VM, not a compiler run
            return F
        return compile_functions([F], jacobians=False).functions[F.name()]
    return model.derive("explicit_probe", build)


def explicit_fit(model, p, x0, rtol: float, method: str = "rk23", motion: float = 1.0) -> ExplicitFit:
    """Whether the explicit pair ``method`` steps ``model`` at its accuracy step (module docstring).

    Parameters
    ----------
    model : CableModel
        The rung's model (a quasi-static one: angles and their rates are the states).
    p : array_like
        Its parameter vector.
    x0 : array_like
        Its initial (static) state (SI).
    rtol : float
        The relative tolerance of the run.
    method : {"rk23", "dopri5"}
        The pair.
    motion : float, optional
        Amplification of the motion over its natural scale (>= 1): the rates probed are the rate
        scales times this.

    Returns
    -------
    ExplicitFit
        The decision with its stability and accuracy steps.
    """
    x0 = np.asarray(x0, dtype=float).ravel()
    J0, J1, S = (a.full() for a in probe_function(model)(x0, p, max(1.0, float(motion))))
    S = S.ravel()
    nq = x0.size // 2
    omega = float(S[nq] / S[0]) if S[0] > 0 else 0.0        # the scales' rate / angle: the forcing frequency
    lam = np.linalg.eigvals(np.stack([J0, J1])).ravel()
    h_stab = stability_step(method, lam)
    h_acc = accuracy_step(method, rtol, omega)
    return ExplicitFit(method, bool(h_stab >= ACCURACY_MARGIN * h_acc), float(h_stab), float(h_acc),
                       float(np.max(np.abs(lam))) if lam.size else 0.0, omega)
