"""``dopri5`` and ``rk23``: explicit Runge-Kutta pairs with error control, run entirely in compiled C.

One C driver (``explicit_rk.c``) holds both pairs as small tables (stages, a_ij, c_i, error weights,
orders, PI beta, dense-output rule) selected by a preprocessor define (:data:`PAIRS`), so each
model gets one library per pair and everything but the table is shared: ``dopri5``, below, and
``rk23``, the Bogacki-Shampine 3(2) pair (Bogacki & Shampine 1989, "A 3(2) pair of Runge-Kutta
formulas", Appl. Math. Lett. 2(4), 321-325; SciPy's RK23, MATLAB's ode23): 4 stages, first same
as last (3 new right-hand sides a step), step exponent 1/3 of its 2nd-order estimate, PI beta
0.08, dense output by the cubic Hermite interpolant of (x_n, f_n, x_n+1, f_n+1) (third order;
SciPy's RK23 uses the same). Why rk23 on Wang's model: its stability function 1 + z + z^2/2 +
z^3/6 is stable on the imaginary axis up to |h lambda| = sqrt(3), so on the undamped Dale
stretch mode (254 rad/s) the step settles at ~60 x 254 / 1.7 = 9k steps per 60 s at rtol
1e-3-1e-4, ~33k right-hand sides against DOPRI5's ~85k, while the slow swing is resolved to
~1e-9 m at that step anyway (``studies/bench_time_domain.py`` times both against SciPy's LSODA at
equal accuracy: rk23 at rtol 1e-3, 9.0k steps and 32.5k right-hand sides, against DOPRI5 at 1e-4, 11.4k steps
and 85k). At rtol 1e-6 rk23's accuracy, not its stability, sets the step (23k steps); below ~1e-6 DOPRI5's
higher order wins (rk23 at 1e-8: 114k steps).

The DOPRI5 pair:

The method is the explicit embedded Runge-Kutta pair of Dormand & Prince (1980) ("A family of
embedded Runge-Kutta formulae", J. Comput. Appl. Math. 6, 19-26) with the step control of
Hairer, Norsett & Wanner, *Solving Ordinary Differential Equations I* (2nd ed., 1993): error
norm RMS of err_i / (atol_i + rtol max(|x_i|, |x_new_i|)) (sec. II.4, eqs. 4.10-4.11), the PI
("stabilized") step control of their DOPRI5 code (Hairer & Wanner, *Solving ODEs II*, sec. IV.2;
beta = 0.04, safety 0.9, step ratio in [0.2, 10], no increase right after a rejection), their
starting step (sec. II.4), first-same-as-last, and DOPRI5's 4th-order dense output (sec. II.6,
Shampine 1986's coefficients) for the output times, so the steps are
never shortened to land on an output time (on the Dale grid, 0.05 s outputs and ~0.01 s steps,
clipping would add up to a step per output). The driver is ``explicit_rk.c`` next to this module.

Why hand-written C: CasADi (3.8) offers no error-controlled explicit integrator (its ``rk``
plugin takes fixed steps), SUNDIALS ARKODE is not exposed through ``casadi.integrator``, and a
Python step loop costs ~35 us per right-hand-side call against ~0.2 us compiled. The driver is
appended to the C that CasADi's ``CodeGenerator`` writes for the model's relative-time ODE (the
DAE function of :mod:`.dae`, x' = h ode(x, t0 + h s) with p extended by (t0, h)), built
and cached on disk by :func:`cablesys.compiled.compile_functions` (same compiler command, cache
key = code hash + compiler identity, atomic writes), and loaded as a CasADi function with
``casadi.external`` (CasADi's external-function C API: ``cablesys_dopri5``, ``_n_in``,
``_sparsity_in``, ``_work``, ...). One call advances over a block of :data:`BLOCK` output times;
a CasADi ``mapaccum`` over the blocks carries the integrator (time, step, state, FSAL stage,
dense-output coefficients, counters, status) from one block to the next, so a whole chunk of
output times is one CasADi call with no Python per step.

Why dopri5 at all: the Dale stretch mode (lambda = -0.38 +- 254i 1/s, nearly undamped) lies by
the imaginary axis, where BDF orders 3-5 are unstable, so CVODES takes ~30-44k steps per 60 s
whatever rtol. DOPRI5 is stability-limited there too, and more than RK4: its stability region
reaches -3.3 on the real axis but only touches the imaginary axis (|R(iy)| - 1 = 1e-6 at y = 1,
3e-3 at 1.5, 0.15 at 2.5), so the error control settles where the mode's own damping balances
that growth, |h lambda| ~ 1.35: ~11k accepted steps per 60 s (plus ~20 % rejected) at any rtol
from 1e-3 to 1e-6, 7 right-hand sides each (FSAL: 6 new) at ~0.25 us compiled. It controls its
error, which the compiled ``rk`` loop (h |lambda| up to 2.8, 4 evaluations per step) does not.

Where it helps: Wang's 2-DOF model, whose only fast mode is the stretch mode (Dale at SciPy LSODA's
accuracy, rtol 1e-4: 11.4k steps, 85k right-hand sides; ``studies/bench_time_domain.py`` times it against LSODA
and CVODES). Not on segmented cables: their axial element modes are fast and as undamped (segmented Dale
N = 4: |lambda| ~ 6000 1/s, 220-380k steps; at rtol 1e-3 the top tension is wrong by hundreds of times its
range, since rtol acts on node coordinates of metres while the tension follows micrometre stretches; 300 m
heave N = 20: |lambda| ~ 530 1/s, ~9.7k steps). There the A-stable BDF2 steps over the modes and is the choice.

Tolerances: the same state scales as the other adaptive methods (``IntegratorSettings.scaled``,
:mod:`cablesys.model.scales`), applied as a per-state absolute tolerance atol x S_i(p) on the
physical states (DOPRI5 takes a vector atol, so no change of variables is needed: the error norm
is identical to integrating x / S with the scalar atol). ``max_num_steps`` is the budget of
attempted steps per output interval, as for CVODES.

Without a compiled library (no C compiler, ``CABLESYS_COMPILE=0``, or ``compiled=False``)
:func:`.integrators.make_integrator` runs CVODES instead, with one logged notice.
"""

