r"""The Kennedy & Strahan (1981) transverse equation of a towed cable, nondimensionalized.

Derivation (checked against the dimensional physics; the OCR of eq. 1 is garbled)
-------------------------------------------------------------------------------
A neutrally buoyant cable of diameter ``d_c`` and length ``L`` lies along the flow
(``x`` from the tow point, increasing downstream, fluid speed ``U`` along ``+x``);
``y(x, t)`` is its small cross-track displacement.  Per unit length:

* cable mass ``m`` and added (displaced-fluid) mass ``M = rho pi d_c^2 / 4``;
* the fluid-inertia (Paidoussis 1966) terms of a slender body in axial flow,
  ``M (d/dt + U d/dx)^2 y = M (y_tt + 2 U y_xt + U^2 y_xx)``;
* tension ``T(x)`` carried by tangential friction, ``F_t = (rho/2) pi d_c c_t U^2``
  per unit length (Kennedy & Strahan (1981) eq. 1b with the ``pi`` convention
  implied by eq. 1c, ``c_T = 4 c_t``), accumulated from the free end, plus a
  constant drogue drag ``T_d = 2 c_t' M U^2`` (the drogue term ``c_t'``):
  ``T(x) = 2 M U^2 [c_t (L - x)/d_c + c_t']``, falling linearly to the drogue;
* the linearized (Taylor/Paidoussis) normal drag on the relative cross-flow
  ``y_t + U y_x``: ``F_n = (rho/2) d_c c_n U (y_t + U y_x)``.

Momentum (Kennedy & Strahan (1981) eq. 1, flexural rigidity dropped)::

    (M+m) y_tt + 2 M U y_xt + M U^2 y_xx - d/dx (T y_x) + (rho/2) d_c c_n U (y_t + U y_x) = 0 .

With ``xi = x/L``, ``tau = U t/L``, ``eps = L/d_c``, ``beta = M/(M+m)``, dividing by
``(M+m) U^2 / L^2`` and using ``M U^2 / d_c = (rho/2)(pi/2) d_c U^2``:

* ``y_xx``: ``beta [1 - T/(M U^2)] = beta (1 - 2 c_t eps - 2 c_t') + 2 beta c_t eps xi = a + b xi``;
* ``y_x`` from ``-T' y_x``: ``2 beta c_t eps``; from the normal drag ``(2/pi) beta c_n eps``;
  together ``c = 2 (c_t + c_n/pi) eps beta``;
* ``y_t`` from the normal drag: ``d = (2/pi) beta c_n eps``.

So (Kennedy & Strahan (1981) eq. 3, the reading given in issue 6 confirmed)::

    eta_tt + 2 beta eta_xt + (a + b xi) eta_xx + c eta_x + d eta_t = 0,
    a = beta (1 - 2 c_t eps - 2 c_t'),  b = 2 beta c_t eps,
    c = 2 (c_t + c_n/pi) eps beta = b + d,  d = (2/pi) beta c_n eps .

``a + b xi < 0`` where tension exceeds the fluid-inertia term (hyperbolic); it
vanishes at ``xi* = -a/b = 1 + (2 c_t' - 1)/(2 c_t eps)``, the free end of the
"lengthened cable" ``L* = L + d_c c_t'/c_t`` that replaces the drogue (report p. 10).

With ``eta = v(xi) exp(i omega tau)`` (eq. 4) the ODE is::

    (a + b xi) v'' + (c + 2 i beta omega) v' + (i omega d - omega^2) v = 0,

and with ``z^2 = a + b xi`` it is Bessel's equation of eq. 5 with
``alpha = (2/b)(c + 2 i omega beta) - 1`` and ``b_o^2 = (4 omega/b^2)(i d - omega)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError, require_nonnegative, require_positive, require_range
from ..scene.fields import quantity, spec

__all__ = ["TowedCable", "Coefficients", "REPORT_SEA_TRIAL", "REPORT_TYPICAL", "added_fluid_mass", "theory_coefficients"]


@dataclass(frozen=True, kw_only=True)
class Coefficients:
    """Nondimensional coefficients of Kennedy & Strahan (1981) eq. 3 (SI-free).

    ``a`` and ``b`` multiply ``eta_xx`` (``a + b xi``), ``c`` multiplies ``eta_x``,
    ``d`` multiplies ``eta_t``; ``beta`` = M/(M+m).
    """

    a: float
    b: float
    c: float
    d: float
    beta: float

    def __post_init__(self):
        for name in ("a", "c", "d"):
            v = getattr(self, name)
            if not math.isfinite(v):
                raise ParameterError(f"coefficients.{name}", v, "must be finite")
        require_positive("coefficients.b", self.b)
        require_nonnegative("coefficients.d", self.d)
        require_range("coefficients.beta", self.beta, 0.0, 1.0, lo_open=True)

    @property
    def p(self) -> float:
        """Real Bessel order of the report, ``p = c/b - 1 = c_n/(pi c_t)`` (eq. 8c)."""
        return self.c / self.b - 1.0

    @property
    def xi_turn(self) -> float:
        """Zero-tension point ``xi* = -a/b`` where ``a + b xi = 0``."""
        return -self.a / self.b

    def q(self, omega):
        """``q = 1 - nu = (c + 2 i beta omega)/b``: parameter of the regular 0F1 solution.

        nu is the exact complex Bessel order of Kennedy & Strahan (1981) eq. 8a.
        """
        return (self.c + 2j * self.beta * np.asarray(omega)) / self.b

    def nu(self, omega):
        """Exact complex order ``nu = 1 - (c + 2 i beta omega)/b`` (eq. 8a)."""
        return 1.0 - self.q(omega)

    def order_ratio(self, omega):
        """``|Im nu| / |Re nu| = 2 beta omega / (b p)``: the eq. 8b smallness measure.

        The report replaces ``nu`` by ``-p`` (eq. 8b/8c); this ratio must be << 1.
        """
        return 2.0 * self.beta * np.abs(np.asarray(omega, dtype=float)) / (self.b * abs(self.p))

    def x_arg(self, xi, omega):
        """Argument ``x = -b_o^2 z^2 / 4 = (omega^2 - i omega d)(a + b xi)/b^2`` of 0F1."""
        xi = np.asarray(xi, dtype=float)
        omega = np.asarray(omega, dtype=float)
        return (omega**2 - 1j * omega * self.d) * (self.a + self.b * xi) / self.b**2


@dataclass(frozen=True, kw_only=True)
class TowedCable:
    """A towed cable and its tow, SI (Kennedy & Strahan (1981) eq. 1-3 symbols).

    length (m) L, speed (m/s) U, diameter (m) d_c, c_t tangential drag,
    c_n linearized normal drag (use the effective c_n* = A c_n, eq. 39, for a
    depressed cable), c_t_drogue the drogue term c_t', beta = M/(M+m).
    """

    # unit (dimension) and the report's symbol of every field, as the Wang scene's fields carry them;
    # length and diameter are the shared quantities of cablesys.scene.fields.QUANTITIES.
    # c_t and c_n keep the report's names because they are other numbers than Wang's coefficients:
    # c_t is referred to pi d_c (F_t = rho/2 pi d_c c_t U^2), Wang's ct_tangential to d (eq. 44), so
    # c_t = ct_tangential / pi (see :attr:`ct_tangential`); c_n is the effective coefficient c_n* = A C_n
    # of the drag linear in the cross-flow (F_n = rho/2 d_c c_n U v_n, eq. 39), Wang's quadratic
    # cd_normal only for a level cable (A = 1). A cable given by C_t, C_n and its drogue's drag area is
    # converted by :func:`theory_coefficients` (or read as a :class:`cablesys.towed.TowedScene`).
    length: float = quantity("length", "cable length L")
    speed: float = spec("velocity", "tow speed U", symbol="U")
    diameter: float = quantity("diameter", "cable diameter d_c", 0.016)
    c_t: float = spec("none", "tangential drag coefficient c_t, referred to pi d_c (= Wang's C_t / pi)", 0.0101,
                      symbol="c_t")
    c_n: float = spec("none", "linearized normal drag coefficient c_n (effective c_n* = A c_n for a depressed "
                      "cable, eq. 39)", 0.16, symbol="c_n")
    c_t_drogue: float = spec("none", "drogue term c_t' (drogue drag 2 c_t' M U^2)", 228.0, symbol="c_t'")
    beta: float = spec("none", "mass ratio beta = M / (M + m): fluid mass M = rho pi d_c^2 / 4 over fluid plus "
                       "cable mass per length", 0.5, symbol="beta")

    def __post_init__(self):
        require_positive("length", self.length, "m")
        require_positive("speed", self.speed, "m/s")
        require_positive("diameter", self.diameter, "m")
        require_positive("c_t", self.c_t)
        require_positive("c_n", self.c_n)
        require_nonnegative("c_t_drogue", self.c_t_drogue)
        require_range("beta", self.beta, 0.0, 1.0, lo_open=True)

    @property
    def ct_tangential(self) -> float:
        """The tangential coefficient in the Wang scene's convention, ``C_t = pi c_t`` (referred to d, eq. 44)."""
        return math.pi * self.c_t

    @property
    def eps(self) -> float:
        """Slenderness ``eps = L/d_c`` (eq. 2)."""
        return self.length / self.diameter

    @property
    def drag_term(self) -> float:
        """``D = 2 c_t eps + 2 c_t'`` (eq. 20a), total tension / (M U^2) at the tow point."""
        return 2.0 * self.c_t * self.eps + 2.0 * self.c_t_drogue

    def coefficients(self) -> Coefficients:
        """Kennedy & Strahan (1981) eq. 3 coefficients."""
        e, bt = self.eps, self.beta
        return Coefficients(
            a=bt * (1.0 - 2.0 * self.c_t * e - 2.0 * self.c_t_drogue),
            b=2.0 * bt * self.c_t * e,
            c=2.0 * (self.c_t + self.c_n / math.pi) * e * bt,
            d=(2.0 / math.pi) * bt * self.c_n * e,
            beta=bt,
        )

    def omega(self, frequency_hz):
        """Nondimensional angular frequency ``omega = 2 pi f L / U`` (eq. 2, tau = U t/L)."""
        f = np.asarray(frequency_hz, dtype=float)
        return 2.0 * math.pi * f * self.length / self.speed

    def time_scale(self) -> float:
        """``L/U`` (s): one unit of nondimensional time tau."""
        return self.length / self.speed


