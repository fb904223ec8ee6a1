"""Time-domain runs: ``simulate(scene)`` and the reusable :class:`Simulator`.

The whole integration between events runs inside one compiled CasADi integrator call
(no Python per step). Slack switches are located as described in :mod:`.events`.
"""

from __future__ import annotations

import logging
import warnings
import re
import time as _time

import casadi as ca
import numpy as np

from ..errors import NumericalWarning, ParameterError
from ..linear.steady import steady_state
from ..model import CableModel, build_model
from ..results import SlackEvent, SnapLoad, TimeResult
from ..scene import Scene
from . import events as ev
from .integrators import ADAPTIVE, IntegratorSettings, make_integrator

log = logging.getLogger(__name__)

REMEDIES = {
    "TOO_MUCH_WORK": "the step size collapsed: use the stiff default 'cvodes' (BDF), loosen rtol, or check for a "
                     "cable that goes slack and taut violently",
    "CONV_FAIL": "Newton iterations failed: tighten tolerances, shorten numerics.output_step, or try 'idas'",
    "ERR_FAIL": "error test failed repeatedly: the motion may be unbounded or discontinuous; check the inputs",
    "nonfinite": "the state became infinite: a fixed-step method above its stability limit; raise "
                 "numerics.steps_per_output or use 'cvodes'",
    "chatter": "the cable switched taut/slack endlessly at one instant (Zeno): set a tension_floor below 0 "
               "or add internal damping",
}


def _reason(err: Exception) -> tuple[str, float | None]:
    text = str(err)
    flag = re.search(r'returned "([A-Z_]+)"', text)
    when = re.search(r"[Aa]t t ?= ?([-+0-9.eE]+)", text)
    return (flag.group(1) if flag else text.strip().splitlines()[-1][:200],
            float(when.group(1)) if when else None)


