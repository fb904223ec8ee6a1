"""Design variables of a chain of sections: the scene's numbers a design tunes, and the parameter labels each sets.

Each variable is one number (a section's AE, its Voigt damping C_I, the intermediate body's mass) that sets one or
more entries of the parameter vector (:class:`.params.ParameterLayout` labels) in proportion; a design (the
frequency-domain one, :mod:`cablesys.isolation`, and the time-domain one, :mod:`cablesys.control.design_problem`)
searches it on a log scale between its bounds.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..errors import ParameterError, require_positive
from .params import section_prefix


def bound_pairs(field: str, value, n: int | None = None) -> tuple:
    """((lo, hi), ...) of a ``[design]`` entry ``field`` (``n`` pairs when given; 0 < lo < hi), else a ParameterError
    naming it."""
    try:
        pairs = tuple((float(a), float(b)) for a, b in value)
    except (TypeError, ValueError):
        raise ParameterError(field, value, "must be a list of [lower, upper] pairs, one per section") from None
    if n is not None and len(pairs) != n:
        raise ParameterError(field, value, f"needs one [lower, upper] pair per section ({n})")
    for i, (lo, hi) in enumerate(pairs):
        require_positive(f"{field}[{i}] lower", lo)
        if not hi > lo:
            raise ParameterError(f"{field}[{i}]", [lo, hi], "upper bound must exceed the lower bound")
    return pairs


@dataclasses.dataclass(frozen=True)
class Variable:
    """One decision variable: its name, the parameter labels it sets, and its log-scaled bounds."""

    name: str
    lower: float
    upper: float
    targets: tuple            # ((parameter label, factor per unit of the variable), ...)

    def value(self, x):
        """Physical value of the normalized variable x in [0, 1] (works on CasADi symbols)."""
        return self.lower * (self.upper / self.lower) ** x

    def normalized(self, v: float) -> float:
        return math.log(v / self.lower) / math.log(self.upper / self.lower)


def section_variables(scene, ae_bounds, damping_bounds, intermediate_mass_bounds=None) -> tuple:
    """The design variables of a chain of sections (the frequency-domain design's,
    :func:`cablesys.isolation.problem.variables`, and the time-domain design's, :mod:`cablesys.control.design_problem`):
    per section i, top first, ``ae_{i+1}`` (AE N) and ``internal_damping_{i+1}`` (C_I N s, Wang 1971 eq. 46) within
    the pairs ``ae_bounds[i]`` and ``damping_bounds[i]``, and with ``intermediate_mass_bounds`` (lo, hi) kg,
    ``intermediate_mass``: the first section's body (the intermediate body) scaled as a whole, its weight and surge
    mass per kg of its heave mass kept (same shape and material). Each targets the layout labels
    (:class:`cablesys.model.params.ParameterLayout`) it sets, with its factor per unit."""
    n = len(scene.sections)
    if len(ae_bounds) != n or len(damping_bounds) != n:
        raise ParameterError("design.ae_bounds", f"{len(ae_bounds)} pairs",
                             f"the scene has {n} sections; give one pair per section (and one damping pair each)")
    out = []
    for i in range(n):
        t_ref = scene.sections[i].cable.tension_ref
        if ae_bounds[i][0] <= t_ref:
            raise ParameterError(f"design.ae_bounds[{i}] lower", ae_bounds[i][0],
                                 f"must exceed the section's reference tension {t_ref:.6g} N so that the zero-tension "
                                 "length l_0 = l_r (1 - T_r / AE) stays positive (Wang 1971 eq. 1)")
        out.append(Variable(f"ae_{i + 1}", *ae_bounds[i], ((f"{section_prefix(n, i)}cable.ae", 1.0),)))
        out.append(Variable(f"internal_damping_{i + 1}", *damping_bounds[i],
                            ((f"{section_prefix(n, i)}cable.internal_damping", 1.0),)))
    if intermediate_mass_bounds is not None:
        if n < 2:
            raise ParameterError("design.intermediate_mass_bounds", intermediate_mass_bounds,
                                 "needs a scene with at least two sections (an intermediate body)")
        b = scene.sections[0].body
        # body 1 scaled as a whole (same shape and material): weight and virtual masses per kg of mass_y
        out.append(Variable("intermediate_mass", *intermediate_mass_bounds,
                            (("sections[0].body.mass_y", 1.0), ("sections[0].body.mass_x", b.mass_x / b.mass_y),
                             ("sections[0].body.weight", b.weight / b.mass_y))))
    return tuple(out)


def kind(name: str) -> str:
    """A variable's kind without its section number: ``ae``, ``internal_damping`` or ``intermediate_mass``."""
    return name.rstrip("_0123456789")


def target(label: str) -> tuple:
    """(section index, "cable" or "body", field) of a variable's layout label, ``sections[i].cable.ae`` in a chain or
    ``cable.ae`` in one section."""
    parts = label.split(".")
    i = int(parts[0][len("sections["):-1]) if parts[0].startswith("sections[") else 0
    return i, parts[-2], parts[-1]


def current_values(scene, variables_: tuple) -> np.ndarray:
    """The scene's own values of the decision variables (first target of each)."""
    vals = []
    for v in variables_:
        i, part, field = target(v.targets[0][0])
        vals.append(getattr(getattr(scene.sections[i], part), field))
    return np.array(vals, float)


def designed_scene(scene, variables_: tuple, values):
    """``scene`` with the variables at ``values``: each target field set to the value times its factor."""
    for var, value in zip(variables_, values):
        for label, factor in var.targets:
            i, part, field = target(label)
            scene = scene.replace_section(i, **{part: {field: float(value) * float(factor)}})
    return scene


def linear_map(layout, p, variables_: tuple) -> tuple:
    """(base, B): the parameter vector p(theta) = base + B theta of the variables' values theta, ``p`` with every
    target zeroed in ``base`` and its factor in B (``layout``: the model's :class:`.params.ParameterLayout`)."""
    base = np.array(p, float)
    B = np.zeros((len(base), len(variables_)))
    for j, var in enumerate(variables_):
        for label, factor in var.targets:
            base[layout.index(label)] = 0.0
            B[layout.index(label), j] = factor
    return base, B
