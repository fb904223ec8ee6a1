"""Immutable results of a slack-cable analysis (a leaf module: imports no solver)."""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from ..results import ResultBase

MODE_TYPES = {"O": "out-of-plane", "A": "in-plane antisymmetric",
              "S": "in-plane symmetric", "H": "in-plane hybrid"}


@dataclass(frozen=True, kw_only=True)
class IrvineMode:
    """One mode of the flat-sag theory: type 'O', 'A' or 'S' and omega (rad/s)."""

    mode_type: str
    omega: float


@dataclass(frozen=True, kw_only=True)
class IrvineModes(ResultBase):
    """Modes of the flat-sag (Irvine-Caughey) theory, ascending: ``omega`` (rad/s) and ``mode_type``.

    Griffin & Rosenthal (1985) eqs. 6-7 and 10; ``lambda2`` is the Irvine parameter used. A
    sequence of :class:`IrvineMode` (iterate, index, ``len``) as well as a result.
    """

    mode_type: tuple[str, ...]
    omega: np.ndarray
    lambda2: float
    success: bool = True
    message: str = ""
    stats: dict = field(default_factory=dict)

    VARIABLES: ClassVar[dict] = {"omega": ("rad/s", "natural angular frequency (flat-sag theory)"),
                                 "mode_type": ("1", "mode type O/A/S"), "mode": ("1", "mode number")}

    def __len__(self) -> int:
        return len(self.omega)

    def __getitem__(self, k):
        if isinstance(k, slice):
            return [self[i] for i in range(len(self))[k]]
        return IrvineMode(mode_type=self.mode_type[k], omega=float(self.omega[k]))

    def __iter__(self):
        return (self[k] for k in range(len(self)))

    def summary(self) -> dict:
        """The mode table (omega in rad/s) with lambda^2.

        Returns
        -------
        dict
            JSON-able.
        """
        return {**super().summary(),
                "modes": [{"mode_type": t, "omega_rad_s": float(w)} for t, w in zip(self.mode_type, self.omega)]}

    def to_xarray(self):
        """Frequencies and types on dimension ``mode``.

        Returns
        -------
        xarray.Dataset
        """
        import xarray as xr
        return xr.Dataset({"omega": ("mode", self.omega), "mode_type": ("mode", list(self.mode_type))},
                          coords={"mode": np.arange(1, len(self) + 1)},
                          attrs={"lambda2": self.lambda2, "theory": "Griffin & Rosenthal (1985) eqs. 6-7, 10"})


