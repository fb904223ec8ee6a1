"""Architecture rules, checked on the source: the layer ladder, no import cycles, no copy-paste.

1. Imports point down the ladder (the table ``LAYERS`` below is the one place it is written):
   foundation (units, errors, results, reader, tables, statistics, outputs, atomic, compiled,
   messages, integration, profiles) < scene < model < statics
   < analyses (simulate, linear, and the slack and towed models) < ladder (which model a scene
   needs, over the analyses) < design (isolation, control, verdict, export, ...: the control
   takes the ladder's model, as every door does) < workflows over any analysis (sweep) < plots
   < cli. A module may import its own layer only inside its own subpackage (``simulate`` does
   not import ``linear``: what both need lives in ``statics``). Lazy imports inside functions count: a dependency is a
   dependency. A subpackage's ``__init__`` is its facade and may re-export any module of its
   own subpackage (``cablesys.slack`` exports its plots).
2. No import cycles: the graph of every ``import`` in the package (module level and inside
   functions, relative ones resolved, a facade ``__init__``'s imports of its own modules included)
   has no strongly connected component of two or more modules.
3. No window of six or more consecutive code lines appears twice in the package
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
    ("foundation", ("cablesys.units", "cablesys.errors", "cablesys.results", "cablesys.result_protocol", "cablesys.reader", "cablesys.options", "cablesys.time_result",
                    "cablesys.statistics", "cablesys.outputs", "cablesys.compiled", "cablesys.derivatives", "cablesys.messages",
                    "cablesys.integration", "cablesys.profiles", "cablesys.lazy", "cablesys.atomic", "cablesys.tables",
                    "cablesys.disk_cache")),
    ("scene", ("cablesys.scene",)),
    ("model", ("cablesys.model",)),
    ("statics", ("cablesys.statics",)),
    ("analyses", ("cablesys.time_domain", "cablesys.linear", "cablesys.slack", "cablesys.towed")),
    ("ladder", ("cablesys.ladder",)),
    ("design", ("cablesys.isolation", "cablesys.control", "cablesys.verdict", "cablesys.examples", "cablesys.export")),
    ("workflows", ("cablesys.sweeps",)),
    ("plots", ("cablesys.plots",)),
    ("cli", ("cablesys.cli", "cablesys.__main__", "cablesys.commands")),
]
RANK = {name: k for k, (name, _) in enumerate(LAYERS)}


def module_name(path: Path, root: Path = PKG) -> str:
    parts = path.relative_to(root.parent).with_suffix("").parts
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


def imports_of(path: Path, mod: str, root: Path = PKG):
    """(line, imported module) for every import in the file, relative ones resolved (``root``: the
    package's directory)."""
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
                yield node.lineno, sub if (root.parent / sub.replace(".", "/")).with_suffix(".py").exists() \
                    or (root.parent / sub.replace(".", "/")).is_dir() else target


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


# -- no import cycles ------------------------------------------------------------------------
def import_graph(root: Path = PKG) -> dict:
    """module -> {imported module: "file:line" of its first import} for every module under ``root``.

    Every ``import`` statement counts, wherever it is (module level, function, class, ``if``):
    a lazy import delays a dependency, it does not remove it. A target is the module the import
    names (``from .x import y``: ``x``, or ``x.y`` when that is a module; ``from . import y``: the
    package's ``__init__`` unless ``y`` is a module). Python also runs the parent packages'
    ``__init__`` of any imported module; that implicit step is not an edge, or every facade that
    re-exports a module would close a cycle with it. An explicit import of the package (``from .
    import name`` of a name its ``__init__`` defines) is an edge, and so are a facade's imports of
    its own modules.
    """
    paths = {module_name(path, root): path for path in sorted(root.rglob("*.py"))}
    graph = {mod: {} for mod in paths}
    for mod, path in paths.items():
        for line, target in imports_of(path, mod, root):
            while target not in paths and "." in target:      # ``import pkg.mod.name``: the module
                target = target.rsplit(".", 1)[0]
            if target in paths and target != mod:
                graph[mod].setdefault(target, f"{path.relative_to(root.parent)}:{line}")
    return graph


def import_cycles(graph: dict) -> list:
    """The strongly connected components of two or more modules (Tarjan 1972), each sorted, in
    sorted order: every module of one can reach every other through imports."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while not comp or comp[-1] != v:
                comp.append(stack.pop())
                on_stack.discard(comp[-1])
            if len(comp) > 1:
                found.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return sorted(found)


def _cycle_report(graph: dict, cycles: list) -> str:
    return "\n".join(" <-> ".join(comp) + "".join(f"\n    {graph[a][b]} imports {b}" for a in comp
                                                  for b in sorted(graph[a]) if b in comp)
                     for comp in cycles)


def test_no_import_cycles():
    graph = import_graph()
    cycles = import_cycles(graph)
    assert not cycles, (f"{len(cycles)} import cycles (move what both sides need below both):\n"
                        + _cycle_report(graph, cycles))


def test_import_cycles_are_found(tmp_path):
    """The detector on a package written for it: a facade cycle (a module importing a name its
    package's ``__init__`` defines, that ``__init__`` re-exporting it), a cycle closed by an import
    inside a function, a three-module cycle through ``import a.b`` and ``from . import mod``; and
    the acyclic imports around them (a facade re-exporting a module that does not import it back,
    a module importing a facade's re-export) found as no cycle."""
    files = {
        "__init__.py": "",
        "fac/__init__.py": "from .part import f\nfrom .plain import g\n\ndef helper():\n    return 1\n",
        "fac/part.py": "from . import helper\n\ndef f():\n    return helper()\n",
        "fac/plain.py": "import math\n\ndef g():\n    return math.pi\n",
        "lazy_a.py": "from .lazy_b import b\n\ndef a():\n    return b()\n",
        "lazy_b.py": "def b():\n    from .lazy_a import a\n    return a\n",
        "ring/__init__.py": "",
        "ring/one.py": "import cablesys.ring.two\n",
        "ring/two.py": "from . import three\n",
        "ring/three.py": "from .one import x\n",
        "user.py": "from .fac import f, g\nfrom .ring import one\n",
    }
    root = tmp_path / "cablesys"
    for name, text in files.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text)
    graph = import_graph(root)
    assert graph["cablesys.fac.part"] == {"cablesys.fac": "cablesys/fac/part.py:1"}
    assert graph["cablesys.lazy_b"] == {"cablesys.lazy_a": "cablesys/lazy_b.py:2"}
    assert import_cycles(graph) == [["cablesys.fac", "cablesys.fac.part"],
                                    ["cablesys.lazy_a", "cablesys.lazy_b"],
                                    ["cablesys.ring.one", "cablesys.ring.three", "cablesys.ring.two"]]
    (root / "fac/part.py").write_text("def f():\n    return 1\n")        # the facade fixed: no cycle
    (root / "lazy_b.py").write_text("def b():\n    return 2\n")
    assert import_cycles(import_graph(root)) == [["cablesys.ring.one", "cablesys.ring.three", "cablesys.ring.two"]]
    report = _cycle_report(graph, import_cycles(graph))
    assert "cablesys/lazy_b.py:2 imports cablesys.lazy_a" in report


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