from __future__ import annotations

import dataclasses
import hashlib
import logging
from importlib import resources

import casadi as ca
import numpy as np

from ..compiled import Compiled, compile_functions
from ..errors import ParameterError, SolverError
from ..model import CableModel
from ..model.scales import state_scales
from .dae import relative_time_dae

log = logging.getLogger(__name__)

__all__ = ["DRIVER", "PAIRS", "ExplicitRKIntegrator", "explicit_rk_library", "make_explicit_rk"]

DRIVER = "cablesys_dopri5"
# the pairs of the driver (explicit_rk.c): method name -> (CS_ERK_METHOD, exported driver name)
PAIRS = {"dopri5": (1, DRIVER), "rk23": (2, "cablesys_rk23")}
HEAD = 13                  # carry layout: see explicit_rk.c
# output times per driver call: the grid is a mapaccum over blocks of them. CasADi's mapaccum costs
# time superlinear in its length to build, the Simulator's chunks
# are up to 4096 output times long, and one block call costs nothing extra at run time
BLOCK = 64
PAUSED = 4                 # the call's step budget is used up: not a failure (explicit_rk.c)
STATUS = {1: ("TOO_MUCH_WORK", "the step budget max_num_steps of one output interval is used up"),
          2: ("ERR_FAILURE", "the step size fell below the rounding level of the time"),
          3: ("NONFINITE", "the right-hand side or the state became non-finite and smaller steps did not help")}


@dataclasses.dataclass(frozen=True)
class _Source:
    code: str
    digest: str


def _driver_source() -> _Source:
    code = resources.files(__package__).joinpath("explicit_rk.c").read_text()
    return _Source(code, hashlib.sha256(code.encode()).hexdigest()[:16])


