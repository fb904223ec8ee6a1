"""Why a time-domain run failed and what to try: the messages of :class:`~.run.Simulator`.

CasADi reports an integrator failure as text (``... returned "TOO_MUCH_WORK" ... at t = ...``);
this module reads the flag and time from it and words the message users see.
"""

from __future__ import annotations

import math
import re

import casadi as ca
import numpy as np

REMEDIES = {
    "TOO_MUCH_WORK": "Remedy: the motion needs far smaller steps than the output interval (a very stiff cable, "
                     "large AE, or one that goes slack and taut violently): use the stiff default 'cvodes' (BDF), "
                     "shorten numerics.output_step, loosen rtol, or raise the budget (--max-steps, "
                     "IntegratorSettings.max_num_steps)",
    "CONV_FAIL": "Newton iterations failed: tighten tolerances, shorten numerics.output_step, or try 'idas'",
    "ERR_FAIL": "error test failed repeatedly: the motion may be unbounded or discontinuous; check the inputs",
    "nonfinite": "the state became infinite: a fixed-step method above its stability limit; raise "
                 "numerics.steps_per_output or use 'cvodes'",
    "chatter": "the cable switched taut/slack endlessly at one instant (Zeno): set a tension_floor below 0 "
               "or add internal damping",
}

RK4_LIMIT = 2.78     # |h lambda| on RK4's stability boundary (2.785 real axis, 2.828 imaginary)


def failure_reason(err: Exception) -> tuple[str, float | None]:
    """The solver's flag (e.g. ``"TOO_MUCH_WORK"``) and the time it names, read from a CasADi error.

    Parameters
    ----------
    err : Exception
        The error raised by a CasADi integrator call.

    Returns
    -------
    tuple
        ``(flag, t)``: the flag, or the last line of the text when there is none; the time (s,
        from the start of the call) or None.
    """
    text = str(err)
    flag = re.search(r'returned "([A-Z_]+)"', text)
    when = re.search(r"[Aa]t t ?= ?([-+0-9.eE]+)", text)
    return (flag.group(1) if flag else text.strip().splitlines()[-1][:200],
            float(when.group(1)) if when else None)


def failure_message(err: Exception, *, method: str, adaptive: bool, max_num_steps: int, steps_before: int,
                    t_a: float, t_b: float, t_kept: float) -> str:
    """The message of an integrator failure between ``t_a`` and ``t_b``: where, why, what to try.

    Parameters
    ----------
    err : Exception
        The CasADi error.
    method : str
        Integrator name.
    adaptive : bool
        Whether the method reports the time of the failure (adaptive steps).
    max_num_steps : int
        The step budget per output interval.
    steps_before : int
        Steps taken in the intervals before.
    t_a, t_b : float
        The interval that failed (s).
    t_kept : float
        Last output time kept (s).

    Returns
    -------
    str
        One message for ``RunRecord.message``.
    """
    flag, when = failure_reason(err)
    at = f" (at t = {when + t_a:.6g} s)" if when is not None and adaptive else ""
    if "TOO_MUCH_WORK" in flag:
        return (f"step budget exhausted: {method} used all max_num_steps = {max_num_steps} steps "
                f"between t = {t_a:.6g} s and {t_b:.6g} s{at} without reaching {t_b:.6g} s "
                f"(besides {steps_before} steps in the intervals before). {REMEDIES['TOO_MUCH_WORK']}. "
                f"Results up to t = {t_kept:.6g} s are kept.")
    key = next((kk for kk in REMEDIES if kk in flag), None)
    return (f"{method} failed between t = {t_a:.6g} s and {t_b:.6g} s{at}: {flag}. "
            f"Remedy: {REMEDIES.get(key, 'check the scene and tolerances')}. Results up to t = {t_kept:.6g} s are kept.")


def rk4_stability_note(h: float, lam_max: float, steps_per_output: int) -> str:
    """A warning text when the fixed RK4 step is above its stability limit, else ``""``.

    Parameters
    ----------
    h : float
        The fixed step (s).
    lam_max : float
        Largest eigenvalue modulus of the ODE Jacobian (1/s).
    steps_per_output : int
        RK4 steps per output interval (to propose a larger one).

    Returns
    -------
    str
        The note, or ``""`` when ``h * lam_max <= RK4_LIMIT``.
    """
    ratio = h * lam_max
    if ratio <= RK4_LIMIT:
        return ""
    need = int(np.ceil(steps_per_output * ratio / RK4_LIMIT))
    return (f"the fixed RK4 step h = {h:.3g} s times the largest eigenvalue |lambda| = {lam_max:.4g} 1/s "
            f"is {ratio:.3g} > {RK4_LIMIT} (RK4 stability limit): expect growth; use steps_per_output >= {need} "
            "or an implicit method ('cvodes', 'collocation')")


def ode_jacobian(model) -> ca.Function:
    """dx'/dx of ``model``'s ODE, ``(x, t, p) -> J``, built once per model (``model.derive``; its
    AD grows with the elements, so only when asked: RK4's stability check, slack events, studies)."""
    x, t, p = model.sym("x", 2 * model.nq), model.sym("t"), model.sym("p", len(model.layout))
    return model.derive("ode_jacobian", lambda: ca.Function("ode_jacobian", [x, t, p], [ca.jacobian(model.ode(x, t, p), x)]))


def spectrum(model, x, t: float, p) -> np.ndarray:
    """The eigenvalues of the ODE Jacobian dx'/dx of ``model`` at state ``x``, time ``t`` (1/s, complex)."""
    return np.linalg.eigvals(np.array(ode_jacobian(model)(x, t, p)))


def largest_rate(model, x, t: float, p) -> float:
    """|lambda|_max of the ODE Jacobian of ``model`` at state ``x``, time ``t`` (1/s).

    Parameters
    ----------
    model : CableModel
        The model.
    x : array_like
        State (SI).
    t : float
        Time (s).
    p : array_like
        Parameter vector.

    Returns
    -------
    float
        The largest eigenvalue modulus.
    """
    return float(np.max(np.abs(spectrum(model, x, t, p))))


def rk4_steps_per_output(lam_max: float, output_step: float, limit: float = RK4_LIMIT) -> int:
    """Fewest RK4 steps per output interval that keep h |lambda|_max <= ``limit`` (at most RK4_LIMIT).

    Parameters
    ----------
    lam_max : float
        Largest eigenvalue modulus (1/s), e.g. :func:`largest_rate`.
    output_step : float
        Output interval (s).
    limit : float, optional
        The bound on h |lambda|_max (a margin below RK4_LIMIT).

    Returns
    -------
    int
        Steps per output interval (>= 1).
    """
    return max(1, math.ceil(output_step * lam_max / limit))
