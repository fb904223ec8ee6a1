"""An irregular sea at the top: a wave spectrum, a vessel (crane-tip) motion RAO, and its realisation.

The sea is realised as a sum of sinusoids so the top motion stays on the fast compiled
(SX) path of :mod:`cablesys.model.top_motion`: at scene-build time the spectrum becomes
``n_components`` entries of ``top_motion.x`` / ``top_motion.y`` (and, when asked, of
``environment.waves``, the deep-water particle velocities of Wang 1971 eq. 26-28).

Conventions (stated once, used by ``rao``, the statistics and the tests):

* wave elevation at the vessel (z up): eta(t) = sum_k a_k sin(omega_k t + eps_k),
  a_k = sqrt(2 S(omega_k) d_omega) on equal bins over the band, omega_k uniform within its bin
  (deterministic amplitudes; phases eps_k ~ U(0, 2 pi) and omega_k from ``numpy.random.default_rng(seed)``);
* a motion RAO R_j(omega) = |R_j| e^{i theta_j} (amplitude per unit wave amplitude, phase
  *lead* theta_j in degrees over the wave elevation at the vessel) gives the motion
  sum_k |R_j(omega_k)| a_k sin(omega_k t + eps_k + theta_j(omega_k));
* surge (+ in the wave direction) is x_s (+ to the right); heave is + up, so y_s = -heave
  (cablesys' y is + down: the heave term is written with amplitude |R| a and phase + pi);
* waves at the cable travel in +x (Wang 1971 eq. 26: argument n x - sigma t + phase); component k
  gets amplitude a_k, length 2 pi g / omega_k^2 and phase pi - eps_k, so that its elevation
  a_k sin(n x - sigma t + phase) equals a_k sin(omega_k t + eps_k) at x = 0.
"""

from __future__ import annotations

import csv
import dataclasses
import io
import math

import numpy as np

from ..errors import (
    ParameterError,
    require_finite,
    require_nonnegative,
    require_positive,
    require_range,
)
from .fields import spec
from .harmonics import Sinusoid, Wave

SPECTRA = ("jonswap", "pierson-moskowitz")
MAX_SPREADING_N = 100.0     # cos^100 spreads +- 13 deg (2 sigma): sharper is a long-crested sea


