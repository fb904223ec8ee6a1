"""Integrator registry: one name per method, all behind ``casadi.integrator``.

- ``cvodes``        CVODES, BDF (variable order 1-5), Newton iterations: stiff-safe default;
- ``cvodes-adams``  CVODES, Adams-Moulton: cheaper per step on non-stiff scenes;
- ``idas``          IDAS on the implicit residual M(q) q'' - f = 0 (q'' algebraic; M never inverted);
- ``rk``            classical fixed-step Runge-Kutta 4 (compiled loop, :func:`rk4_interval`): the
                    fastest choice when the step is below the stability limit (no error control);
- ``dopri5``        Dormand-Prince 5(4), explicit with error control and dense output, a compiled C
                    driver (:mod:`.explicit_rk`); CVODES when nothing is compiled;
- ``rk23``          Bogacki-Shampine 3(2), the same compiled driver: 3 evaluations a step, stable on the
                    imaginary axis to |h lambda| = sqrt(3) (undamped stiff modes); CVODES without compiler;
- ``collocation``   fixed-step Radau collocation (implicit), for comparison.

Every integrator runs in relative time s with the parameter vector extended by (t_0, h):
physical time t = t_0 + h s. With h = 1 the grid is in seconds from t_0 (one call over all
output times); with the grid (0, 1) the same integrator steps one interval of any length h,
which the slack-event location and the failure fallback use.

The DAE is one SX function of the model (built once per model and form, kept in
``model.cache``), compiled to C with its Jacobian and cached on disk by
:mod:`cablesys.compiled` unless ``compiled=False`` (then CasADi's virtual machine runs it).

Tolerances: CasADi (3.8) gives CVODES and IDAS one scalar ``abstol`` (``scale_abstol`` multiplies
it by the DAE function's nominal values, which are 1 for an SX function). So the adaptive methods
integrate the scaled states x~ = x / S(p) (``IntegratorSettings.scaled``, the default; S from
:mod:`cablesys.model.scales`: stretch by its static value, angle by the top's amplitude over the
length, node positions by one element's static stretch, rates by these times the forcing
frequency), and ``atol`` is per state atol x S_i: a fraction of each state's natural size, the
same in any unit system. :class:`ScaledIntegrator` takes and gives physical states. Measured in
``studies/bench_state_scaling.py`` (BDF <= 2 at rtol 1e-4, atol 1e-7 m unscaled vs rtol / 10
scaled; errors over each series' range against a tight run): 300 m heave N = 20, 742 vs 502 steps,
tension 0.83 vs 0.86 %; segmented Dale N = 10, 2670 vs 2368 steps, tension 3.4 % both; ramped Dale
(Wang), 652 vs 778 steps, tension 1.4e-4 vs 1.0e-4, stretch rate 1 vs 0.3 %. At the library's
default tolerances the scaled run resolves the dynamic tension (ramped Dale, cvodes rtol 1e-7,
atol 1e-9: 8.2k steps and tension 1.3e-3, stretch rate 20 % unscaled; 19k steps, 6e-7 and 1e-4
scaled: the SI atol was 1.4 % of the static stretch). After an abrupt start (Dale as published)
the undamped stretch mode rings throughout (amplitude ~11 % of the tension range); BDF2 damps it: 18 %
tension error at 2.8k steps unscaled, 8 % at 33k scaled.
What sets the cost is stability: the undamped stretch mode (254 rad/s on Dale) limits BDF orders
3-5, which are not A-stable, to steps of about 0.6/omega_stretch whatever the tolerance (unscaled:
27k steps per 60 s at rtol 1e-6, 24k at 1e-3).
``cvodes-bdf2`` (orders <= 2, A-stable) steps over it: 0.9-2k steps at rtol 1e-3-1e-4, but second
order, so it is the cheapest only at engineering accuracy (body error >= 1e-5 m on Dale). A smooth
start (``top_motion.ramp_s``, the default) removes the ringing that an abrupt start adds (BDF2:
160k -> 11k steps at rtol 1e-6). The compiled ``rk`` loop at the fewest steps inside RK4's
stability limit is the fastest at equal accuracy (no error control: the Simulator warns when
h |lambda|_max exceeds the limit).
"""

