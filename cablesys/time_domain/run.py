"""Time-domain runs: ``simulate(scene)`` and the reusable :class:`Simulator`.

Between events the integration runs in compiled CasADi integrator calls over chunks of
:attr:`Simulator.CHUNKS` output intervals (no Python per step; chunks give progress, streaming
and interrupts). The compiled loops that cannot see a signal inside a call (``rk``, ``dopri5``,
``rk23``) get chunks sized from the measured cost of the last call to take about
:attr:`Simulator.CHUNK_MAX_S` each, and the explicit pairs a budget of steps per call as well, so an
interrupt is acted on within about that time; CVODES and IDAS see it inside the call (through
CasADi). Each block of results is stored whole: an interrupt during the storing is held back to its
end (:func:`cablesys.atomic.interrupts_deferred`). Slack switches are located as described in
:mod:`.events`. The integrator's step budget is ``max_num_steps`` per output interval: exhausting
it fails the run with a named message (it is not silently multiplied).
"""

from __future__ import annotations

import logging
import time as _time
import warnings

import casadi as ca
import numpy as np

from ..atomic import interrupts_deferred
from ..errors import NumericalWarning, ParameterError
from ..model import CableModel, build_model
from ..results import SlackEvent
from ..scene import Scene
from . import events as ev
from .columns import Columns
from .failures import (
    REMEDIES,
    failure_message,
    failure_reason,
    largest_rate,
    rk4_stability_note,
)
from .explicit_rk import PAIRS
from .initial import initial_state
from .peaks import attach as attach_peaks
from .integrators import (
    ADAPTIVE,
    IntegratorSettings,
    compiled_by_default,
    compiled_dae,
    compiled_functions,
    helpers_compiled,
    make_integrator,
)
from .sampled import label_states
from .record import (
    InterruptFlag,
    RunInterrupted,
    RunRecord,
    check_run_size,
    check_scene_run_size,
)
from .track import Track

log = logging.getLogger(__name__)

__all__ = ["Simulator", "initial_state", "simulate"]   # initial_state lives in .initial


