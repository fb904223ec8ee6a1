"""The MPC without preview: the top motion over the horizon predicted from its measured past only (an
autoregressive model per channel, Burg's coefficients)."""

from __future__ import annotations

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.signal import lfilter, lfiltic

from ..errors import ParameterError


class ARPredictor:
    """Prediction of the top motion from its measured past only: an autoregressive model per channel
    (x_s, y_s), s_j = -sum_{i=1}^{n} a_i s_{j-i}, fitted on the record measured at the control interval (the
    last ``window`` samples; re-fitted every ``refit`` samples, and at every sample while the order grows)
    and iterated ahead over the horizon (AR prediction of
    waves: Fusco & Ringwood 2010, "Short-term wave forecasting for real-time control of wave energy
    converters", IEEE Trans. Sustain. Energy 1(2), 99-106). The coefficients are Burg's (Burg 1975, *Maximum
    entropy spectral analysis*, PhD thesis, Stanford; the recursion as in Kay & Marple 1981, Proc. IEEE 69(11),
    1380-1419, sec. V.B): reflection coefficients |k_m| <= 1, so the model is stable and a prediction fitted on
    the ramp's growing start does not grow without bound. The order is ``order``, or a quarter of the
    samples measured while fewer than 4 ``order`` (a record short for its order gives poles near z = 1 whose
    transient swamps a 20 s prediction; one sample: held). The rates and accelerations at the RK4 stage
    times (:meth:`.payout.HeaveProblem.exogenous`) are those of the cubic spline (not-a-knot) through the
    last measured samples and the predicted ones. A sinusoid obeys the AR(2) recursion s_j = 2 cos(omega dt)
    s_{j-1} - s_{j-2}, which Burg's estimate approaches as the record grows."""

    def __init__(self, problem, order: int = 24, window: int = 240, refit: int = 20):
        if not (isinstance(order, int) and order >= 1):
            raise ParameterError("ar_order", order, "must be an integer >= 1")
        if not (isinstance(window, int) and window >= 4 * order):
            raise ParameterError("ar_window", window, f"must be an integer >= 4 ar_order = {4 * order}")
        if not (isinstance(refit, int) and refit >= 1):
            raise ParameterError("ar_refit", refit, "must be an integer >= 1 (samples)")
        self.problem, self.order, self.window, self.refit = problem, order, window, refit
        self._a, self._fitted = None, 0
        self.samples: list = []                  # measured (x_s, y_s) at t_j = j dt

    def measure(self, t: float) -> None:
        """Record the top's measured position (x_s, y_s) at t (s): the motion reference unit's sample."""
        e = np.array(self.problem.model.top(t, self.problem.p)).ravel()
        self.samples.append(e[1:3])

    def predict(self, steps: int) -> np.ndarray:
        """Positions (steps, 2) at the next ``steps`` sample times, each channel by its AR model."""
        s = np.array(self.samples[-self.window:])
        n = len(s)
        if n < 2:
            return np.repeat(s[-1:], steps, axis=0)
        order = min(self.order, max(n // 4, 1))
        if self._a is None or len(self._a) != order + 1 or len(self.samples) - self._fitted >= self.refit:
            self._a, self._fitted = burg(s, order), len(self.samples)     # (order + 1, 2)
        a = self._a
        out = np.empty((steps, 2))
        for ch in range(2):       # the AR recursion with zero innovations from the last samples: an all-pole filter
            zi = lfiltic([1.0], a[:, ch], s[::-1, ch][:order])
            out[:, ch] = lfilter([1.0], a[:, ch], np.zeros(steps), zi=zi)[0]
        return out

    def exogenous(self, k: int, n_h: int) -> np.ndarray:
        """The rows E (n_h + 1, ne) of intervals k .. k + n_h as :meth:`.payout.HeaveProblem.exogenous` lays
        them out, from the samples measured up to t_k = k dt (call :meth:`measure` first) and the prediction."""
        prob = self.problem
        dt, m = prob.dt, 2 * prob.substeps + 1
        past = np.array(self.samples[-8:])
        pred = self.predict(n_h + 2)
        pos = np.vstack([past, pred])
        tj = dt * (k - len(past) + 1 + np.arange(len(pos)))
        times = (dt * (k + np.arange(n_h + 1))[:, None] + (dt / (m - 1)) * np.arange(m)[None, :]).ravel()
        if len(pos) >= 4:
            spl = CubicSpline(tj, pos, axis=0)
            v, d1, d2 = spl(times), spl(times, 1), spl(times, 2)
        else:
            v, d1, d2 = np.repeat(pos[-1:], len(times), axis=0), np.zeros((len(times), 2)), np.zeros((len(times), 2))
        e = np.column_stack([times, v, d1, d2])       # (t, x_s, y_s, x_s', y_s', x_s'', y_s'')
        return e.reshape(n_h + 1, -1)


def burg(x: np.ndarray, order: int) -> np.ndarray:
    """Burg's AR coefficients a (order + 1, m), a_0 = 1, of each column of the series x (n, m) (or of x (n,):
    a (order + 1,)): x_j + sum_i a_i x_{j-i} = e_j (Kay & Marple 1981, sec. V.B: each reflection
    coefficient k_m minimizes the sum of the forward and backward prediction errors' squares,
    k_m = -2 f.b / (f.f + b.b), |k_m| <= 1; Levinson's update of a)."""
    x = np.asarray(x, float)
    f = (x[:, None] if x.ndim == 1 else x).copy()
    b = f.copy()
    a = np.zeros((order + 1, f.shape[1]))
    a[0] = 1.0
    for m in range(1, order + 1):
        fp, bp = f[1:], b[:-1]
        den = np.sum(fp * fp + bp * bp, axis=0)
        k = np.where(den > 0, -2.0 * np.sum(fp * bp, axis=0) / np.where(den > 0, den, 1.0), 0.0)
        f, b = fp + k * bp, bp + k * fp
        a[: m + 1] = a[: m + 1] + k * a[m::-1]
    return a[:, 0] if x.ndim == 1 else a