from __future__ import annotations

import dataclasses

import casadi as ca
import numpy as np

from ..compiled import SIZE_FLAGS, Compiled, compilation_enabled, compile_functions, compiles, generate
from ..integration import METHODS, IntegratorMethod, resolve
from ..model import CableModel
from ..model.scales import state_scales
from .dae import relative_time_dae, relative_time_jacobian
from .explicit_rk import PAIRS, explicit_rk_library, fallback_settings, make_explicit_rk
from .rkc import coefficients
from .rkc import step as rkc_step

FIXED_LOOPS = ("rk", "rkc")        # the fixed-step methods stepped by one compiled loop (:func:`rk4_interval`)

# the registry and the protocol of a user method live in cablesys.integration (the scene checks names there)
ADAPTIVE = tuple(name for name, m in METHODS.items() if m.adaptive)


@dataclasses.dataclass(frozen=True)
class IntegratorSettings:
    """Method and accuracy settings (immutable).

    ``method`` is a name in :data:`~cablesys.integration.METHODS` or a user
    :class:`~cablesys.integration.IntegratorMethod`; after construction ``method`` is always the
    name (for results and messages) and :attr:`integrator_method` the method itself.
    """

    method: str | IntegratorMethod = "cvodes"
    rtol: float = 1e-8
    atol: float = 1e-8                # scaled: per state atol x S_i (cablesys.model.scales); unscaled: SI
    steps_per_output: int = 10        # fixed-step methods only
    max_num_steps: int = 20000        # step budget per output interval (typical runs use < 100); more fails by name
    compiled: bool = True             # the DAE as cached compiled C (see cablesys.compiled); False: CasADi VM
    scaled: bool = True               # adaptive methods integrate x~ = x / S(p) (cablesys.model.scales): atol x S_i per state
    jit: bool = False                 # former opt-in compilation; now an alias of ``compiled``
    stages: int = 0                   # ``rkc`` only: Runge-Kutta-Chebyshev stages per step (>= 2; .rkc.stages_for)
    custom: IntegratorMethod | None = dataclasses.field(default=None, repr=False)   # set from ``method``

    def __post_init__(self):
        if isinstance(self.method, IntegratorMethod):
            object.__setattr__(self, "custom", self.method)
            object.__setattr__(self, "method", self.method.name)
        elif self.custom is not None and self.custom.name != self.method:
            object.__setattr__(self, "custom", None)     # dataclasses.replace(method=<another name>)
        if self.custom is None:
            resolve(self.method)
        if self.method == "rkc" and self.custom is None:
            coefficients(self.stages)          # a ParameterError names the stages outside [2, MAX_STAGES]
            # (cablesys.time_domain.rkc.stages_for chooses them from the model's spectrum and the step)

    @property
    def integrator_method(self) -> IntegratorMethod:
        """The :class:`~cablesys.integration.IntegratorMethod` these settings run."""
        return self.custom if self.custom is not None else resolve(self.method)


# Element-by-element (SX) compiled C up to this many cable elements: gcc's time and memory grow faster than linearly
# with that code (N = 20: seconds; N = 40: ~40 s; N = 80: 70-100 s at -O0 and 1.8 GB), so past it the segmented
# cable's explicit-form DAE is built from its element kernel (kernel_dae) and other models run in the VM.
COMPILE_MAX_ELEMENTS = 20