@dataclass(frozen=True, kw_only=True)
class Equilibrium(ResultBase):
    """Static shape of the chain: node arc length s (m, unstretched), x, z (m), element tension (N).

    ``discretization``: the lumped-mass element layout the shape was solved on (the modes of
    :func:`cablesys.slack.modes` need it); ``node_state``: on the shared cable
    (:mod:`cablesys.slack.shared`), the node model's element-kernel form (:func:`cablesys.slack.shared.span_form`;
    :func:`cablesys.slack.shared.span_model` is the model itself), its node positions q* (m) and parameter vector,
    about which its modes are taken, else None; ``stats``: ``wall_time_s`` (``seconds``) and
    ``iterations`` of the statics solver."""

    scene: Any
    s: np.ndarray
    x: np.ndarray
    z: np.ndarray
    tension: np.ndarray
    method: str
    iterations: int
    seconds: float
    discretization: Any = None
    message: str = ""
    success: bool = True
    node_state: Any = field(default=None, repr=False, compare=False)

    VARIABLES: ClassVar[dict] = {"s": ("m", "unstretched arc length"), "x": ("m", "horizontal node position"),
                                 "z": ("m", "vertical node position (up)"), "tension": ("N", "element tension"),
                                 "node": ("1", "node"), "element": ("1", "element")}
    SUMMARY_EXCLUDE: ClassVar[tuple] = ("seconds", "iterations")

    @property
    def stats(self) -> dict:
        """Solver statistics: ``wall_time_s`` (s) and ``iterations``."""
        return {"wall_time_s": self.seconds, "iterations": self.iterations}

    def summary(self) -> dict:
        """Headline numbers (tensions in N, sag in m, lambda^2) without the node arrays.

        Returns
        -------
        dict
            JSON-able.
        """
        doc = self.to_dict()
        del doc["nodes"], doc["element_tension_N"]
        return {**super().summary(), **doc}

    def to_xarray(self):
        """Node positions (dim ``node``) and element tensions (dim ``element``).

        Returns
        -------
        xarray.Dataset
        """
        import xarray as xr
        return xr.Dataset({"x": ("node", self.x), "z": ("node", self.z), "tension": ("element", self.tension)},
                          coords={"s": ("node", self.s)},
                          attrs={"method": self.method, "sag_m": self.sag, "horizontal_tension_N": self.horizontal_tension})

    def static_tensions(self) -> dict:
        """{"tension": element tensions (N)}: what the verdict judges against ``scene.limits``
        (:func:`cablesys.verdict.judge`)."""
        return {"tension": np.asarray(self.tension, float)}

    @property
    def element_lengths(self) -> np.ndarray:
        return np.hypot(np.diff(self.x), np.diff(self.z))

    @property
    def horizontal_tension(self) -> float:
        """H, the horizontal tension component (the same in every element), N."""
        return float(np.mean(self.tension * np.diff(self.x) / self.element_lengths))

    @property
    def chord_tension(self) -> float:
        """H1 = H / cos(theta) (Griffin & Rosenthal 1985 section 5), N."""
        return self.horizontal_tension / math.cos(self.scene.inclination)

    @property
    def normal_offset(self) -> np.ndarray:
        """Distance of each node below the chord line (m)."""
        th = self.scene.inclination
        return self.x * math.sin(th) - self.z * math.cos(th)

    @property
    def sag(self) -> float:
        """Largest distance of the cable below its chord, s (m)."""
        return float(np.max(self.normal_offset))

    @property
    def sag_to_length(self) -> float:
        """s / L with L the unstretched length (the abscissa of Figs. 6-8)."""
        return self.sag / self.scene.cable.length

    @property
    def virtual_length(self) -> float:
        """Le1 = integral (ds/dc)^3 dc along the chord (eq. 5 in chord axes), m."""
        th = self.scene.inclination
        dc = np.diff(self.x) * math.cos(th) + np.diff(self.z) * math.sin(th)
        return float(np.sum(self.element_lengths ** 3 / dc ** 2))

    @property
    def lambda2(self) -> float:
        """Irvine's lambda^2 of this shape in chord axes (eqs. 4 and 22), cable weight only."""
        sc = self.scene
        w, _ = sc.cable.weight_and_added_mass(sc.medium, sc.gravity)
        th = sc.inclination
        H1 = self.chord_tension
        return (w * math.cos(th) * sc.chord / H1) ** 2 * sc.chord / (
            H1 * self.virtual_length / sc.cable.ae)

    def to_dict(self) -> dict:
        return {"method": self.method, "iterations": self.iterations, "seconds": self.seconds,
                "horizontal_tension_N": self.horizontal_tension,
                "max_tension_N": float(np.max(self.tension)),
                "min_tension_N": float(np.min(self.tension)),
                "sag_m": self.sag, "sag_to_length": self.sag_to_length,
                "lambda2": self.lambda2,
                "nodes": {"s_m": self.s.tolist(), "x_m": self.x.tolist(), "z_m": self.z.tolist()},
                "element_tension_N": self.tension.tolist()}


