"""One Dask cluster for the whole test session (2 worker processes, 1 thread each).

Every test that needs a running cluster takes :func:`dask_client`; they are grouped on one pytest-xdist worker
(``xdist_group("dask")``, run with ``--dist loadgroup``), so a session starts one cluster, not one per module or test.
Tests that kill a worker, start a scheduler of their own or run the ``throwmap sweep`` command (which starts its own
local cluster, as a user's run does) are the exceptions.
"""

from __future__ import annotations

import logging

import pytest


@pytest.fixture(scope="session")
def dask_client():
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0",
                                  silence_logs=logging.CRITICAL) as cluster, distributed.Client(cluster) as c:
        yield c