def compiled_by_default(model: CableModel, method=None) -> bool:
    """Whether a run of ``model`` compiles by default: up to :data:`COMPILE_MAX_ELEMENTS` elements, and
    the fixed-step ``rk`` loop of a segmented model at any size (it steps the mapped element kernel,
    :mod:`cablesys.model.segmented_kernel`, whose C is ~30 kB whatever N: gcc under 2 s at N = 80, and
    a right-hand side 8x cheaper than the VM's, ``studies/bench_vs_moordyn.py`` slack row).

    Parameters
    ----------
    model : CableModel
        The model (a segmented model counts its elements; the 2-DOF models count as one).
    method : str, optional
        The integration method of the run.

    Returns
    -------
    bool
        True to compile (and cache) the integrator's functions, False to run them in CasADi's
        virtual machine (the Simulator's output functions follow the element rule alone:
        :func:`helpers_compiled`).
    """
    if int(getattr(model, "n_elements", 1)) <= COMPILE_MAX_ELEMENTS:
        return True
    if getattr(model, "kernel_ode", None) is None or not kernel_method(method):
        return False
    # the fixed-step loop, or an adaptive method on the ODE form: the DAE and its Jacobian from the element kernel
    return method in FIXED_LOOPS or kernel_dae(model, implicit=False)


def kernel_method(method) -> bool:
    """Whether ``method`` steps the segmented model's element kernel compiled past :data:`COMPILE_MAX_ELEMENTS`
    elements (:func:`compiled_by_default`): the fixed-step loops, and the adaptive methods on the explicit ODE form;
    not the compiled explicit pairs (:data:`.explicit_rk.PAIRS`) nor the implicit (DAE-form) methods."""
    return method in FIXED_LOOPS or (method is not None and method not in PAIRS and not resolve(method).implicit)


# The functions a run evaluates at the output times (helpers_compiled) past COMPILE_MAX_ELEMENTS elements: compiled
# while their C is predicted under HELPERS_MAX_C_BYTES (their SX code grows with N), the prediction being their
# serialized length x HELPERS_C_PER_SERIALIZED (0.25-0.28 measured on the harsh_sea ROV lift, planar, N = 23-92:
# 0.22-0.86 MB of C; compiled.compiler_command picks the flags by the serialized length, -O1, -O0 past 1.5 MB, as
# ladder.plan_cost predicts). Outputs per output time there: N = 23 18 us in CasADi's VM, 3 us compiled (-O1);
# N = 46 36 us in the VM, 14 us compiled (-O0); 2400 output times, shared load: 0.05 s of a 0.45 s run at N = 46.
# The compile (~1 s at N = 23 or 46) is once per structure.
HELPERS_MAX_C_BYTES = 1_000_000
HELPERS_C_PER_SERIALIZED = 0.3


def helpers_c_bytes(functions) -> int:
    """The predicted size (bytes) of the C of ``functions`` compiled together without Jacobians (see
    :data:`HELPERS_C_PER_SERIALIZED`)."""
    return int(HELPERS_C_PER_SERIALIZED * sum(len(f.serialize()) for f in functions))


def helpers_compiled(model: CableModel, settings: IntegratorSettings, functions=None) -> IntegratorSettings:
    """``settings`` for the functions a run evaluates at the output times (slack gaps, top motion,
    outputs): compiled as the integrator is, but past :data:`COMPILE_MAX_ELEMENTS` elements only when
    ``jit`` asks or ``functions`` (those helpers) are predicted under :data:`HELPERS_MAX_C_BYTES` of C."""
    if settings.compiled and not settings.jit and int(getattr(model, "n_elements", 1)) > COMPILE_MAX_ELEMENTS and (
            functions is None or helpers_c_bytes(functions) > HELPERS_MAX_C_BYTES):
        return dataclasses.replace(settings, compiled=False)
    return settings