@dataclasses.dataclass(frozen=True, kw_only=True)
class SeaSpectrum:
    """A JONSWAP or Pierson-Moskowitz sea (one-sided S(omega), DNV-RP-C205 sec. 3.5.5)."""

    kind: str = spec("none", f"spectrum: one of {SPECTRA}", "jonswap")
    hs: float = spec("length", "significant wave height H_s = 4 sqrt(m0)")
    tp: float = spec("time", "peak period T_p")
    gamma: float = spec("none", "JONSWAP peak-enhancement factor (1..7; ignored for pierson-moskowitz)", 3.3)
    heading_deg: float = spec("angle_deg", "direction the waves travel, deg from +x towards +z (a [top_motion.rao] table is "
                                           "for this heading, a [top_motion.vessel] table is read at heading - "
                                           "vessel_heading_deg; waves_at_cable off +x make the scene 3-D)", 0.0)
    seed: int = spec("none", "seed of the random phases (same seed, same sea)", 0)
    n_components: int = spec("none", "number of sinusoids (equal frequency bins)", 100)
    omega_min: float = spec("frequency", "lower end of the band; 0: where 0.1 % of the energy lies below", 0.0)
    omega_max: float = spec("frequency", "upper end of the band; 0: where 0.1 % of the energy lies above", 0.0)
    waves_at_cable: bool = spec("none", "also add the sea's particle velocities at the cable (Wang 1971 eq. 26-28)", False)
    spreading_n: float = spec("none", "directional spreading D(theta) ~ cos^n(theta - heading_deg) within 90 deg of the "
                                      "heading (DNV-RP-C205 sec. 3.5.8; 2-4 for a wind sea), each component travelling "
                                      "its own direction drawn from D; 0: long-crested", 0.0)

    def __post_init__(self):
        if self.kind not in SPECTRA:
            raise ParameterError("top_motion.spectrum.kind", self.kind, f"must be one of {SPECTRA}")
        require_positive("top_motion.spectrum.hs", self.hs, "m")
        require_positive("top_motion.spectrum.tp", self.tp, "s")
        require_range("top_motion.spectrum.gamma", self.gamma, 1.0, 7.0)
        require_finite("top_motion.spectrum.heading_deg", self.heading_deg)
        for name in ("seed", "n_components"):
            v = getattr(self, name)
            if not isinstance(v, int) or isinstance(v, bool) or v < 0:
                raise ParameterError(f"top_motion.spectrum.{name}", v, "must be an integer >= 0")
        if not 2 <= self.n_components <= 5000:
            raise ParameterError("top_motion.spectrum.n_components", self.n_components, "must be in [2, 5000]")
        require_nonnegative("top_motion.spectrum.omega_min", self.omega_min, "rad/s")
        require_nonnegative("top_motion.spectrum.omega_max", self.omega_max, "rad/s")
        if self.omega_min and self.omega_max and not self.omega_max > self.omega_min:
            raise ParameterError("top_motion.spectrum.omega_max", self.omega_max,
                                 f"must be > omega_min = {self.omega_min} rad/s")
        if not isinstance(self.waves_at_cable, bool):
            raise ParameterError("top_motion.spectrum.waves_at_cable", self.waves_at_cable, "must be true or false")
        require_range("top_motion.spectrum.spreading_n", self.spreading_n, 0.0, MAX_SPREADING_N)

    @property
    def omega_peak(self) -> float:
        """omega_p = 2 pi / T_p (rad/s)."""
        return 2 * math.pi / self.tp

    def density(self, omega) -> np.ndarray:
        """S(omega) in m^2 s/rad (:mod:`cablesys.scene.spectra`)."""
        from .spectra import jonswap, pierson_moskowitz
        if self.kind == "pierson-moskowitz":
            return pierson_moskowitz(omega, self.hs, self.tp)
        return jonswap(omega, self.hs, self.tp, self.gamma)

    def band(self) -> tuple[float, float]:
        """(omega_min, omega_max): given, or the 0.1 % and 99.9 % points of the cumulative energy."""
        wp = self.omega_peak
        w = np.linspace(0.2 * wp, 8.0 * wp, 8001)
        cum = np.concatenate([[0.0], np.cumsum(0.5 * (self.density(w)[1:] + self.density(w)[:-1]) * np.diff(w))])
        cum /= cum[-1]
        lo = self.omega_min or float(np.interp(1e-3, cum, w))
        hi = self.omega_max or float(np.interp(1 - 1e-3, cum, w))
        if not hi > lo:
            raise ParameterError("top_motion.spectrum.omega_max", hi, f"must be > omega_min = {lo} rad/s")
        return lo, hi

    def components(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(omega_k, a_k, eps_k): a random frequency in each of the equal bins dw (so the sum does not
        repeat after 2 pi / dw), amplitudes sqrt(2 S(omega_k) dw), random phases (rad)."""
        lo, hi = self.band()
        n = self.n_components
        dw = (hi - lo) / n
        rng = np.random.default_rng(self.seed)
        eps = rng.uniform(0.0, 2 * math.pi, n)
        omega = lo + dw * (np.arange(n) + rng.uniform(0.0, 1.0, n))    # one random frequency per bin:
        amp = np.sqrt(2.0 * self.density(omega) * dw)                     # no repetition period 2 pi / dw
        return omega, amp, eps

    @property
    def long_crested(self) -> bool:
        """True without directional spreading (every component travels ``heading_deg``)."""
        return self.spreading_n == 0.0

    def spreading(self, theta_deg) -> np.ndarray:
        """D(theta) (1/rad) of the cos^n spreading about ``heading_deg`` (DNV-RP-C205 sec. 3.5.8, eq. 3.5.8.4):
        Gamma(1 + n/2) / (sqrt(pi) Gamma(1/2 + n/2)) cos^n(theta - theta_p) for |theta - theta_p| <= 90 deg, else 0;
        its integral over theta is 1."""
        n = self.spreading_n
        d = np.radians(np.asarray(theta_deg, float) - self.heading_deg)
        d = (d + math.pi) % (2 * math.pi) - math.pi
        c = math.exp(math.lgamma(1 + n / 2) - math.lgamma(0.5 + n / 2)) / math.sqrt(math.pi)
        return np.where(np.abs(d) <= 0.5 * math.pi, c * np.clip(np.cos(d), 0.0, None) ** n, 0.0)

    def direction_quadrature(self, m: int = 64) -> tuple[np.ndarray, np.ndarray]:
        """(theta_j in deg, w_j summing to 1): Gauss-Legendre nodes over heading +- 90 deg weighted by
        :func:`spreading`, for the linear response of a spread sea (sum_j w_j |H(omega, theta_j)|^2); the long-crested
        sea: the heading alone, weight 1."""
        if self.long_crested:
            return np.array([self.heading_deg]), np.array([1.0])
        x, w = np.polynomial.legendre.leggauss(m)
        theta = self.heading_deg + 90.0 * x
        wt = w * self.spreading(theta) * 0.5 * math.pi
        return theta, wt / wt.sum()

    def directions(self) -> np.ndarray:
        """The direction (deg from +x towards +z) each component of :meth:`components` travels: ``heading_deg`` for
        a long-crested sea; drawn from :meth:`spreading` by inverse transform sampling of its cumulative on a fine
        grid (one direction per frequency component, so the realised sea keeps its spectrum and its components stay
        uncorrelated: Jefferys, "Simulation of wave power spectra", Appl. Ocean Res. 9, 1987), from a random stream
        of its own (``seed``), so that spreading leaves the frequencies and phases as they were."""
        n = self.n_components
        if self.long_crested:
            return np.full(n, float(self.heading_deg))
        grid = self.heading_deg + np.linspace(-90.0, 90.0, 4001)
        dens = self.spreading(grid)
        cum = np.concatenate([[0.0], np.cumsum(0.5 * (dens[1:] + dens[:-1]) * np.diff(grid))])
        u = np.random.default_rng([self.seed, 1]).uniform(0.0, 1.0, n)
        return np.interp(u * cum[-1], cum, grid)

    def elevation(self, t) -> np.ndarray:
        """eta(t) at the vessel (m, z up) of this realisation."""
        w, a, e = self.components()
        t = np.asarray(t, float)
        return np.sum(a[:, None] * np.sin(w[:, None] * t.ravel()[None, :] + e[:, None]), axis=0).reshape(t.shape)


@dataclasses.dataclass(frozen=True, kw_only=True)
class MotionRAO:
    """Vessel or crane-tip motion per unit wave amplitude, per frequency (linear interpolation,
    end values held outside the table). Inline arrays or ``file``: a CSV with header
    ``omega,surge_amplitude,surge_phase_deg,heave_amplitude,heave_phase_deg`` (read at load time
    and kept inline, so a dumped scene reproduces the run)."""

    omega: tuple = spec("frequency", "table frequencies, strictly increasing", ())
    surge_amplitude: tuple = spec("none", "surge amplitude per unit wave amplitude [m/m]", ())
    surge_phase_deg: tuple = spec("none", "surge phase lead over the wave elevation [deg]", ())
    heave_amplitude: tuple = spec("none", "heave (+ up) amplitude per unit wave amplitude [m/m]", ())
    heave_phase_deg: tuple = spec("none", "heave phase lead over the wave elevation [deg]", ())
    file: str = spec("none", "CSV file with the table instead of the arrays (path relative to the working directory)", "")

    _COLUMNS = ("omega", "surge_amplitude", "surge_phase_deg", "heave_amplitude", "heave_phase_deg")

    def __post_init__(self):
        if self.file:
            if self.omega:
                raise ParameterError("top_motion.rao.file", self.file, "give either the file or the inline arrays")
            for k, v in _read_rao_csv(self.file).items():
                object.__setattr__(self, k, v)
            object.__setattr__(self, "file", "")
        w = tuple(float(v) for v in self.omega)
        if len(w) < 1:
            raise ParameterError("top_motion.rao.omega", self.omega, "needs at least one frequency")
        for i in range(len(w)):
            require_positive(f"top_motion.rao.omega[{i}]", w[i], "rad/s")
            if i and not w[i] > w[i - 1]:
                raise ParameterError("top_motion.rao.omega", w, f"must be strictly increasing (entry {i})")
        object.__setattr__(self, "omega", w)
        for name in self._COLUMNS[1:]:
            v = tuple(float(x) for x in getattr(self, name))
            if not v:
                v = (0.0,) * len(w)
            if len(v) != len(w):
                raise ParameterError(f"top_motion.rao.{name}", f"{len(v)} values", f"needs one per frequency ({len(w)})")
            for i, x in enumerate(v):
                require_finite(f"top_motion.rao.{name}[{i}]", x)
                if name.endswith("amplitude"):
                    require_nonnegative(f"top_motion.rao.{name}[{i}]", x)
            object.__setattr__(self, name, v)

    def __call__(self, dof: str, omega) -> np.ndarray:
        """Complex RAO |R| e^{i theta} of ``dof`` ('surge' or 'heave') at ``omega``."""
        amp, ph = interpolate_rao(self.omega, getattr(self, f"{dof}_amplitude"),
                                  np.radians(getattr(self, f"{dof}_phase_deg")), omega)
        return amp * np.exp(1j * ph)


def interpolate_rao(table_omega, amplitude, phase_rad, omega):
    """(|R|, theta): a table's amplitude and unwrapped phase (rad) interpolated linearly at ``omega`` (end values
    held); the RAO is |R| e^{i theta}."""
    return np.interp(omega, table_omega, amplitude), np.interp(omega, table_omega, np.unwrap(phase_rad))


def read_csv_rows(path, field: str) -> list[dict]:
    """The rows of a CSV table file (UTF-8, BOM accepted) as dicts; errors name ``field``."""
    from ..reader import read_text  # UTF-8 (BOM accepted), named decode errors
    try:
        return list(csv.DictReader(io.StringIO(read_text(path, field), newline="")))
    except csv.Error as err:
        raise ParameterError(field, str(path), f"cannot be parsed as CSV ({err})") from None


def _read_rao_csv(path) -> dict:
    rows = read_csv_rows(path, "top_motion.rao.file")
    cols = MotionRAO._COLUMNS
    if not rows or any(c not in rows[0] for c in ("omega", "heave_amplitude")):
        raise ParameterError("top_motion.rao.file", str(path), f"needs a header with columns {', '.join(cols)}")
    try:
        return {c: tuple(float(r[c]) for r in rows) for c in cols if c in rows[0]}
    except (TypeError, ValueError):
        raise ParameterError("top_motion.rao.file", str(path), "every table entry must be a number") from None


HEAVE_ONLY = None   # no RAO table: the top heaves with the surface (|R_heave| = 1, phase 0), no surge


def top_transfer(rao, omega, wave_heading_deg: float = 0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Complex amplitudes (X_s, Y_s, Z_s) of the top motion per unit wave amplitude, in cablesys axes
    (x + right, y + down, z sway), relative to the wave elevation eta = Re(-i e^{i omega t}) = sin(omega t).

    ``rao`` is None (the top heaves with the surface), a :class:`MotionRAO` (surge and heave in the
    plane, Z_s = 0) or a :class:`cablesys.scene.vessel.VesselRAO` (a 6-DOF vessel RAO at a lever arm,
    for waves travelling ``wave_heading_deg`` from +x). Returns the multipliers of eta's complex
    amplitude: x_s = Re(X_s eta_c e^{iwt}), likewise y_s and z_s."""
    omega = np.asarray(omega, float)
    if rao is None:
        return np.zeros(omega.shape, complex), -np.ones(omega.shape, complex), np.zeros(omega.shape, complex)
    if isinstance(rao, MotionRAO):
        return rao("surge", omega), -rao("heave", omega), np.zeros(omega.shape, complex)
    return rao.transfer(omega, wave_heading_deg)


