"""A process that a signal ended, as launch reports it (stable API).

    killed_by_signal(msg) -> bool
    ended_by(msg) -> Signal | None

launch's "process has died [pid N, exit code -11, cmd '…']" (launch/actions/execute_local.py) gives a process that a
signal ended the signal's number, negated (asyncio's returncode). What each signal says of the death is the signal's
POSIX meaning (signal(7)); who sent it is not in the line: SIGKILL is what the kernel's out-of-memory killer sends,
and `kill -9` too.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

_EXIT = re.compile(r"exit code (-\d+)")  # a signal's number, negated


@dataclass(frozen=True)
class Signal:
    number: int
    name: str
    happened: str  # what it did to the process, in words for a person ("crashed" is navigation's claim word)
    fix: str


_SIGNALS = {
    4: ("SIGILL", "ended on an illegal instruction", "A program built for another CPU, or a corrupt binary: "
        "rebuild it on this machine."),
    6: ("SIGABRT", "aborted itself", "Read its lines just before: an uncaught C++ exception (\"terminate called after "
        "throwing\") or a failed assertion aborts a program."),
    7: ("SIGBUS", "ended on a bus error", "Often a shared-memory file that is full or gone (/dev/shm): check its "
        "free space, then run the program under gdb for the backtrace."),
    8: ("SIGFPE", "ended on an arithmetic error (a division by zero)", "Run it under gdb (the launch prefix "
        "'gdb -ex run --args') for the line that divided; check the parameters that can be zero."),
    9: ("SIGKILL", "was killed, and nothing in my logs says by whom: the kernel's out-of-memory killer sends that "
        "signal, and so does kill -9", "Check the kernel's log for the out-of-memory killer (journalctl -k | grep -i "
        "oom, or dmesg) and the process's memory use; give it more memory or load less."),
    11: ("SIGSEGV", "ended on a segmentation fault (a crash), and nothing in my logs says where",
         "Run it under gdb (the launch prefix 'gdb -ex run --args') or read its core dump for the backtrace; "
         "packages built against different versions of a library (a binary install mixed with a source build) "
         "crash this way too."),
}


def killed_by_signal(msg: str) -> bool:
    """launch reports a process that a signal ended (a crash: SIGSEGV -11, SIGABRT -6) with a negative exit code."""
    found = _EXIT.search(msg)
    return found is not None and int(found[1]) < 0


def ended_by(msg: str) -> Signal | None:
    """The crash or kill launch's death line reports; None for an exit code, or for a signal that stops a program on
    request (SIGINT, SIGTERM: a shutdown)."""
    found = _EXIT.search(msg)
    if found is None or -int(found[1]) not in _SIGNALS:
        return None
    number = -int(found[1])
    name, happened, fix = _SIGNALS[number]
    return Signal(number, name, happened, fix)
