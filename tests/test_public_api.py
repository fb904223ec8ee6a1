"""The public API: what each package exports is documented and every result type keeps the protocol.

Modelled on python-control's ``docstrings_test.py``: every exported function has a numpydoc
docstring with a Parameters section naming each of its arguments and a Returns section; every
exported class has a docstring; every result class (a subclass of ``ResultBase``) offers
``success``, ``message``, ``stats``, ``summary`` and ``to_xarray``.
"""

import ast
import dataclasses
import importlib
import importlib.util
import inspect
import pkgutil
import re
from pathlib import Path

import pytest

import cablesys
from cablesys.results import AnalysisResult, ResultBase

PACKAGES = ["cablesys"] + [f"cablesys.{name}" for name in cablesys._SUBPACKAGES] + ["cablesys.statics"]


def _exported():
    seen = {}
    for pkg_name in PACKAGES:
        try:
            pkg = importlib.import_module(pkg_name)
        except ModuleNotFoundError:        # an optional subpackage not present in this checkout
            continue
        for name in getattr(pkg, "__all__", ()):
            obj = getattr(pkg, name)
            if inspect.ismodule(obj):
                continue
            seen.setdefault(id(obj), (f"{pkg_name}.{name}", obj))
    return sorted(seen.values(), key=lambda t: t[0])


EXPORTED = _exported()
# Exported functions whose modules were being rewritten by other work when this test was
# written: their numpydoc sections are owed. Strict xfail: once documented, the entry must go.
PENDING: set = set()
FUNCTIONS = [pytest.param(n, o, id=n, marks=[pytest.mark.xfail(strict=True, reason="docstring owed")]
                          if n in PENDING else []) for n, o in EXPORTED if inspect.isfunction(o)]
CLASSES = [(n, o) for n, o in EXPORTED if inspect.isclass(o)]


def _section(doc: str, title: str) -> str:
    """Text of a numpydoc section (from its underlined title to the next title)."""
    m = re.search(rf"^\s*{title}\n\s*-{{3,}}\n(.*?)(?=^\s*\w[\w ]*\n\s*-{{3,}}\n|\Z)", doc, re.MULTILINE | re.DOTALL)
    return m.group(1) if m else ""


def test_every_package_declares_all():
    for pkg_name in PACKAGES:
        try:
            pkg = importlib.import_module(pkg_name)
        except ModuleNotFoundError:
            continue
        assert hasattr(pkg, "__all__"), f"{pkg_name} has no __all__"
        for name in pkg.__all__:
            assert hasattr(pkg, name), f"{pkg_name}.__all__ names {name!r}, which it does not define"


@pytest.mark.parametrize("name,func", FUNCTIONS)
def test_exported_function_docstring(name, func):
    doc = inspect.getdoc(func) or ""
    assert doc, f"{name} has no docstring"
    params = [p for p in inspect.signature(func).parameters.values()
              if p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD) and p.name not in ("self", "cls")]
    if params:
        section = _section(doc, "Parameters")
        assert section, f"{name}: docstring has no 'Parameters' section"
        heads = re.findall(r"^(\w+(?:\s*,\s*\w+)*)\s*:", section, re.MULTILINE)    # "a, b : type" names both
        names = {n.strip() for head in heads for n in head.split(",")}
        missing = [p.name for p in params if p.name not in names]
        assert not missing, f"{name}: parameters {missing} not documented"
    assert _section(doc, "Returns") or _section(doc, "Yields"), f"{name}: docstring has no 'Returns' section"


@pytest.mark.parametrize("name,cls", CLASSES, ids=[n for n, _ in CLASSES])
def test_exported_class_docstring(name, cls):
    assert cls.__doc__ and not cls.__doc__.startswith(f"{cls.__name__}("), f"{name} has no docstring"