def sea_sinusoids(spectrum: SeaSpectrum, rao) -> tuple[tuple, tuple, tuple]:
    """(x, y, z sinusoids) of the top motion realising ``spectrum`` through ``rao`` (see
    :func:`top_transfer`), each component through the RAO at its own direction in a spread sea
    (:meth:`SeaSpectrum.directions`); an axis the motion does not reach has no terms."""
    if not spectrum.long_crested and isinstance(rao, MotionRAO):
        raise ParameterError("top_motion.spectrum.spreading_n", spectrum.spreading_n,
                             "must be 0 with a [top_motion.rao] table, which holds surge and heave for one heading: "
                             "a spread sea needs [top_motion.vessel] (its tables per heading)")
    return realise(spectrum, lambda w, heading: top_transfer(rao, w, heading))


def rotation_sinusoids(spectrum: SeaSpectrum, vessel) -> tuple[tuple, tuple, tuple]:
    """(x, y, z sinusoids) of a vessel's small rotation about cablesys' axes (rad) realising ``spectrum`` through
    :meth:`cablesys.scene.vessel.VesselRAO.rotation_transfer`: the same components, with the same phases, as the
    translation's :func:`sea_sinusoids` (one rigid vessel)."""
    return realise(spectrum, vessel.rotation_transfer)


