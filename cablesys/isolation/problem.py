"""The dual-isolation design problem (Wang 1971 p. 33): decision variables, bounds, sea, limits.

Wang: "this model is applicable to vibration isolation systems where the motion of the lower
body is minimized by the placement of an intermediate body along the cable as well as by
varying the spring constant of the cable itself" (a dual isolation system). The decision
variables are, per section i, the spring coefficient (AE)_i and the Voigt internal damping
C_I,i (eq. 46), and optionally the size of the intermediate body (its weight and virtual
masses scaled together). Everything is in SI and immutable; a scene TOML can carry it as a
``[design]`` table (:func:`settings_from_dict`).

Inside the NLP each variable is v = lo (hi/lo)^x with x in [0, 1]: the variables span one to
three decades, and log scaling gives IPOPT a well-conditioned problem; it also keeps every
value strictly positive (so C_I needs a lower bound > 0).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..errors import ParameterError, require_positive, require_range
from ..model.design_variables import Variable, bound_pairs, current_values, section_variables  # noqa: F401  (re-exported)
from ..reader import build, located

OBJECTIVES = ("significant", "rao_band")


@dataclasses.dataclass(frozen=True, kw_only=True)
class DesignSettings:
    """What to optimize, within which bounds, under which sea, subject to which limits.

    Per-section tuples are ordered from the top (section 1 hangs from the ship).
    """

    ae_bounds: tuple                        # ((lo, hi), ...) N, spring coefficient (AE)_r per section
    damping_bounds: tuple                   # ((lo, hi), ...) N s, internal damping C_I per section (eq. 46)
    intermediate_mass_bounds: tuple | None = None   # (lo, hi) kg: virtual heave mass of body 1 (scaled body)
    objective: str = "significant"          # or "rao_band"
    hs: float = 2.5                         # m, significant wave height (JONSWAP)
    tp: float = 8.0                         # s, peak period
    gamma: float = 3.3                      # JONSWAP peak enhancement
    omega_min: float = 0.25                 # rad/s, frequency grid of the spectral integrals
    omega_max: float = 3.0
    n_omega: int = 60
    band: tuple = (0.5, 1.5)                # rad/s, band of the "rao_band" objective
    strain_limit: tuple = (0.1, 0.1)        # static stretch u_0 / l_0 per section
    working_load: tuple = (2e4, 2e4)        # N, limit on mean + n_sigma std of the tension per section
    n_sigma: float = 3.0                    # slack: mean - n_sigma std > TENS; peak: mean + n_sigma std < WLL
    n_starts: int = 4
    outer_iterations: int = 6               # self-consistent drag linearization (see objective.py)
    outer_tol: float = 1e-3                 # relative change of the objective between outer iterations
    quadrature_log2: int = 7                # 2 x 2^k Sobol points of the Gaussian equivalent linearization
    equivalent_tol: float = 1e-3            # its self-consistency tolerance on the response std
    max_iter: int = 100                     # IPOPT iterations per solve
    tol: float = 1e-8                       # IPOPT tolerance

    def __post_init__(self):
        ae = bound_pairs("design.ae_bounds", self.ae_bounds)
        n = len(ae)
        object.__setattr__(self, "ae_bounds", ae)
        object.__setattr__(self, "damping_bounds", bound_pairs("design.damping_bounds", self.damping_bounds, n))
        if self.intermediate_mass_bounds is not None:
            (m,) = bound_pairs("design.intermediate_mass_bounds", (self.intermediate_mass_bounds,))
            object.__setattr__(self, "intermediate_mass_bounds", m)
        if self.objective not in OBJECTIVES:
            raise ParameterError("design.objective", self.objective, f"must be one of {OBJECTIVES}")
        require_positive("design.hs", self.hs, "m")
        require_positive("design.tp", self.tp, "s")
        require_range("design.gamma", self.gamma, 1.0, 7.0)
        require_positive("design.omega_min", self.omega_min, "rad/s")
        if not self.omega_max > self.omega_min:
            raise ParameterError("design.omega_max", self.omega_max, f"must exceed design.omega_min = {self.omega_min}")
        if not isinstance(self.n_omega, int) or not 8 <= self.n_omega <= 2000:
            raise ParameterError("design.n_omega", self.n_omega, "must be an integer in [8, 2000]")
        band = tuple(float(b) for b in self.band)
        if len(band) != 2 or not self.omega_min <= band[0] < band[1] <= self.omega_max:
            raise ParameterError("design.band", self.band, f"must be [lo, hi] inside [{self.omega_min}, {self.omega_max}] rad/s")
        object.__setattr__(self, "band", band)
        for name in ("strain_limit", "working_load"):
            v = tuple(float(a) for a in getattr(self, name))
            if len(v) != n:
                raise ParameterError(f"design.{name}", v, f"needs one value per section ({n})")
            for i, a in enumerate(v):
                require_positive(f"design.{name}[{i}]", a)
            object.__setattr__(self, name, v)
        require_positive("design.n_sigma", self.n_sigma)
        for name, lo, hi in (("n_starts", 1, 64), ("outer_iterations", 1, 50), ("max_iter", 1, 100000),
                             ("quadrature_log2", 4, 14)):
            v = getattr(self, name)
            if not isinstance(v, int) or not lo <= v <= hi:
                raise ParameterError(f"design.{name}", v, f"must be an integer in [{lo}, {hi}]")
        require_range("design.outer_tol", self.outer_tol, 1e-12, 1.0)
        require_range("design.equivalent_tol", self.equivalent_tol, 1e-8, 0.1)
        require_range("design.tol", self.tol, 1e-14, 1e-2)

    @property
    def n_sections(self) -> int:
        return len(self.ae_bounds)

    @property
    def omega(self) -> np.ndarray:
        return np.linspace(self.omega_min, self.omega_max, self.n_omega)

    def replace(self, **changes) -> "DesignSettings":
        return dataclasses.replace(self, **changes)


def settings_from_dict(table: dict, source=None) -> DesignSettings:
    """A :class:`DesignSettings` from a TOML ``[design]`` table (SI; keys as the field names).

    Parameters
    ----------
    table : dict
        The parsed ``[design]`` table; numbers must be numbers (never strings or booleans),
        bounds arrays of ``[lower, upper]`` pairs.
    source : cablesys.reader.SourceMap or str, optional
        Where the table came from; errors then name the file and line.

    Returns
    -------
    DesignSettings
        The validated settings.

    Raises
    ------
    ParameterError
        Naming ``design.<key>``, its value and the allowed range.
    """
    try:
        return build(DesignSettings, table, "design")
    except ParameterError as err:
        raise located(err, source) from None


def _toml_value(v) -> str:
    if isinstance(v, str):
        return f'"{v}"'
    if isinstance(v, (tuple, list)):
        return "[" + ", ".join(_toml_value(a) for a in v) + "]"
    return repr(v)


def settings_to_toml(settings: DesignSettings) -> str:
    """The ``[design]`` table of ``settings`` (read back by :func:`settings_from_dict`).

    Parameters
    ----------
    settings : DesignSettings
        The settings to write.

    Returns
    -------
    str
        TOML text of the ``[design]`` table.
    """
    lines = ["[design]"]
    for f in dataclasses.fields(settings):
        v = getattr(settings, f.name)
        if v is not None:
            lines.append(f"{f.name} = {_toml_value(v)}")
    return "\n".join(lines) + "\n"


def variables(scene, settings: DesignSettings) -> tuple:
    """The decision variables of ``settings`` for ``scene`` (whose structure must match).

    Parameters
    ----------
    scene : Scene
        The scene (its section count fixes the variables).
    settings : DesignSettings
        Bounds and which variables are free.

    Returns
    -------
    tuple of Variable
        Name, bounds and scaling of each decision variable (:func:`section_variables`).
    """
    return section_variables(scene, settings.ae_bounds, settings.damping_bounds, settings.intermediate_mass_bounds)