class Simulator(ev.EventLocator):
    """Integrators and helper functions for one model, output grid and method; reusable for sweeps."""

    MAX_EVENTS_PER_INTERVAL = 50   # more switches than this in one output interval is a failure
    # output intervals per whole-horizon integrator call (uniform output grids), in this order whatever each call
    # takes (CVODES and IDAS see signals inside a call; each restart costs ~300 steps)
    CHUNKS = (256, 1024, 4096)
    # the loops blind to signals inside a call (rk, dopri5, rk23): chunks from SMALL_CHUNKS + CHUNKS, the
    # largest whose predicted time is within CHUNK_MAX_S (s), starting at the smallest; the explicit pairs
    # also stop a call after a budget of steps worth CHUNK_MAX_S (FIRST_STEP_BUDGET before any measurement)
    SMALL_CHUNKS = (16, 64)
    CHUNK_MAX_S = 0.2
    FIRST_STEP_BUDGET = 4096
    STORE_ROWS = 4096          # a block is stored once this many output times wait (or after Track.FLUSH_S)

    def __init__(self, model: CableModel, times, settings: IntegratorSettings | None = None):
        self.model = model
        self.times = np.asarray(times, dtype=float)
        if self.times.ndim != 1 or self.times.size < 2 or np.any(np.diff(self.times) <= 0):
            raise ParameterError("times", f"{self.times.size} values", "must be >= 2 strictly increasing output times")
        check_run_size(self.times.size, model.n_sections, field="times",
                       per_output=2 * model.nq + len(model.slack_index) + len(model.output_labels) + 2)
        t_build = _time.perf_counter()
        steps = np.diff(self.times)
        n_int = self.times.size - 1
        self._uniform = bool(np.allclose(steps, steps[0], rtol=1e-9, atol=0.0))
        self.settings = settings or IntegratorSettings()
        self._blind = self.settings.custom is None and self.settings.method in ("rk", *PAIRS)
        # chunks may start at any output time: on a uniform grid (one integrator per length), and for the
        # signal-blind loops on any grid (an integrator per chunk: the whole horizon in one call could
        # not be interrupted)
        self._sliding = self._uniform or self._blind
        first = self._sizes()[0]
        self._chunk = min(n_int, first) if self._sliding else n_int
        self._budget = self.FIRST_STEP_BUDGET
        self._chunks = {}                        # chunk length -> integrator over that many output intervals
        self._flag = InterruptFlag()
        self._chunk_integrator(self._chunk)
        self._step = make_integrator(model, self.settings, [0.0, 1.0], "step")
        self._dense = make_integrator(model, self.settings, np.linspace(0.0, 1.0, self.DENSE + 1), "dense")
        x, t = model.sym("x", 2 * model.nq), model.sym("t")
        p = model.sym("p", len(model.layout))
        g = model.cable_force(x, p)
        xdot = model.ode(x, t, p)
        g1 = ca.mtimes(ca.jacobian(g, x), xdot)
        g2 = ca.mtimes(ca.jacobian(g1, x), xdot) + ca.jacobian(g1, t)
        self._gap_and_rate = ca.Function("gap_rate", [x, t, p], [g, g1])
        self._gap_rates = ca.Function("gap_rates", [x, t, p], [g, g1, g2])
        helpers = [self._gap_and_rate, model.top, model.outputs]
        self._gap_and_rate, self._top_c, self._outputs_c = compiled_functions(   # one cached library
            model, helpers_compiled(model, self.settings, helpers), helpers)
        # the same functions over many output times, numpy in and out (no DM conversion, no map per call)
        self._gap_cols, self._top_cols, self._outputs_cols = (
            Columns(f) for f in (self._gap_and_rate, self._top_c, self._outputs_c))
        self.build_s = _time.perf_counter() - t_build
        self.compiled = compiled_dae(model, self.settings)   # compiled/cached DAE: build and load times
        self._stats = {}

    # -- helpers -------------------------------------------------------------------------
    def _chunk_integrator(self, m: int, k: int = 0) -> ca.Function:
        """The integrator over ``m`` output intervals from the output time ``k`` (on a uniform grid built
        once per length; otherwise the last one is kept)."""
        key = m if self._uniform else (k, m)
        if key not in self._chunks:
            if self._uniform:
                grid = np.arange(m + 1) * (self.times[1] - self.times[0])
            else:
                grid = self.times[k:k + m + 1] - self.times[k]
                self._chunks.clear()
            self._chunks[key] = make_integrator(self.model, self.settings, grid, f"chunk{m}")
        return self._chunks[key]

    def _sizes(self) -> tuple:
        """Chunk lengths (output intervals per call) this run may use, smallest first."""
        return tuple(self.SMALL_CHUNKS) + tuple(self.CHUNKS) if self._blind else tuple(self.CHUNKS)

    def _next_chunk(self, size: int, m: int, wall: float, f) -> int:
        """The next chunk length after a call that reached ``m`` output intervals in ``wall`` seconds (and,
        for an explicit pair, its step budget from the measured cost of a step)."""
        if not self._blind:
            # a fixed sequence, not the wall time: each call restarts CVODES / IDAS, so chunk boundaries set by
            # the machine's load would change the step sequence, and the result at the tolerance, from run to run
            return next((c for c in self.CHUNKS if c > size), size)
        try:
            st = f.stats()
            tried = int(st.get("nsteps", 0)) + int(st.get("n_rejected", 0))
        except (RuntimeError, AttributeError):
            tried = 0
        if tried and hasattr(f, "call_budget"):
            self._budget = int(np.clip(self.CHUNK_MAX_S * tried / max(wall, 1e-9), 256, 1e8))
        per = wall / max(m, 1)
        fits = [c for c in self._sizes() if c * per <= self.CHUNK_MAX_S]
        return max(fits) if fits else self._sizes()[0]

    def _store(self, track: Track) -> None:
        """Hand the accepted outputs to ``track`` (labelled, streamed) whole: an interrupt waits for the
        end. At most about :attr:`STORE_ROWS` output times wait for a block, so that storing one (CSV
        rows through ``on_block``) takes a bounded time however fast the integration runs."""
        if self._flag.hit:              # a signal whose KeyboardInterrupt a CasADi call swallowed
            raise KeyboardInterrupt("interrupt noted during a CasADi call")
        with interrupts_deferred():
            track.flush(force=track.n - track.n_done >= self.STORE_ROWS)

    def _count(self, f: ca.Function) -> None:
        try:
            st = f.stats()
        except RuntimeError:        # no statistics before a first successful evaluation
            return
        for key in ("nsteps", "nfevals", "nresevals", "njevals"):
            if key in st:
                self._stats[key] = self._stats.get(key, 0) + int(st[key])

    def _call(self, f: ca.Function, **kw) -> dict:
        """Evaluate integrator ``f`` and count its steps; an interrupt inside CasADi becomes KeyboardInterrupt.

        CasADi catches the signal and reports a generic failure ("CV_RHSFUNC_FAIL"), so the
        interrupt flag set by our handler (or the text, for plugins that pass it on) tells. A handler that raises
        inside a conversion of CasADi's result to NumPy (``DM.__array__``) surfaces as a SystemError ("returned a
        result with an exception set"): the flag tells that one too.
        """
        try:
            out = f(**kw)
        except SystemError as err:
            self._count(f)
            if self._flag.hit or isinstance(err.__cause__, KeyboardInterrupt):
                raise KeyboardInterrupt("interrupted while reading the integrator's result") from err
            raise
        except RuntimeError as err:
            self._count(f)
            if self._flag.hit or "KeyboardInterrupt" in str(err):
                raise KeyboardInterrupt(str(err).strip().splitlines()[-1]) from err
            raise
        self._count(f)
        return out

    def _advance(self, x, t_a, h, p):
        """State at t_a + h (one integrator call; at most ``max_num_steps`` steps)."""
        xf = np.array(self._call(self._step, x0=x, p=np.concatenate([p, [t_a, h]]))["xf"]).ravel()
        if not np.all(np.isfinite(xf)):
            raise FloatingPointError("nonfinite")
        return xf

    def _check_fixed_step(self, x0, p) -> str:
        """For 'rk': warn when h |lambda|_max at the start exceeds RK4's stability limit."""
        if self.settings.method != "rk":
            return ""
        lam = largest_rate(self.model, x0, self.times[0], self._with_mode(p, np.zeros(len(self.model.slack_index))))
        h = float(np.min(np.diff(self.times))) / self.settings.steps_per_output
        note = rk4_stability_note(h, lam, self.settings.steps_per_output)
        if note:
            warnings.warn(note, NumericalWarning, stacklevel=4)
        return note

    def _with_mode(self, p, mode):
        p = p.copy()
        p[list(self.model.slack_index)] = mode
        return p

    # -- the run ------------------------------------------------------------------------
    def run(self, p, x0, *, on_block=None, progress=None) -> RunRecord:
        """Integrate from ``x0`` at ``times[0]`` over the output times.

        Parameters
        ----------
        p : array_like
            Parameter vector of the model (``model.parameters(scene)``).
        x0 : array_like
            Initial state ``(q, dq/dt)`` (SI).
        on_block : callable, optional
            ``on_block(times, data)`` receives each block of newly reached output times with its
            labelled series (about every :attr:`FLUSH_S` seconds of wall time), e.g. to stream them
            to disk so that a killed run leaves a readable prefix.
        progress : callable, optional
            ``progress(t, t_end, wall_s)`` after each block (default: a log line at INFO level
            every 10 s for runs longer than a few seconds).

        Returns
        -------
        RunRecord
            Series, states, modes, events, snap loads, ``success``/``message`` and ``stats``
            (``nsteps``, ``wall_time_s``, ``max_num_steps`` per output interval...). An
            integrator failure returns ``success=False`` with the results up to the failure.

        Raises
        ------
        RunInterrupted
            On Ctrl-C (or SIGTERM under the ``cablesys`` command), carrying the record so far.
        """
        p = np.asarray(p, dtype=float)
        x0 = np.asarray(x0, dtype=float)
        self._stats = {}
        stability_note = self._check_fixed_step(x0, p)
        wall = _time.perf_counter()
        g0, _ = self._gap_and_rate(x0, self.times[0], self._with_mode(p, np.zeros(len(self.model.slack_index))))
        mode = (np.array(g0).ravel() < 0).astype(float)
        track = Track(self, p, x0, mode, on_block, progress)
        interrupted = False
        started = _time.monotonic()
        with InterruptFlag() as self._flag:
            try:
                success, message = self._integrate(track, p, mode, stability_note)
            except KeyboardInterrupt:
                interrupted, success = True, False
            try:
                with interrupts_deferred():        # the last block whole, whatever signal comes now
                    X, M, data = track.arrays()
            except KeyboardInterrupt:              # a signal during the last block, which was stored first
                interrupted, success = True, False
                X, M, data = track.arrays()
            if interrupted:
                message = self._interrupted_message(started, float(self.times[X.shape[1] - 1]))
        stats = dict(self._stats, method=self.settings.method, wall_s=_time.perf_counter() - wall,
                     build_s=self.build_s, n_events=len(track.events), max_num_steps=self.settings.max_num_steps)
        stats["wall_time_s"] = stats["wall_s"]
        stats.update(run_s=stats["wall_s"], load_s=self.compiled.load_s, compiled=self.compiled.compiled)
        if stability_note:
            stats["warning"] = stability_note
        record = RunRecord(time=self.times[: X.shape[1]].copy(), data=data, success=success, message=message,
                           stats=stats, events=tuple(track.events), snaps=tuple(track.snaps),
                           initially_slack=tuple(int(i) for i in np.nonzero(M[:, 0])[0]),
                           states=X, modes=M, state_labels=self.model.state_labels, interrupted=interrupted)
        if interrupted:
            raise RunInterrupted(record)
        return record

    def _interrupted_message(self, started: float, t_kept: float) -> str:
        """What an interrupted run says: the signal, when it came, how soon the run stopped, what is kept."""
        now, at = _time.monotonic(), self._flag.signal_time
        if at is None:
            when = f"after {now - started:.3g} s of wall time"
        else:
            self._stats.update(interrupt_s=at - started, stop_after_s=now - at)
            when = f"by {self._flag.signal_name} {at - started:.3g} s into the run (stopped {now - at:.2g} s later)"
        return f"interrupted {when}; results up to t = {t_kept:.6g} s are kept"

    def _integrate(self, track: Track, p, mode, stability_note: str) -> tuple[bool, str]:
        """Fill ``track``: whole chunks of output intervals while nothing switches, then interval by interval."""
        times, events = self.times, track.events
        n_int = times.size - 1
        k, size = 0, self._chunk
        # 1) one compiled call per chunk of output times (no Python per step)
        while k < n_int:
            m = min(size, n_int - k)
            x, pm = track.x_last, self._with_mode(p, mode)
            f = self._chunk_integrator(m, k)
            if hasattr(f, "call_budget"):          # an explicit pair: a call stops after this many steps
                f.call_budget = self._budget
            t_call = _time.perf_counter()
            try:
                Xs = np.array(self._call(f, x0=x, p=np.concatenate([pm, [times[k], 1.0]]))["xf"])
            except RuntimeError as err:
                log.info("chunk integration failed (%s); stepping interval by interval", failure_reason(err)[0])
                break
            wall = _time.perf_counter() - t_call
            paused = bool(getattr(f, "paused", False))   # the step budget ran out: resume from the last output
            cols = np.column_stack([x, Xs])
            finite = np.all(np.isfinite(cols), axis=0)
            n_ok = int(np.argmin(finite)) if not finite.all() else m + 1
            j_bad = None
            if len(self.model.slack_index):     # a model without slack switches (quasi-static N > 1) has no gap to watch
                G, D = self._gap_cols(cols[:, :n_ok], times[None, k:k + n_ok], pm)
                j_bad = ev.first_bad_interval(G, D, np.diff(times[k:k + n_ok]), mode == 1.0)
            n_keep = j_bad if j_bad is not None else n_ok       # columns 0 .. n_keep-1 are accepted
            if self._sliding:           # sized by the cost of the intervals this call reached
                size = self._next_chunk(size, max(n_ok - 1, 1), wall, f)
            if n_keep > 1:
                track.add(cols[:, 1:n_keep], mode)
            k += n_keep - 1
            self._store(track)
            if n_keep < m + 1 and not (paused and self._sliding and j_bad is None and n_keep > 1):
                break
        # 2) interval by interval after an event (or a failure), locating switches
        x, t_a = track.x_last, times[k]
        switches_here = 0
        events_in_interval = 0
        while k < n_int:
            t_b = times[k + 1]
            pm = self._with_mode(p, mode)
            try:
                xb = self._advance(x, t_a, t_b - t_a, pm)
                hit = self._first_event(x, t_a, xb, t_b, pm, mode)
            except (RuntimeError, FloatingPointError) as err:
                return False, self._failure(err, t_a, t_b, times[k])
            if hit is None:
                x, t_a, k = xb, t_b, k + 1
                track.add(x[:, None], mode)
                self._store(track)
                switches_here = events_in_interval = 0
                continue
            t_star, i_sec = hit
            x = self._advance(x, t_a, t_star - t_a, pm) if t_star > t_a else x
            kind = "taut" if mode[i_sec] == 1.0 else "slack"
            mode[i_sec] = 1.0 - mode[i_sec]
            _, rate = self._gap_and_rate(x, t_star, self._with_mode(p, mode))
            events.append(SlackEvent(time=float(t_star), section=i_sec, kind=kind, rate=float(np.array(rate)[i_sec, 0])))
            if kind == "taut":
                snap = self._snap(x, t_star, self._with_mode(p, mode), i_sec, times[-1])
                if snap is not None:
                    track.snaps.append(snap)
            t_a = t_star
            switches_here = switches_here + 1 if t_star - (events[-2].time if len(events) > 1 else -np.inf) < 1e-12 else 0
            events_in_interval += 1
            if switches_here > 4 or events_in_interval > self.MAX_EVENTS_PER_INTERVAL:
                return False, (f"taut/slack chattering at t = {t_star:.9g} s ({events_in_interval} switches "
                               f"in one output interval): {REMEDIES['chatter']}"
                               + ("; " + stability_note if stability_note else ""))
        return True, ""

    def _failure(self, err: Exception, t_a: float, t_b: float, t_kept: float) -> str:
        """The message of an integrator failure between t_a and t_b (see :func:`.failures.failure_message`)."""
        return failure_message(err, method=self.settings.method, adaptive=self.settings.method in ADAPTIVE,
                               max_num_steps=self.settings.max_num_steps, steps_before=self._stats.get("nsteps", 0),
                               t_a=t_a, t_b=t_b, t_kept=t_kept)

    def labelled(self, times, X, modes, p) -> dict:
        """Labelled outputs and top motion (``x_s``, ``y_s``; ``z_s`` in space; a vessel's rotation ``rot_z_s`` ... where it
        moves several prescribed points) for states ``X`` at ``times``.

        Parameters
        ----------
        times : array_like
            (n,) output times (s).
        X : numpy.ndarray
            (2 nq, n) states.
        modes : numpy.ndarray
            (n_sections, n) slack switches.
        p : array_like
            Parameter vector.

        Returns
        -------
        dict
            ``{label: (n,) array}`` in SI units.
        """
        return label_states(self.model, times, X, modes, p, self._top_cols, self._outputs_cols)


