"""What one time-domain run returns, how it stops when interrupted, and how big it may be.

:class:`RunRecord` is the result of :meth:`Simulator.run` and :func:`simulate`: a
:class:`~cablesys.results.TimeResult` (labelled series, events, snap loads, statistics,
``steady_amplitude``) that also keeps the raw states and slack modes at the output times and
says whether the run finished, failed or was interrupted.

An interrupt (Ctrl-C, or SIGTERM when the ``cablesys`` command is running) raises
:class:`RunInterrupted`, a ``KeyboardInterrupt`` that carries the record computed so far.
"""

from __future__ import annotations

import contextlib
import dataclasses
import signal
import threading

import numpy as np

from ..atomic import INTERRUPTS, interrupt_handler
from ..errors import ParameterError
from ..results import TimeResult

# Limits on the work a run may ask for, checked before anything is built.
MAX_OUTPUTS = 10_000_000            # output times per run
MAX_MEMORY_BYTES = 2 * 1024 ** 3    # estimated memory for states and labelled series
_COPIES = 3                         # states/series are held about this many times (lists, arrays, writers)


@dataclasses.dataclass(frozen=True, eq=False)
class RunRecord(TimeResult):
    """A time-domain run (Wang 1971): labelled series, raw states and modes, and how it ended.

    Parameters
    ----------
    states : numpy.ndarray
        ``(2 nq, n)`` states ``(q, dq/dt)`` at the output times reached (SI).
    modes : numpy.ndarray
        ``(n_sections, n)`` slack switches (1 slack, 0 taut) at those times.
    state_labels : tuple of str
        Labels of the rows of ``states`` (``phi``, ``u``, ``phi_rate``, ``u_rate``...).
    interrupted : bool
        True when the run was stopped by an interrupt (``success`` is then False).
    peaks : cablesys.time_domain.peaks.Peaks, optional
        The tension extremes located between the output samples (:func:`.peaks.refine_extremes`); the
        summary reports them in place of the grid's.
    """

    states: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros((0, 0)))
    modes: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros((0, 0)))
    state_labels: tuple = ()
    interrupted: bool = False
    peaks: object = None

    @property
    def status(self) -> str:
        """``"success"``, ``"failed"`` or ``"interrupted"``."""
        return "interrupted" if self.interrupted else ("success" if self.success else "failed")

    @property
    def n_outputs(self) -> int:
        """Number of output times reached."""
        return int(self.time.size)

    def named(self, scene_name: str, model, build_s: float) -> RunRecord:
        """A copy naming the scene and the model that ran (its rung ``kind`` and elements: a quasi-static
        segmented run has no node profiles to infer them from), with the setup time ``build_s`` (s)."""
        info = {"name": model.kind, "segments": int(getattr(model, "n_elements", 1) or 1)}
        return dataclasses.replace(self, scene_name=scene_name, model_info=self.model_info or info,
                                   stats={**self.stats, "build_s": build_s})

    def amplitudes(self, period: float, n_periods: int = 3, labels=None) -> dict:
        """Steady amplitudes (half peak-to-peak over the last ``n_periods`` periods) of several series.

        Parameters
        ----------
        period : float
            Forcing period (s).
        n_periods : int
            Number of trailing periods.
        labels : iterable of str, optional
            Series to measure (default: every series).

        Returns
        -------
        dict
            ``{label: amplitude}`` in the series' SI unit.
        """
        return {lbl: self.steady_amplitude(lbl, period, n_periods) for lbl in (labels or self.labels)}

    def amplitude_drift(self, label: str, period: float, n_periods: int = 3) -> float:
        """How far the run is from steady: |A(last n periods) - A(the n periods before)|.

        Parameters
        ----------
        label : str
            Series to measure.
        period : float
            Forcing period (s).
        n_periods : int
            Periods per window.

        Returns
        -------
        float
            Change of the half peak-to-peak amplitude, in the series' SI unit.
        """
        t = self.time
        t1 = t[-1] - n_periods * period
        t0 = t1 - n_periods * period
        if t0 < t[0] - 1e-9 * period:
            raise ValueError(f"the run lasts {t[-1] - t[0]:.4g} s, shorter than {2 * n_periods} periods of {period:.4g} s")
        y = self[label][(t >= t0 - 1e-12) & (t <= t1 + 1e-12)]
        return abs(self.steady_amplitude(label, period, n_periods) - 0.5 * float(np.max(y) - np.min(y)))

    def summary(self) -> dict:
        """The :class:`TimeResult` summary plus ``status`` and ``n_outputs``, with the extremes of ``peaks``.

        Returns
        -------
        dict
            JSON-able numbers for ``summary.json``.
        """
        out = super().summary()
        out.update(status=self.status, n_outputs=self.n_outputs)
        if self.peaks is None:
            return {**out, "peaks": "maxima of the output samples (not refined between them)"}
        return self.peaks.apply(self, out)


class RunInterrupted(KeyboardInterrupt):
    """A run stopped by an interrupt; ``result`` holds what was computed (a :class:`RunRecord`)."""

    def __init__(self, result):
        t = float(result.time[-1]) if result.time.size else float("nan")
        super().__init__(f"interrupted; results up to t = {t:.6g} s are kept")
        self.result = result


