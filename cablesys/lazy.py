"""Lazy public names of a package (PEP 562): ``import cablesys.linear`` does not import SciPy's
statistics or CasADi until a name is used, so the command line and its ``--help`` start fast."""

from __future__ import annotations

import importlib


def lazy_exports(package: str, exports: dict, public: list):
    """Module ``__getattr__`` and ``__dir__`` for ``package`` importing each public name on first use.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    exports : dict
        Public name -> module that defines it, relative to the package (``".modal"``, ``"..integration"``).
    public : list
        The package's ``__all__``.

    Returns
    -------
    (callable, callable)
        ``__getattr__`` and ``__dir__`` for the package's namespace.
    """
    import sys

    def __getattr__(name):
        if name in exports:
            value = getattr(importlib.import_module(exports[name], package), name)
            setattr(sys.modules[package], name, value)
            return value
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def __dir__():
        return sorted(set(vars(sys.modules[package])) | set(public))

    return __getattr__, __dir__