@dataclass(frozen=True, kw_only=True)
class ModeSet(ResultBase):
    """Natural modes about an equilibrium, ascending in omega.

    omega (rad/s); mode_type 'O'|'A'|'S'|'H' (out-of-plane, in-plane
    antisymmetric, symmetric, hybrid); symmetric_fraction: share of the
    in-plane mode's mass-weighted norm that is mirror symmetric about the
    mid-chord (1 for S, 0 for A); shapes: (n_modes, n_nodes, 3) nodal
    displacements in x (horizontal), y (out of plane), z (up), normalized by
    Griffin & Rosenthal (1985) eq. 25 so that sum(M psi^2) = 1 (kg^-1/2 m).
    """

    omega: np.ndarray
    mode_type: tuple[str, ...]
    symmetric_fraction: np.ndarray
    shapes: np.ndarray
    s: np.ndarray
    n_elements: int
    solver: str
    seconds: float
    success: bool = True
    message: str = ""

    VARIABLES: ClassVar[dict] = {"omega": ("rad/s", "natural angular frequency"), "mode_type": ("1", "mode type O/A/S/H"),
                                 "symmetric_fraction": ("1", "mirror-symmetric share of the in-plane norm"),
                                 "shape": ("kg^-1/2 m", "mass-normalized mode shape (eq. 25)"),
                                 "mode": ("1", "mode number"), "s": ("m", "unstretched arc length"),
                                 "dof": ("1", "displacement component")}
    SUMMARY_EXCLUDE: ClassVar[tuple] = ("seconds",)

    @property
    def stats(self) -> dict:
        """Solver statistics: ``wall_time_s`` (s)."""
        return {"wall_time_s": self.seconds}

    def summary(self) -> dict:
        """Mode table (type and omega in rad/s) with the protocol entries.

        Returns
        -------
        dict
            JSON-able.
        """
        return {**super().summary(), "modes": self.table()}

    def __len__(self) -> int:
        return len(self.omega)

    def table(self) -> list[dict]:
        """[{'mode_type', 'omega_rad_s'}] ascending: the JSON row format (omega in rad/s)."""
        return [{"mode_type": t, "omega_rad_s": float(w)} for t, w in zip(self.mode_type, self.omega)]

    def of_type(self, *types: str) -> np.ndarray:
        return np.array([w for t, w in zip(self.mode_type, self.omega) if t in types])

    def to_xarray(self):
        """Frequencies and types on ``mode``, shapes on (``mode``, ``node``, ``dof``).

        Returns
        -------
        xarray.Dataset
        """
        import xarray as xr
        return xr.Dataset(
            {"omega": ("mode", self.omega), "mode_type": ("mode", list(self.mode_type)),
             "symmetric_fraction": ("mode", self.symmetric_fraction),
             "shape": (("mode", "node", "dof"), self.shapes)},
            coords={"mode": np.arange(1, len(self) + 1), "s": ("node", self.s),
                    "dof": ["x", "y", "z"]},
            attrs={"n_elements": self.n_elements, "solver": self.solver,
                   "normalization": "Griffin & Rosenthal (1985) eq. 25: sum M psi^2 = 1"})