def realise(spectrum: SeaSpectrum, transfer) -> tuple[tuple, tuple, tuple]:
    """Three tuples of :class:`Sinusoid`: sum_k |T(omega_k)| a_k sin(omega_k t + eps_k + arg T(omega_k)) per axis of
    ``transfer(omega, heading_deg) -> (T_x, T_y, T_z)`` (complex, per unit wave amplitude), each component through
    ``transfer`` at its own direction in a spread sea; an axis the motion does not reach has no terms."""
    w, a, eps = spectrum.components()
    if spectrum.long_crested:
        transfer = transfer(w, spectrum.heading_deg)
    else:
        per = [transfer(np.array([wk]), float(dk)) for wk, dk in zip(w, spectrum.directions())]
        transfer = tuple(np.concatenate([p[i] for p in per]) for i in range(3))
    out = []
    for T in transfer:
        terms = []
        for wk, ak, ek, Tk in zip(w, a, eps, T):
            amp = float(abs(Tk) * ak)
            if amp > 0.0:
                terms.append(Sinusoid(amplitude=amp, frequency=float(wk), phase=float((ek + np.angle(Tk)) % (2 * math.pi))))
        out.append(tuple(terms))
    return out[0], out[1], out[2]


def sea_waves(spectrum: SeaSpectrum, gravity: float) -> tuple:
    """Wang (1971) eq. 26 wave components of the realised sea (see the module docstring), each travelling its
    direction (:meth:`SeaSpectrum.directions`; unset for a long-crested sea along +x: a planar scene)."""
    w, a, eps = spectrum.components()
    along_x = spectrum.long_crested and spectrum.heading_deg % 360.0 == 0.0
    dirs = [None] * len(w) if along_x else [float(d) for d in spectrum.directions()]
    return tuple(Wave(amplitude=float(ak), length=float(2 * math.pi * gravity / wk**2),
                      phase=float((math.pi - ek) % (2 * math.pi)), heading_deg=dk)
                 for wk, ak, ek, dk in zip(w, a, eps, dirs))


def _close(u, v) -> bool:
    fu, fv = dataclasses.astuple(u), dataclasses.astuple(v)
    # an unset field (a wave's heading_deg: along +x) matches only an unset one
    return all(p is q if p is None or q is None else math.isclose(p, q, rel_tol=1e-9, abs_tol=1e-12)
               for p, q in zip(fu, fv))


def append_once(existing: tuple, new: tuple) -> tuple:
    """``existing + new`` unless ``existing`` already ends with ``new`` (a scene written out and read
    back holds its realised components; reading it must not add them twice)."""
    n = len(new)
    if n and len(existing) >= n and all(_close(u, v) for u, v in zip(existing[-n:], new)):
        return tuple(existing)
    return tuple(existing) + tuple(new)


def user_count(obj, name: str) -> int:
    """How many entries of ``obj.name`` the user gave (the rest realise the sea)."""
    return getattr(obj, "_user_count", {}).get(name, len(getattr(obj, name)))
