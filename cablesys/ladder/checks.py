"""The a posteriori check's two parts, per reported quantity: the discretization (N against N / 2, Richardson) and
the integration (the same N at the run's rtol against rtol / TIGHTEN).

The a posteriori check of a run with N elements (:func:`cablesys.ladder.auto.richardson_step`) compares it with a run
at N / 2 (and, from N = THIRD_MIN_SEGMENTS on, with one at N / 4: :func:`richardson_triple`). Run at one integrator setting, their difference does not measure the integration error: the error a
step-size controller leaves changes with the step sequence, so it differs between N and N / 2 in size and sign, and a
small quantity on large scaled states (a centimetre amplitude on a chain held at large mean angles by a current) can
carry more integration than discretization error (the generated scenes, ``studies/ladder_generated.py``,
``studies/results/ladder_generated.json``).

So the check runs at the tighter rtol / TIGHTEN (and atol / TIGHTEN): the N / 2 run, and the same N again, whose
result is returned. The tight run's integration error is estimated from the pair: with the local error per step held
to the tolerance Tol, a method of order p takes steps ~ Tol^(1/(p+1)) and leaves a global error ~ Tol^(p/(p+1))
(Hairer, Norsett & Wanner, *Solving Ordinary Differential Equations I*, 2nd ed. 1993, sec. II.4; H. J. Stetter,
"Tolerance proportionality in ODE-codes", 1980), so for I(r) = c r^e, e = p / (p + 1),
y(r) - y(r / TIGHTEN) = I(r / TIGHTEN) (TIGHTEN^e - 1) and the tight run's integration error is
|y(r) - y(r / TIGHTEN)| / (TIGHTEN^e - 1) (:func:`integration_errors`; p is the lowest order the method steps with:
:data:`METHOD_ORDER`). The rule is pessimistic where the errors fall faster than Tol^e and may understate below
est.RESOLUTION, the floor every stated error has (tests/test_ladder_checks.py). The stated error of each quantity
is the tight pair's Richardson estimate plus that integration part. Fixed-step methods (``rk``, ``rkc``,
``collocation``: no rtol) are not checked for it.
"""

from __future__ import annotations

import math

from . import estimate as est
from . import metrics
from .rungs import takes_elements

TIGHTEN = 10.0
"""rtol (and atol) of the check runs over the candidate's."""

METHOD_ORDER = {"cvodes": 1, "cvodes-adams": 1, "idas": 1, "cvodes-bdf2": 2, "rk23": 2, "dopri5": 4}
"""The lowest order p each adaptive method steps with (CVODES and IDAS vary the order from 1; BDF2's is at most 2; the
Bogacki-Shampine and Dormand-Prince pairs' error estimators are of order 2 and 4): the exponent p / (p + 1) of the
global error's dependence on the tolerance (module docstring). A lower p states a larger integration error."""


def adaptive(method: str) -> bool:
    """True when ``method`` controls its step by rtol and atol (:data:`METHOD_ORDER`)."""
    return str(method) in METHOD_ORDER


def tightened(kw: dict, settings) -> dict:
    """The run options ``kw`` with the method, rtol / TIGHTEN and atol / TIGHTEN of the candidate's ``settings`` (an
    :class:`~cablesys.time_domain.IntegratorSettings`)."""
    return dict(kw, method=str(settings.method), rtol=settings.rtol / TIGHTEN, atol=settings.atol / TIGHTEN)


def integration_factor(method: str) -> float:
    """1 / (TIGHTEN^e - 1), e = p / (p + 1) (:data:`METHOD_ORDER`): the tight run's integration error per unit of its
    difference from the run at TIGHTEN x its rtol (module docstring)."""
    p = METHOD_ORDER[str(method)]
    return 1.0 / (TIGHTEN ** (p / (p + 1.0)) - 1.0)


def irregular(scene) -> bool:
    """Whether ``scene``'s top moves in an irregular sea or a recorded motion (its statistics are extremes and means of
    one random record, :func:`richardson`)."""
    top = scene.top_motion
    return top.spectrum is not None or top.series is not None


def _stretch(choice, e: dict, per: dict) -> tuple[dict, dict]:
    """``e`` and ``per`` plus the quasi-static segmented cable's stretch part, which runs at every N share and their
    differences cannot see (:func:`~.estimate.quasistatic_segmented_error`); unchanged for other rungs."""
    if choice.name != "quasi-static":
        return e, per
    stretch = choice.numbers.get("estimates", {}).get("quasi-static", {}).get("stretch", {})
    return ({k: v + stretch.get(k, 0.0) for k, v in e.items()},
            {k: v + stretch.get(metrics.group(k), 0.0) for k, v in per.items()})


def _order(choice) -> float:
    return choice.numbers.get("estimates", {}).get("segmented_1", {}).get("order", est.ORDER)


def richardson(fine: dict, coarse: dict, choice, irregular: bool = False) -> tuple[dict, dict]:
    """({body, tension}, {quantity: e}) of the run at N (statistics ``fine``) from the run at N / 2 (``coarse``, both
    :func:`.metrics.statistics`): |y_N - y_N/2| / (2^p - 1) at the rung's order p, at least est.RESOLUTION, plus for the
    quasi-static segmented cable its stretch part (:func:`_stretch`).

    In an irregular sea (``irregular``) the factor is 1, the whole difference: the statistics are the extremes and
    means of one random record, and which peak is the largest, and how the slow drift falls in the window, changes
    with N by jumps of the size of the difference itself (the ROV lift in Hs 6 m: its 7 cm surge amplitude at N = 7,
    8, 10, 12, 14, 16, 20 scatters by 2 mm about a limit 1 mm away), not smoothly as N^-p."""
    factor = 1.0 if irregular else 1.0 / (2.0 ** _order(choice) - 1.0)
    e = {k: max(v * factor, est.RESOLUTION) for k, v in metrics.errors(coarse, fine).items()}
    per = {k: max(v * factor, est.RESOLUTION) for k, v in metrics.quantity_errors(coarse, fine).items()}
    return _stretch(choice, e, per)