class Simulator:
    """Integrators and helper functions for one model, output grid and method; reusable for sweeps."""

    DENSE = 32     # points of the dense grid used to bracket a switch inside one interval
    MAX_EVENTS_PER_INTERVAL = 50   # more switches than this in one output interval is a failure

    def __init__(self, model: CableModel, times, settings: IntegratorSettings | None = None):
        self.model = model
        self.times = np.asarray(times, dtype=float)
        if self.times.ndim != 1 or self.times.size < 2 or np.any(np.diff(self.times) <= 0):
            raise ParameterError("times", f"{self.times.size} values", "must be >= 2 strictly increasing output times")
        self.settings = settings or IntegratorSettings()
        t_build = _time.perf_counter()
        self._full = make_integrator(model, self.settings, self.times - self.times[0], "full")
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
        self._jac = ca.Function("ode_jacobian", [x, t, p], [ca.jacobian(xdot, x)])
        n = self.times.size
        self._gap_rate_map = self._gap_and_rate.map(n)
        self._outputs_map = model.outputs.map(n)
        self._top_map = model.top.map(n)
        self.build_s = _time.perf_counter() - t_build
        self._stats = {}

    # -- helpers -------------------------------------------------------------------------
    def _count(self, f: ca.Function) -> None:
        st = f.stats()
        for key in ("nsteps", "nfevals", "nresevals", "njevals"):
            if key in st:
                self._stats[key] = self._stats.get(key, 0) + int(st[key])

    def _advance(self, x, t_a, h, p, depth: int = 0):
        """State at t_a + h. An interval too long for max_num_steps is split in halves (up to
        2^12 pieces), so a long output interval does not fail a run that is merely long."""
        try:
            xf = np.array(self._step(x0=x, p=np.concatenate([p, [t_a, h]]))["xf"]).ravel()
        except RuntimeError as err:
            if "TOO_MUCH_WORK" not in str(err) or depth >= 12:
                raise
            self._count(self._step)
            x_mid = self._advance(x, t_a, 0.5 * h, p, depth + 1)
            return self._advance(x_mid, t_a + 0.5 * h, 0.5 * h, p, depth + 1)
        self._count(self._step)
        if not np.all(np.isfinite(xf)):
            raise FloatingPointError("nonfinite")
        return xf

    RK4_LIMIT = 2.78     # |h lambda| on RK4's stability boundary (2.785 real axis, 2.828 imaginary)

    def _check_fixed_step(self, x0, p) -> str:
        """For 'rk': warn when h |lambda|_max at the start exceeds RK4's stability limit."""
        if self.settings.method != "rk":
            return ""
        lam = np.linalg.eigvals(np.array(self._jac(x0, self.times[0], self._with_mode(p, np.zeros(self.model.n_sections)))))
        h = float(np.min(np.diff(self.times))) / self.settings.steps_per_output
        ratio = h * float(np.max(np.abs(lam)))
        if ratio <= self.RK4_LIMIT:
            return ""
        need = int(np.ceil(self.settings.steps_per_output * ratio / self.RK4_LIMIT))
        note = (f"the fixed RK4 step h = {h:.3g} s times the largest eigenvalue |lambda| = {np.max(np.abs(lam)):.4g} 1/s "
                f"is {ratio:.3g} > {self.RK4_LIMIT} (RK4 stability limit): expect growth; use steps_per_output >= {need} "
                "or an implicit method ('cvodes', 'collocation')")
        warnings.warn(note, NumericalWarning, stacklevel=4)
        return note

    def _with_mode(self, p, mode):
        p = p.copy()
        p[list(self.model.slack_index)] = mode
        return p

    # -- the run ------------------------------------------------------------------------
    def run(self, p, x0) -> tuple:
        """Integrate from ``x0`` at ``times[0]``; returns (X, modes, events, snaps, success, message, stats)."""
        p = np.asarray(p, dtype=float)
        x0 = np.asarray(x0, dtype=float)
        self._stats = {}
        stability_note = self._check_fixed_step(x0, p)
        wall = _time.perf_counter()
        nsec, times = self.model.n_sections, self.times
        g0, _ = self._gap_and_rate(x0, times[0], self._with_mode(p, np.zeros(nsec)))
        mode = (np.array(g0).ravel() < 0).astype(float)
        X, modes = [x0], [mode.copy()]
        events, snaps = [], []
        success, message = True, ""
        k = 0
        # 1) one compiled call over all output times
        try:
            pm = self._with_mode(p, mode)
            Xs = np.array(self._full(x0=x0, p=np.concatenate([pm, [times[0], 1.0]]))["xf"])
            self._count(self._full)
            cols = np.column_stack([x0, Xs])
            finite = np.all(np.isfinite(cols), axis=0)
            n_ok = int(np.argmin(finite)) if not finite.all() else times.size
            G, D = (np.array(a) for a in self._gap_and_rate(cols[:, :n_ok], times[None, :n_ok],
                                                           np.tile(pm[:, None], (1, n_ok))))
            j_bad = ev.first_bad_interval(G, D, np.diff(times[:n_ok]), mode == 1.0)
            n_keep = j_bad if j_bad is not None else n_ok       # columns 0 .. n_keep-1 are accepted
            X += list(cols[:, 1:n_keep].T)
            modes += [mode.copy()] * (n_keep - 1)
            k = n_keep - 1
        except RuntimeError as err:
            log.info("one-shot integration failed (%s); stepping interval by interval", _reason(err)[0])
        # 2) interval by interval after an event (or a failure), locating switches
        x, t_a = X[-1], times[k]
        switches_here = 0
        events_in_interval = 0
        while k < times.size - 1:
            t_b = times[k + 1]
            pm = self._with_mode(p, mode)
            try:
                xb = self._advance(x, t_a, t_b - t_a, pm)
                hit = self._first_event(x, t_a, xb, t_b, pm, mode)
            except (RuntimeError, FloatingPointError) as err:
                flag, when = _reason(err)
                key = next((kk for kk in REMEDIES if kk in flag), None)
                success = False
                message = (f"{self.settings.method} failed between t = {t_a:.6g} s and {t_b:.6g} s"
                           + (f" (at t = {when + t_a:.6g} s)" if when is not None and self.settings.method in ADAPTIVE else "")
                           + f": {flag}. Remedy: {REMEDIES.get(key, 'check the scene and tolerances')}. "
                           f"Results up to t = {times[k]:.6g} s are kept.")
                break
            if hit is None:
                x, t_a, k = xb, t_b, k + 1
                X.append(x); modes.append(mode.copy())
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
                    snaps.append(snap)
            t_a = t_star
            switches_here = switches_here + 1 if t_star - (events[-2].time if len(events) > 1 else -np.inf) < 1e-12 else 0
            events_in_interval += 1
            if switches_here > 4 or events_in_interval > self.MAX_EVENTS_PER_INTERVAL:
                success, message = False, (f"taut/slack chattering at t = {t_star:.9g} s ({events_in_interval} switches "
                                           f"in one output interval): {REMEDIES['chatter']}"
                                           + ("; " + stability_note if stability_note else ""))
                break
        stats = dict(self._stats, method=self.settings.method, wall_s=_time.perf_counter() - wall,
                     build_s=self.build_s, n_events=len(events))
        if stability_note:
            stats["warning"] = stability_note
        return np.array(X).T, np.array(modes).T, tuple(events), tuple(snaps), success, message, stats

    def _dense_states(self, x, t_a, h, pm):
        """States at t_a + h * (0, 1/DENSE, ..., 1) from one integrator call."""
        Xd = np.array(self._dense(x0=x, p=np.concatenate([pm, [t_a, h]]))["xf"])
        self._count(self._dense)
        if not np.all(np.isfinite(Xd)):
            raise FloatingPointError("nonfinite")
        return np.column_stack([x, Xd]), t_a + h * np.linspace(0.0, 1.0, self.DENSE + 1)

    def _rates_at(self, X, T, pm):
        G = self._gap_rates(X, T[None, :], np.tile(pm[:, None], (1, T.size)))   # CasADi maps over columns
        return [np.array(v) for v in G]

    def _refine(self, X, T, j, pm, i, which: int):
        """Root of derivative ``which`` (0: g, 1: dg/dt) of section i in [T[j-1], T[j]]."""
        x0, t0 = X[:, j - 1], T[j - 1]

        def fun(t):
            xt = self._advance(x0, t0, t - t0, pm) if t > t0 else x0
            vals = self._gap_rates(xt, t, pm)
            return float(np.array(vals[which])[i, 0]), float(np.array(vals[which + 1])[i, 0])
        G = self._rates_at(X[:, j - 1:j + 1], T[j - 1:j + 1], pm)
        return ev.newton_bracketed(fun, T[j - 1], T[j], G[which][i, 0], G[which][i, 1],
                                   1e-13 * max(1.0, abs(T[j])))

    def _first_event(self, xa, t_a, xb, t_b, pm, mode):
        """Earliest located switch in (t_a, t_b] as (time, section), or None."""
        G, D, _ = self._rates_at(np.column_stack([xa, xb]), np.array([t_a, t_b]), pm)
        suspects = [i for i in range(len(mode))
                    if ev.first_bad_interval(G[i:i + 1], D[i:i + 1], [t_b - t_a], mode[i:i + 1] == 1.0) is not None]
        if not suspects:
            return None
        X, T = self._dense_states(xa, t_a, t_b - t_a, pm)
        G, D, _ = self._rates_at(X, T, pm)
        found = [(t, i) for i in suspects if (t := self._locate(X, T, G, D, pm, mode, i)) is not None]
        return min(found) if found else None

    def _locate(self, X, T, G, D, pm, mode, i):
        """First crossing of section i on the dense grid (X, T), refined; None if there is none."""
        slack = mode[i:i + 1] == 1.0
        sign = -1.0 if slack[0] else 1.0
        lo = 0                                   # search intervals (T[lo], T[lo+1]], ...
        while lo < T.size - 1:
            j = ev.first_bad_interval(G[i:i + 1, lo:], D[i:i + 1, lo:], np.diff(T[lo:]), slack)
            if j is None:
                return None
            j += lo
            if sign * G[i, j] < -1e-12 * max(1.0, abs(G[i, j - 1]), abs(G[i, j])):
                return self._refine(X, T, j, pm, i, 0)          # bracketed by the dense points
            if T[j] - T[j - 1] > 1e-9 * max(1.0, abs(T[j])):   # a dip between dense points: look closer
                sub = self._first_event(X[:, j - 1], T[j - 1], X[:, j], T[j], pm, mode)
                if sub is not None and sub[1] == i:
                    return sub[0]
            lo = j
        return None

    def _snap(self, x, t_star, pm, i_sec, t_end):
        """First tension maximum after section ``i_sec`` went taut at ``t_star`` (dg/dt = 0, d2g/dt2 < 0)."""
        J = np.array(self._jac(x, t_star, pm))
        iu = self.model.q_labels.index("u" if self.model.n_sections == 1 else f"u_{i_sec + 1}")
        w2 = max(-J[self.model.nq + iu, iu], 1e-12)
        window = min(t_end - t_star, 2.0 * np.pi / np.sqrt(w2))      # within one stretch period
        if window <= 0:
            return None
        try:
            X, T = self._dense_states(x, t_star, window, pm)
            G, D, _ = self._rates_at(X, T, pm)
            j = next((j for j in range(1, T.size) if D[i_sec, j - 1] > 0 >= D[i_sec, j]), None)
            if j is None:
                return None
            t_pk = self._refine(X, T, j, pm, i_sec, 1)
            x_pk = self._advance(X[:, j - 1], T[j - 1], t_pk - T[j - 1], pm) if t_pk > T[j - 1] else X[:, j - 1]
        except (RuntimeError, FloatingPointError):
            return None
        g = float(np.array(self._gap_and_rate(x_pk, t_pk, pm)[0])[i_sec, 0])
        tens = pm[self.model.layout.index(("" if self.model.n_sections == 1 else f"sections[{i_sec}].") + "cable.tension_floor")]
        return SnapLoad(time=float(t_pk), section=i_sec, tension=g + float(tens))

    def outputs(self, X, modes, p) -> dict:
        """Labelled outputs and top motion at the output times reached."""
        n = X.shape[1]
        P = np.tile(np.asarray(p, float)[:, None], (1, n))
        P[list(self.model.slack_index), :] = modes
        pad = self.times.size - n
        Xp = np.pad(X, ((0, 0), (0, pad)), mode="edge")
        Pp = np.pad(P, ((0, 0), (0, pad)), mode="edge")
        E = np.array(self._top_map(self.times, Pp))
        Y = np.array(self._outputs_map(Xp, E, Pp))[:, :n]
        data = {lbl: Y[i] for i, lbl in enumerate(self.model.output_labels)}
        data["x_s"], data["y_s"] = E[1, :n], E[2, :n]
        return data


