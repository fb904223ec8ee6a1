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


class _DictStore:
    """A stand-in for the disk store: keeps what it is offered."""

    def __init__(self, items=None):
        self.items, self.saved = dict(items or {}), []

    def load(self, key):
        return self.items.get(key)

    def save(self, key, item):
        self.saved.append(key)
        self.items[key] = item


def test_attached_store_is_asked_before_building_and_offered_what_is_built():
    store = _DictStore({"stored": "from disk"})
    cache, calls = FunctionCache(), []
    cache.attach(store)
    assert cache.store is store
    assert cache.get("stored", lambda: calls.append(1) or "built") == "from disk" and not calls
    assert cache.get("new", lambda: calls.append(1) or "built") == "built" and calls == [1]
    assert store.saved == ["new"] and cache.hits == 1
    assert cache.get("new", lambda: calls.append(1)) == "built" and calls == [1]    # memory first
    copy = pickle.loads(pickle.dumps(cache))            # another process: no items, the same store
    assert len(copy) == 0 and isinstance(copy.store, _DictStore) and copy.get("new", lambda: None) == "built"
