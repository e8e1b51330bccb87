"""The same per-capture unit on a Dask distributed cluster (optional: ``pip install 'mdpipe[dask]'``).

``tcp://HOST:8786`` connects to a running ``dask scheduler``, whose ``dask worker`` s read the captures and
write OUT through a filesystem they share with this machine (the paths given must be valid there too);
``local`` starts a ``LocalCluster`` of ``workers`` single-threaded worker processes here.
"""

import logging
import os
import secrets
from dataclasses import replace

from mdpipe.batch import unit
from mdpipe.errors import MdpipeError

INSTALL = "pip install 'mdpipe[dask]'"
CONNECT_TIMEOUT_S = 10


class SchedulerError(MdpipeError):
    """Dask is missing or its scheduler cannot be reached."""


def _client(scheduler, workers):
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise SchedulerError(f"--scheduler needs Dask distributed, which is not installed: {INSTALL}") from None
    if scheduler == "local":
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None,
                               silence_logs=logging.ERROR)
        return Client(cluster), cluster
    try:
        return Client(scheduler, timeout=CONNECT_TIMEOUT_S), None
    except (OSError, ValueError, TypeError) as exc:
        raise SchedulerError(f"cannot reach the Dask scheduler at {scheduler} ({exc}); start one there with "
                             "`dask scheduler`, or use --scheduler local") from None


def execute(jobs, *, scheduler, workers):
    """Yield the :class:`mdpipe.batch.unit.Outcome` of every job as it finishes on the cluster."""
    client, cluster = _client(scheduler, workers)
    from distributed import as_completed

    # the workers run elsewhere (another folder, another machine): absolute paths, valid on the shared mount
    jobs = [replace(job, capture=os.path.abspath(job.capture), out_dir=os.path.abspath(job.out_dir), given=job.capture)
            for job in jobs]

    token = secrets.token_hex(4)
    futures, finished = {}, False
    try:
        futures = {client.submit(unit.run, job, key=f"mdpipe-{token}-{i}", pure=False): job
                   for i, job in enumerate(jobs)}
        for future in as_completed(futures):
            try:
                outcome = future.result()
            except Exception as exc:  # the task itself never raises: its worker died or could not run it
                job = futures[future]
                outcome = unit.failure(job, f"{job.capture}: the Dask worker failed ({type(exc).__name__}: {exc})")
            yield outcome
        finished = True
    finally:
        if not finished:
            client.cancel(list(futures))
        client.close()
        if cluster is not None:
            cluster.close()
