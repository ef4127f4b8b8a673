"""`kill -USR1` on a running serve (live/stacks.py): every thread's stack on stderr, printed by a thread of its own,
and the process's signal state as it was afterwards."""

from __future__ import annotations

import os
import signal
import sys
import threading
import time

import pytest

from hexar.live.stacks import format_stacks, stacks_on_request


def _parked(ready: threading.Event, release: threading.Event) -> None:
    ready.set()
    release.wait(10)


def test_sigusr1_prints_each_threads_stack_innermost_first(capfd: pytest.CaptureFixture[str]) -> None:
    ready, release = threading.Event(), threading.Event()
    worker = threading.Thread(target=_parked, args=(ready, release), name="robot-reader")
    worker.start()
    ready.wait(5)
    try:
        with stacks_on_request():
            os.kill(os.getpid(), signal.SIGUSR1)
            err, deadline = "", time.monotonic() + 5
            while "robot-reader" not in err and time.monotonic() < deadline:
                time.sleep(0.05)
                err += capfd.readouterr().err
    finally:
        release.set()
        worker.join(5)
    header = next(line for line in err.splitlines() if "robot-reader" in line)
    assert header.startswith("Thread 0x") and header.endswith("most recent call first):")
    block = err.split(header, 1)[1].lstrip("\n").split("\n\n", 1)[0].splitlines()
    # innermost first: the Event's wait, then the function that parked the thread
    assert "in wait" in block[0] and any(line.endswith("in _parked") for line in block)
    assert "test_sigusr1_prints_each_threads_stack_innermost_first" in err  # the main thread's stack too


def test_the_previous_handler_and_wakeup_fd_come_back() -> None:
    before = signal.getsignal(signal.SIGUSR1)
    with stacks_on_request():
        assert signal.getsignal(signal.SIGUSR1) is not before
    assert signal.getsignal(signal.SIGUSR1) is before
    assert signal.set_wakeup_fd(-1) == -1  # none left behind


def test_another_wakeup_fd_is_left_alone() -> None:
    read_fd, write_fd = os.pipe()
    os.set_blocking(write_fd, False)
    signal.set_wakeup_fd(write_fd)
    before = signal.getsignal(signal.SIGUSR1)
    try:
        with stacks_on_request():
            assert signal.getsignal(signal.SIGUSR1) is before
        assert signal.set_wakeup_fd(-1) == write_fd
    finally:
        os.close(read_fd)
        os.close(write_fd)


def test_format_stacks_names_an_unknown_thread() -> None:
    frame = sys._getframe()
    text = format_stacks({0x1234: frame}, {})
    assert text.startswith("Thread 0x0000000000001234 (unnamed; most recent call first):")
    assert 'in test_format_stacks_names_an_unknown_thread' in text.splitlines()[1]
