"""`hexar triage` on this machine: the recordings in this process (one worker) or on forked worker processes.

The pool is forked once the explainers and their models are loaded, so no worker builds them again. Work goes out
in chunks of a few recordings and comes back as the results file's lines: one round trip per chunk, and nothing
for the parent to encode. scikit-learn and LIME (the pizza explainer's, a second and more to import) are loaded by
one worker only: the others hand the recordings that need them back, and the parent passes those to that worker,
which meanwhile keeps triaging the rest. Two workers thus pay the import once, in parallel with the other's work,
not once each or before forking.
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import signal
import threading
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass
from multiprocessing.connection import Connection, wait
from multiprocessing.process import BaseProcess

from hexar.fleet.errors import TriageError
from hexar.fleet.work import warm, work, work_chunk

CHUNK = 8  # recordings per round trip: ~50 ms of work, small against a run, large against a pipe message
IN_FLIGHT = 2  # chunks per worker: the next one waits in its pipe while it works on this one
# Recordings waiting for scikit-learn that make an idle light worker load it too, at the end of the run.
BACKLOG = 2 * CHUNK

Chunk = list[tuple[str, str]]
Reply = tuple[list[str], Chunk]


# The math libraries' own thread pools (OpenBLAS under numpy and scipy, OpenMP under scikit-learn): triage is
# parallel across recordings, a process each, and its matrices are small, so a pool's extra threads only spin on
# the cores the workers need. Measured on the 1,000-recording fleet with one worker: 7.3 s of CPU with them, 4.7 s
# without, the same tasks table.
MATH_THREADS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")


def one_math_thread() -> None:
    """One thread per math library in this process and the workers it starts, unless the user set a number. Read
    when a library loads: called before triage imports numpy (a process that imported it already keeps its pools)."""
    for var in MATH_THREADS:
        os.environ.setdefault(var, "1")


def default_workers() -> int:
    return max(1, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1))


def _serve(conn: Connection) -> None:
    """A worker: chunks in, lines and handed-back recordings out, until told to stop. Ctrl-C is the parent's,
    which stops handing out work and keeps what is finished."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    while (job := conn.recv()) is not None:
        chunk, light = job
        conn.send(work_chunk(chunk, light))


@dataclass
class _Worker:
    process: BaseProcess
    conn: Connection
    light: bool  # has not loaded scikit-learn, and is not to
    out: int = 0  # chunks sent, not yet answered


def run_local(todo: list[tuple[str, str]], workers: int, on_done: Callable[[list[str]], None],
              meanwhile: Callable[[], None] | None = None) -> None:
    """Triage `todo`, passing each batch of finished results-file lines to `on_done` as it arrives. `meanwhile`
    runs on a thread of this process once the workers are forked (a fork must not copy a thread's held lock)."""
    if workers == 1:
        for path, rel in todo:
            on_done([work(path, rel)])
        return
    size = max(1, min(CHUNK, len(todo) // (workers * 4)))
    queue = deque(todo[i:i + size] for i in range(0, len(todo), size))
    left: deque[tuple[str, str]] = deque()  # handed back for a worker with scikit-learn
    warm()
    pool = _start(min(workers, len(queue)))
    if meanwhile is not None:
        threading.Thread(target=meanwhile, name="hexar-triage-meanwhile", daemon=True).start()
    try:
        _feed(pool, queue, left)
        while any(w.out for w in pool):
            for ready in wait([w.conn for w in pool if w.out]):
                w = next(w for w in pool if w.conn is ready)
                lines, back = w.conn.recv()
                w.out -= 1
                left.extend(back)
                if lines:
                    on_done(lines)
                _feed(pool, queue, left)
    except (EOFError, OSError) as err:  # a worker's end of a pipe closed: it was killed, or crashed
        codes = ", ".join(str(w.process.exitcode) for w in pool if w.process.exitcode is not None)
        raise TriageError(f"a triage worker stopped (exit code {codes or 'unknown'}); run the same command "
                          "again to finish the rest") from err
    finally:
        _stop(pool)


def _start(n: int) -> list[_Worker]:
    ctx = multiprocessing.get_context("fork")
    pool = []
    for i in range(n):
        parent, child = ctx.Pipe()
        proc = ctx.Process(target=_serve, args=(child,), daemon=True)
        proc.start()
        child.close()
        pool.append(_Worker(proc, parent, light=i > 0))
    return pool


def _feed(pool: list[_Worker], queue: deque[Chunk], left: deque[tuple[str, str]]) -> None:
    """Top every worker up to IN_FLIGHT chunks: handed-back recordings first to a worker that loads scikit-learn,
    else fresh ones; at the end, a long line of handed-back ones lets a light worker load it too."""
    for w in pool:
        while w.out < IN_FLIGHT:
            if w.light and not queue and len(left) >= BACKLOG:
                w.light = False
            if not w.light and left:
                chunk = [left.popleft() for _ in range(min(CHUNK, len(left)))]
            elif queue:
                chunk = queue.popleft()
            else:
                break
            w.conn.send((chunk, w.light))
            w.out += 1


def _stop(pool: list[_Worker]) -> None:
    """Finished: each worker is told to stop. Interrupted or failed: unfinished chunks are dropped (the
    results file has what is done), so the workers are ended rather than waited for."""
    for w in pool:
        if w.out == 0 and w.process.is_alive():
            with contextlib.suppress(OSError):  # it died meanwhile: join below reaps it
                w.conn.send(None)
        else:
            w.process.terminate()
    for w in pool:
        w.process.join()
        w.conn.close()