def explicit_rk_library(model: CableModel, compiled: bool = True, method: str = "dopri5") -> Compiled:
    """The model's relative-time ODE and the driver of one explicit pair in one compiled library
    (built once per model and pair, cached on disk).

    Parameters
    ----------
    model : CableModel
        The model (its explicit ODE; any kind).
    compiled : bool, optional
        False returns the uncompiled Compiled (no driver: the caller falls back).
    method : str, optional
        The pair, a key of :data:`PAIRS`: ``"dopri5"`` (Dormand-Prince 5(4)) or ``"rk23"``
        (Bogacki-Shampine 3(2)).

    Returns
    -------
    Compiled
        ``functions[PAIRS[method][1]]`` is the driver (when ``compiled``); build and load times.
    """
    number, driver = _pair(method)
    src = _driver_source()

    def build():
        rhs = relative_time_dae(model, implicit=False, scaled=False)
        defines = (f"\n#define CS_ERK_METHOD {number}\n#define CS_ERK_NAME {driver}\n"
                   f"#define CS_ERK_NX {2 * model.nq}\n#define CS_ERK_NP {len(model.layout) + 2}\n"
                   f"#define CS_ERK_NK {BLOCK}\n"
                   f"#define CS_ERK_RHS {rhs.name()}\n#define CS_ERK_RHS_WORK {rhs.name()}_work\n")
        return compile_functions([rhs], jacobians=False, enabled=compiled, extra_c=defines + src.code,
                                 extra_names=(driver,))
    return model.derive(f"{method}:{src.digest}:{BLOCK}:{'compiled' if compiled else 'vm'}", build)


def _pair(method: str) -> tuple[int, str]:
    try:
        return PAIRS[method]
    except KeyError:
        raise ParameterError("method", method, f"an explicit pair of the compiled driver: {tuple(PAIRS)}") from None


class ExplicitRKIntegrator:
    """An explicit pair of the compiled driver (DOPRI5 or BS3) over a fixed relative grid, called
    like a CasADi integrator.

    ``F(x0=..., p=...)`` (or positional) -> ``{"xf": ndarray (nx, len(grid) - 1)}``; ``stats()`` of
    the last call: ``nsteps`` (accepted), ``n_rejected``, ``nfevals``, ``status``. A failure
    raises :class:`~cablesys.errors.SolverError` naming the flag and the time, with the states
    reached kept on the error (``err.states``, ``err.times``: relative grid times).

    :attr:`call_budget` (attempted steps per call; 0: none) bounds the cost of one call: when it
    is used up the call returns early with :attr:`paused` True and NaN columns after the last
    output time reached, so a caller can look for an interrupt and resume from there.

    Parameters
    ----------
    function : casadi.Function
        ``(x0, p) -> (xf, carry)``: the driver mapped over the grid.
    grid : array_like
        The relative output grid (first entry the start).
    method : str, optional
        The pair's name, for messages (``"dopri5"``, ``"rk23"``).
    """

    def __init__(self, function: ca.Function, grid, method: str = "dopri5"):
        self.function, self.grid, self.method = function, np.asarray(grid, dtype=float), method
        self._stats = None
        self.call_budget = 0
        self.paused = False

    def __call__(self, *args, **kw) -> dict:
        kw.update(zip(("x0", "p"), args))
        p = np.asarray(kw["p"], dtype=float).ravel()
        out = self.function(x0=kw["x0"], p=p, budget=float(self.call_budget))
        X, c = np.array(out["xf"]), np.array(out["carry"]).ravel()
        status = int(c[5])
        self._stats = {"nsteps": int(c[2]), "n_rejected": int(c[3]), "nfevals": int(c[4]), "status": status}
        self.paused = status == PAUSED
        if status and not self.paused:
            flag, why = STATUS.get(status, (f"STATUS_{status}", "unknown failure"))
            t0, h = p[-2], p[-1]
            s_fail = float(c[6])
            n_ok = int(np.argmin(np.all(np.isfinite(X), axis=0))) if not np.all(np.isfinite(X)) else X.shape[1]
            err = SolverError(
                f'{self.method} returned "{flag}" at t = {h * (s_fail - self.grid[0]):.9g} (s from the start of the call; '
                f"time {t0 + h * s_fail:.9g} s): {why} (after {c[2]:.0f} accepted and {c[3]:.0f} rejected steps); "
                f"the states at the first {n_ok} output times are kept")
            err.flag, err.time, err.states, err.times = flag, float(t0 + h * s_fail), X[:, :n_ok], self.grid[1:n_ok + 1]
            err.stats = dict(self._stats)
            raise err
        return {"xf": X}        # numpy: every caller takes np.array of it (a DM round trip cost 0.25 ms per 1k outputs)

    def stats(self) -> dict:
        """Counters of the last call (RuntimeError before any, as CasADi's integrators)."""
        if self._stats is None:
            raise RuntimeError(f"{self.method}: no statistics before a first evaluation")
        return dict(self._stats)


