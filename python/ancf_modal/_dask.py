"""``ancf_modal.sweep(..., client=client)``: a parameter study's points on a
Dask cluster (``dask.distributed``, imported only when a client is given;
``pip install "./python[dask]"``).

The extension checks the request first, as a local sweep does; then
:func:`run_shards` sends the model to the workers once (scattered) and the
grid as shards ``k/n`` (point ``i`` in shard ``i mod n + 1``: every part of
the grid in every shard, so the shards take about the same time), about
:data:`CHUNKS_PER_THREAD` per worker thread. Each task is the local
sweep's own evaluation of its shard, ``sweep(..., threads=1, shard=(k, n))``,
on the one thread the worker gives it; its points' warnings are the
client's to raise, so the worker drops them. The extension joins the
gathered shards (``SweepJob::join``: as ``sweep_merge`` joins shards, then
the modes tracked in index order), which gives the local result.
"""

import importlib
import uuid
import warnings
from typing import Any, Dict, List, Mapping

from ._native import ModelError, ModelWarning, SweepResult, sweep

# Shards per worker thread: enough that a slow shard or a late worker leaves
# the others little to wait for, few enough that a task's fixed cost (the
# request resolved again on the worker, a few milliseconds with Dask's own)
# stays small beside its points.
CHUNKS_PER_THREAD = 4


def shard_count(total: int, threads: int) -> int:
    """How many shards ``total`` points are split into for ``threads``
    worker threads (at least one, at most one point each)."""
    return max(1, min(total, CHUNKS_PER_THREAD * max(threads, 1)))


def run_shard(
    model: Any, params: Mapping[str, Any], quantity: str, options: Dict[str, Any], k: int, n: int
) -> SweepResult:
    """One task: shard ``k/n`` of the sweep, its points on this thread."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        return sweep(model, params, quantity, threads=1, shard=(k, n), **options)


def run_shards(
    client: Any,
    model: Any,
    params: Mapping[str, Any],
    quantity: str,
    options: Dict[str, Any],
    total: int,
    progress: bool,
) -> List[SweepResult]:
    """The shards of the sweep of ``total`` points computed on ``client``'s
    workers, in the order of ``k``; with ``progress`` Dask's progress bar
    while they run. An interrupt (or a task's exception) cancels the rest."""
    # Imported here, only with a client; its functions are untyped, so Any.
    distributed: Any = importlib.import_module("distributed")

    if not isinstance(client, distributed.Client):
        raise ModelError(
            f"client `{client!r}`: must be a dask.distributed.Client (or None: on this machine)"
        )
    if client.status != "running":
        raise ModelError(
            f"client `{client!r}`: its status is `{client.status}`, not running "
            "(a closed client, or one whose cluster was closed: open a new one)"
        )
    threads = sum(client.nthreads().values())
    if threads == 0:
        raise ModelError(
            f"client `{client!r}`: its cluster has no workers yet "
            "(start some, and wait for them: client.wait_for_workers(n))"
        )
    n = shard_count(total, threads)
    tag = uuid.uuid4().hex[:12]
    scattered = client.scatter(model, hash=False)
    futures = [
        client.submit(
            run_shard,
            scattered,
            params,
            quantity,
            options,
            k,
            n,
            key=f"ancf-modal-sweep-{tag}-{k}of{n}",
            pure=False,
        )
        for k in range(1, n + 1)
    ]
    try:
        if progress:
            distributed.progress(futures)
        # Waited for here, then gathered: an interrupt while gather waits
        # leaves Dask's own waiting tasks failing noisily.
        for _ in distributed.as_completed(futures):
            pass
        return list(client.gather(futures))
    except BaseException:
        client.cancel(futures)
        raise
    finally:
        client.cancel([scattered])
