"""`kill -USR1 PID` prints every thread's stack to stderr, and `hexar serve` goes on: a serve that will not end
after SIGTERM (a DDS call that blocks) shows where, without a debugger on the robot.

faulthandler's all-threads dump did this before, from inside the signal handler and without the GIL, walking the
interpreter's thread states while other threads may be creating or ending theirs; in one CI run on Python 3.13 a
serve on the DDS transport died with SIGSEGV right after the signal. Here the signal's only effect is a byte on a pipe
(`signal.set_wakeup_fd`, written by the C-level handler whichever thread is running), and a thread of its own reads
it and prints the stacks under the GIL from `sys._current_frames()`, in faulthandler's format. That thread runs even
while the main thread waits in a C call that released the GIL (closing a DDS participant), which a Python-level
handler, run by the main thread only, would not.
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
import threading
import traceback
from collections.abc import Iterator
from types import FrameType


def format_stacks(frames: dict[int, FrameType], names: dict[int, str]) -> str:
    """Each thread's stack, innermost call first, as faulthandler prints it (with the thread's name)."""
    out = []
    for ident, frame in frames.items():
        out.append(f"Thread 0x{ident:016x} ({names.get(ident, 'unnamed')}; most recent call first):")
        out += [f'  File "{fs.filename}", line {fs.lineno} in {fs.name}'
                for fs in reversed(traceback.extract_stack(frame))]
        out.append("")
    return "\n".join(out)


def _print_stacks() -> None:
    names = {t.ident: t.name for t in threading.enumerate() if t.ident is not None}
    with contextlib.suppress(OSError, ValueError):  # a stderr closed under us: nowhere to print
        sys.stderr.write(format_stacks(sys._current_frames(), names))
        sys.stderr.flush()


@contextlib.contextmanager
def stacks_on_request() -> Iterator[None]:
    """While inside: SIGUSR1 prints every thread's stack. The previous SIGUSR1 handler and wakeup fd come back
    afterwards (the CLI also runs inside tests). Off the main thread, or without SIGUSR1, it does nothing."""
    if threading.current_thread() is not threading.main_thread() or not hasattr(signal, "SIGUSR1"):
        yield
        return
    read_fd, write_fd = os.pipe()
    os.set_blocking(write_fd, False)  # the C handler must never block on a full pipe
    previous_fd = signal.set_wakeup_fd(write_fd, warn_on_full_buffer=False)
    if previous_fd != -1:  # an event loop's wakeup fd is not ours to take: no stacks then
        signal.set_wakeup_fd(previous_fd)
        os.close(read_fd)
        os.close(write_fd)
        yield
        return
    previous = signal.signal(signal.SIGUSR1, lambda *_: None)  # the C handler writes the byte; nothing else to do

    def watch() -> None:
        while True:
            try:
                got = os.read(read_fd, 64)
            except OSError:
                return
            if not got:
                return  # the write end closed: the context ended
            if signal.SIGUSR1 in got:
                _print_stacks()

    watcher = threading.Thread(target=watch, name="hexar-stacks", daemon=True)
    watcher.start()
    try:
        yield
    finally:
        signal.signal(signal.SIGUSR1, previous)
        signal.set_wakeup_fd(previous_fd)
        os.close(write_fd)
        watcher.join(1.0)
        os.close(read_fd)
