"""Plots of RAOs, modes and the nonlinear/linear comparison (reads results only; matplotlib lazily)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..plots import save_figure
from ..results import unit_of


def _plt():
    import matplotlib
    matplotlib.use(matplotlib.get_backend())
    import matplotlib.pyplot as plt
    return plt


NOISE = 1e-9      # a response below 1e-9 of its input (per unit input) is numerical zero


def noise_floor(curves) -> float:
    """The amplitude below which a curve of these RAOs is numerical noise: 1e-9 of the largest
    response per unit input (and at least 1e-300)."""
    peak = max((float(np.max(c)) for c in curves if len(c)), default=0.0)
    return max(NOISE * peak, NOISE if peak == 0.0 else 0.0, 1e-300)


def is_noise(amplitude, floor: float) -> bool:
    """True when no point of ``amplitude`` rises above ``floor`` (identically zero or rounding noise)."""
    return not np.any(np.asarray(amplitude) > floor)


def _mark(ax, natural, label=True, forcing=None):
    """Natural frequencies dashed (one colour each), forcing frequencies solid red, a sea band shaded."""
    for k, (name, w) in enumerate(natural.items()):
        ax.axvline(w, color=f"C{(k + 3) % 10}", ls="--", lw=1.1, label=f"natural {name} = {w:.3g} rad/s" if label else None)
    forcing = dict(forcing or {})
    lo, hi = forcing.pop("sea band low", None), forcing.pop("sea band high", None)
    if lo is not None and hi is not None:
        ax.axvspan(lo, hi, color="C0", alpha=0.07, label="sea band (99.8 % of the energy)" if label else None)
    for name, w in forcing.items():
        ax.axvline(w, color="red", ls="-", lw=1.3, alpha=0.8, label=name if label else None)


def _wrap(title: str, width: int = 70) -> str:
    import textwrap
    return "\n".join(textwrap.wrap(title, width)) if title else title


def plot_rao_bode(raos: dict, output: str, input: str, natural: dict, path, title: str = "",
                  forcing: dict | None = None, units: str = "SI") -> Path:
    """Magnitude and unwrapped phase (deg) of ``output`` per unit ``input`` for several RAOs ({legend: RAO}).

    Curves that are numerical zero (below :data:`NOISE` of the largest response per unit input)
    are not drawn but named in the figure; points of a drawn curve below that floor are blanked
    (with their phase). Log frequency axis when the band spans a decade or more; natural and
    forcing frequencies are marked and labelled in distinct styles. ``units`` "fps" shows the
    amplitude per ft of top motion in ft/lbf.
    """
    from ..units import per_input_unit
    plt = _plt()
    fu, u = per_input_unit(unit_of(output) or ("N" if output.startswith("tension") else "-"), units)
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True)
    curves = {}
    for name, r in raos.items():
        inp = input if input in r.input_labels else r.input_labels[0]
        curves[name] = (r, inp, r.amplitude(output, inp) * fu)
    floor = noise_floor([c[2] for c in curves.values()])
    zero, drawn = [], []
    for k, (name, (r, inp, amp)) in enumerate(curves.items()):
        if is_noise(amp, floor):
            zero.append(name)
            continue
        keep = amp > floor
        a1.plot(r.omega, np.where(keep, amp, np.nan), color=f"C{k}", label=name)
        ph = np.degrees(np.unwrap(np.angle(r(output, inp)[keep])))
        phase = np.full(len(r.omega), np.nan)
        phase[keep] = ph
        a2.plot(r.omega, phase, color=f"C{k}")
        drawn.append((r.kind, amp[keep]))
    omega = next(iter(curves.values()))[0].omega
    if omega[-1] / max(omega[0], 1e-300) >= 10.0:
        a1.set_xscale("log")
    if drawn:
        a1.set_yscale("log")
        lo = min(float(np.min(a)) for _, a in drawn)
        damped = [float(np.max(a)) for kind, a in drawn if kind != "exact"]
        hi = max(float(np.max(a)) for _, a in drawn)
        if damped and hi > 20 * max(damped):
            hi = 20 * max(damped)               # the undamped exact peak is clipped
        a1.set_ylim(max(lo, hi * 1e-8) / 3, hi * 3)
    else:
        a1.text(0.5, 0.5, "identically zero (below 1e-9 of the input)", transform=a1.transAxes, ha="center")
    _mark(a1, natural, forcing=forcing)
    _mark(a2, natural, label=False, forcing=forcing)
    a1.set_xlim(omega[0], omega[-1])
    a1.set_ylabel(f"|{output}| per unit {input} [{u}]")
    a2.set_ylabel("phase, unwrapped [deg]")
    a2.set_xlabel("forcing frequency omega [rad/s]")
    if zero:
        a1.text(0.01, 0.02, "not drawn (numerical zero): " + "; ".join(zero), transform=a1.transAxes, fontsize=7,
                va="bottom")
    a1.legend(fontsize=7, loc="best")
    a1.grid(True, which="both", alpha=0.3)
    a2.grid(True, which="both", alpha=0.3)
    fig.suptitle(_wrap(title or f"RAO of {output} for top motion {input}"), fontsize=10)
    save_figure(fig, path, dpi=110)
    return Path(path)


def plot_modes(modes, length: float, path, title: str = "") -> Path:
    """Sketch of each mode: the straight cable at rest and displaced along the mode shape."""
    plt = _plt()
    n = len(modes.omega_undamped)
    fig, axes = plt.subplots(1, n, figsize=(3.5 * n, 4.5), squeeze=False)
    for k, ax in enumerate(axes[0]):
        shape = dict(zip(modes.q_labels, modes.shapes[:, k]))
        for s, style in ((0.0, "k-"), (1.0, "C0-"), (-1.0, "C1--")):
            phi = s * 0.25 * shape.get("phi", 0.0)
            l = length * (1 + s * 0.1 * shape.get("u", 0.0))
            x, y = -l * np.sin(phi), l * np.cos(phi)       # Wang (1971): e_t = (-sin phi, cos phi), y down
            ax.plot([0, x], [0, y], style, lw=2, label={0.0: "at rest", 1.0: "+ mode", -1.0: "- mode"}[s])
            ax.plot(x, y, "o", color=style[:2] if s else "k", ms=8)
        ax.invert_yaxis()
        ax.set_aspect("equal")
        ax.set_xlim(-0.5 * length, 0.5 * length)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("depth y [m]")
        ax.set_title(f"mode {k + 1} ({modes.dominant[k]}): {modes.omega_undamped[k]:.3g} rad/s", fontsize=9)
        ax.legend(fontsize=7, loc="lower left")
    fig.suptitle(title or "mode shapes (stretch exaggerated)")
    save_figure(fig, path, dpi=110)
    return Path(path)


def plot_nonlinear_rao(omega, curves: dict, natural: dict, ylabel: str, path, title: str = "",
                       points: dict | None = None) -> Path:
    """Amplitude-vs-frequency curves ({legend: values}) with optional markers ({legend: (w, a)})."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for name, vals in curves.items():
        ax.plot(omega, vals, label=name)
    for name, (w, a) in (points or {}).items():
        ax.plot(w, a, "o", mfc="none", ms=8, label=name)
    _mark(ax, natural)
    ax.set_xlabel("forcing frequency omega [rad/s]")
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title)
    save_figure(fig, path, dpi=110)
    return Path(path)


