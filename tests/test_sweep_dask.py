"""The same sweep on a Dask LocalCluster (2 worker processes) gives the same Dataset as the local path."""

import numpy as np
import pytest

import cablesys
from cablesys.scene import dale_scene

distributed = pytest.importorskip("distributed", reason="install the sweep extra: pip install -e '.[sweep]'")


@pytest.mark.slow
def test_dask_local_cluster_equals_local_processes(tmp_path):
    scene = dale_scene(duration=2.0)
    vary = {"cable.ae": [20.0, 200.0], "body.weight": [0.2, 0.3, -1.0]}     # -1 N: an invalid case, recorded
    kw = {"metrics": ["tension_*"], "progress": False}
    local = cablesys.sweep(scene, vary, "run", workers=2, **kw)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        remote = cablesys.sweep(scene, vary, "run", scheduler=client, out=tmp_path, **kw)
        assert remote.attrs["backend"] == "dask"
        # the address form connects its own client; everything is stored already, so nothing runs
        again = cablesys.sweep(scene, vary, "run", scheduler=cluster.scheduler_address, out=tmp_path, **kw)
        assert again.attrs["n_computed"] == 0
    assert list(remote.data_vars) == list(local.data_vars)
    np.testing.assert_array_equal(remote["status"].values, local["status"].values)
    np.testing.assert_array_equal(remote["message"].values, local["message"].values)
    for name in remote.data_vars:
        if name.startswith("tension"):
            np.testing.assert_array_equal(remote[name].values, local[name].values)
    assert list(local["status"].values[:, 2]) == ["error", "error"]