class InterruptFlag:
    """Notes SIGINT (and SIGTERM, when a Python handler is installed for it) during a run.

    CasADi checks for signals inside its integrators and then reports a generic failure
    ("CV_RHSFUNC_FAIL"; the text "rhs failed: KeyboardInterrupt" goes to stderr only), so the
    simulator must learn from the signal record :data:`cablesys.atomic.INTERRUPTS` that the
    failure was an interrupt. Python's default SIGINT handler is replaced for the run by
    :func:`cablesys.atomic.interrupt_handler` (which can hold the interrupt back while a block of
    results is stored); another Python handler is wrapped to note the signal and then called.
    The previous handlers are restored on exit. Outside the main thread this does nothing.
    """

    def __init__(self):
        self._start = INTERRUPTS.count
        self._forced = False
        self._saved = {}

    @property
    def hit(self) -> bool:
        """Whether a signal came since :meth:`__enter__`."""
        return self._forced or INTERRUPTS.count > self._start

    @hit.setter
    def hit(self, value: bool) -> None:
        self._forced = bool(value)

    @property
    def signal_time(self) -> float | None:
        """``time.monotonic()`` of the first signal since :meth:`__enter__` (None without one)."""
        return INTERRUPTS.times[self._start] if INTERRUPTS.count > self._start else None

    @property
    def signal_name(self) -> str:
        """Name of that signal (``"SIGINT"``...), or ``"interrupt"``."""
        return INTERRUPTS.names[self._start] if INTERRUPTS.count > self._start else "interrupt"

    def __enter__(self):
        if INTERRUPTS.absorb_from is not None and INTERRUPTS.count > INTERRUPTS.absorb_from:
            # under the cablesys command a signal came before this run and did not stop the command
            # (a CasADi call swallowed its KeyboardInterrupt): stop now, before any work
            raise KeyboardInterrupt(f"{INTERRUPTS.names[-1]} before the run")
        self._start, self._forced = INTERRUPTS.count, False
        if threading.current_thread() is not threading.main_thread():
            return self
        for sig in (signal.SIGINT, signal.SIGTERM):
            prev = signal.getsignal(sig)
            if prev is interrupt_handler or not callable(prev):   # noted already / SIG_DFL, SIG_IGN: leave it
                continue
            if prev is signal.default_int_handler:
                handler = interrupt_handler
            else:
                def handler(signum, frame, prev=prev):
                    INTERRUPTS.note(signum)
                    prev(signum, frame)
            with contextlib.suppress(ValueError, OSError):
                signal.signal(sig, handler)
                self._saved[sig] = prev
        return self

    def __exit__(self, *exc):
        for sig, prev in self._saved.items():
            with contextlib.suppress(ValueError, OSError):
                signal.signal(sig, prev)
        self._saved = {}
        return False


def check_run_size(n_outputs: int, n_sections: int, *, field: str = "numerics.output_step",
                   asked: str = "", per_output: int | None = None) -> None:
    """Refuse a run whose output count or memory estimate exceeds the limits.

    Parameters
    ----------
    n_outputs : int
        Number of output times asked for.
    n_sections : int
        Cable sections of the scene (each has 4 states, 1 slack switch and 11 output series).
    field, asked : str
        The input named in the error and how it was asked (e.g. ``"duration 1e12 s / step 0.05 s"``).
    per_output : int, optional
        Numbers kept per output time when the model is known (states, switches, series);
        default: an estimate from ``n_sections``.

    Returns
    -------
    None
        Raises :class:`~cablesys.errors.ParameterError` when a limit is exceeded.
    """
    asked = asked or f"{n_outputs:.4g} output times"
    if not np.isfinite(n_outputs) or n_outputs > MAX_OUTPUTS:
        raise ParameterError(field, asked, f"gives {n_outputs:.4g} output times; at most {MAX_OUTPUTS:.0e} per run",
                             "raise numerics.output_step or shorten numerics.duration")
    need = run_memory_bytes(n_outputs, n_sections, per_output)
    if need > MAX_MEMORY_BYTES:
        raise ParameterError(field, asked, f"needs about {need / 1024 ** 3:.3g} GiB for the series; the limit is "
                             f"{MAX_MEMORY_BYTES / 1024 ** 3:.3g} GiB", "raise numerics.output_step or shorten numerics.duration")


def run_memory_bytes(n_outputs: float, n_sections: int, per_output: int | None = None) -> float:
    """Estimated bytes held for ``n_outputs`` output times (states, modes, series, top motion).

    Parameters
    ----------
    n_outputs : float
        Number of output times.
    n_sections : int
        Cable sections.
    per_output : int, optional
        Numbers per output time, when known (default: 16 per section + 3).

    Returns
    -------
    float
        Bytes (8 per number, :data:`_COPIES` copies).
    """
    if per_output is None:
        per_output = 4 * n_sections + n_sections + 11 * n_sections + 3
    return 8.0 * _COPIES * per_output * float(n_outputs)


def scene_output_count(scene) -> float:
    """Number of output times of ``scene`` (duration / output_step + 1), without building the grid.

    Parameters
    ----------
    scene : cablesys.scene.Scene
        The scene.

    Returns
    -------
    float
        ``floor(duration / output_step) + 1`` (a float: it may be astronomically large).
    """
    n = scene.numerics
    return float(np.floor(n.duration / n.output_step + 1e-9)) + 1.0


def check_scene_run_size(scene) -> None:
    """:func:`check_run_size` for a scene's duration and output step (before any grid is built).

    Parameters
    ----------
    scene : cablesys.scene.Scene
        The scene to run.

    Returns
    -------
    None
        Raises :class:`~cablesys.errors.ParameterError` when a limit is exceeded.
    """
    n = scene.numerics
    check_run_size(scene_output_count(scene), scene.n_sections,
                   asked=f"{n.output_step:g} s over numerics.duration = {n.duration:g} s")