def _all_result_classes():
    for mod in pkgutil.walk_packages(cablesys.__path__, "cablesys."):
        if mod.name.endswith(("__main__", ".cli")):
            continue
        importlib.import_module(mod.name)
    out, todo = [], [ResultBase]
    while todo:
        c = todo.pop()
        for s in c.__subclasses__():
            out.append(s)
            todo.append(s)
    return sorted(set(out), key=lambda c: c.__qualname__)


RESULTS = _all_result_classes()


def test_the_package_has_its_result_types():
    names = {c.__name__ for c in RESULTS}
    assert {"TimeResult", "LinearModel", "Modes", "RAO", "HarmonicResponse", "PeriodicSolution",
            "StochasticResponse", "DesignResult", "Equilibrium", "ModeSet", "Convergence", "TransferGrid",
            "Eigenfrequencies"} <= names


@pytest.mark.parametrize("cls", RESULTS, ids=[c.__name__ for c in RESULTS])
def test_result_type_keeps_the_protocol(cls):
    assert dataclasses.is_dataclass(cls) and cls.__dataclass_params__.frozen, f"{cls.__name__} is not frozen"
    fields = {f.name for f in dataclasses.fields(cls)}
    for attr in ("success", "message", "stats"):
        assert attr in fields or isinstance(inspect.getattr_static(cls, attr, None), property), \
            f"{cls.__name__} has no {attr}"
    assert callable(cls.summary) and callable(cls.to_xarray)
    assert "to_xarray" in vars(cls) or any("to_xarray" in vars(b) for b in cls.__mro__[1:-2]), \
        f"{cls.__name__} does not build a dataset"
    assert cls.__repr__ is ResultBase.__repr__ or "__repr__" in vars(cls)
    assert cls.__doc__ and not cls.__doc__.startswith(f"{cls.__name__}(")


def test_results_are_short_json_and_labelled():
    """A real result: short repr, JSON summary, units and long names on every variable."""
    import json

    import numpy as np

    from cablesys.towed import (
        REPORT_TYPICAL,
        TowedCable,
        c_star,
        modes,
        phase_lag,
        phase_velocity,
        transfer_function,
        transfer_grid,
    )

    coef = TowedCable(**REPORT_TYPICAL).coefficients()
    for res in (transfer_grid(coef, np.linspace(0.0, 1.0, 401), np.linspace(0.1, 3.0, 300)),
                modes(coef, 4), transfer_function(coef, 1.0, 2.0), c_star(coef, 0.5, np.linspace(0.1, 3.0, 5)),
                phase_velocity(coef, np.linspace(0.0, 1.0, 11)[:, None], np.array([0.5, 1.0])),
                phase_lag(coef, np.array([0.2, 0.9]), np.array([1.0, 2.0]))):
        assert isinstance(res, AnalysisResult) and res.success and res.message == ""
        assert res.stats["wall_time_s"] >= 0.0
        assert len(repr(res)) < 400 and "array(" not in repr(res)
        json.dumps(res.summary())
        ds = res.to_xarray()
        for name, var in list(ds.data_vars.items()) + list(ds.coords.items()):
            assert var.attrs.get("units") and var.attrs.get("long_name"), name
        assert ds.attrs["success"] == 1


def _readme_python_block() -> str:
    text = (Path(__file__).resolve().parents[1] / "README.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) == 1, "the README has one Python section"
    return blocks[0]


def test_readme_python_section_uses_only_the_public_api():
    """Every ``cablesys.x.y`` in the README's Python section is exported by the package that holds it."""
    tree = ast.parse(_readme_python_block())
    for node in ast.walk(tree):
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            names = [a.name for a in node.names] if isinstance(node, ast.Import) else [node.module]
            assert all(not n.startswith("cablesys.") for n in names), "import only cablesys itself"
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "cablesys":
            assert node.attr in cablesys.__all__, node.attr
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Attribute) \
                and isinstance(node.value.value, ast.Name) and node.value.value.id == "cablesys":
            sub = importlib.import_module(f"cablesys.{node.value.attr}")
            assert node.attr in sub.__all__, f"cablesys.{node.value.attr}.{node.attr}"


