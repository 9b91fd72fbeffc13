"""The one Dask module: the tuned local cluster (or a scheduler's address for many machines) and the
map of one task per flight over it.

Used by the dataset writer, the detector sweep (and so certify), the population validation, the e-obs
trade-off and seed 001's Monte Carlo study. Dask is imported only inside the functions (importing
flightmode never starts it). Dask's documentation: "Dask.distributed: LocalCluster" and "Futures"
(``Client.submit``, ``as_completed``), https://distributed.dask.org.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from typing import Any

from flightmode.errors import ClusterError

HOST = "127.0.0.1"  # the local cluster listens on the loopback interface only
SCHEDULER_TIMEOUT = "5s"  # a scheduler address that does not answer in this time is an error
WORKER_WAIT_S = 30.0  # a scheduler with no worker after this long is an error


# glibc's largest dynamic mmap threshold on 64-bit systems (DEFAULT_MMAP_THRESHOLD_MAX, 4 Mi * sizeof(long):
# mallopt(3), M_MMAP_THRESHOLD)
GLIBC_MMAP_THRESHOLD_MAX = 32 * 2**20


def _config() -> dict[str, Any]:
    """The Dask settings every flightmode cluster runs with: no statistical profiler (it samples the
    task thread's stack every 10 ms), and glibc's allocator as a plain process has it once warm.

    Dask sets MALLOC_TRIM_THRESHOLD_ in its workers (65536: memory handed back to the system at once).
    Setting any of glibc's thresholds turns off its dynamic mmap threshold (mallopt(3)), so every block
    over 128 KiB, every array of a flight, was a fresh mmap whose pages the kernel zeroes again: one
    flight's sensing took 2.3-2.5 s in a process started with that variable (2**30 as well) against
    1.2 s without, the flying 7.3 s against 6.9 s (airline-mix member 2, a Fokker 100, 1.2 h). So the
    workers get both thresholds where a warm plain process has them: mmap above glibc's dynamic
    maximum (32 MiB), no trimming below 1 GiB (a flight's arrays are freed and made again each
    flight: handing them back only to fault them in again costs time, and the workers have no memory
    limit). Measured in a worker before the mmap threshold: the profiler off took one flight from
    13.6-14.3 s to 11.2-11.9 s, against 9.1-10.1 s in a plain process."""
    return {
        "distributed.worker.profile.enabled": False,
        "distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": 2**30,
        "distributed.nanny.pre-spawn-environ.MALLOC_MMAP_THRESHOLD_": GLIBC_MMAP_THRESHOLD_MAX,
    }


def dask_setup(worker: Any) -> None:
    """The local cluster's worker preload (Dask calls a preload module's ``dask_setup`` as each worker
    starts): the worker process ignores SIGINT. Ctrl-C at a terminal sends SIGINT to the whole
    foreground process group, the LocalCluster's worker processes too; each then died printing
    KeyboardInterrupt's traceback from its event loop over the one line the command prints. The
    client alone handles the interrupt: it closes the cluster, whose nannies stop their workers."""
    import signal
    import threading

    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.SIG_IGN)


@contextmanager
def open_client(
    workers: int = 2, scheduler: str | None = None, *, allowed_failures: int = 3
) -> Iterator[Any]:
    """A ``dask.distributed.Client``, closed (with its cluster) when the block ends.

    ``scheduler`` None: a LocalCluster of ``workers`` processes of one thread each (one flight per
    worker process at a time bounds its memory), on 127.0.0.1 with the dashboard on a free local
    port, no memory limit (a flight's arrays are what they are; Dask's pausing and spilling only slow
    it), the workers' logs silenced (a failed task's error reaches the caller). ``scheduler``
    ``tcp://HOST:PORT``: that scheduler's workers (many machines); a :class:`ClusterError` if it
    does not answer within 5 s or has no worker within 30 s. ``allowed_failures``: how many times
    Dask re-runs a task whose worker died elsewhere (Dask's default, 3: a study's flight is pure and
    is simply run again; the dataset passes 0, since it retries and records failures itself)."""
    import logging

    import dask
    from dask.distributed import Client, LocalCluster

    if scheduler is not None:
        try:
            c = Client(scheduler, timeout=SCHEDULER_TIMEOUT)
        except Exception as e:
            raise ClusterError(
                f"the Dask scheduler at {scheduler} does not answer ({type(e).__name__}): start it "
                "with `dask scheduler` (address tcp://HOST:PORT), or drop --scheduler to run on "
                "this machine"
            ) from None
        # a scheduler lost mid-run: the client's reconnect loop logs its tracebacks on standard error,
        # while the caller turns the cancelled futures into one line (datasets.make); silenced as the
        # local cluster's logs are, for the client's life
        log = logging.getLogger("distributed.client")
        level = log.level
        log.setLevel(logging.CRITICAL + 1)
        try:
            try:
                c.wait_for_workers(1, timeout=WORKER_WAIT_S)
            except Exception:
                raise ClusterError(
                    f"the Dask scheduler at {scheduler} has no worker: start some with `dask worker {scheduler}`"
                ) from None
            yield c
        finally:
            c.close()
            log.setLevel(level)
        return
    if isinstance(workers, bool) or not isinstance(workers, int) or workers <= 0:
        raise ClusterError(f"--workers {workers!r}: must be a positive integer")
    with dask.config.set({**_config(), "distributed.scheduler.allowed-failures": int(allowed_failures)}):
        cluster = LocalCluster(
            n_workers=workers,
            threads_per_worker=1,
            processes=True,
            host=HOST,
            dashboard_address=f"{HOST}:0",
            memory_limit=0,
            silence_logs=logging.CRITICAL,
            preload=[__name__],  # dask_setup above: the workers leave Ctrl-C to the client
        )
    try:
        with Client(cluster) as c:
            yield c
    finally:
        cluster.close()


def map_flights(
    fn: Callable,
    args: Sequence[tuple],
    workers: int = 1,
    on_done: Callable[[int], None] | None = None,
    *,
    client: Any = None,
    scheduler: str | None = None,
    keys: Sequence[str] | None = None,
) -> list:
    """``[fn(*a) for a in args]``, one task per flight, results in the order of ``args`` whatever the
    completion order; ``on_done(n)`` as call ``n`` (its position in ``args``) finishes.

    Runs in this process when ``workers`` <= 1 and neither ``client`` nor ``scheduler`` is given;
    on ``client`` when given; else on :func:`open_client` (``workers`` processes, or ``scheduler``).
    ``keys``: Dask task keys, one per call (unique to the work, so two studies sharing a scheduler
    never share a task); default Dask's own. The first failed call's error is raised."""
    args = list(args)
    if keys is not None and len(keys) != len(args):
        raise ValueError(f"map_flights: {len(keys)} keys for {len(args)} calls")
    if client is None and scheduler is None and workers <= 1:
        out = []
        for n, a in enumerate(args):
            out.append(fn(*a))
            if on_done:
                on_done(n)
        return out
    if client is None:
        with open_client(workers, scheduler) as c:
            return _map(c, fn, args, on_done, keys)
    return _map(client, fn, args, on_done, keys)


def _map(c, fn, args: list, on_done, keys) -> list:
    from dask.distributed import as_completed

    futs = {}
    for n, a in enumerate(args):
        kw = {"key": keys[n]} if keys is not None else {}
        futs[c.submit(fn, *a, pure=False, **kw)] = n
    done: dict[int, object] = {}
    for f in as_completed(futs):
        done[futs[f]] = f.result()
        if on_done:
            on_done(futs[f])
    return [done[n] for n in range(len(args))]


__all__ = ["HOST", "open_client", "map_flights"]
