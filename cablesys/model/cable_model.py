"""The model object (CasADi functions of one scene structure) and its cache of derived functions.

A :class:`CableModel` is immutable: its functions are built once by
:func:`~cablesys.model.build_model`. Analyses derive further functions from it (the
linearization Jacobians, collocation and harmonic-balance residuals, the static rootfinder,
the compiled integrator); they are built once per model and kept in the model's
:class:`FunctionCache`, an explicit object with a documented interface, not a dict filled
under ad hoc keys. A copy made with ``dataclasses.replace`` (a different model) starts
with an empty cache.

A cache may be attached to a disk store (:meth:`FunctionCache.attach`, done by
:func:`~cablesys.model.build_model` with :class:`cablesys.compiled.DerivedStore`): an item
not yet built in this process is first asked of the store (a compiled library built by an
earlier run of the same model structure), and a newly built one is offered to it.
"""

from __future__ import annotations

import dataclasses
import threading
from collections.abc import Callable
from typing import Any

import casadi as ca
import numpy as np

from .params import ParameterLayout, section_suffix


class FunctionCache:
    """Functions derived from one model, each built once under a key.

    ``get(key, build)`` returns the object stored under ``key``, calling ``build()`` the first
    time. Keys name what is derived and its structural options (``"linearize"``,
    ``"colloc_41"``); numbers that vary between calls must be arguments of the functions
    (entries of ``p``), never part of a key. Safe to share between threads (a build may
    itself ask the cache for another key). Pickling keeps no functions: a copy in another
    process builds its own (or loads it from the attached store, which is kept).

    Parameters
    ----------
    store : object, optional
        A disk store with ``load(key) -> item or None`` and ``save(key, item)`` (see
        :meth:`attach`).
    """

    def __init__(self, store=None):
        self._items: dict[str, Any] = {}
        self._lock = threading.RLock()
        self._store = store
        self.hits = 0            # items this cache took from its store instead of building them

    def attach(self, store) -> None:
        """Use ``store`` (``load(key)`` / ``save(key, item)``) behind this cache: on a miss the
        store is asked first; what is built is offered to it (it keeps what it can reuse)."""
        self._store = store

    @property
    def store(self):
        """The attached disk store (None: memory only)."""
        return self._store

    def get(self, key: str, build: Callable[[], Any]) -> Any:
        """The function stored under ``key``, built by ``build()`` on first use.

        Parameters
        ----------
        key : str
            Name of the derived function and its structural options.
        build : callable
            No-argument function that builds it.

        Returns
        -------
        object
            What ``build()`` returned the first time.
        """
        with self._lock:
            if key not in self._items:
                item = self._store.load(key) if self._store is not None else None
                if item is None:
                    item = build()
                    if self._store is not None:
                        self._store.save(key, item)
                else:
                    self.hits += 1
                self._items[key] = item
            return self._items[key]

    def __contains__(self, key: str) -> bool:
        return key in self._items

    def __len__(self) -> int:
        return len(self._items)

    def keys(self) -> tuple:
        """Keys built so far."""
        return tuple(self._items)

    def clear(self) -> None:
        """Forget every derived function (they are rebuilt on next use)."""
        with self._lock:
            self._items.clear()

    def __getstate__(self):
        return {"store": self._store}

    def __setstate__(self, state):
        self.__init__(state.get("store"))

    def __repr__(self) -> str:
        return f"FunctionCache({', '.join(self._items) or 'empty'})"


