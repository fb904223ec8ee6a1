"""The ladder's choice as users get it (compiled C) and as the suite runs (CasADi's VM, tests/conftest.py).

:func:`cablesys.ladder.choice.choose` prices the rungs as they will run, by ``compiles()`` (compilation on and a C compiler found)
(:func:`~cablesys.ladder.choice.element_plan`: the quasi-static segmented cable competes by cost only compiled;
``_pick``: where nothing drives the swing the quasi-static rung goes first only compiled). :func:`priced` sets that
pricing alone; the linear response the estimates rest on is evaluated as ``CABLESYS_COMPILE`` says (the VM in the
suite), so a decision test builds no C there (compiled, the choice itself compiles Wang's describing-function
residual and its per-phase Jacobian, mapped over 16 phases: a small library, once a structure on a fresh cache). Runs compiled as users run them are
in tests/test_ladder_compiled.py.
"""

import contextlib
import re

import pytest

from cablesys.ladder import choice as ch

VM_NOTE = "compiled code is off (CasADi's virtual machine): with it the ladder would run"


@contextlib.contextmanager
def priced(compiled: bool):
    """Within the block the ladder prices its rungs as compiled code (``compiled``) or the VM runs them."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(ch, "compiles", lambda enabled=True: bool(compiled and enabled))
        yield


def said(compiled, vm) -> None:
    """Assert the VM choice's reason names the compiled choice (rung and N) when the two differ, and says nothing of
    compiled code when they agree; the compiled reason never does."""
    assert "compiled code is off" not in compiled.reason
    if (compiled.name, compiled.segments) == (vm.name, vm.segments):
        assert "compiled code is off" not in vm.reason, vm.reason
    else:
        n = f" N = {compiled.segments}" if compiled.segments > 1 else ""
        assert re.search(re.escape(f"{VM_NOTE} {compiled.name}{n}") + "(;|$)", vm.reason), vm.reason


def both(scene, tolerance=None, **kw):
    """(compiled, VM) choices of ``scene`` by :func:`~cablesys.ladder.choice.choose`, checked by :func:`said`."""
    with priced(True):
        compiled = ch.choose(scene, tolerance, **kw)
    with priced(False):
        vm = ch.choose(scene, tolerance, **kw)
    said(compiled, vm)
    return compiled, vm
