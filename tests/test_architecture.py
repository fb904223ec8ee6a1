"""Architecture rules, checked on the source: the layer ladder and no copy-paste.

1. Imports point down the ladder (the table ``LAYERS`` below is the one place it is written):
   foundation (units, errors, results, reader, tables, statistics, outputs, atomic, compiled,
   messages, integration, profiles) < scene < model < statics
   < analyses (simulate, linear, and the slack and towed models) < design (design, ladder,
   verdict, export, ...) < workflows over any analysis (sweep) < plots < cli. A module may import its
   own layer only inside its own subpackage (``simulate`` does not import ``linear``: what
   both need lives in ``statics``). Lazy imports inside functions count: a dependency is a
   dependency. A subpackage's ``__init__`` is its facade and may re-export any module of its
   own subpackage (``cablesys.slack`` exports its plots).
2. No window of six or more consecutive code lines appears twice in the package
   (declarations such as imports, ``__all__`` lists, dataclass field lists and docstrings
   excluded): share the piece instead.
"""

import ast
import re
from collections import defaultdict
from pathlib import Path

PKG = Path(__file__).resolve().parents[1] / "cablesys"

# The one table of layers (lowest first). A module belongs to the layer of the longest
# matching prefix; ``*.plots*`` and ``*.cli`` modules of any subpackage sit in the plots and
# cli layers. New packages: add them here.
LAYERS = [
    ("foundation", ("cablesys.units", "cablesys.errors", "cablesys.results", "cablesys.reader", "cablesys.options", "cablesys.time_result",
                    "cablesys.statistics", "cablesys.outputs", "cablesys.compiled", "cablesys.messages",
                    "cablesys.integration", "cablesys.profiles", "cablesys.lazy", "cablesys.atomic", "cablesys.tables",
                    "cablesys.disk_cache")),
    ("scene", ("cablesys.scene",)),
    ("model", ("cablesys.model",)),
    ("statics", ("cablesys.statics",)),
    ("analyses", ("cablesys.time_domain", "cablesys.linear", "cablesys.slack", "cablesys.towed")),
    ("design", ("cablesys.isolation", "cablesys.ladder", "cablesys.verdict", "cablesys.examples", "cablesys.export")),
    ("workflows", ("cablesys.sweeps",)),
    ("plots", ("cablesys.plots",)),
    ("cli", ("cablesys.cli", "cablesys.__main__", "cablesys.commands")),
]
RANK = {name: k for k, (name, _) in enumerate(LAYERS)}


def module_name(path: Path) -> str:
    parts = path.relative_to(PKG.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def layer_of(mod: str) -> str:
    if mod == "cablesys":                   # the facade (``from . import __version__``)
        return "foundation"
    last = mod.split(".")[-1]
    if mod.count(".") >= 2 and last == "cli":
        return "cli"
    if mod.count(".") >= 2 and (last == "plots" or ".plots." in mod + "."):
        return "plots"
    best, layer = -1, None
    for name, prefixes in LAYERS:
        for pre in prefixes:
            if (mod == pre or mod.startswith(pre + ".")) and len(pre) > best:
                best, layer = len(pre), name
    assert layer is not None, f"{mod} is in no layer: add it to LAYERS in {__file__}"
    return layer


def subpackage(mod: str) -> str:
    return ".".join(mod.split(".")[:2])


def imports_of(path: Path, mod: str):
    """(line, imported module) for every import in the file, relative ones resolved."""
    tree = ast.parse(path.read_text(), filename=str(path))
    is_pkg = path.name == "__init__.py"
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name.startswith("cablesys"):
                    yield node.lineno, a.name
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = mod.split(".") if is_pkg else mod.split(".")[:-1]
                base = base[:len(base) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if not target.startswith("cablesys"):
                continue
            for a in node.names:           # ``from . import save_figure`` or ``from .x import y``
                sub = f"{target}.{a.name}"
                yield node.lineno, sub if (PKG.parent / sub.replace(".", "/")).with_suffix(".py").exists() \
                    or (PKG.parent / sub.replace(".", "/")).is_dir() else target


SOURCES = sorted(PKG.rglob("*.py"))


def test_every_module_has_a_layer():
    for path in SOURCES:
        layer_of(module_name(path))


def test_imports_point_down_the_ladder():
    bad = []
    for path in SOURCES:
        mod = module_name(path)
        if mod == "cablesys":               # the facade: lazy table of re-exports
            continue
        here = layer_of(mod)
        for line, target in imports_of(path, mod):
            if path.name == "__init__.py" and subpackage(target) == subpackage(mod):
                continue                   # a facade re-exports its own modules
            there = layer_of(target)
            up = RANK[there] > RANK[here]
            sideways = (RANK[there] == RANK[here] and subpackage(target) != subpackage(mod)
                        and here not in ("foundation", "plots", "cli"))
            if up or sideways:
                bad.append(f"{path.relative_to(PKG.parent)}:{line} ({here}) imports {target} ({there})")
    assert not bad, "imports against the layer rule:\n" + "\n".join(bad)


# -- no copy-paste -----------------------------------------------------------------------------
WINDOW = 6
_DECL = re.compile(r"^(import |from \S+ import|@|__all__|[A-Za-z_][\w.]*\s*:\s*[\w\[\], .|\"']+(=.*)?$|\)|\]|\}|\"\"\"|''')")


def _code_lines(path: Path):
    """(line number, normalized text) of the lines that are code, not declarations or docs."""
    text = path.read_text()
    tree = ast.parse(text)
    skip = set()
    for node in ast.walk(tree):            # docstrings
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(getattr(body[0], "value", None), ast.Constant) \
                    and isinstance(body[0].value.value, str):
                skip.update(range(body[0].lineno, body[0].end_lineno + 1))
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            skip.update(range(node.lineno, node.end_lineno + 1))
    out = []
    for k, raw in enumerate(text.splitlines(), 1):
        line = raw.split("#", 1)[0].strip()
        if k in skip or not line or _DECL.match(line):
            continue
        out.append((k, re.sub(r"\s+", " ", line)))
    return out


# Pairs of files known to repeat a block, with the owner's task: the test fails on any other
# pair, and on a listed pair that no longer repeats (then delete its entry).
KNOWN_REPEATS: dict = {}


def test_no_block_of_six_lines_is_repeated():
    seen = defaultdict(list)
    for path in SOURCES:
        lines = _code_lines(path)
        for i in range(len(lines) - WINDOW + 1):
            block = tuple(t for _, t in lines[i:i + WINDOW])
            if sum(len(t) for t in block) < 120:        # trivial windows (closing brackets, returns)
                continue
            seen[block].append(f"{path.relative_to(PKG.parent)}:{lines[i][0]}")
    dups = {b: w for b, w in seen.items() if len(w) > 1}
    pairs = {tuple(sorted({x.rsplit(":", 1)[0] for x in w})) for w in dups.values()}
    stale = [k for k in KNOWN_REPEATS if k not in pairs]
    assert not stale, f"no longer repeated (delete from KNOWN_REPEATS): {stale}"
    dups = {b: w for b, w in dups.items() if tuple(sorted({x.rsplit(":", 1)[0] for x in w})) not in KNOWN_REPEATS}
    report = "\n".join(f"{', '.join(w)}:\n    " + "\n    ".join(b) for b, w in list(dups.items())[:10])
    assert not dups, f"{len(dups)} repeated blocks of {WINDOW} code lines; share them:\n{report}"