def dae_function(model: CableModel, implicit: bool, compiled: bool = True, scaled: bool = False) -> Compiled:
    """The model's DAE function, compiled and cached when ``compiled`` (built once per model).

    Parameters
    ----------
    model : CableModel
        The model.
    implicit : bool
        The residual form M q'' - f = 0 (IDAS) instead of the ODE.
    compiled : bool, optional
        Compiled C (cached on disk) instead of CasADi's virtual machine.
    scaled : bool, optional
        In the scaled states x / S(p) (see :func:`.dae.relative_time_dae`; a function of its own, its own key).

    Returns
    -------
    Compiled
        ``functions[name]`` is the DAE; ``build_s``/``load_s`` the times of its first build.
    """
    kernel = kernel_dae(model, implicit, compiled)
    key = (f"dae:{'implicit' if implicit else 'explicit'}:{'compiled' if compiled else 'vm'}"
           + (":scaled" if scaled else "") + (":kernel" if kernel else ""))

    def build():
        # the integrators need the state blocks of the Jacobian only (d/dp would grow with the scene's
        # parameter count); never use this library for parameter sensitivities
        if kernel:
            functions = kernel_dae_functions(model, scaled)
            size = len(generate(functions, jacobians=False))    # MX serializes shorter than its C
            comp = compile_functions(functions, jacobians=False, enabled=compiled, size=size,
                                     optimization=kernel_dae_optimization(size))
            name = functions[0].name()                          # the DAE; its Jacobian is found by casadi.external
            return dataclasses.replace(comp, functions={name: comp.functions[name]})
        return compile_functions([relative_time_dae(model, implicit, scaled)], jacobians=("x", "z"), enabled=compiled)
    return model.derive(key, build)


def kernel_dae_functions(model: CableModel, scaled: bool) -> list:
    """What :func:`dae_function` compiles for the element-kernel DAE (:func:`kernel_dae`): the DAE
    (:func:`.dae.relative_time_dae`) and its Jacobian ``jac_<name>`` by the chain rule over the elements
    (:func:`.dae.relative_time_jacobian`), under the name ``casadi.external`` looks for beside the DAE.

    CasADi's AD of the whole mapped DAE (:func:`cablesys.derivatives.state_jacobian`) is the same matrix to rounding
    but costs ~40 right-hand sides (12 forward directions through every element, then nonzero copies into the
    result) and ten times the C.
    """
    # harsh_sea ROV lift, planar, CVODES BDF2: N = 46, 333 us per Jacobian by AD of the mapped DAE (48 % of a run),
    # 29 us by the chain rule; 1.84 MB of C against 0.18 MB (N = 23: 1.40 / 0.16 MB)
    f = relative_time_dae(model, False, scaled, kernel=True)
    return [f, relative_time_jacobian(model, f, scaled)]


# The element-kernel DAE (kernel_dae) is loops over the elements plus, with AD's Jacobian, that Jacobian's nonzero
# copies, whose C grew with N (harsh_sea ROV lift, planar: N = 28 1.49 MB, N = 56 2.05 MB) past compiled.SIZE_FLAGS's
# -O1 limit, and at -O0 every right-hand side and Jacobian cost 2-3x more (N = 56, CVODES BDF2, rtol 1e-5, 200 s:
# 105-115 us per step at -O0, 45 us at -O1; studies/bench_vs_moordyn.py notes "harsh_sea_profile"). With the chain
# rule's Jacobian (kernel_dae_functions) the C stays near 0.2 MB (N = 23: 0.16 MB, N = 92: 0.21 MB), -O2 by the size
# rule; up to KERNEL_O1_MAX_BYTES of C it is compiled at least at -O1 (compiled.COMPILE_S_PER_MB: ~4.5 s per MB);
# past it the size rule holds (the compiler's memory).
KERNEL_O1_MAX_BYTES = 6_000_000


def kernel_dae_optimization(c_bytes: int) -> str | None:
    """The optimization flag of the element-kernel DAE's ``c_bytes`` of C: -O1 where the size rule
    (:data:`cablesys.compiled.SIZE_FLAGS`) would pick -O0 and the C is at most :data:`KERNEL_O1_MAX_BYTES`,
    else None (the size rule's own flag)."""
    default = next(flag for limit, flag in SIZE_FLAGS if c_bytes < limit)
    return "-O1" if default == "-O0" and c_bytes <= KERNEL_O1_MAX_BYTES else None