def make_explicit_rk(model: CableModel, settings, grid, name: str = "F") -> ExplicitRKIntegrator | None:
    """The integrator of ``model`` by the explicit pair ``settings.method`` (``dopri5`` or
    ``rk23``, :data:`PAIRS`) over the relative ``grid``, or None without a compiled library (the
    caller falls back to CVODES).

    Parameters
    ----------
    model : CableModel
        The model.
    settings : IntegratorSettings
        ``method`` (a key of :data:`PAIRS`), ``rtol``, ``atol`` (per state atol x S_i(p) when
        ``scaled``), ``max_num_steps`` (per output interval), ``compiled``/``jit``.
    grid : array_like
        Relative output grid s (t = t0 + h s, (t0, h) appended to p); outputs at grid[1:].
    name : str, optional
        Name of the CasADi function.

    Returns
    -------
    ExplicitRKIntegrator or None
    """
    method = settings.method
    comp = explicit_rk_library(model, bool(settings.compiled or settings.jit), method)
    if not comp.compiled:
        return None
    grid = np.asarray(grid, dtype=float)
    nx, npx, n = 2 * model.nq, len(model.layout) + 2, len(grid) - 1
    nb = -(-n // BLOCK)
    # blocks of BLOCK output times (columns), the last one padded with the final time (no steps there)
    s_out = np.concatenate([grid[1:], np.full(nb * BLOCK - n, grid[-1])]).reshape(nb, BLOCK).T
    acc = comp.functions[_pair(method)[1]].mapaccum(f"{name}_steps", nb, [0], [0])
    x0, p, budget = ca.MX.sym("x0", nx), ca.MX.sym("p", npx), ca.MX.sym("budget")
    S = state_scales(model)(p[:-2]) if settings.scaled else ca.DM.ones(nx)
    head = np.zeros(HEAD)
    head[0] = head[7] = grid[0]                     # s and the start of the last step; the rest 0 (explicit_rk.c)
    carry0 = ca.vertcat(ca.DM(head), x0, ca.DM.zeros(6 * nx))
    tol = ca.vertcat(settings.rtol, settings.max_num_steps, budget)
    C, X = acc(carry0, ca.DM(s_out), ca.repmat(p, 1, nb), ca.repmat(tol, 1, nb),
               ca.repmat(settings.atol * S, 1, nb))
    F = ca.Function(name, [x0, p, budget], [X[:, :n], C[:, -1]], ["x0", "p", "budget"], ["xf", "carry"])
    return ExplicitRKIntegrator(F, grid, method)


def fallback_settings(model: CableModel, settings):
    """The settings CVODES runs instead of ``dopri5`` or ``rk23`` when its driver is not compiled
    (no C compiler, ``CABLESYS_COMPILE=0``, or ``compiled=False``); one logged notice per model
    and pair.

    Parameters
    ----------
    model : CableModel
        The model (the notice is logged once per model).
    settings : IntegratorSettings
        The ``dopri5`` or ``rk23`` settings.

    Returns
    -------
    IntegratorSettings
        The same tolerances, scaling and step budget with ``method="cvodes"``.
    """
    method = settings.method
    comp = explicit_rk_library(model, bool(settings.compiled or settings.jit), method)
    model.derive(f"{method}:fallback-notice", lambda: log.warning(
        "%s needs its compiled C driver (%s): running CVODES (BDF) instead", method,
        comp.note or "not compiled") or True)
    return dataclasses.replace(settings, method="cvodes")
