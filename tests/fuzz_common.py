"""Input generators shared by the property-based tests (tests/test_fuzz_*.py).

A generated input starts from a valid document and applies a few mutations a user or a
script could make: a value replaced by another TOML type or an extreme number, a key
deleted or added, a table turned into an array of tables or back; then the text is
written with a byte-order mark, in another encoding, or with a stray byte. The only
allowed outcomes of reading it are a valid object or a named :class:`CablesysError`.

``CABLESYS_FUZZ_EXAMPLES`` scales every test's example count (CI keeps the default).
"""

from __future__ import annotations

import atexit
import dataclasses
import json
import math
import os
import re

from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

SCALE = float(os.environ.get("CABLESYS_FUZZ_EXAMPLES", "1"))
# measurement mode (CABLESYS_FUZZ_REPORT=file.json): tally outcomes per entry point instead of
# stopping at the first raw exception, and write the counts and the slowest example at exit
REPORT = os.environ.get("CABLESYS_FUZZ_REPORT")
TALLY: dict = {}


def tally(entry: str, outcome: str, seconds: float, detail: str = "") -> None:
    """Count one outcome ('result', 'named error', 'raw: <type>', ...) of an entry point;
    ``detail`` (the input and message of a bad outcome) is kept for the first few."""
    t = TALLY.setdefault(entry, {"examples": 0, "outcomes": {}, "max_seconds": 0.0, "details": []})
    t["examples"] += 1
    t["outcomes"][outcome] = t["outcomes"].get(outcome, 0) + 1
    t["max_seconds"] = max(t["max_seconds"], round(seconds, 2))
    if detail and len(t["details"]) < 8:
        t["details"].append(f"{outcome}: {detail}"[:1500])


def _write_report():
    if REPORT and TALLY:
        with open(REPORT, "w") as f:
            json.dump(TALLY, f, indent=1, sort_keys=True)


atexit.register(_write_report)


def fuzz_settings(n: int):
    """Bounded hypothesis settings: n examples (times CABLESYS_FUZZ_EXAMPLES), no deadline."""
    return settings(max_examples=max(1, int(n * SCALE)), deadline=None, derandomize=SCALE == 1,
                    suppress_health_check=list(HealthCheck), database=None)


# ------------------------------------------------------------------------------ TOML text
_BARE = re.compile(r"^[A-Za-z0-9_-]+$")


def _key(k: str) -> str:
    return k if _BARE.match(k) else json.dumps(k, ensure_ascii=False)


def _val(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, list):
        return "[" + ", ".join(_val(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{_key(k)} = {_val(x)}" for k, x in v.items()) + "}"
    raise TypeError(type(v))


def dumps(doc: dict) -> str:
    """A TOML text of ``doc`` (nested tables written inline, one top-level key per line)."""
    return "".join(f"{_key(k)} = {_val(v)}\n" for k, v in doc.items())


# ------------------------------------------------------------------------------ values
_TEXT = st.text(alphabet=st.characters(codec="utf-8", exclude_categories=("Cs", "Cc")), max_size=8)
NUMBERS = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([0.0, -0.0, -1.0, 1e-300, -1e-300, 1e300, 1e-9, 1e9, 0.5, 2.0, 1e6]),
    st.integers(min_value=-2**63, max_value=2**63 - 1),
    st.sampled_from([0, 1, -1, 3, 4, 10**6, 10**9]),
)
SCALARS = st.one_of(NUMBERS, _TEXT, st.booleans(), st.sampled_from(["9", "1e3", "nan", "", "SI", "fps"]))
VALUES = st.one_of(
    SCALARS,
    st.lists(NUMBERS, max_size=5),
    st.lists(SCALARS, max_size=3),
    st.dictionaries(_TEXT, SCALARS, max_size=2),
    st.lists(st.dictionaries(st.sampled_from(["amplitude", "frequency", "length", "mass", "position", "x"]),
                             NUMBERS, max_size=3), min_size=1, max_size=2),
)


def _paths(doc, prefix=()):
    """Every (path, value) of a nested dict/list document."""
    out = []
    if isinstance(doc, dict):
        for k, v in doc.items():
            out.append((prefix + (k,), v))
            out += _paths(v, prefix + (k,))
    elif isinstance(doc, list):
        for i, v in enumerate(doc):
            out.append((prefix + (i,), v))
            out += _paths(v, prefix + (i,))
    return out


def _parent(doc, path):
    for p in path[:-1]:
        doc = doc[p]
    return doc


@st.composite
def mutated(draw, base: dict, n_max: int = 3, extra_keys=("foo", "length", "n_modes", "units")):
    """``base`` (a parsed TOML document) after 0..n_max random edits."""
    doc = json.loads(json.dumps(base))                      # deep copy of plain data
    for _ in range(draw(st.integers(0, n_max))):
        paths = _paths(doc)
        if not paths:
            break
        path, value = draw(st.sampled_from(paths))
        parent = _parent(doc, path)
        kind = draw(st.sampled_from(["replace", "replace", "replace", "number", "delete", "add", "wrap", "unwrap"]))
        if kind == "replace":
            parent[path[-1]] = draw(VALUES)
        elif kind == "number" and isinstance(value, (int, float)) and not isinstance(value, bool):
            parent[path[-1]] = draw(st.sampled_from([-value, value * 1e6, value * 1e-6, 0, value + 0.5]))
        elif kind == "delete":
            del parent[path[-1]]
        elif kind == "add" and isinstance(value, dict):
            value[draw(st.sampled_from(extra_keys))] = draw(VALUES)
        elif kind == "wrap" and isinstance(value, dict):
            parent[path[-1]] = [value]
        elif kind == "unwrap" and isinstance(value, list) and value and isinstance(value[0], dict):
            parent[path[-1]] = value[0]
    return doc


@st.composite
def encoded(draw, text: str) -> bytes:
    """``text`` as bytes: UTF-8 (mostly), with a BOM, in UTF-16 or Latin-1, or with a stray byte."""
    how = draw(st.sampled_from(["utf8", "utf8", "utf8", "bom", "utf16", "latin1", "stray"]))
    if how == "bom":
        return b"\xef\xbb\xbf" + text.encode()
    if how == "utf16":
        return text.encode("utf-16")
    if how == "latin1":
        return text.encode("latin-1", errors="replace") + "# Ø\n".encode("latin-1")
    if how == "stray":
        raw = text.encode()
        i = draw(st.integers(0, len(raw)))
        return raw[:i] + draw(st.sampled_from([b"\xff", b"\xc3", b"\x00", b"\xfe\xff"])) + raw[i:]
    return text.encode()


def nonfinite_fields(obj, prefix: str = "", allowed=("tension_floor",)) -> list[str]:
    """Dotted names of non-finite numbers in a (nested) dataclass; ``allowed`` may be -inf."""
    bad = []
    if dataclasses.is_dataclass(obj):
        for f in dataclasses.fields(obj):
            bad += nonfinite_fields(getattr(obj, f.name), f"{prefix}.{f.name}" if prefix else f.name, allowed)
    elif isinstance(obj, (tuple, list)):
        for i, v in enumerate(obj):
            bad += nonfinite_fields(v, f"{prefix}[{i}]", allowed)
    elif isinstance(obj, float) and not math.isfinite(obj):
        if not (obj == -math.inf and prefix.split(".")[-1] in allowed):
            bad.append(prefix)
    return bad
