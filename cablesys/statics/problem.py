"""The static problem of every model: its residual at rest and the equilibrium it defines.

A steady state solves f(q, q' = 0, e = 0, p) = 0 (Wang 1971 eq. 47-48 with all rates zero, the
top at rest) from the same CasADi model used in the time domain, with the waves and the slack
switches off (:func:`static_parameters`) and the residual scaled to O(1) (:func:`static_residual`).
The 2-DOF solve (:mod:`.steady`) and the segmented cable's catenary (:mod:`.catenary`) both solve
it and report a :class:`SteadyState` (:func:`at_rest`).
"""

from __future__ import annotations

import dataclasses

import casadi as ca
import numpy as np

from ..model import CableModel


@dataclasses.dataclass(frozen=True)
class SteadyState:
    """An equilibrium: coordinates, outputs (labelled), the relative residual reached
    (forces over total weight, moments over weight x length; see :func:`static_residual`)."""

    q: np.ndarray
    q_labels: tuple
    outputs: dict
    residual: float

    @property
    def x(self) -> np.ndarray:
        """Full state (q, q' = 0)."""
        return np.concatenate([self.q, np.zeros_like(self.q)])


def static_parameters(model: CableModel, p) -> np.ndarray:
    """A copy of the parameter vector ``p`` with the entries a steady state ignores set to 0."""
    p = np.array(p, dtype=float)
    p[static_zeroed(model)] = 0.0
    return p


def static_zeroed(model: CableModel) -> list[int]:
    """Parameter entries a steady state ignores: wave amplitudes and the slack switches."""
    waves = [i for i, lbl in enumerate(model.layout.labels)
             if lbl.startswith("environment.waves[") and lbl.endswith(".amplitude")]
    return waves + list(model.slack_index)


def static_residual(model: CableModel) -> ca.Function:
    """``(q, p) -> r``: the static residual f(q, q' = 0, e = 0, p) with waves and slack off,
    scaled to O(1) (built once per model; shared by :func:`.steady.steady_state`, the catenary
    of :mod:`.catenary` and the design NLP).

    u-rows (forces) are divided by the total weight, phi-rows (moments) by weight x length,
    so that solver tolerances are relative and not below round-off for heavy, long systems
    (Wang 1971 eq. 47-48 with all rates zero).

    Parameters
    ----------
    model : CableModel
        A 2-DOF or section-chain model.

    Returns
    -------
    casadi.Function
        ``static_residual(q, p) -> r`` (dimensionless), built once per model (``model.cache``).
    """
    def build():
        q = ca.SX.sym("q", model.nq)
        p = ca.SX.sym("p", len(model.layout))
        zeroed = set(static_zeroed(model))
        ps = ca.vertcat(*[0.0 if i in zeroed else p[i] for i in range(len(model.layout))])
        # a seabed's statics have their own laws (the laid-down line's friction: model/segmented_seabed.py)
        forces = getattr(model, "static_force", None)
        if forces is not None:
            f = forces(q, ca.SX.zeros(model.nq), ca.SX.zeros(model.top.size1_out(0)), ps)
        else:
            _, f = model.dynamics(q, ca.SX.zeros(model.nq), ca.SX.zeros(model.top.size1_out(0)), ps)
        return ca.Function("static_residual", [q, p], [f / residual_scales(model, p)], ["q", "p"], ["r"])
    return model.derive("static_residual", build)


def total_weight(labels, p):
    """The total weight in the medium (N) of the bodies and cables whose parameters ``p`` (symbolic or numeric) carry
    these labels: sum |W_b| + |w| l_r over bodies and cable sections (a chain's cables, a system's lines)."""
    return sum(ca.fabs(p[i]) for i, lb in enumerate(labels) if lb.endswith("body.weight")) + sum(
        ca.fabs(p[i] * p[labels.index(lb.replace("weight_per_length", "length"))])
        for i, lb in enumerate(labels) if lb.endswith(".weight_per_length"))


def residual_scales(model: CableModel, p):
    """The scale of each equation of motion's residual, from the (symbolic) parameters ``p``: the total submerged
    weight (N) for the force rows, weight x cable length (N m) for the moment rows (``phi``); dividing by it makes
    solver tolerances relative, not below round-off for heavy, long systems."""
    lab = model.layout.labels
    weight = total_weight(lab, p)
    length = sum(p[i] for i, lb in enumerate(lab) if lb.endswith("cable.length"))
    return ca.vertcat(*[weight * length if lbl.startswith("phi") else weight for lbl in model.q_labels])


def at_rest(model: CableModel, q, p, residual: float) -> SteadyState:
    """The :class:`SteadyState` at coordinates ``q`` (rates zero, top at rest: e = 0), its outputs
    evaluated with the static parameters ``p`` (:func:`static_parameters`)."""
    x = np.concatenate([q, np.zeros_like(q)])
    y = np.array(model.outputs(x, np.zeros(model.top.size1_out(0)), p)).ravel()
    return SteadyState(q=q, q_labels=model.q_labels, outputs=dict(zip(model.output_labels, y)), residual=residual)
