"""The accepted part of a run: states and modes at the output times, labelled block by block."""

from __future__ import annotations

import logging
import time as _time

import numpy as np

log = logging.getLogger("cablesys.time_domain.run")


class Track:
    """Accepted states and modes at the output times; labels them block by block.

    Blocks are labelled (and handed to ``on_block`` and ``progress``) at most every
    ``FLUSH_S`` seconds of wall time, and at the end.
    """

    FLUSH_S = 0.5
    LOG_AFTER_S, LOG_EVERY_S = 5.0, 10.0     # default progress: a log line every 10 s after 5 s

    def __init__(self, sim, p, x0, mode, on_block, progress):
        self.sim, self.p, self.on_block, self.progress = sim, p, on_block, progress
        self.X, self.M, self.data = [], [], []            # labelled blocks
        self.pX, self.pM = [x0[:, None]], [mode[:, None].copy()]   # accepted, not yet labelled
        self.n, self.n_done = 1, 0
        self.events, self.snaps = [], []
        self.t0 = self.t_flush = _time.perf_counter()
        self.t_log = self.t0 + self.LOG_AFTER_S

    @property
    def x_last(self) -> np.ndarray:
        return (self.pX[-1] if self.pX else self.X[-1])[:, -1]

    def add(self, X, mode) -> None:
        self.pX.append(X)
        self.pM.append(np.repeat(mode[:, None], X.shape[1], axis=1))
        self.n += X.shape[1]

    def flush(self, force: bool = False) -> None:
        if not force and getattr(self.sim, "_flag", None) is not None and self.sim._flag.hit:
            # the signal came while CasADi evaluated a plain function, which swallows the exception
            raise KeyboardInterrupt("interrupt noted during a CasADi call")
        now = _time.perf_counter()
        if not force and now - self.t_flush < self.FLUSH_S:
            return
        self.t_flush = now
        if self.pX:
            Xb, Mb = np.hstack(self.pX), np.hstack(self.pM)
            self.pX, self.pM = [], []
            T = self.sim.times[self.n_done:self.n]
            data = self.sim.labelled(T, Xb, Mb, self.p)
            self.X.append(Xb)
            self.M.append(Mb)
            self.data.append(data)
            self.n_done = self.n
            if self.on_block is not None:
                self.on_block(T, data)
        t, t_end = float(self.sim.times[self.n - 1]), float(self.sim.times[-1])
        if self.progress is not None:
            self.progress(t, t_end, now - self.t0)
        elif now >= self.t_log:
            self.t_log = now + self.LOG_EVERY_S
            log.info("t = %.6g of %.6g s (%.0f %%), %.1f s elapsed", t, t_end, 100 * t / t_end if t_end else 100, now - self.t0)

    def arrays(self) -> tuple:
        """(states, modes, labelled series) of every accepted output time."""
        self.flush(force=True)
        data = {k: np.concatenate([d[k] for d in self.data]) for k in self.data[0]}
        return np.hstack(self.X), np.hstack(self.M), data