@dataclasses.dataclass(frozen=True, eq=False)
class CableModel:
    """CasADi functions of one scene structure; every scene number is an entry of ``p``.

    Functions (all SX, built once):
      ``dynamics(q, qd, e, p) -> (M, f)`` with M q'' = f;
      ``ode(x, t, p) -> x'`` with x = (q, q') and the top motion composed in;
      ``top(t, p) -> e``; ``outputs(x, e, p) -> y`` (labels ``output_labels``);
      ``energy(x, e, p) -> (K, V)``; ``cable_force(x, p) -> F_bc - TENS`` per section.
    Tension outputs per section i (N; suffix ``_i`` in a chain, :meth:`label`): ``tension_top``,
    the force of the cable on its top point (the ship, or body i-1), and ``tension_bottom``, its
    force on body i; both carry everything hanging below that end (at an intermediate body the
    upper section's ``tension_bottom`` is the size of the vector sum of the body's weight, drag,
    inertia force -M_bv a_b and the lower section's pull, whose size is its ``tension_top``).
    ``tension`` is the force of the section's stretch law: in Wang's straight cable
    F_bc = k u + (C_I / l_r) u' (eq. 54; bounded by TENS when slack), its mean
    tension (hanging at rest W_c/2 above ``tension_bottom``); in the segmented cable the lowest
    element's tension. Wang's end tensions are signed (negative: the straight cable would push).
    ``cache`` holds the functions analyses derive from these (:class:`FunctionCache`).
    """

    layout: ParameterLayout
    n_sections: int
    angles: str
    q_labels: tuple
    output_labels: tuple
    dynamics: ca.Function
    ode: ca.Function
    top: ca.Function
    outputs: ca.Function
    energy: ca.Function
    cable_force: ca.Function
    slack_index: tuple          # positions of the per-section slack switches in p
    symbolic: type = ca.SX      # the symbol type of the model's functions (a sampled series is SX too: a table lookup)
    kind: str = "wang"          # which rung of the model ladder: "wang", "quasi-static", "segmented"
    cache: FunctionCache = dataclasses.field(init=False, repr=False)
    # how build_model made it: ``stored`` (loaded from the disk cache), ``build_s``, ``structure_key``
    build_info: dict = dataclasses.field(init=False, repr=False, compare=False)
    derived: dataclasses.InitVar[dict | None] = None    # deprecated, ignored: use ``cache``

    def __post_init__(self, derived):
        object.__setattr__(self, "cache", FunctionCache())
        object.__setattr__(self, "build_info", {})

    def __getattr__(self, name):
        """A function of a model loaded from the disk cache, deserialized on first use (only reached
        when the attribute is not set yet: see :func:`cablesys.model.store.load_model`)."""
        pending = self.__dict__.get("_pending")
        if pending is None or name not in pending:
            if name in self.__dict__:              # another thread deserialized it meanwhile
                return self.__dict__[name]
            raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")
        f = ca.Function.deserialize(pending[name])
        object.__setattr__(self, name, f)
        pending.pop(name, None)
        return f

    def derive(self, key: str, build):
        """``self.cache.get(key, build)`` (see :meth:`FunctionCache.get`): a derived function, built once."""
        return self.cache.get(key, build)

    def label(self, name: str, i: int) -> str:
        """Coordinate or output label of section ``i``: ``tension_mid`` (one section) or ``tension_mid_2``."""
        return f"{name}{section_suffix(self.n_sections, i)}"

    def output_index(self, name: str, i: int) -> int:
        """Position of output ``name`` of section ``i`` in ``output_labels``."""
        return self.output_labels.index(self.label(name, i))

    def q_index(self, name: str, i: int) -> int:
        """Position of coordinate ``name`` (``phi`` or ``u``) of section ``i``; a shared ``phi`` has one."""
        label = self.label(name, i)
        return self.q_labels.index(label if label in self.q_labels else name)

    def sym(self, name: str, n: int = 1):
        """A symbol of the model's symbolic type, for composing its functions."""
        return self.symbolic.sym(name, n)

    @property
    def nq(self) -> int:
        return len(self.q_labels)

    @property
    def state_labels(self) -> tuple:
        return self.q_labels + tuple(f"{q}_rate" for q in self.q_labels)

    def parameters(self, scene) -> np.ndarray:
        """Numeric parameter vector of ``scene`` (same structure as the model)."""
        return self.layout.values(scene)
