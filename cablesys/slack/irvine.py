"""Closed forms of the Irvine–Caughey linear theory of a slack cable.

Everything here is a pure function of SI numbers, as summarized by
Griffin & Rosenthal (1985), sections 3-5 and 7 (equation numbers below are
theirs). The linear theory assumes a flat (parabolic) sag, s/l < 1/8.

Nomenclature: ``m`` mass per unit length (kg/m), ``g`` gravity (m/s^2),
``span`` the chord l (m), ``H`` the horizontal (chordwise) tension (N),
``EA`` the axial stiffness (N), ``Le`` the virtual length of eq. 5 (m).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from ..errors import ParameterError, require_nonnegative, require_positive
from .results import IrvineMode, IrvineModes

#: lambda^2 at the first crossover of the symmetric and antisymmetric modes
#: (eq. 6 with beta*l/2 = pi), Griffin & Rosenthal (1985) section 3.
LAMBDA2_CROSSOVER = 4.0 * math.pi ** 2

#: lambda^2 at the onset of catenary effects (5 % frequency shift), eq. 13.
LAMBDA2_CRIT = 1.26


def virtual_length(span: float, sag: float) -> float:
    """Virtual length Le = l (1 + 8 (d/l)^2), Griffin & Rosenthal (1985) eq. 5."""
    span = require_positive("span", span, "m")
    sag = require_nonnegative("sag", sag, "m")
    return span * (1.0 + 8.0 * (sag / span) ** 2)


def lambda_squared(*, m: float, g: float, span: float, H: float, EA: float,
                   Le: float | None = None) -> float:
    """Irvine's parameter lambda^2 = (m g l / H)^2 l / (H Le / EA).

    Griffin & Rosenthal (1985) eq. 4; ``Le`` defaults to the flat-sag virtual
    length of eq. 5 with the parabolic sag d = m g l^2 / (8 H).

    Parameters
    ----------
    m : float
        Mass per unit length (kg/m).
    g : float
        Gravity (m/s^2); m g is the weight per length (use the submerged weight in water).
    span : float
        Span l (m).
    H : float
        Horizontal tension (N).
    EA : float
        Axial stiffness (N).
    Le : float, optional
        Virtual length (m).

    Returns
    -------
    float
        lambda^2 (1).
    """
    m = require_positive("m", m, "kg/m")
    g = require_positive("g", g, "m/s^2")
    span = require_positive("span", span, "m")
    H = require_positive("H", H, "N")
    EA = require_positive("EA", EA, "N")
    if Le is None:
        Le = virtual_length(span, m * g * span ** 2 / (8.0 * H))
    Le = require_positive("Le", Le, "m")
    return (m * g * span / H) ** 2 * span / (H * Le / EA)


def _sym_residual(x: float, lam2: float) -> float:
    # eq. 6 multiplied by cos(x) so that it has no poles:
    #   sin x - (x - 4 x^3 / lambda^2) cos x = 0
    return math.sin(x) - (x - 4.0 * x ** 3 / lam2) * math.cos(x)


def symmetric_roots(lambda2: float, n: int) -> np.ndarray:
    """First ``n`` positive roots x = beta l / 2 of the symmetric-mode equation.

    tan x = x - (4 / lambda^2) x^3, Griffin & Rosenthal (1985) eq. 6.

    Bracketing (why no root can be skipped): on each branch
    ((k - 1/2) pi, (k + 1/2) pi) the difference tan x - x + 4 x^3 / lambda^2
    has derivative sec^2 x - 1 + 12 x^2 / lambda^2 > 0, so it rises
    monotonically from -inf to +inf and has exactly one root there; on
    (0, pi/2) it starts at 0 and rises, so it has none. The k-th root is
    therefore the single root of the pole-free residual
    sin x - (x - 4x^3/lambda^2) cos x on the k-th branch, found by brentq.
    lambda^2 = 0 gives the taut string x = (2k - 1) pi / 2 (eq. 9);
    lambda^2 = inf the inextensible cable tan x = x (eq. 11).
    """
    lam2 = float(lambda2)
    if not math.isinf(lam2):
        lam2 = require_nonnegative("lambda2", lambda2)
    elif lam2 < 0:
        raise ParameterError("lambda2", lambda2, "must be >= 0 (inf for an inextensible cable)")
    if int(n) != n or n < 1:
        raise ParameterError("n", n, "must be an integer >= 1")
    if lam2 == 0.0:
        return (2.0 * np.arange(1, n + 1) - 1.0) * math.pi / 2.0
    roots = np.empty(int(n))
    for k in range(1, int(n) + 1):
        a, b = (k - 0.5) * math.pi, (k + 0.5) * math.pi
        if math.isinf(lam2):
            f = lambda x: math.sin(x) - x * math.cos(x)  # noqa: E731  eq. 11
        else:
            f = lambda x, l2=lam2: _sym_residual(x, l2)  # noqa: E731
        roots[k - 1] = brentq(f, a, b, xtol=1e-14, rtol=1e-14)
    return roots


def string_omega(k: np.ndarray | int, *, span: float, H: float, m: float) -> np.ndarray:
    """Taut-string circular frequencies omega_k = k pi / l sqrt(H/m).

    Griffin & Rosenthal (1985) eq. 10 (f_n = n / 2l sqrt(T/m)); these are the
    out-of-plane modes (all k) and the in-plane antisymmetric modes (even k)
    of the flat-sag cable.
    """
    return np.asarray(k, dtype=float) * math.pi / span * math.sqrt(H / m)


def symmetric_omega(n: int, *, lambda2: float, span: float, H: float, m: float) -> np.ndarray:
    """Symmetric in-plane frequencies omega = (2 x / l) sqrt(H/m), eqs. 6-7."""
    x = symmetric_roots(lambda2, n)
    return 2.0 * x / span * math.sqrt(H / m)


def irvine_modes(n_modes: int, *, lambda2: float, span: float, H: float, m: float) -> IrvineModes:
    """The ``n_modes`` lowest modes of a horizontal flat-sag cable, ascending.

    Out-of-plane: string frequencies (k = 1, 2, ...); in-plane antisymmetric:
    even string frequencies (eq. 10); in-plane symmetric: eq. 6-7.

    Parameters
    ----------
    n_modes : int
        Number of modes (>= 1).
    lambda2 : float
        Irvine's parameter lambda^2 (eq. 4).
    span : float
        Span l (m).
    H : float
        Horizontal tension (N).
    m : float
        Mass per unit length, with the added mass in water (kg/m).

    Returns
    -------
    IrvineModes
        Ascending in omega (rad/s); iterating it gives one :class:`IrvineMode` per mode.
    """
    n = int(n_modes)
    if n < 1:
        raise ParameterError("n_modes", n_modes, "must be an integer >= 1")
    o = string_omega(np.arange(1, n + 1), span=span, H=H, m=m)
    a = string_omega(2 * np.arange(1, n + 1), span=span, H=H, m=m)
    s = symmetric_omega(n, lambda2=lambda2, span=span, H=H, m=m)
    modes = [IrvineMode(mode_type=t, omega=float(w))
             for t, ws in (("O", o), ("A", a), ("S", s)) for w in ws]
    modes.sort(key=lambda md: md.omega)
    return IrvineModes(mode_type=tuple(md.mode_type for md in modes[:n]),
                       omega=np.array([md.omega for md in modes[:n]]), lambda2=float(lambda2))


# --- onset of catenary effects (section 4) ---------------------------------

def lambda2_onset(n: int) -> float:
    """lambda_n^2 = 4 a^3 / (a - tan a), a = 0.525 n pi, n odd.

    Griffin & Rosenthal (1985) eq. 17b: the onset of slack effects in the
    n-th symmetric mode (n = 1 gives ~1.26, eq. 13).
    """
    if int(n) != n or n < 1 or n % 2 == 0:
        raise ParameterError("n", n, "must be an odd integer >= 1")
    a = 0.525 * n * math.pi
    return 4.0 * a ** 3 / (a - math.tan(a))


def critical_tension(*, weight: float, EA: float, lambda2: float = LAMBDA2_CRIT) -> float:
    """H_crit = (W^2 EA / lambda^2)^(1/3) with Le = l.

    Griffin & Rosenthal (1985) eqs. 12 and 17a; with lambda^2 = 1.26 this is
    H_crit = 0.93 (W^2 EA)^(1/3) (eq. 15). ``weight`` W = m g l (N).
    """
    W = require_positive("weight", weight, "N")
    EA = require_positive("EA", EA, "N")
    lam2 = require_positive("lambda2", lambda2)
    return (W ** 2 * EA / lam2) ** (1.0 / 3.0)


def critical_sag(*, weight: float, EA: float, span: float, lambda2: float = LAMBDA2_CRIT) -> float:
    """s_crit = W l / (8 H_crit) = 0.134 (W/EA)^(1/3) l, eq. 16 (from eq. 18, theta = 0)."""
    span = require_positive("span", span, "m")
    return weight * span / (8.0 * critical_tension(weight=weight, EA=EA, lambda2=lambda2))


# --- inclined cable (section 5) --------------------------------------------

def lambda_squared_inclined(*, m: float, g: float, chord: float, theta: float,
                            H1: float, EA: float, Le1: float | None = None) -> float:
    """lambda_1^2 = (m g l1 cos(theta) / H1)^2 l1 / (H1 Le1 / EA).

    Griffin & Rosenthal (1985) eq. 22 (Irvine 1978): the horizontal theory in
    chord axes with the transverse load m g cos(theta) per unit chord length,
    chord tension H1 = H / cos(theta) and chord l1 = l / cos(theta).
    ``theta`` in radians; Le1 defaults to l1 as in eq. 23.
    """
    theta = float(theta)
    if not (-math.pi / 2 < theta < math.pi / 2):
        raise ParameterError("theta", theta, "must be in (-pi/2, pi/2) rad")
    chord = require_positive("chord", chord, "m")
    Le1 = chord if Le1 is None else require_positive("Le1", Le1, "m")
    return lambda_squared(m=m * math.cos(theta), g=g, span=chord, H=H1, EA=EA, Le=Le1)


def critical_chord_tension(*, weight: float, EA: float, theta: float,
                           lambda2: float = LAMBDA2_CRIT) -> float:
    """H1 = (W1^2 EA cos^2(theta) / lambda_1^2)^(1/3) = 0.93 cos^(2/3) theta (W1^2 EA)^(1/3).

    Griffin & Rosenthal (1985) eqs. 23a and 24; W1 = m g l1.
    """
    return critical_tension(weight=weight * abs(math.cos(theta)), EA=EA, lambda2=lambda2)


def chordwise_tension_increment(*, m: float, g: float, span: float, theta: float) -> float:
    """Delta H = m g l sin(theta), eq. 19: change of chord tension end to end."""
    return m * g * span * math.sin(theta)


def inclined_validity(*, sag: float, span: float, theta: float) -> float:
    """epsilon = 8 s tan(theta) / l, eq. 20; the flat-sag theory needs it << 1."""
    return 8.0 * sag * math.tan(theta) / span


# --- added mass in water (section 7) ---------------------------------------

def virtual_mass_ratio(*, added_mass_factor: float, specific_gravity: float) -> float:
    """m_W / m_A = 1 + C_am / S, Griffin & Rosenthal (1985) eq. 26."""
    c = require_nonnegative("added_mass_factor", added_mass_factor)
    S = require_positive("specific_gravity", specific_gravity)
    return 1.0 + c / S


def omega_in_water(omega_air: float, *, added_mass_factor: float, specific_gravity: float) -> float:
    """omega_W = omega_A / sqrt(m_W / m_A) for transverse modes, eq. 27."""
    return omega_air / math.sqrt(virtual_mass_ratio(
        added_mass_factor=added_mass_factor, specific_gravity=specific_gravity))


def added_mass_factor(*, omega_air: float, omega_water: float, specific_gravity: float) -> float:
    """C_am = S ((omega_A / omega_W)^2 - 1), Griffin & Rosenthal (1985) eq. 28.

    Derived from eqs. 26-27 (the OCR of eq. 28 drops the bracket).
    """
    wa = require_positive("omega_air", omega_air, "rad/s")
    ww = require_positive("omega_water", omega_water, "rad/s")
    S = require_positive("specific_gravity", specific_gravity)
    return S * ((wa / ww) ** 2 - 1.0)
