"""`hexar triage --ray`: the same per-recording work as Ray tasks, on a local Ray instance or a cluster.

The only module of HEXAR that imports Ray (the optional `fleet` extra). On a cluster every node needs HEXAR
installed and the recordings at the same path (a shared file system); results come back to the driver, which
appends them to the same results file as the local pool.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from typing import Any

from hexar.fleet.errors import TriageError
from hexar.fleet.work import warm, work

IN_FLIGHT_PER_CPU = 4  # submitted but unfinished tasks: bounded, so the driver's memory stays flat


def run_ray(todo: list[tuple[str, str]], address: str, workers: int | None,
            on_done: Callable[[list[str]], None]) -> None:
    try:
        import ray
    except ImportError as err:
        raise TriageError("--ray needs Ray: pip install 'hexar[fleet]'") from err
    started = not ray.is_initialized()
    try:
        if started:
            if address:
                ray.init(address=address, logging_level=logging.ERROR, log_to_driver=False)
            else:
                ray.init(num_cpus=workers, include_dashboard=False, logging_level=logging.ERROR, log_to_driver=False)
    except (ConnectionError, RuntimeError, ValueError) as err:
        raise TriageError(f"cannot start or reach Ray at {address or 'a local instance'}: {err}") from err

    @ray.remote(num_cpus=1)
    def triage_task(path: str, rel: str) -> str:
        warm()
        return work(path, rel)

    try:
        cpus = ray.cluster_resources().get("CPU", 1)  # type: ignore[no-untyped-call]
        window = max(1, int(cpus)) * IN_FLIGHT_PER_CPU
        queue = iter(todo)
        pending = [triage_task.remote(path, rel) for path, rel in _take(queue, window)]
        while pending:
            finished, pending = ray.wait(pending, num_returns=1)
            on_done([ray.get(ref) for ref in finished])
            pending += [triage_task.remote(path, rel) for path, rel in _take(queue, len(finished))]
    except KeyboardInterrupt:
        for ref in pending:
            ray.cancel(ref, force=True)
        raise
    finally:
        if started:
            ray.shutdown()


def _take(queue: Any, n: int) -> list[tuple[str, str]]:
    out = []
    for _ in range(n):
        item = next(queue, None)
        if item is None:
            break
        out.append(item)
    return out
