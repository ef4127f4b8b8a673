"""How late records reach the live node, in this machine's seconds, however fast the robot's clock runs.

A lossy network delivers what it lost late, when DDS resends it; a recording replayed at x10 runs the robot's clock
ten times faster than ours. Lateness is therefore measured against when the robot's clock passed a record's stamp,
on our clock, not against the stamps themselves.
"""

from __future__ import annotations

import math
from bisect import bisect_left
from collections import deque
from itertools import takewhile


class Lateness:
    """The moments the robot's clock moved on (one a millisecond at most) and the records that came behind it.

    Not locked: the live log (live/log.py) calls it under its own lock.
    """

    def __init__(self, kept: int, join_s: float) -> None:
        # what arrives this soon after the first record may be a late joiner's transient-local history
        self.join_s = join_s
        self._first = 0.0
        # when the robot's clock passed each stamp, on this machine's clock
        self._front_t: deque[int] = deque(maxlen=kept)
        self._front_at: deque[float] = deque(maxlen=kept)
        # (arrival on this machine's clock, stamp, how many of our seconds late it came, whether it came while
        # joining)
        self._late: deque[tuple[float, int, float, bool]] = deque(maxlen=kept)

    def note(self, t: int, behind: int, now: float, late: bool) -> None:
        """A record stamped `t` arrived at `now`, `behind` ns behind the newest stamp kept (negative: it moved the
        robot's clock on); `late` says whether a record behind counts as late (not a clock that jumped back)."""
        if not self._first:
            self._first = now
        if behind < 0:
            if self._front_at and now - self._front_at[-1] < 0.001:
                self._front_t[-1] = t  # within a millisecond: passed no later than that entry says
            else:
                self._front_t.append(t)
                self._front_at.append(now)
        elif behind > 0 and late:
            # when the robot's clock first reached t; for a stamp older than any remembered, the oldest remembered
            # moment (so at least that late)
            front = self._front_t
            passed = self._front_at[min(bisect_left(front, t), len(front) - 1)] if front else now
            self._late.append((now, t, now - passed, now - self._first < self.join_s))

    def forget_front(self) -> None:
        """After a clock jump back: the remembered stamps are from the abandoned future."""
        self._front_t.clear()
        self._front_at.clear()

    def last_arrival(self) -> float:
        """When the last late record came, on our clock; -inf when none has."""
        return self._late[-1][0] if self._late else -math.inf

    def count_since(self, since: float, stamped_by: int) -> int:
        """How many records stamped at or before `stamped_by` arrived late after `since`."""
        # kept in the order they arrived: the newest first, up to the first that came before `since`
        return sum(1 for arrived, t, _, _ in takewhile(lambda late: late[0] > since, reversed(self._late))
                   if t <= stamped_by)

    def late_s(self, since: float, over_s: float) -> list[float]:
        """How late (our seconds) each record that came after `since` was, sorted, counting only those later than
        `over_s` and none of a late joiner's history."""
        return sorted(s for arrived, _, s, joining in self._late if arrived > since and s > over_s and not joining)
