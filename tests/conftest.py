import os
import sys
from pathlib import Path

import signal

import pytest

os.environ.setdefault("MPLBACKEND", "Agg")
# a test run started as a background job inherits SIGINT ignored, and so would every process it starts; the
# interrupt tests need Python's own SIGINT handling (KeyboardInterrupt), as in a terminal
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)
# The suite builds well over a hundred model structures once each; compiling every one to C
# (cablesys.compiled: seconds per structure on a fresh cache) would dominate CI time. Tests run
# CasADi's virtual machine unless they switch compilation on themselves (tests/test_compiled.py);
# CABLESYS_COMPILE=1 runs the whole suite compiled.
os.environ.setdefault("CABLESYS_COMPILE", "0")
ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture
def run_study(tmp_path):
    """Run ``studies/<name>.py --out tmp --quick`` in a subprocess; return the out folder."""
    import subprocess

    def _run(name, *args):
        out = tmp_path / name
        cmd = [sys.executable, str(ROOT / "studies" / f"{name}.py"), "--out", str(out), *args]
        env = dict(os.environ, MPLBACKEND="Agg")
        proc = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=ROOT)
        assert proc.returncode == 0, f"{name} failed:\n{proc.stdout[-2000:]}\n{proc.stderr[-4000:]}"
        return out
    return _run


@pytest.fixture(scope="module")
def dale():
    """(scene, Wang's model, p) of the Dale et al. scene, built once per test module."""
    from cablesys.model import build_model
    from cablesys.scene import dale_scene
    scene = dale_scene()
    model = build_model(scene)
    return scene, model, model.parameters(scene)


@pytest.fixture(scope="module")
def compiling(tmp_path_factory, request):
    """Compilation on (the suite runs the VM by default), into a cache of the requesting test module."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("CABLESYS_COMPILE", "1")
        mp.setenv("CABLESYS_CACHE", str(tmp_path_factory.mktemp(f"{request.module.__name__}-cache")))
        mp.delenv("CABLESYS_CACHE_DIR", raising=False)
        mp.delenv("CABLESYS_CC", raising=False)
        mp.setenv("CABLESYS_CFLAGS", "-O1")
        yield


@pytest.fixture(scope="module")
def quick_compile(compiling):
    """Compilation on at -O0 (the same C as the default -O1, compiled in half the time)."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("CABLESYS_CFLAGS", "-O0")
        yield
