"""flightmode.cluster on a real LocalCluster of two worker processes (kept short: one cluster, a few
tasks of the standard library's own functions, so the workers import nothing of the tests)."""

from __future__ import annotations

import operator
import os
import signal
from urllib.parse import urlparse

import pytest

from flightmode import cluster
from flightmode.errors import ClusterError


def test_in_process_map_keeps_order_and_reports_each_call():
    seen = []
    assert cluster.map_flights(operator.mul, [(1, 2), (3, 4), (5, 6)], 1, seen.append) == [2, 12, 30]
    assert seen == [0, 1, 2]


def test_a_local_cluster_of_two_processes_maps_in_order_and_raises_a_failure():
    with cluster.open_client(2) as c:
        info = c.scheduler_info()
        assert len(info["workers"]) == 2
        assert all(w["nthreads"] == 1 for w in info["workers"].values())
        assert all(urlparse(a).hostname == cluster.HOST for a in info["workers"])
        assert urlparse(c.dashboard_link).hostname == cluster.HOST
        # the measured tuning reaches every worker process: no statistical profiler
        assert set(
            c.run(lambda: __import__("dask").config.get("distributed.worker.profile.enabled")).values()
        ) == {False}
        # glibc's mmap threshold fixed at its dynamic maximum (cluster._config: Dask's trim threshold
        # alone turned the dynamic one off, and sensing took twice as long in a worker)
        assert set(c.run(os.environ.get, "MALLOC_MMAP_THRESHOLD_").values()) == {
            str(cluster.GLIBC_MMAP_THRESHOLD_MAX)
        }
        # Ctrl-C is the client's: the worker processes ignore SIGINT (cluster.dask_setup), so the
        # interrupt that reaches the whole process group prints no worker traceback
        assert set(c.run(signal.getsignal, signal.SIGINT).values()) == {signal.SIG_IGN}
        seen = []
        args = [(i, i + 1) for i in range(6)]
        got = cluster.map_flights(
            operator.mul, args, on_done=seen.append, client=c, keys=[f"t-{i}" for i in range(6)]
        )
        assert got == [i * (i + 1) for i in range(6)]
        assert sorted(seen) == list(range(6))
        with pytest.raises(ZeroDivisionError):
            cluster.map_flights(operator.truediv, [(1, 1), (1, 0)], client=c)
        # the same workers reached through their scheduler's address (many machines: `dask scheduler`)
        assert cluster.map_flights(operator.add, [(1, 2), (3, 4)], scheduler=c.scheduler.address) == [3, 7]


def test_a_scheduler_that_does_not_answer_is_a_cluster_error(monkeypatch):
    monkeypatch.setattr(cluster, "SCHEDULER_TIMEOUT", "1s")  # the same path as the 5 s default, sooner
    with pytest.raises(ClusterError, match="does not answer"):  # discard port 9: nothing listens
        with cluster.open_client(scheduler="tcp://127.0.0.1:9"):
            pass


def test_keys_must_match_the_calls():
    with pytest.raises(ValueError, match="2 keys for 1 calls"):
        cluster.map_flights(operator.mul, [(1, 2)], 2, keys=["a", "b"])


def test_importing_flightmode_cluster_does_not_import_dask():
    import subprocess
    import sys

    code = "import sys, flightmode.cluster; print('dask' in sys.modules)"
    assert (
        subprocess.run([sys.executable, "-c", code], capture_output=True, text=True).stdout.strip() == "False"
    )