@dataclass(frozen=True, kw_only=True)
class Convergence(ResultBase):
    """Frequencies at element counts n, 2n, 4n and their Richardson extrapolation.

    omega: (n_levels, n_modes) rad/s, modes matched within the in-plane and
    out-of-plane families by index; order: observed convergence order
    p = log2((w1 - w2) / (w2 - w3)) per mode; richardson: w3 + (w3 - w2) /
    (2^p_assumed - 1) with p_assumed = 2 (the lumped-mass chain's order).
    """

    levels: tuple[int, ...]
    mode_type: tuple[str, ...]
    omega: np.ndarray
    order: np.ndarray
    richardson: np.ndarray
    p_assumed: float = 2.0
    success: bool = True
    message: str = ""
    stats: dict = field(default_factory=dict)

    VARIABLES: ClassVar[dict] = {"omega": ("rad/s", "natural angular frequency at each element count"),
                                 "richardson": ("rad/s", "Richardson-extrapolated natural frequency"),
                                 "order": ("1", "observed convergence order"), "level": ("1", "number of elements"),
                                 "mode": ("1", "mode number"), "mode_type": ("1", "mode type O/A/S/H")}

    def summary(self) -> dict:
        """Extrapolated frequencies (rad/s) and observed orders, JSON-able.

        Returns
        -------
        dict
        """
        return {**super().summary(), "levels": list(self.levels), "modes": self.table(),
                "order": [float(o) for o in self.order]}

    def to_xarray(self):
        """Frequencies on (``level``, ``mode``) and the extrapolation on ``mode``.

        Returns
        -------
        xarray.Dataset
        """
        import xarray as xr
        return xr.Dataset({"omega": (("level", "mode"), self.omega), "richardson": ("mode", self.richardson),
                           "order": ("mode", self.order)},
                          coords={"level": list(self.levels), "mode": np.arange(1, len(self.richardson) + 1),
                                  "mode_type": ("mode", list(self.mode_type))})

    @property
    def relative_error_finest(self) -> np.ndarray:
        """|w_finest - w_Richardson| / w_Richardson per mode."""
        return np.abs(self.omega[-1] - self.richardson) / self.richardson

    def table(self) -> list[dict]:
        order = np.argsort(self.richardson)
        return [{"mode_type": self.mode_type[i], "omega_rad_s": float(self.richardson[i])} for i in order]


@dataclass(frozen=True, kw_only=True)
class SlackAnalysis(ResultBase):
    """A slack scene analysed: its static ``equilibrium`` and the natural ``modes`` about it.

    ``success`` when both succeeded; ``stats``: ``wall_time_s`` (s) of the whole analysis and
    the statistics of each part. Unpacking it as ``eq, modes = ...`` (the old tuple) still
    works, with a DeprecationWarning.
    """

    equilibrium: Equilibrium
    modes: ModeSet
    stats: dict = field(default_factory=dict)

    VARIABLES: ClassVar[dict] = {**Equilibrium.VARIABLES, **ModeSet.VARIABLES}

    @property
    def success(self) -> bool:
        """True when the statics and the modes both succeeded."""
        return bool(self.equilibrium.success and self.modes.success)

    @property
    def message(self) -> str:
        """Why not ("" on success): the messages of the failed parts, named."""
        parts = [f"{name}: {r.message}" for name, r in (("equilibrium", self.equilibrium), ("modes", self.modes))
                 if r.message]
        return "; ".join(parts)

    @property
    def scene(self):
        """The slack scene analysed (the equilibrium's)."""
        return self.equilibrium.scene

    def static_tensions(self) -> dict:
        """The equilibrium's element tensions, N (:meth:`Equilibrium.static_tensions`)."""
        return self.equilibrium.static_tensions()

    def __iter__(self):
        warnings.warn("unpacking slack.analyze(...) as (equilibrium, modes) is deprecated: use its "
                      ".equilibrium and .modes", DeprecationWarning, stacklevel=2)
        return iter((self.equilibrium, self.modes))

    def summary(self) -> dict:
        """Headline numbers: the equilibrium's (N, m) and the mode table (omega in rad/s).

        Returns
        -------
        dict
            JSON-able.
        """
        return {**super().summary(), "equilibrium": self.equilibrium.summary(), "modes": self.modes.table()}

    def to_xarray(self):
        """The equilibrium's and the modes' datasets merged (shared coordinate ``s`` on ``node``).

        Returns
        -------
        xarray.Dataset
        """
        import xarray as xr
        eq, md = self.equilibrium.to_xarray(), self.modes.to_xarray()
        for ds in (eq, md):
            ds.attrs.pop("stats", None), ds.attrs.pop("success", None), ds.attrs.pop("message", None)
        return xr.merge([eq, md], compat="no_conflicts", join="exact", combine_attrs="drop_conflicts")