CHECKED_MIN_SEGMENTS = 4
"""Least N whose a posteriori check runs at N / 2 (:func:`cablesys.ladder.auto.needs_richardson`): N / 2 of a smaller N
is Wang's straight cable (N = 1), another model, or not the same sequence."""


def checked(name: str, segments: int) -> bool:
    """Whether a run of rung ``name`` with ``segments`` elements per section is checked a posteriori: against N / 2
    on every quantity, and, stepped by an :func:`adaptive` method, for its integration error (the same N again at
    rtol / TIGHTEN, module docstring), which the stated error then holds: an element rung from CHECKED_MIN_SEGMENTS
    on."""
    return takes_elements(name) and int(segments) >= CHECKED_MIN_SEGMENTS


THIRD_MIN_SEGMENTS = 8
"""Least N whose check also runs N / 4 (:func:`richardson_triple`): below it N / 4 < 2 is Wang's straight cable, another
model, not the next member of the node model's sequence."""


def richardson_triple(fine: dict, coarse: dict, quarter: dict, choice, irregular: bool = False) -> tuple[dict, dict, dict]:
    """({body, tension}, {quantity: e}, {quantity: observed order}) of the run at N from the runs at N / 2 and N / 4
    (statistics ``fine``, ``coarse``, ``quarter``): :func:`richardson`'s |y_N - y_N/2| / (2^p - 1) where the three runs
    show the asymptotic range, else a larger factor.

    The pair N, N / 2 alone cannot tell whether N / 2 is already in the range where the error falls as N^-p; before
    it the Richardson estimate understates. The third run gives each quantity's observed order
    p_obs = log2(|y_N/4 - y_N/2| / |y_N/2 - y_N|) (Roache, *Verification and Validation in Computational Science and
    Engineering*, 1998, ch. 5; Celik et al., J. Fluids Eng. 130, 078001, 2008): where the two differences have one
    sign and p_obs >= p the estimate keeps the factor 1 / (2^p - 1); where 1 <= p_obs < p it is 1 / (2^p_obs - 1);
    otherwise (oscillating, or slower than first order) the factor is 1, the whole last difference (Roache's grid
    convergence index with its safety factor 3 on the second-order estimate). The body and tension groups
    (:func:`.metrics.errors`) take each difference with its quantity's factor. In an irregular sea every quantity states max(|y_N - y_N/2|, |y_N/2 - y_N/4| / 2^p): the
    whole last difference (:func:`richardson`), and the one before reduced by the order, in case the last two runs
    agree by chance. At least est.RESOLUTION, plus the stretch part (:func:`_stretch`)."""
    p = _order(choice)
    orders, factor = {}, {}
    for k in fine:
        if k not in coarse or k not in quarter:
            continue
        a, b = quarter[k] - coarse[k], coarse[k] - fine[k]
        po = math.log2(abs(a) / abs(b)) if a != 0 and b != 0 else None
        orders[k] = po
        monotone = a * b > 0 and po is not None
        factor[k] = (1.0 / (2.0 ** p - 1.0) if monotone and po >= p else
                     1.0 / (2.0 ** po - 1.0) if monotone and po >= 1.0 else 1.0)
    if irregular:
        last, before = metrics.quantity_errors(coarse, fine), metrics.quantity_differences(quarter, coarse, fine)
        per = {k: max(v, before.get(k, 0.0) / 2.0 ** p, est.RESOLUTION) for k, v in last.items()}
        last_g, before_g = metrics.errors(coarse, fine), metrics.errors(quarter, coarse)
        e = {g: max(v, before_g[g] / 2.0 ** p, est.RESOLUTION) for g, v in last_g.items()}
        return (*_stretch(choice, e, per), orders)
    per = {k: max(v * factor.get(k, 1.0), est.RESOLUTION) for k, v in metrics.quantity_errors(coarse, fine).items()}
    e = {g: max(v, est.RESOLUTION) for g, v in metrics.errors(coarse, fine, factor).items()}
    return (*_stretch(choice, e, per), orders)


def integration_errors(tight: dict, loose: dict, method: str) -> tuple[dict, dict]:
    """({body, tension}, {quantity: e}): the integration error of the run with statistics ``tight`` estimated from the
    same model run at TIGHTEN x its rtol (``loose``): their difference x :func:`integration_factor`, each quantity
    relative to its own scale and floor as the other errors (:func:`.metrics.quantity_errors`)."""
    f = integration_factor(method)
    e = {k: v * f for k, v in metrics.errors(loose, tight).items()}
    per = {k: v * f for k, v in metrics.quantity_errors(loose, tight).items()}
    return e, per


def summary(per_integration: dict, rtol: float, method: str) -> str:
    """The reason's clause on the integration part: the rtol pair and the quantity with the largest part."""
    worst = max(per_integration, key=per_integration.get, default=None)
    text = f"integration ({method}, rtol {rtol * TIGHTEN:.2g} vs {rtol:.2g}, the latter kept)"
    if worst is None:
        return text
    return text + f": largest part {worst} {per_integration[worst]:.2g}"


def total(richardson_part: dict, integration_part: dict) -> dict:
    """The stated error of each key: the discretization part plus the integration part (0 where it has none)."""
    return {k: v + integration_part.get(k, 0.0) for k, v in richardson_part.items()}
