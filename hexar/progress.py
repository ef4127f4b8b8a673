"""What a slow step is doing, said on stderr while a person waits at `hexar ask` or `hexar chat`.

A step that ends within a second says nothing. One that takes longer (the embedded model loading on first use,
the model choosing an explainer on a busy laptop, a long recording being decoded) prints one line saying what it
does as soon as the second has passed, and how long it took when it ends. Only the commands a person waits on
turn this on (`shown`); the page, the live node and the library stay silent. `HEXAR_PROGRESS_AFTER` sets the
delay in seconds (0 says every step, as the tests do).
"""

from __future__ import annotations

import os
import sys
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import TextIO

from hexar.safe_text import visible

_STREAM: TextIO | None = None
_LOCK = threading.Lock()
DEFAULT_AFTER_S = 1.0


@contextmanager
def shown(stream: TextIO | None = None) -> Iterator[None]:
    """Say slow steps on stderr while a command runs, when a person watches it (stderr is a terminal) or
    `HEXAR_PROGRESS=1` asks for it (a log, a test); a pipe or file gets only the answers and errors."""
    global _STREAM
    out = stream or sys.stderr
    wanted = os.environ.get("HEXAR_PROGRESS", "") == "1" or (os.environ.get("HEXAR_PROGRESS", "") != "0"
                                                             and out.isatty())
    before, _STREAM = _STREAM, (out if wanted else _STREAM)
    try:
        yield
    finally:
        _STREAM = before


def _after() -> float:
    try:
        return max(0.0, float(os.environ.get("HEXAR_PROGRESS_AFTER", DEFAULT_AFTER_S)))
    except ValueError:
        return DEFAULT_AFTER_S


def _say(line: str) -> None:
    stream = _STREAM
    if stream is None:
        return
    with _LOCK:
        try:
            stream.write(line + "\n")
            stream.flush()
        except (OSError, ValueError):  # a closed or broken stderr must not break the answer
            pass


@contextmanager
def step(what: str) -> Iterator[None]:
    """Around a step that may be slow: `what` is what it does, in words ("loading the embedded model")."""
    if _STREAM is None:
        yield
        return
    began = time.perf_counter()
    said = threading.Event()

    def announce() -> None:
        said.set()
        _say(f"hexar: {visible(what)}…")

    after = _after()
    timer: threading.Timer | None = None
    if after <= 0:
        announce()
    else:
        timer = threading.Timer(after, announce)
        timer.daemon = True
        timer.start()
    try:
        yield
    finally:
        if timer is not None:
            timer.cancel()
        if said.is_set():
            _say(f"hexar: {visible(what)}: done in {time.perf_counter() - began:.1f} s")