def simulate(scene: Scene, *, model: CableModel | None = None, method: str | None = None,
             rtol: float | None = None, atol: float | None = None, times=None, x0=None,
             simulator: Simulator | None = None, jit: bool = False, max_num_steps: int | None = None,
             on_block=None, progress=None) -> RunRecord:
    """Run ``scene`` in the time domain (Wang 1971 equations of motion).

    Parameters
    ----------
    scene : Scene
        The scene; ``scene.numerics`` gives method, tolerances, duration and output step.
    model : CableModel, optional
        A model built from a scene of the same structure (default: built here).
    method, rtol, atol : optional
        Override ``scene.numerics``.
    times : array_like, optional
        Output times (s); default ``scene.output_times``.
    x0 : array_like, optional
        Initial state; default from ``scene.initial`` and the steady state.
    simulator : Simulator, optional
        A reusable simulator (its model, times and settings are used).
    jit : bool
        Compile the model with the C compiler (about 3x faster runs, ~2 s more build).
    max_num_steps : int, optional
        Integrator step budget per output interval (default 100000).
    on_block, progress : callable, optional
        See :meth:`Simulator.run`.

    Returns
    -------
    RunRecord
        A :class:`~cablesys.results.TimeResult` with states and modes. An integrator failure
        returns ``success=False`` with the results computed so far.

    Raises
    ------
    ParameterError
        Bad input, or a run larger than the limits in :mod:`.record` (checked before building).
    RunInterrupted
        On an interrupt; ``err.result`` holds the record so far.
    """
    if times is None and simulator is None:
        check_scene_run_size(scene)
    t_build = _time.perf_counter()
    built_here = simulator is None       # the compiled library is loaded inside build_s only then
    model = model or (simulator.model if simulator else build_model(scene))
    num = scene.numerics
    if simulator is None:
        extra = {} if max_num_steps is None else {"max_num_steps": int(max_num_steps)}
        settings = IntegratorSettings(method=method or num.integrator, rtol=rtol or num.rtol, atol=atol or num.atol,
                                      steps_per_output=num.steps_per_output, jit=jit,
                                      compiled=compiled_by_default(model, method or num.integrator),
                                      **extra)   # jit=True compiles any size
        simulator = Simulator(model, scene.output_times if times is None else times, settings)
    build_s = _time.perf_counter() - t_build
    p = model.parameters(scene)
    x0 = initial_state(scene, model, p) if x0 is None else np.asarray(x0, float)
    try:
        record, interrupted = simulator.run(p, x0, on_block=on_block, progress=progress), False
    except RunInterrupted as err:
        record, interrupted = err.result, True
    # build_s apart from load_s: a caller's simulator was built (and its library loaded) before this call
    record = record.named(scene.name, model, build_s - (record.stats.get("load_s", 0.0) if built_here else 0.0))
    if interrupted:
        raise RunInterrupted(record) from None
    if not record.success:
        log.warning(record.message)
    return attach_peaks(record, simulator, p)      # the summary's extremes located between samples

