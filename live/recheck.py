"""Second looks at unasked explanations, for networks that deliver late.

A robot on a lossy Wi-Fi link, or one whose network dropped out for a while, gets its messages through all the
same: DDS resends what a reliable reader missed. But a resent message arrives after the ones sent behind it on
other topics, so the failing /task_info can be explained before the skill event or the log line that says why
it failed is in. The node therefore looks again at each unasked explanation a few times after giving it: when
records stamped before the failure arrived since, it explains the failure again and, if the causes changed,
publishes the new answer as a correction. A healthy network delivers nothing late and costs one count per look.
"""

from __future__ import annotations

import heapq
import itertools
import threading
import time
from typing import Generic, TypeVar

# looks after an unasked explanation: Cyclone DDS resends within a second; Fast DDS within its 3 s heartbeat period,
# or 6 s when a resend is lost too; a dropout later
AFTER_S = (1.0, 4.0, 8.0, 15.0)
MAX_WAITING = 64  # a burst of failures beyond this drops the looks due last

J = TypeVar("J")


class Rechecks(Generic[J]):
    """Jobs due at a time on this machine's monotonic clock; thread-safe."""

    def __init__(self) -> None:
        self._due: list[tuple[float, int, J]] = []
        self._order = itertools.count()
        self._lock = threading.Lock()
        self.dropped = 0

    def add(self, job: J, look: int, since: float) -> bool:
        """Schedule look number `look` (0-based) of `job`, counted from `since`; False when there is none."""
        if look >= len(AFTER_S):
            return False
        with self._lock:
            heapq.heappush(self._due, (since + AFTER_S[look], next(self._order), job))
            if len(self._due) > MAX_WAITING:
                self._due.remove(max(self._due))
                heapq.heapify(self._due)
                self.dropped += 1
        return True

    def take_due(self) -> list[J]:
        now = time.monotonic()
        with self._lock:
            due = []
            while self._due and self._due[0][0] <= now:
                due.append(heapq.heappop(self._due)[2])
            return due

    def wait_s(self) -> float | None:
        """Seconds until the next look is due (0 when one is), None when none waits."""
        with self._lock:
            return max(0.0, self._due[0][0] - time.monotonic()) if self._due else None

    def __len__(self) -> int:
        with self._lock:
            return len(self._due)