def kernel_dae(model: CableModel, implicit: bool, compiled: bool = True) -> bool:
    """Whether :func:`dae_function` builds the DAE from the segmented cable's element kernel (MX, mapped over the
    elements: :mod:`cablesys.model.segmented_kernel`) instead of its element-by-element SX ``ode``: compiled, in
    the explicit form, past :data:`COMPILE_MAX_ELEMENTS` elements, with a C compiler found (in the VM the MX form is
    slower than the SX one). The straight-line SX code and its Jacobian grow
    with N (megabytes of C that gcc takes minutes over, hence the VM past COMPILE_MAX_ELEMENTS); the kernel's C
    grows with the Jacobian's nonzeros only and compiles in seconds (``studies/bench_kernel_dae.py``)."""
    return (compiles(compiled) and not implicit and getattr(model, "kernel_ode", None) is not None
            and int(getattr(model, "n_elements", 1)) > COMPILE_MAX_ELEMENTS and model.loop_ode is model.kernel_ode)


def uses_scaling(settings: IntegratorSettings) -> bool:
    """Whether ``settings`` integrate the scaled states (adaptive methods with ``scaled``; a fixed
    step has no error test for the scales to act on)."""
    return bool(settings.scaled) and settings.integrator_method.adaptive and not (
        settings.method in FIXED_LOOPS and settings.custom is None)


def _explicit_pair(settings: IntegratorSettings) -> bool:
    """Whether ``settings`` name a pair of the compiled explicit driver (:data:`.explicit_rk.PAIRS`)."""
    return settings.custom is None and settings.method in PAIRS


def compiled_dae(model: CableModel, settings: IntegratorSettings) -> Compiled:
    """The compiled model code :func:`make_integrator` uses for ``settings`` (the DAE, or the RK4
    interval for ``rk``), with its first build/load times."""
    if settings.method in FIXED_LOOPS and settings.custom is None:
        return rk4_interval(model, int(settings.steps_per_output), settings.compiled or settings.jit, _stages(settings))
    if _explicit_pair(settings):
        comp = explicit_rk_library(model, settings.compiled or settings.jit, settings.method)
        if comp.compiled:
            return comp
        settings = fallback_settings(model, settings)
    return dae_function(model, settings.integrator_method.implicit, settings.compiled or settings.jit,
                        uses_scaling(settings))


class ScaledIntegrator:
    """A CasADi integrator of the scaled DAE seen in the physical states: called like the
    integrator (``F(x0=..., p=...)`` -> ``{"xf": ndarray, "zf": ndarray}``, positional (x0, p) too), it
    divides x0 by S(p) and multiplies the outputs back, so callers never see x~.
    ``stats()`` and every other attribute are the wrapped integrator's (its step counts).

    Parameters
    ----------
    integrator : casadi.Function
        The integrator of the scaled DAE.
    scales : casadi.Function
        ``state_scales(p) -> S`` of the model.
    n_params : int
        Length of the model's p (the integrator's p has (t_0, h) appended).
    nq : int
        Number of coordinates (the algebraic q'' of the implicit form is scaled by the rate scales).
    """

    def __init__(self, integrator: ca.Function, scales: ca.Function, n_params: int, nq: int):
        self.integrator, self.scales, self.n_params, self.nq = integrator, scales, n_params, nq

    def __call__(self, *args, **kw) -> dict:
        names = ("x0", "p", "z0")
        kw.update(zip(names, args))
        p = np.asarray(kw["p"], dtype=float).ravel()
        S = np.array(self.scales(p[: self.n_params])).ravel()
        kw["x0"] = np.asarray(kw.get("x0", np.zeros(S.size)), dtype=float).ravel() / S
        if "z0" in kw:
            kw["z0"] = np.asarray(kw["z0"], dtype=float).ravel() / S[self.nq:]
        out = self.integrator(**kw)
        out = dict(out)
        # numpy, as the explicit driver's (every caller takes np.array of it; a DM round trip cost ~20 us per output
        # time of a 184-state run)
        out["xf"] = np.array(out["xf"]) * S[:, None]
        if "zf" in out and out["zf"].numel():
            out["zf"] = np.array(out["zf"]) * S[self.nq:, None]
        return out

    def __getattr__(self, name):
        return getattr(self.integrator, name)


