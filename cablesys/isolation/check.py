"""``design --check``: the design's predicted heave reduction against the time domain, each with its stated error.

The design predicts the lower body's significant heave 2 sigma (m) of the baseline and the designed
scene by the Gaussian equivalent linearization of the drag (:func:`.solve.equivalent_jacobian_shift`).
The check runs both scenes in the time domain, in one realisation of the design sea moving the top as
the design does, and compares. Two errors are stated, each from quantities the design computes:

* Linearization: statistical linearization has more than one criterion. The design's is the least
  mean-square error one, N = E[dr/dxi] (Atalik & Utku 1976; Roberts & Spanos, "Random Vibration and
  Statistical Linearization", 2003, ch. 5); for a drag element |v| v with v ~ N(0, s^2) it gives
  2 E|v| = sqrt(8/pi) s. Equating the mean squares of the nonlinear and the linear force instead
  (c^2 E[v^2] = E[v^4], E[v^4] = 3 s^4: c = sqrt(3) s; one of the energy-type criteria reviewed by
  Elishakoff, Shock Vib. Digest 32 (2000) 179-188) gives a damping sqrt(3 pi / 8) = 1.085 times larger.
  The prediction is redone with the equivalent part of the Jacobian dJ = E[dr/dxi] - dr/dxi(q_0)
  scaled by that factor (all of dJ: it is mostly drag, :mod:`cablesys.linear.stochastic`); the spread
  |ln(A_alt / A)| of the two predictions (2 sigma, and the ratio designed / baseline) is the stated
  linearization error: a bias, not a random error.
* Sampling: one record of T seconds estimates 2 sigma with a random error; for the sea as cablesys
  realises it (sinusoids with random phases) and the linear response at the realised frequencies it is
  :func:`cablesys.linear.sampling.mean_square_covariance` (Bendat & Piersol 2010 sec. 8.2.2 in the
  limit of many components); the ratio's error uses the covariance of the two responses to the same sea.

* Realisation: the time domain's sea is a finite sum of sinusoids (:mod:`cablesys.scene.sea`) over its
  own band; the linear response's mean square in it, sum_k |z_k|^2 / 2, differs from the spectral
  prediction int |H|^2 S d omega by a known amount (a quadrature of a resonant integrand with the
  realisation's components), stated as the realisation offset |ln(2 sigma_realised / 2 sigma_predicted)|.

The two agree when |ln(time domain / prediction)| <= linearization spread + realisation offset +
2 x sampling error (about 95 % of records for a Gaussian sampling error).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..linear.linearization import linearize
from ..linear.sampling import log_ratio_error, mean_square_covariance, significant_amplitude_error
from ..linear.spectra import jonswap
from ..linear.stochastic import BUOY
from ..model import build_model
from ..scene.sea import MotionRAO, SeaSpectrum
from ..statistics import significant_amplitude
from .problem import DesignSettings
from .solve import equivalent_jacobian_shift

CRITERIA_FACTOR = math.sqrt(3 * math.pi / 8)   # equal-mean-square over least-squares damping of |v| v, Gaussian v
SAMPLING_SIGMAS = 2.0                           # the sampling band: 2 standard errors

# the design's top input, the buoy orbit (1, i) of Wang (1971) eq. 26 at x = 0 per unit wave amplitude
# (:data:`cablesys.linear.stochastic.BUOY`), as a motion RAO on the elevation eta = sin(omega t): surge
# leads the elevation by 90 deg, heave follows it (scene/sea.py conventions)
BUOY_ORBIT_RAO = MotionRAO(omega=(1.0,), surge_amplitude=(1.0,), surge_phase_deg=(90.0,), heave_amplitude=(1.0,),
                           heave_phase_deg=(0.0,))


def check_scene(scene, settings: DesignSettings):
    """``scene`` with only the design sea at the top (JONSWAP of the design's Hs, Tp, gamma; the scene's own
    sea's seed, components and band if it has one), moving the top on the buoy orbit as the design does;
    other top motion is removed (the design does not see it)."""
    base = scene.top_motion.spectrum or SeaSpectrum(hs=settings.hs, tp=settings.tp)
    sea = dataclasses.replace(base, kind="jonswap", hs=settings.hs, tp=settings.tp, gamma=settings.gamma,
                              heading_deg=0.0, waves_at_cable=False)
    top = dataclasses.replace(scene.top_motion, x=(), y=(), spectrum=sea, rao=BUOY_ORBIT_RAO)
    return dataclasses.replace(scene, top_motion=top)


def _blend(exact, stochastic, factor: float):
    """The linear model with the equivalent part of the Jacobian scaled: X_0 + factor (X_eq - X_0)."""
    names = ("M", "C", "K", "F0", "F1", "F2")
    return dataclasses.replace(stochastic, **{n: getattr(exact, n) + factor * (getattr(stochastic, n) - getattr(exact, n))
                                              for n in names})


def _heave(lin, omega, index: int) -> np.ndarray:
    """Complex y_b per unit wave amplitude on ``omega`` for the buoy-orbit input."""
    _, Y = lin.transfer(omega)
    nu = Y.shape[2]
    d = np.zeros(nu, complex)
    d[:BUOY.size] = BUOY
    return Y[:, index, :] @ d


def _predict(scene, settings: DesignSettings) -> tuple:
    """(2 sigma by the design's criterion, 2 sigma by the equal-mean-square one (m), the stochastic linear
    model, the body heave's output index and label)."""
    model = build_model(scene)
    p = model.parameters(scene)
    _, st = equivalent_jacobian_shift(model, p, settings)
    label = model.label("y_b", model.n_sections - 1)
    k = st.output_labels.index(label)
    S = jonswap(settings.omega, settings.hs, settings.tp, settings.gamma)
    alt = _blend(linearize(model, p), st.linear, CRITERIA_FACTOR)
    sig_alt = math.sqrt(float(np.trapezoid(np.abs(_heave(alt, settings.omega, k)) ** 2 * S, settings.omega)))
    return float(st.significant_amplitude(label)), significant_amplitude(sig_alt), st.linear, k, label


def linearization_errors(scene, new_scene, settings: DesignSettings) -> dict:
    """The design's predictions of the body heave 2 sigma (m) of the baseline and the designed scene and of their
    ratio, each with its linearization error |ln(alt / design)| (module docstring): what the design states
    without a time-domain check."""
    (a, a_alt, *_), (b, b_alt, *_) = _predict(scene, settings), _predict(new_scene, settings)
    return {"baseline_m": a, "designed_m": b, "ratio": b / a,
            "baseline_error_rel": abs(math.log(a_alt / a)), "designed_error_rel": abs(math.log(b_alt / b)),
            "ratio_error_rel": abs(math.log((b_alt / a_alt) / (b / a))),
            "how": f"the spread between the design's least-squares linearization criterion and equal mean squares "
                   f"(equivalent damping x {CRITERIA_FACTOR:.4f}, Roberts & Spanos ch. 5)"}


def prediction(scene, settings: DesignSettings, sea: SeaSpectrum) -> dict:
    """The design's prediction for ``scene`` and what its errors are computed from.

    Returns
    -------
    dict
        ``significant_heave_m`` (2 sigma by the design's criterion), ``significant_heave_alt_m`` (by the
        equal-mean-square criterion), and for the sampling error the body heave's complex amplitudes
        ``z`` (m) at the realised components of ``sea``.
    """
    sig, sig_alt, lin, k, label = _predict(scene, settings)
    w, a, _ = sea.components()
    return {"significant_heave_m": sig, "significant_heave_alt_m": sig_alt, "z": a * _heave(lin, w, k), "omega": w,
            "label": label}


def time_domain_check(scene, new_scene, settings: DesignSettings, run) -> dict:
    """The baseline and the designed scene in the time domain (:func:`check_scene`: the design sea on the
    buoy orbit) by the model the design optimizes (``as-built``), against the design's prediction.

    The statistics window is the run's own (:attr:`cablesys.time_result.TimeResult.statistics_window`): for the
    design sea, an irregular one, the second half of the run after the smooth start, the longest settled record
    (the sampling error falls with its length), as `cablesys run` of the same scene reports it.

    Parameters
    ----------
    scene, new_scene : Scene
        The baseline and the designed scene.
    settings : DesignSettings
        The design's sea and quadrature.
    run : callable
        ``run(scene) -> TimeResult``: the time domain by the design's model (the command passes
        :func:`cablesys.ladder.simulate` with ``model="as-built"``).

    Returns
    -------
    dict
        Per scene (``baseline``, ``designed``): predicted and time-domain 2 sigma (m), the linearization
        spread, the sampling error and ``agree``; ``ratio``: the same for designed / baseline.
    """
    out, z, m, preds = {}, {}, {}, {}
    T = None
    for name, sc in (("baseline", scene), ("designed", new_scene)):
        sc = check_scene(sc, settings)
        pred = prediction(sc, settings, sc.top_motion.spectrum)
        r = run(sc)
        y = np.asarray(r[pred["label"]])
        t0, t1 = r.statistics_window          # the run's one window: an irregular sea's is the second half
        T = float(t1 - t0)
        td = significant_amplitude(float(np.std(y[r.window_mask()])))
        z[name], m[name], preds[name] = pred["z"], 0.5 * float(np.sum(np.abs(pred["z"]) ** 2)), pred
        v = mean_square_covariance(pred["z"], pred["z"], pred["omega"], T)
        s_rel = significant_amplitude_error(m[name], v) / significant_amplitude(math.sqrt(m[name]))
        lin = abs(math.log(pred["significant_heave_alt_m"] / pred["significant_heave_m"]))
        offset = abs(math.log(significant_amplitude(math.sqrt(m[name])) / pred["significant_heave_m"]))
        out[name] = _entry(pred["significant_heave_m"], td, lin, s_rel, offset, "_m") | {
            "realised_sea_m": significant_amplitude(math.sqrt(m[name])),
            "significant_heave_alt_criterion_m": pred["significant_heave_alt_m"],
            "model": r.stats["model"]["name"], "segments": r.stats["model"]["segments"], "window_s": [float(t0), float(t1)]}
    w_k = preds["baseline"]["omega"]
    v_aa = mean_square_covariance(z["baseline"], z["baseline"], w_k, T)
    v_bb = mean_square_covariance(z["designed"], z["designed"], w_k, T)
    v_ab = mean_square_covariance(z["designed"], z["baseline"], w_k, T)
    pb, pd = preds["baseline"], preds["designed"]
    ratio_pred = pd["significant_heave_m"] / pb["significant_heave_m"]
    ratio_alt = pd["significant_heave_alt_m"] / pb["significant_heave_alt_m"]
    ratio_td = out["designed"]["time_domain_m"] / out["baseline"]["time_domain_m"]
    ratio_real = math.sqrt(m["designed"] / m["baseline"])
    out["ratio"] = _entry(ratio_pred, ratio_td, abs(math.log(ratio_alt / ratio_pred)),
                          log_ratio_error(m["baseline"], m["designed"], v_aa, v_bb, v_ab),
                          abs(math.log(ratio_real / ratio_pred)))
    out["ratio"]["realised_sea"] = ratio_real
    out["ratio"]["alt_criterion"] = ratio_alt
    out["how"] = (f"agree: |ln(time domain / predicted)| <= linearization spread + realisation offset + "
                  f"{SAMPLING_SIGMAS:g} x sampling error; realisation offset: the linear response in the realised "
                  f"sinusoids against the spectrum; linearization spread: the design's least-squares criterion against equal mean squares "
                  f"(damping x {CRITERIA_FACTOR:.4f}); sampling error: one record of {T:.0f} s of the design sea "
                  f"(seed {scene_seed(scene, settings)}) on the buoy orbit, the top moved by that sea alone (the scene's "
                  "other top motion and motion RAO are not in the design's prediction)")
    return out


def scene_seed(scene, settings) -> int:
    """The seed of the check's sea realisation."""
    return int(check_scene(scene, settings).top_motion.spectrum.seed)


def _entry(predicted: float, time_domain: float, linearization: float, sampling: float, offset: float,
           unit: str = "") -> dict:
    """Predicted and time-domain values (keys end in ``unit``) with their relative (log) errors and whether
    they agree."""
    diff = math.log(time_domain / predicted) if predicted > 0 and time_domain > 0 else math.inf
    allowed = linearization + offset + SAMPLING_SIGMAS * sampling
    return {f"predicted{unit}": predicted, f"time_domain{unit}": time_domain, "linearization_error_rel": linearization,
            "realisation_offset_rel": offset, "sampling_error_rel": sampling, "difference_rel": diff,
            "allowed_rel": allowed, "agree": bool(abs(diff) <= allowed)}
