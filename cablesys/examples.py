"""Example scenes shipped with the package (``cablesys/data/*.toml``)."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

EXAMPLES = {"rov-lift": "rov_lift.toml", "light-lift": "light_lift.toml", "clump-span": "clump_span.toml",
            "dual-isolation": "dual_isolation.toml"}


def example_path(name: str) -> Path:
    """Path of a shipped example scene by its name (``rov-lift``) or file name."""
    from .errors import ParameterError
    file = EXAMPLES.get(name, name)
    path = Path(str(resources.files("cablesys") / "data" / file))
    if not path.is_file():
        raise ParameterError("example", name, f"must be one of {sorted(EXAMPLES)}")
    return path


def example_text(name: str) -> str:
    """The TOML text of a shipped example scene."""
    return example_path(name).read_text()
