"""`hexar triage` on this machine: the recordings in this process (one worker) or on a forked process pool."""

from __future__ import annotations

import os
import signal
from collections.abc import Callable, Iterator
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from typing import Any

from hexar.fleet.work import warm, work


def default_workers() -> int:
    return max(1, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1))


def _ignore_sigint() -> None:
    """Workers leave Ctrl-C to the parent, which stops handing out work and keeps what is finished."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def run_local(todo: list[tuple[str, str]], workers: int, on_done: Callable[[dict[str, Any]], None]) -> None:
    if workers == 1:
        for path, rel in todo:
            on_done(work(path, rel))
        return
    import multiprocessing

    warm()
    with ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("fork"),
                             initializer=_ignore_sigint) as pool:
        pending: set[Future[dict[str, Any]]] = set()
        queue: Iterator[tuple[str, str]] = iter(todo)
        try:
            # A bounded window of submitted work: memory stays flat for any number of recordings.
            for path, rel in queue:
                pending.add(pool.submit(work, path, rel))
                if len(pending) >= workers * 4:
                    break
            while pending:
                finished, pending = wait(pending, return_when=FIRST_COMPLETED)
                for fut in finished:
                    on_done(fut.result())
                    nxt = next(queue, None)
                    if nxt is not None:
                        pending.add(pool.submit(work, *nxt))
        except KeyboardInterrupt:
            for fut in pending:
                fut.cancel()
            raise
