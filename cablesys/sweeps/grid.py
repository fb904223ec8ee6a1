"""The case grid of a sweep: which labelled values, combined how, and the value lists of the CLI.

A sweep varies named values (``cable.ae``, ``sections[1].body.weight``,
``top_motion.y[0].frequency``, ``numerics.drag_segments``, ``stochastic.hs``). By default the
cases are the outer product of the lists, one dimension per name. Names zipped together
form one dimension: they advance in step (the first name indexes the dimension, the others
are coordinates along it).
"""

from __future__ import annotations

import dataclasses
import itertools
import math

import numpy as np

from ..errors import ParameterError


@dataclasses.dataclass(frozen=True)
class Grid:
    """Cases of a sweep: ``dims`` (one per dimension), each holding one or more zipped names.

    ``names[d]`` are the names of dimension ``d`` (the first one names the dimension);
    ``values[d][j]`` the list of name ``j`` of dimension ``d``. Case ``k`` is the C-order
    flat index of the tuple of positions along the dimensions.
    """

    names: tuple          # ((name, ...), ...) per dimension
    values: tuple         # ((list, ...), ...) per dimension, same nesting as names

    @classmethod
    def build(cls, vary: dict, zip=False) -> Grid:
        """From ``vary`` {name: values}; ``zip`` False (outer product), True (all in step) or a
        list of name groups that advance in step (the other names are crossed with them)."""
        if not isinstance(vary, dict) or not vary:
            raise ParameterError("vary", vary, "must be a non-empty dict {label: list of values}")
        lists = {}
        for name, vals in vary.items():
            arr = list(np.atleast_1d(np.asarray(vals, dtype=object)).tolist())
            if not arr:
                raise ParameterError(f"vary[{name!r}]", vals, "needs at least one value")
            lists[str(name)] = tuple(_plain(v, name) for v in arr)
            kinds = {isinstance(v, str) for v in lists[str(name)]}
            if len(kinds) > 1:          # one column of one type: all numbers or all text
                bad = next(v for v in lists[str(name)] if isinstance(v, str))
                raise ParameterError(f"vary[{name!r}]", bad, "mixes text and numbers "
                                     f"({', '.join(map(str, lists[str(name)]))}): give all numbers or all text")
        if zip is True:
            groups = [tuple(lists)]
        elif not zip:
            groups = []
        else:
            groups = [tuple(g) for g in zip]
        seen = [n for g in groups for n in g]
        for n in seen:
            if n not in lists:
                raise ParameterError("zip", n, f"names a value that is not varied; varied: {list(lists)}")
        if len(set(seen)) != len(seen):
            raise ParameterError("zip", groups, "each name may appear in one group only")
        dims, used = [], set()
        for name in lists:                     # dimension order follows the order of ``vary``
            if name in used:
                continue
            group = next((g for g in groups if name in g), (name,))
            lengths = {len(lists[n]) for n in group}
            if len(lengths) != 1:
                raise ParameterError("zip", {n: len(lists[n]) for n in group}, "zipped lists must have equal lengths")
            dims.append(group)
            used.update(group)
        return cls(names=tuple(dims), values=tuple(tuple(lists[n] for n in g) for g in dims))

    @property
    def dims(self) -> tuple:
        """Dimension names (the first name of each group)."""
        return tuple(g[0] for g in self.names)

    @property
    def all_names(self) -> tuple:
        return tuple(n for g in self.names for n in g)

    @property
    def shape(self) -> tuple:
        return tuple(len(v[0]) for v in self.values)

    def __len__(self) -> int:
        return math.prod(self.shape)

    def case(self, k: int) -> dict:
        """{name: value} of flat case ``k``."""
        pos = np.unravel_index(k, self.shape)
        return {n: vals[i] for g, vs, i in zip(self.names, self.values, pos) for n, vals in zip(g, vs)}

    def cases(self):
        """All cases in flat order."""
        for pos in itertools.product(*(range(s) for s in self.shape)):
            yield {n: vals[i] for g, vs, i in zip(self.names, self.values, pos) for n, vals in zip(g, vs)}


def _plain(v, name: str = "vary value"):
    """A JSON/netCDF-friendly scalar (Python int, float or str) of the list of ``name``."""
    if isinstance(v, (bool, np.bool_)):
        return int(v)
    if isinstance(v, (int, np.integer)):
        return int(v)
    if isinstance(v, (float, np.floating)):
        return float(v)
    if isinstance(v, str):
        return v
    raise ParameterError(f"vary[{name!r}]", v, "must be a number or a string")


def parse_values(text: str) -> list:
    """Values of a command-line ``--vary NAME=SPEC``.

    Parameters
    ----------
    text : str
        A comma list (``2000,3000,4000``; strings allowed: ``cvodes,idas``) or a range
        ``start:stop:lin|log:count`` (both ends included; ``log`` spaces geometrically).

    Returns
    -------
    list
        The values (int, float or str), in SI as the scene's fields are.
    """
    text = text.strip()
    if ":" in text:
        parts = text.split(":")
        if len(parts) != 4 or parts[2] not in ("lin", "log"):
            raise ParameterError("--vary", text, "a range is start:stop:lin|log:count, e.g. 1e5:1e7:log:20")
        try:
            a, b, n = float(parts[0]), float(parts[1]), int(parts[3])
        except ValueError:
            raise ParameterError("--vary", text, "start and stop must be numbers and count an integer") from None
        if n < 1:
            raise ParameterError("--vary", text, "count must be >= 1")
        if parts[2] == "log":
            if a <= 0 or b <= 0:
                raise ParameterError("--vary", text, "a log range needs positive ends")
            return list(np.geomspace(a, b, n))
        return list(np.linspace(a, b, n))
    out = []
    for item in text.split(","):
        item = item.strip()
        if not item:
            raise ParameterError("--vary", text, "empty value in the comma list")
        try:
            out.append(int(item) if item.lstrip("+-").isdigit() else float(item))
        except ValueError:
            out.append(item)
    return out


def parse_vary(specs) -> dict:
    """The ``vary`` dict of :func:`cablesys.sweep` from command-line specs.

    Parameters
    ----------
    specs : list of str
        ``NAME=VALUES`` items, e.g. ``["cable.ae=1e5:1e7:log:20", "body.weight=2000,3000"]``
        (values as in :func:`parse_values`).

    Returns
    -------
    dict
        {label: list of values}, in the order given. A label given twice is a ParameterError
        (one list per label; a range and a list of one label are not merged).
    """
    vary, given = {}, {}
    for s in specs:
        if "=" not in s:
            raise ParameterError("--vary", s, "must be NAME=VALUES, e.g. cable.ae=1e5:1e7:log:20")
        name, spec = (t.strip() for t in s.split("=", 1))
        if name in vary:
            raise ParameterError("--vary", s, f"repeats the label {name!r} (given before as {given[name]}): "
                                 "one --vary per label")
        vary[name], given[name] = parse_values(spec), s
    return vary
