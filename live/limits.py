"""How much the live event log keeps, and the thresholds by which it tells a clock jump from late data."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Limits:
    """What the live log keeps: the current and last `keep_tasks` tasks, streams within `horizon_s` of the
    newest event, at most `max_records` records per stream, log text cut at `max_chars`."""

    keep_tasks: int = 5
    horizon_s: float = 900.0
    max_records: int = 100_000
    max_chars: int = 16_384
    dedup_keys: int = 50_000
    # Grids (/map, /global_costmap/costmap) changed this many times per topic are kept, the latest: a latched map
    # may be hours old and still the one the planner uses, so no horizon applies to them.
    max_grids: int = 16
    # A clock that goes back by more than this, on several fresh messages in a row, is a clock jump.
    jump_back_s: float = 30.0
    jump_confirm: int = 3
    # For `resend_s` of our seconds after the node heard a participant again that DDS had dropped (live/contact.py),
    # records stamped since it was last heard (or up to `jump_back_s` before) are what DDS resends as the link
    # comes back, however old: late, never a clock that jumped back. A 35 s dropout's resends were taken for one,
    # and the events after them, the failure they explained among them, were dropped as "the abandoned future".
    resend_s: float = 30.0
    # Records that arrive behind the robot's clock (stamped before the newest one kept) are remembered, this many,
    # with when they came: a lossy network delivers what it lost late, when DDS resends it. As many moments of the
    # robot's clock moving on are remembered (one a millisecond at most), to tell how late in our seconds.
    late_kept: int = 4096
    # What arrives this soon after the first record may be a late joiner's transient-local history: it counts as
    # arriving late (a second look at an explanation reads it), but not as a network's lateness.
    join_s: float = 5.0