@pytest.mark.slow
def test_readme_python_section_runs(tmp_path, monkeypatch):
    from cablesys.slack.scene import EXAMPLE_TOML
    from cablesys.towed.scene import EXAMPLE_TOML as TOWED_TOML

    (tmp_path / "cable.toml").write_text(EXAMPLE_TOML)       # `cablesys slack --example`
    (tmp_path / "towed.toml").write_text(TOWED_TOML)        # `cablesys towed --example`
    monkeypatch.chdir(tmp_path)
    exec(compile(_readme_python_block(), "README.md", "exec"), {})


def _check_protocol(res):
    import json

    assert isinstance(res, AnalysisResult), type(res).__name__
    assert isinstance(res.success, bool) and isinstance(res.message, str) and isinstance(res.stats, dict)
    assert res.success == (res.message == ""), (type(res).__name__, res.message)
    json.dumps(res.summary())
    assert len(repr(res)) < 600 and "array([" not in repr(res)
    ds = res.to_xarray()
    items = list(ds.coords.items()) + (list(ds.data_vars.items()) if hasattr(ds, "data_vars") else [(ds.name, ds)])
    unlabelled = [str(n) for n, v in items if not (v.attrs.get("units") and v.attrs.get("long_name"))]
    assert not unlabelled, (type(res).__name__, unlabelled)
    assert ds.attrs["success"] == int(res.success)


def test_real_results_of_every_wang_analysis_keep_the_protocol():
    """One of each result of the Wang model, computed (a few seconds): the protocol holds on values."""
    import numpy as np

    from cablesys.linear import (
        harmonic_response,
        jonswap,
        periodic_steady_state,
        stochastic_response,
    )
    from cablesys.linear.periodic import scene_input_amplitude

    scene = cablesys.dale_scene(omega_ratio=1.0, duration=2.0)
    model = cablesys.build_model(scene)
    p = model.parameters(scene)
    lin = cablesys.linearize(model, p)
    w, z = scene_input_amplitude(scene)
    om = np.linspace(0.3, 3.0, 40)
    results = [cablesys.simulate(scene, model=model), lin, cablesys.modes(lin),
               cablesys.rao(lin, np.linspace(0.5, 2.0, 20)), harmonic_response(model, p, [w], z),
               periodic_steady_state(model, p, w, input_amplitude=z, n_harmonics=8),
               stochastic_response(model, p, om, jonswap(om, 0.01, 5.0), n_log2=6)]
    for res in results:
        _check_protocol(res)
    for res in results[1:]:
        assert res.stats["wall_time_s"] >= 0.0


def test_real_slack_results_keep_the_protocol():
    import tomllib

    from cablesys.slack.scene import EXAMPLE_TOML, scene_from_dict

    scene = scene_from_dict(tomllib.loads(EXAMPLE_TOML))
    res = cablesys.slack.analyze(scene, 4, n_elements=40)
    for res in (res, res.equilibrium, res.modes):
        _check_protocol(res)


def test_no_module_and_function_share_a_name():
    """Packages are nouns and verbs are functions: ``cablesys.simulate`` is a function, never a package
    that hides (or is hidden by) a function of the same name (issue 10)."""
    clashes = []
    for info in pkgutil.walk_packages(cablesys.__path__, "cablesys."):
        module = importlib.import_module(info.name)
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name)
            if info.ispkg and inspect.isfunction(obj) and importlib.util.find_spec(f"{info.name}.{name}"):
                clashes.append(f"{info.name}.{name}")
    for name in cablesys.__all__:
        obj = getattr(cablesys, name)
        if inspect.isfunction(obj) and importlib.util.find_spec(f"cablesys.{name}") is not None:
            clashes.append(f"cablesys.{name}")
    assert not clashes, f"a function and a module share these names: {clashes}"
    assert inspect.isfunction(cablesys.simulate) and inspect.isfunction(cablesys.sweep)
    assert inspect.isfunction(cablesys.design)