def added_fluid_mass(density: float, diameter: float) -> float:
    """Displaced fluid mass per unit length ``M = rho pi d_c^2 / 4`` (kg/m), Kennedy & Strahan (1981) eq. 1-2."""
    return density * math.pi * diameter**2 / 4.0


def theory_coefficients(*, diameter: float, mass_per_length: float, ct_tangential: float, cd_normal: float,
                        density: float = 1025.0, amplification: float = 1.0,
                        drogue_drag_area: float = 0.0) -> dict:
    """The theory's ``c_t``, ``c_n``, ``c_t_drogue`` (c_t') and ``beta`` from a cable in the Wang scene's terms.

    The one place the conversion is written (Kennedy & Strahan (1981); Wang (1971) for C_t, C_n):

    * ``c_t = C_t / pi``: the report's tangential friction ``F_t = (rho/2) pi d_c c_t U^2`` (eq. 1b,
      referred to the circumference) equals Wang's ``(rho/2) C_t d U^2`` (eq. 44, referred to d);
    * ``c_n = A C_n``: the report's normal force ``R |U_N/U|^2`` with ``R = (rho/2) c_n d_c U^2``
      (eq. 33-35) is Wang's quadratic normal drag with ``C_n = c_n`` (eq. 42, referred to d); the
      linear theory takes the effective ``c_n* = A c_n`` of eq. 39, ``A`` from eq. 38 (1 for a level
      cable; :func:`cablesys.towed.amplification`, :func:`cablesys.towed.effective_amplification`);
    * ``c_t' = (C_D A)_drogue / (pi d_c^2)``: the drogue's drag ``(rho/2) (C_D A)_drogue U^2`` is the
      report's end tension ``T(L) = 2 c_t' M U^2`` (eq. 1-3, tension ``T(x) = 2 M U^2 [c_t (L - x)/d_c
      + c_t']``) with ``M = rho pi d_c^2 / 4``; the "lengthened cable" of p. 10 adds ``d_c c_t'/c_t``;
    * ``beta = M / (M + m)`` (eq. 2).

    Parameters
    ----------
    diameter : float
        Cable diameter d_c (m).
    mass_per_length : float
        Cable mass per unit length in air m (kg/m).
    ct_tangential : float
        Tangential friction coefficient C_t, referred to d (Wang 1971 eq. 44).
    cd_normal : float
        Quadratic normal drag coefficient C_n, referred to d (Wang 1971 eq. 42).
    density : float, optional
        Fluid density rho (kg/m^3).
    amplification : float, optional
        A of eq. 38-39 (c_n* = A c_n); 1 for a level cable.
    drogue_drag_area : float, optional
        Drag area (C_D A) of the drogue (m^2); 0 for none.

    Returns
    -------
    dict
        ``{"c_t", "c_n", "c_t_drogue", "beta"}``, the keyword arguments of :class:`TowedCable`
        other than length, speed and diameter.
    """
    require_positive("diameter", diameter, "m")
    require_positive("mass_per_length", mass_per_length, "kg/m")
    require_positive("ct_tangential", ct_tangential)
    require_positive("cd_normal", cd_normal)
    require_positive("density", density, "kg/m^3")
    require_positive("amplification", amplification)
    require_nonnegative("drogue_drag_area", drogue_drag_area, "m^2")
    M = added_fluid_mass(density, diameter)
    return {"c_t": ct_tangential / math.pi, "c_n": amplification * cd_normal,
            "c_t_drogue": drogue_drag_area / (math.pi * diameter**2), "beta": M / (M + mass_per_length)}


# Report's sea-trial coefficients (Kennedy & Strahan (1981) p. 31): c_n* = 0.16,
# c_t = 0.0101, beta = 0.5, d_c = 16 mm, c_t' = 228; L and U vary per run.
REPORT_SEA_TRIAL = dict(diameter=0.016, c_t=0.0101, c_n=0.16, c_t_drogue=228.0, beta=0.5)

# Report's "typical values" for the damping time (p. 17): c_t = .0025, c_n = .07,
# c_t' = 57, eps = 75000, d_c = .01 m, U = 3 m/s  ->  L = eps d_c = 750 m.
REPORT_TYPICAL = dict(length=750.0, speed=3.0, diameter=0.01, c_t=0.0025, c_n=0.07,
                      c_t_drogue=57.0, beta=0.5)
