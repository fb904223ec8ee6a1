"""The a posteriori check's two parts, per reported quantity: the discretization (N against N / 2, Richardson) and
the integration (the same N at the run's rtol against rtol / TIGHTEN).

The a posteriori check of a run with N elements (:func:`cablesys.ladder.auto.richardson_step`) compares it with a run
at N / 2. Run at one integrator setting, their difference does not measure the integration error: the error a
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

from . import estimate as est
from . import metrics

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


def richardson(fine: dict, coarse: dict, choice) -> tuple[dict, dict]:
    """({body, tension}, {quantity: e}) of the run at N (statistics ``fine``) from the run at N / 2 (``coarse``, both
    :func:`.metrics.statistics`): |y_N - y_N/2| / (2^p - 1) at the rung's order p, at least est.RESOLUTION, plus for the
    quasi-static segmented cable its stretch part, which both runs share and their difference cannot see
    (:func:`~.estimate.quasistatic_segmented_error`)."""
    order = choice.numbers.get("estimates", {}).get("segmented_1", {}).get("order", est.ORDER)
    factor = 1.0 / (2.0 ** order - 1.0)
    e = {k: max(v * factor, est.RESOLUTION) for k, v in metrics.errors(coarse, fine).items()}
    per = {k: max(v * factor, est.RESOLUTION) for k, v in metrics.quantity_errors(coarse, fine).items()}
    if choice.name == "quasi-static":
        stretch = choice.numbers.get("estimates", {}).get("quasi-static", {}).get("stretch", {})
        e = {k: v + stretch.get(k, 0.0) for k, v in e.items()}
        per = {k: v + stretch.get(metrics.group(k), 0.0) for k, v in per.items()}
    return e, per


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