def plot_response_spectrum(stoch, output: str, natural: dict, path, title: str = "") -> Path:
    """Sea spectrum and the response spectrum of ``output``."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(stoch.omega, stoch.spectrum, label="sea spectrum S(omega) [m^2 s/rad]")
    u = unit_of(output) or "-"
    ax.plot(stoch.omega, stoch.response_spectrum(output),
            label=f"{output} response spectrum [{u}^2 s/rad], significant amp. {stoch.significant_amplitude(output):.3g} {u}")
    _mark(ax, natural)
    ax.set_xlabel("omega [rad/s]")
    ax.set_ylabel("spectral density")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title)
    save_figure(fig, path, dpi=110)
    return Path(path)


def plot_sea_response(resp, natural: dict, path, title: str = "", forcing: dict | None = None,
                      units: str = "SI") -> Path:
    """The sea spectrum with the motion response spectra (top) and the tension response spectra (bottom)
    of a :class:`~cablesys.linear.sea_response.SeaResponse`; legends give sigma and the most probable
    maximum over the exposure. Responses below 1e-9 of the largest are listed, not drawn."""
    from ..units import output_unit
    plt = _plt()
    fm, um = output_unit("m", units)
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    a1.plot(resp.omega, resp.sea * fm**2, "k", lw=1.5, label="sea elevation S(omega)")
    peak = max(float(np.max(v)) for v in resp.spectra.values()) if resp.spectra else 0.0
    zero = []
    for k, (o, S) in enumerate(resp.spectra.items()):
        s = resp.statistics[o]
        tension = o.startswith("tension")
        f, u = output_unit("N" if tension else (unit_of(o) or "-"), units)
        if is_noise(S, NOISE * peak if tension else NOISE * float(np.max(resp.sea))):
            zero.append(o)
            continue
        (a2 if tension else a1).plot(resp.omega, S * f**2, color=f"C{k}", label=f"{o}: sigma {s['std'] * f:.3g} {u}, "
                                     f"MPM {(s['most_probable_max'] - s['mean']) * f:+.3g} {u} over {resp.exposure:.4g} s")
    for ax in (a1, a2):
        _mark(ax, {k: w for k, w in natural.items() if resp.omega[0] <= w <= resp.omega[-1]}, label=ax is a1,
              forcing={k: w for k, w in (forcing or {}).items() if not k.startswith("sea band")})
        ax.grid(True, alpha=0.3)
    a1.set_ylabel(f"spectral density [{um}^2 s/rad]")
    a2.set_ylabel(f"tension spectral density [{output_unit('N', units)[1]}^2 s/rad]")
    a2.set_xlabel("omega [rad/s]")
    a1.legend(fontsize=7)
    if a2.lines:
        a2.legend(fontsize=7)
    if zero:
        a1.text(0.99, 0.5, "not drawn (numerical zero): " + ", ".join(zero), transform=a1.transAxes, fontsize=7,
                ha="right")
    fig.suptitle(_wrap(title or "response spectra in the sea"), fontsize=10)
    save_figure(fig, path, dpi=110)
    return Path(path)
