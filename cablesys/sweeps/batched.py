"""RAO sweeps in batches: one mapped CasADi call linearizes every case of a chunk.

The linearization of :func:`cablesys.linear.linearize` is two Jacobian evaluations per case
(``dr/dxi`` and ``(y, dy/dxi)`` at the steady state); for a chunk of cases of one structure
they are evaluated by ``Function.map(n)`` over the columns of (xi_0, p), one call instead of
n (the same expression graph, so the same numbers). The steady states stay per case (each
with its own guesses and checks), and so do the natural frequencies and RAO metrics
(:func:`.analyses.rao_summary`).
"""

from __future__ import annotations

import numpy as np

from ..errors import CablesysError
from .analyses import rao_summary


def linear_models(model, P) -> list:
    """LinearModel (or the exception that stopped it) per column of the parameter matrix ``P``."""
    from ..linear import steady_state
    from ..linear.linearization import (
        from_jacobian,
        functions,
        operating_xi,
        taut_parameters,
    )
    out: list = [None] * P.shape[1]
    cols, steady = [], []
    for k in range(P.shape[1]):
        p = taut_parameters(model, P[:, k])
        try:
            steady.append(steady_state(model, p))
            cols.append((k, p))
        except (CablesysError, RuntimeError, ValueError, ArithmeticError) as err:
            out[k] = err
    if not cols:
        return out
    fns = functions(model)
    n = len(cols)
    XI = np.column_stack([operating_xi(model, s.q) for s in steady])
    PP = np.column_stack([p for _, p in cols])
    n_xi = XI.shape[0]
    J = np.array(fns["jac"].map(n)(XI, PP))
    Y, JY = (np.array(v) for v in fns["out_jac"].map(n)(XI, PP))
    for j, ((k, _), s) in enumerate(zip(cols, steady)):
        blk = slice(j * n_xi, (j + 1) * n_xi)
        out[k] = from_jacobian(model, J[:, blk], JY[:, blk], s.q, Y[:, j], kind="exact")
    return out


def rao_chunk(scenes: list, options: list, cache) -> list:
    """(summary, success, message) or an exception, per scene; scenes of one structure share one mapped call."""
    from ..model import structure_of
    groups: dict = {}
    for i, sc in enumerate(scenes):
        groups.setdefault(structure_of(sc), []).append(i)
    out: list = [None] * len(scenes)
    for idx in groups.values():
        model = cache.model(scenes[idx[0]])
        P = np.column_stack([model.parameters(scenes[i]) for i in idx])
        for i, lin in zip(idx, linear_models(model, P)):
            if isinstance(lin, Exception):
                out[i] = lin
                continue
            try:
                out[i] = rao_summary(scenes[i], lin, options[i])
            except (CablesysError, RuntimeError, ValueError, ArithmeticError) as err:
                out[i] = err
    return out
