"""The model's explicit cache of derived functions (no mutable dict field, no module-level cache)."""

import dataclasses
import pickle
import threading

from cablesys.linear import linearize
from cablesys.model import FunctionCache, build_model
from cablesys.scene import dale_scene


def test_cache_builds_once_per_key_even_from_threads():
    cache, calls = FunctionCache(), []

    def build():
        calls.append(1)
        return object()

    got = []
    threads = [threading.Thread(target=lambda: got.append(cache.get("k", build))) for _ in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(calls) == 1 and all(g is got[0] for g in got)
    assert "k" in cache and len(cache) == 1 and cache.keys() == ("k",)
    assert len(pickle.loads(pickle.dumps(cache))) == 0       # a copy elsewhere builds its own
    cache.clear()
    assert len(cache) == 0


def test_model_cache_is_per_model_and_a_replaced_copy_starts_empty():
    scene = dale_scene()
    model = build_model(scene)
    linearize(model, model.parameters(scene))
    assert "linearize" in model.cache and "static_residual" in model.cache
    other = dataclasses.replace(model, kind="copy")
    assert len(other.cache) == 0 and other.cache is not model.cache
    assert "cache" not in {f.name for f in dataclasses.fields(model) if f.init}