def compiled_functions(model: CableModel, settings: IntegratorSettings, functions) -> list:
    """``functions`` of this model (SX, distinct names) as compiled code, one library, built once
    per model and set of names; the originals when ``settings`` ask for the virtual machine."""
    functions = list(functions)
    enabled = settings.compiled or settings.jit
    key = "fns:" + ",".join(f.name() for f in functions) + (":compiled" if enabled else ":vm")
    comp = model.derive(key, lambda: compile_functions(functions, jacobians=False, enabled=enabled))
    return [comp.functions[f.name()] for f in functions]


def _stages(settings: IntegratorSettings) -> int:
    """The RKC stages of ``settings`` (0: classical RK4)."""
    return int(settings.stages) if settings.method == "rkc" else 0


def rk4_interval(model: CableModel, n_sub: int, compiled: bool = True, stages: int = 0) -> Compiled:
    """One output interval of classical RK4 (or, with ``stages`` >= 2, of RKC with that many stages,
    :mod:`.rkc`) as one (compiled) function, built once per model.

    ``cablesys_rk4_interval(x, s0, ds, p) -> x(s0 + ds)`` takes ``n_sub`` equal steps of
    the relative-time DAE (:func:`.dae.relative_time_dae`); the step loop is a CasADi ``mapaccum``, so
    the generated C is one step inside a loop (CasADi's own ``rk`` plugin cannot be code
    generated, and evaluating it in the virtual machine costs one function call per stage).
    """
    def build():
        nx, npx = 2 * model.nq, len(model.layout) + 2
        # a model may offer an ode for compiled loops (the segmented element kernel, MX: its C has constant
        # size); in CasADi's VM its map calls cost more than the SX ode's straight line (72 vs 53 us per RHS
        # at N = 80), so the VM steps the SX ode
        ode = getattr(model, "loop_ode", model.ode) if compiles(compiled) else model.ode
        S = ca.MX if ode.is_a("MXFunction") else ca.SX
        x, s, hs, p = S.sym("x", nx), S.sym("s"), S.sym("hs"), S.sym("p", npx)

        def f(xx, ss):
            return p[-1] * ode(xx, p[-2] + p[-1] * ss, p[:-2])
        if stages:
            x_next = rkc_step(f, x, s, hs, stages)
        else:
            k1 = f(x, s)
            k2 = f(x + 0.5 * hs * k1, s + 0.5 * hs)
            k3 = f(x + 0.5 * hs * k2, s + 0.5 * hs)
            k4 = f(x + hs * k3, s + hs)
            x_next = x + hs / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        step = ca.Function("cablesys_rk4_step", [x, s, hs, p], [x_next, s + hs])
        loop = step.mapaccum("cablesys_rk4_loop", n_sub, [0, 1], [0, 1])
        xm, s0, ds, pm = ca.MX.sym("x", nx), ca.MX.sym("s0"), ca.MX.sym("ds"), ca.MX.sym("p", npx)
        X, _ = loop(xm, s0, ca.repmat(ds / n_sub, 1, n_sub), ca.repmat(pm, 1, n_sub))
        interval = ca.Function("cablesys_rk4_interval", [xm, s0, ds, pm], [X[:, -1]])
        # the flags by the loop's C (~30 kB at any N for the kernel, cheap to generate), not by its serialized
        # form, which grows with N (0.57 MB at N = 80: -O1 instead of -O2, 17 % slower)
        size = len(generate([interval], jacobians=False)) if S is ca.MX else None
        return compile_functions([interval], jacobians=False, enabled=compiled, size=size)
    return model.derive(f"{f'rkc{stages}' if stages else 'rk4'}:{n_sub}:{'compiled' if compiled else 'vm'}", build)