def initial_state(scene: Scene, model: CableModel, p) -> np.ndarray:
    """x0 from ``scene.initial``; unset angle/stretch come from the steady state."""
    ini = scene.initial
    q = steady_state(model, p).q if (ini.phi is None or ini.u is None) else None
    q0 = np.array([(ini.phi if ini.phi is not None else q[i]) if lbl.startswith("phi")
                   else (ini.u if ini.u is not None else q[i]) for i, lbl in enumerate(model.q_labels)])
    qd0 = np.array([ini.phi_rate if lbl.startswith("phi") else ini.u_rate for lbl in model.q_labels])
    return np.concatenate([q0, qd0])


def simulate(scene: Scene, *, model: CableModel | None = None, method: str | None = None,
             rtol: float | None = None, atol: float | None = None, times=None, x0=None,
             simulator: Simulator | None = None, jit: bool = False) -> TimeResult:
    """Run ``scene`` in the time domain; returns a :class:`~cablesys.results.TimeResult`.

    ``method``/``rtol``/``atol`` override ``scene.numerics``; ``times`` the output times;
    ``jit`` compiles the model with the C compiler (about 3x faster runs, ~2 s more build).
    An integrator failure returns ``success=False`` with the results computed so far.
    """
    t_build = _time.perf_counter()
    model = model or (simulator.model if simulator else build_model(scene))
    num = scene.numerics
    if simulator is None:
        settings = IntegratorSettings(method=method or num.integrator, rtol=rtol or num.rtol,
                                      atol=atol or num.atol, steps_per_output=num.steps_per_output, jit=jit)
        simulator = Simulator(model, scene.output_times if times is None else times, settings)
    build_s = _time.perf_counter() - t_build
    p = model.parameters(scene)
    x0 = initial_state(scene, model, p) if x0 is None else np.asarray(x0, float)
    X, modes, events, snaps, ok, msg, stats = simulator.run(p, x0)
    stats["build_s"] = build_s
    if not ok:
        log.warning(msg)
    data = simulator.outputs(X, modes, p)
    return TimeResult(time=simulator.times[: X.shape[1]], data=data, success=ok, message=msg, stats=stats,
                      events=events, snaps=snaps, scene_name=scene.name,
                      initially_slack=tuple(int(i) for i in np.nonzero(modes[:, 0])[0]))
