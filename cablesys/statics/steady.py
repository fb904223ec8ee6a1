"""Steady state: the equilibrium of a scene with its top at rest ((phi_0, u_0) of the 2-DOF model).

Solves f(q, q' = 0, e = 0, p) = 0 from the same CasADi model used in the time domain
(Wang 1971 eq. 47-48 with all rates zero), with CasADi's KINSOL rootfinder (line search).
Waves are switched off (a steady state has none); current and tow speed stay.
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np

from ..errors import SolverError
from ..messages import casadi_warnings_captured, kinsol_flags
from ..model import CableModel
from .catenary import anchored_guess, hanging_guess, segmented_steady
from .problem import SteadyState, at_rest, static_parameters, static_residual


def _rootfinder(model: CableModel) -> ca.Function:
    return model.derive("steady_kinsol", lambda: ca.rootfinder(
        "steady", "kinsol", static_residual(model),
        {"strategy": "linesearch", "abstol": 1e-12, "error_on_fail": False, "print_level": 0,
         # failed starting guesses are expected and retried: KINSOL's own messages off (its return
         # flag is printed regardless: steady_state collects it, cablesys.messages)
         "disable_internal_warnings": True}))


def starting_guesses(model: CableModel, p):
    """Starting guesses for the statics and the periodic solution. A 2-DOF model: every section's hanging stretch
    u = (weight below + W_c / 2) / k (dV/du = 0 of Wang 1971 eq. 15 at phi = 0) with several
    angles, the hanging one (all angles 0) first.

    A segmented model (node coordinates) yields its own first guess instead: the anchored line's
    (:func:`.catenary.anchored_guess`: a span between the top and an ``[anchor]``) or the straight
    hanging cable's (:func:`.catenary.hanging_guess`).

    Parameters
    ----------
    model : CableModel
        A 2-DOF (Wang) model, or a segmented one.
    p : array_like
        Parameter vector (``model.layout``).

    Yields
    ------
    numpy.ndarray
        Generalized coordinates q in ``model.q_labels`` order.
    """
    if getattr(model, "line_nodes", None) is not None:     # a system of lines joined at points
        from .system import system_guess
        yield system_guess(model, p)
        return
    if getattr(model, "segments", None):
        yield np.asarray(anchored_guess(model, p) if getattr(model, "anchored", False) else hanging_guess(model, p), float)
        return
    lay = model.layout
    n = model.n_sections
    pre = (lambda i: "") if n == 1 else (lambda i: f"sections[{i}].")
    val = lambda lbl: p[lay.index(lbl)]
    u, below = [0.0] * n, 0.0
    for i in reversed(range(n)):
        k = val(f"{pre(i)}cable.ae") / val(f"{pre(i)}cable.length")
        w_c = val(f"{pre(i)}cable.weight_per_length") * val(f"{pre(i)}cable.length")
        u[i] = (below + val(f"{pre(i)}body.weight") + 0.5 * w_c) / k
        below += val(f"{pre(i)}body.weight") + w_c
    for phi in (0.0, 0.3, -0.3, 0.8, -0.8, 1.2, -1.2, 1.45, -1.45):
        q = []
        for lbl in model.q_labels:
            if lbl.startswith("phi"):
                q.append(phi)
            else:
                i = 0 if lbl == "u" else int(lbl.split("_")[-1]) - 1
                q.append(u[i])
        yield np.array(q)


def steady_state(model: CableModel, p, *, guess=None, solver: ca.Function | None = None) -> SteadyState:
    """Equilibrium of the scene with parameters ``p`` (top at rest, no waves).

    Raises :class:`SolverError` if no equilibrium is found from any starting guess. A segmented
    model (node coordinates) gets its elastic catenary (:mod:`cablesys.statics.catenary`), a system of lines joined
    at points its own statics (:mod:`cablesys.statics.system`).

    Parameters
    ----------
    model : CableModel
        The model (2-DOF, chain, quasi-static or segmented).
    p : array_like
        Parameter vector (``model.parameters(scene)``); wave amplitudes and slack switches are ignored.
    guess : array_like, optional
        Starting coordinates q (rad, m); tried before the built-in hanging guesses.
    solver : casadi.Function, optional
        A rootfinder to use instead of the model's cached KINSOL (``model.cache``).

    Returns
    -------
    SteadyState
        Coordinates ``q``, labelled ``outputs`` (angles in rad, lengths in m, tensions in N) and the
        relative residual reached.
    """
    if getattr(model, "line_nodes", None) is not None:     # a system of lines joined at points (statics/system.py)
        from .system import system_steady
        return system_steady(model, p, guess=guess)
    if getattr(model, "segments", None):
        return segmented_steady(model, p, guess=guess)
    if getattr(model, "kind", None) == "element-coordinates":
        return _element_steady(model, p, guess)
    p = static_parameters(model, p)
    rf = solver or _rootfinder(model)
    resid_fn = static_residual(model)
    guesses = ([np.asarray(guess, float)] if guess is not None else []) + list(starting_guesses(model, p))
    gap_fn = model.cable_force
    best, flags = None, set()
    for g0 in guesses:
        with casadi_warnings_captured() as kinsol:      # a guess that stalls is expected: the next is tried
            q = np.array(rf(g0, p)).ravel()
        flags.update(kinsol_flags(kinsol))
        if not np.all(np.isfinite(q)):
            continue
        r = float(np.max(np.abs(np.array(resid_fn(q, p)))))
        phis = [q[i] for i, lbl in enumerate(model.q_labels) if lbl.startswith("phi")]
        taut = np.all(np.array(gap_fn(np.concatenate([q, np.zeros_like(q)]), p)) > 0)
        if not (taut and all(abs(a) < math.pi / 2 for a in phis)):
            continue          # a root of the equations, but an inverted or compressed cable
        if best is None or r < best[1]:
            best = (q, r)
        if r < 1e-10:
            break
    if best is None or best[1] > 1e-9:
        raise SolverError("steady state not found: the equilibrium rootfinder (KINSOL) found no hanging "
                          "equilibrium (every |phi| < 90 deg, every section's tension above its floor; best residual "
                          f"{best[1] if best else float('nan'):.3g}); a buoyant body on a rod only balances inverted, "
                          "and a very strong current or tow speed streams the cable horizontally: check weights and "
                          f"speeds, or give an initial guess{' (KINSOL: ' + ', '.join(sorted(flags)) + ')' if flags else ''}")
    return at_rest(model, best[0], p, best[1])


def _element_steady(model: CableModel, p, guess=None) -> SteadyState:
    """The equilibrium of the segmented cable in element coordinates (:mod:`cablesys.model.element_coordinates`): the
    node model's elastic catenary (:func:`.catenary.segmented_steady`) mapped by ``from_nodes`` (the same physics in
    other coordinates), its residual that of the element model's own static equations there."""
    rest = np.zeros(model.top.size1_out(0))
    if guess is not None:               # the guess in element coordinates, as node positions
        guess = np.array(model.to_nodes(np.concatenate([guess, np.zeros_like(guess)]), rest, p)).ravel()[:model.node_model.nq]
    st = steady_state(model.node_model, p, guess=guess)
    q = np.array(model.from_nodes(np.concatenate([st.q, np.zeros_like(st.q)]), rest, p)).ravel()[:model.nq]
    p = static_parameters(model, p)
    return at_rest(model, q, p, float(np.max(np.abs(np.array(static_residual(model)(q, p))))))