def _rk4_integrator(model: CableModel, settings: IntegratorSettings, grid, name: str) -> ca.Function:
    """``name(x0, p) -> xf``: RK4 over the output intervals of ``grid`` (``steps_per_output`` each),
    with the same inputs/outputs as a CasADi integrator."""
    comp = rk4_interval(model, int(settings.steps_per_output), settings.compiled or settings.jit, _stages(settings))
    interval = comp.functions["cablesys_rk4_interval"]
    n = len(grid) - 1
    over = interval.mapaccum(f"{name}_intervals", n, [0], [0])
    x0, p = ca.MX.sym("x0", 2 * model.nq), ca.MX.sym("p", len(model.layout) + 2)
    X = over(x0, ca.DM(grid[:-1]).T, ca.DM(np.diff(grid)).T, ca.repmat(p, 1, n))
    return ca.Function(name, [x0, p], [X], ["x0", "p"], ["xf"])


def make_integrator(model: CableModel, settings: IntegratorSettings, grid, name: str = "F"):
    """A CasADi integrator over the relative ``grid`` (first entry 0 excluded from outputs).

    With ``settings.scaled`` (the default) an adaptive method integrates the scaled states
    x~ = x / S(p) (:mod:`cablesys.model.scales`), so ``atol`` is per state atol x S_i, and the
    returned :class:`ScaledIntegrator` takes and gives physical states like the integrator.

    Parameters
    ----------
    model : CableModel
        The model.
    settings : IntegratorSettings
        Method (:mod:`cablesys.integration`), tolerances, steps per output.
    grid : array_like
        Relative output grid s (time t = t_0 + h s, with (t_0, h) appended to p).
    name : str, optional
        Name of the CasADi function.

    Returns
    -------
    casadi.Function or ScaledIntegrator
        The integrator (``casadi.integrator``, the compiled RK4 loop, or the scaled integrator
        wrapped in physical states).
    """
    if settings.method in FIXED_LOOPS and settings.custom is None:
        return _rk4_integrator(model, settings, np.asarray(grid, dtype=float), name)
    if _explicit_pair(settings):
        F = make_explicit_rk(model, settings, np.asarray(grid, dtype=float), name)
        if F is not None:
            return F
        settings = fallback_settings(model, settings)
    method = settings.integrator_method
    plugin, opts = method.plugin, method.plugin_options()
    grid = np.asarray(grid, dtype=float)
    if method.adaptive:
        opts.update(reltol=settings.rtol, abstol=settings.atol, max_num_steps=settings.max_num_steps)
        if method.implicit:
            # q'' is algebraic (index 1): its accuracy follows from q', so keep it out of the error test
            opts.update(calc_ic=True, suppress_algebraic=True)
        if model.kind == "segmented" and (plugin == "idas" or opts.get("linear_multistep_method") == "bdf"):
            # The segmented cable's axial element modes are stiff, undamped and oscillatory. BDF orders
            # 3-5 are not A-stable (their stability regions cut into the imaginary axis), so the error
            # control of a variable-order BDF must follow that ringing: 1.6 million steps for 40 s of
            # the Dale scene with 10 elements at any rtol. Orders <= 2 are A-stable and step over it
            # (3.4k steps at rtol 1e-3, body amplitude within 1e-4 of the tight reference).
            opts.setdefault("max_order", 2)
    else:
        opts["number_of_finite_elements"] = int(settings.steps_per_output * (len(grid) - 1))
        if plugin == "collocation":
            opts["rootfinder"] = "newton"   # the q'' system is small and dense
    opts["print_stats"] = False
    comp = compiled_dae(model, settings)
    dae = next(iter(comp.functions.values()))
    F = ca.integrator(name, plugin, dae, float(grid[0]), list(grid[1:]), opts)
    if uses_scaling(settings):
        return ScaledIntegrator(F, state_scales(model), len(model.layout), model.nq)
    return F
