"""Contact with the robot: which of its DDS participants the node hears, and the times a link lost one.

DDS drops a remote participant that stops announcing itself once its lease runs out (Cyclone DDS's default 10 s,
Fast DDS's 20 s), with every writer it had, and finds it again, under the same GUID, when its announcements come
through once more. What the robot published in between on a volatile topic (/task_info, /diagnostics, the skills'
events) is never resent to a reader it had dropped, so after a Wi-Fi dropout of that length the node has a hole
in what it heard: an answer about that time says so instead of reading the hole as "nothing happened".

The transports tell this module who wrote each record (`heard`, the writer's GUID prefix) and, every half second,
which participants write the robot's topics (`seen`, from the middleware's matched writers). A participant that
was heard and is gone opens a gap at the last record heard from it; its next record closes it. One that left for
good (a process that ended) keeps its gap open: the answer says when it was last heard.

A dropped participant is not the whole story: a robot that drops the node first (a Fast DDS robot's 20 s lease
against a Cyclone node's 10 s) forgets its readers and sends nothing of the hole, while the node never drops it,
and a publisher that keeps its last 10 messages loses older ones on a link that stalls for less than a lease.
Where the transport sees each message's sequence number (rclpy), a jump in a writer's numbers is such a loss
(`sequence`). The DDS transport has no such number (the Python binding of Cyclone does not hand it over), and
Cyclone drops what a writer hands over again below what it had. There, a participant that publishes a state
again and again (diagnostics, the battery flag, odometry: every second or faster) and then says nothing for as long
as the node's own lease (`quiet_after`) was cut off from the node long enough for the robot to drop it, whatever the
node's side of DDS made of it: a Fast DDS robot that dropped a Cyclone node while the node kept it (a cut of 10-20
s with the vendors' defaults) is told from that silence (scripts/bench_live_outage.py). A shorter silence is a link
both sides kept, which resends what the robot's publishers still hold.
"""

from __future__ import annotations

import sys
import threading
import time
from collections import deque
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from hexar.events import contract as c

if TYPE_CHECKING:
    from hexar.events.tasks import Task

GUID_PREFIX = 12  # bytes of an RTPS GUID that name its participant (the last 4 name the entity)
POLL_S = 0.5
KEEP_GAPS = 50
# The topics that carry events, whose loss can hide what happened: the task's updates, the log, the skills' events,
# a goal sent. The others hold a state published again and again (the battery flag, diagnostics, poses, 20-50 Hz
# odometry and commands, a goal's latest status, a map), a stalled link loses a few of them with nothing hidden,
# and some publishers keep only their latest by design.
EVENT_TOPICS = frozenset({c.TASK_INFO, c.ROSOUT, c.EPISODIC_MEMORY, c.SAY_EVENTS, c.PIZZA_EVENTS, c.GOAL_POSE})
# States a robot publishes on and on, however idle (the diagnostic aggregator at 1 Hz, the battery flag, the base's
# odometry): a participant that sends them and then says nothing at all is not idle but out of reach.
STEADY_TOPICS = frozenset({c.DIAGNOSTICS, c.IS_CHARGING, c.ODOM})
STEADY_LEAST = 5  # records of a steady topic in a row, each at most a quarter of the silence that counts apart
ENDED = frozenset({"failed", "succeeded", "canceled", "invalid"})  # a task's outcome once its last update came


def participant_of(guid: bytes) -> bytes:
    """The participant part of a writer's GUID (rmw's 16-byte gid or a DDS endpoint key)."""
    return bytes(guid[:GUID_PREFIX])


@dataclass
class Gap:
    """A participant not heard from `since` (our wall clock, time.time()) until `until` (None: not yet heard
    again); `since_t` and `until_t` are the robot's clock then, as the live log's newest stamp."""

    who: str
    since: float
    since_t: int
    alone: bool = True  # nothing else of the robot was heard after `since` when it was dropped
    until: float | None = None
    until_t: int | None = None
    missed: int = 0  # messages known never to have come (a writer's sequence numbers jumped); `who` is the topic
    named: bool = True  # `who` names its nodes; else it is the participant's GUID, which no answer says aloud
    quiet: bool = False  # told from a steady participant's silence, not from DDS dropping it

    def overlaps(self, start_t: int, end_t: int | None) -> bool:
        if self.until_t is None:  # not heard again: it matters to a task it left while the task ran
            return start_t <= self.since_t and (end_t is None or self.since_t <= end_t)
        return (end_t is None or self.since_t <= end_t) and self.until_t >= start_t

    def as_dict(self) -> dict[str, object]:
        return {"who": self.who, "last_heard": _clock(self.since), "heard_again": _clock(self.until)
                if self.until is not None else None, "seconds": round((self.until or time.time()) - self.since, 1),
                "missed": self.missed}


def _clock(wall: float | None) -> str:
    return time.strftime("%H:%M:%S", time.localtime(wall)) if wall is not None else ""


class Contact:
    """Thread-safe: a transport's thread tells who it heard and who is there; the node's worker reads the gaps."""

    def __init__(self, newest: Callable[[], int], wall: Callable[[], float] = time.time,
                 clock: Callable[[], float] = time.monotonic, report: Callable[[str], None] | None = None) -> None:
        self._newest = newest  # the robot's clock: the live log's newest stamp
        self._wall, self._clock = wall, clock
        self.speaker = "hexar serve"  # who says the stderr lines (the web page's live run: "hexar web")
        self._report = report or (lambda line: print(f"{self.speaker}: {line}", file=sys.stderr, flush=True))
        self._lock = threading.Lock()
        self._last: dict[bytes, tuple[float, int]] = {}  # participant -> (wall, robot clock) of its last record
        self._names: dict[bytes, str] = {}
        self._present: set[bytes] = set()
        self._open: dict[bytes, Gap] = {}
        self._closed: deque[Gap] = deque(maxlen=KEEP_GAPS)
        self._next_poll = 0.0
        # writer GUID -> (its last sequence number, wall and robot clock then); set by a transport that sees them
        self._seqs: dict[bytes, tuple[int, float, int]] = {}
        self._losses: deque[Gap] = deque(maxlen=KEEP_GAPS)
        self._quiet_s: float | None = None
        self._steady: dict[bytes, deque[float]] = {}  # participant -> when its latest steady records came
        self._spoke: deque[tuple[float, bytes]] = deque(maxlen=4096)  # (when, who), at most twice a second each
        self._logged: dict[bytes, float] = {}  # participant -> when it last went into _spoke

    def quiet_after(self, seconds: float) -> None:
        """Tell a silence this long of a participant that publishes steadily as a hole (the DDS transport, with
        its own lease: a robot drops the node after that long and resends nothing of it)."""
        self._quiet_s = seconds

    def sequence(self, writer: bytes, topic: str, seq: int) -> None:
        """A record's sequence number from its writer (`writer`: its whole GUID). A writer numbers what it sends
        one by one, so a jump is that many messages that never reached this node (a link that dropped them, or a
        writer that no longer kept them for it); a lower number is a resend of one already had."""
        now = self._wall()
        with self._lock:
            prev = self._seqs.get(writer)
            if prev is not None and seq <= prev[0]:
                return
            if prev is None and len(self._seqs) >= 20 * KEEP_GAPS:  # writers come and go with the robot's processes
                for old in sorted(self._seqs, key=lambda w: self._seqs[w][1])[:KEEP_GAPS]:
                    del self._seqs[old]
            newest = self._newest()
            self._seqs[writer] = (seq, now, newest)
            if prev is None or seq == prev[0] + 1 or topic not in EVENT_TOPICS:
                return
            loss = Gap(topic, prev[1], prev[2], until=now, until_t=newest, missed=seq - prev[0] - 1)
            self._losses.append(loss)
        self._report(f"{loss.missed} message{'s' if loss.missed > 1 else ''} on {topic} never reached this node "
                     f"(sent between {_clock(loss.since)} and {_clock(now)})")

    def heard(self, participant: bytes, topic: str = "") -> None:
        """A record came from `participant` (its GUID prefix), on `topic`."""
        now = self._wall()
        with self._lock:
            newest = self._newest()
            last = self._last.get(participant)
            self._last[participant] = (now, newest)
            if now - self._logged.get(participant, float("-inf")) >= POLL_S:
                self._logged[participant] = now
                self._spoke.append((now, participant))
            gap = self._open.pop(participant, None)
            if gap is None:
                gap = self._silence(participant, last, now)
                if topic in STEADY_TOPICS:
                    self._steady.setdefault(participant, deque(maxlen=STEADY_LEAST)).append(now)
                if gap is None:
                    return
            gap.until, gap.until_t = now, newest
            self._closed.append(gap)
        self._report(f"heard {gap.who} again, {now - gap.since:.0f} s after its last record "
                     f"({_clock(gap.since)} to {_clock(now)})" + (", though its DDS participant was never dropped"
                                                                   if gap.quiet else ""))

    def _silence(self, participant: bytes, last: tuple[float, int] | None, now: float) -> Gap | None:
        """A gap for a steady participant that said nothing for `quiet_after` seconds (None: no such silence)."""
        if self._quiet_s is None or last is None or now - last[0] < self._quiet_s:
            return None
        steady = self._steady.get(participant)
        if steady is None or len(steady) < STEADY_LEAST or last[0] - steady[-1] > self._quiet_s / 4:
            return None  # not one that speaks on and on, or it had stopped its steady topics before: idle
        if any(b - a > self._quiet_s / 4 for a, b in zip(steady, list(steady)[1:], strict=False)):
            return None
        steady.clear()  # its steady rhythm must be seen again before another silence counts
        names = self._names.get(participant, "")
        # a silence ends when the link is back, when the robot's other processes speak again too: whether they
        # spoke while it lasted tells this process from the robot
        others = any(last[0] + 1.0 < when < now - 1.0 for when, who in self._spoke if who != participant)
        return Gap(names or f"participant {participant.hex()[:8]}", last[0], last[1], quiet=True, alone=not others,
                   named=bool(names))

    def named(self, participant: bytes, names: str) -> None:
        """What a participant's nodes are called, as soon as the transport reads it (ROS 2's graph topic comes with
        Fast DDS's next heartbeat, up to 3 s after its other topics); a gap already open for it takes the names."""
        if not names:
            return
        with self._lock:
            self._name(participant, names)
            gap = self._open.get(participant)
            if gap is not None and not gap.named:
                gap.who, gap.named = self._names[participant], True

    def _name(self, participant: bytes, names: str) -> None:
        """Every node a participant was seen to hold: a process destroys its nodes one by one as it ends, and is
        still known by what it held."""
        held = set(self._names.get(participant, "").split(", ")) | set(names.split(", "))
        self._names[participant] = ", ".join(sorted(held - {""}))

    def due(self) -> bool:
        """Whether it is time to look at who is there (at most every POLL_S)."""
        now = self._clock()
        if now < self._next_poll:
            return False
        self._next_poll = now + POLL_S
        return True

    def seen(self, present: Mapping[bytes, str]) -> None:
        """The participants that write the robot's topics now (GUID prefix -> their nodes' names, or "")."""
        now = self._wall()
        lost: list[Gap] = []
        with self._lock:
            for participant, names in present.items():
                if names:
                    self._name(participant, names)
            for participant in self._present - present.keys():
                last = self._last.get(participant)
                if last is None or participant in self._open:
                    continue  # never heard from it: nothing was missed
                names = self._names.get(participant, "")
                gap = Gap(names or f"participant {participant.hex()[:8]}", last[0], last[1],
                          alone=not self._others_since(participant, last[0]), named=bool(names))
                self._open[participant] = gap
                lost.append(gap)
            self._present = set(present)
            if len(self._last) > 4 * KEEP_GAPS:  # participants come and go with every process: forget old ones
                for participant in sorted(self._last, key=lambda p: self._last[p][0])[:KEEP_GAPS]:
                    if participant not in self._present and participant not in self._open:
                        del self._last[participant]
                        self._names.pop(participant, None)
                        self._logged.pop(participant, None)
                        self._steady.pop(participant, None)
        for gap in lost:
            self._report(f"lost contact with {gap.who} (its lease ran out, or it ended), last record "
                         f"{now - gap.since:.0f} s ago ({_clock(gap.since)})")

    def _others_since(self, participant: bytes, since: float) -> bool:
        """Whether another participant was heard after `since` (a second later: the same loss drops them all)."""
        return any(when > since + 1.0 for p, (when, _) in self._last.items() if p != participant)

    def gaps(self, start_t: int, end_t: int | None) -> list[Gap]:
        """The gaps that overlap the robot's time from `start_t` to `end_t` (None: to now), oldest first."""
        with self._lock:
            for participant, gap in self._open.items():  # another of the robot's processes may have spoken since
                gap.alone = gap.alone and not self._others_since(participant, gap.since)
            gaps = [*self._closed, *self._open.values(), *self._losses]
        return sorted((g for g in gaps if g.overlaps(start_t, end_t)), key=lambda g: g.since)

    def back_since(self, within_s: float) -> int | None:
        """The robot's clock when the node last heard, before its hole, a participant that DDS had dropped and
        that was heard again within the last `within_s` seconds (the earliest, if several): what it sent from then
        on may still come, resent by its writers, which never dropped the node. None: no such participant. A
        robot that went quiet (it dropped the node) resends nothing."""
        now = self._wall()
        with self._lock:
            return min((g.since_t for g in self._closed
                        if not g.quiet and g.until is not None and now - g.until <= within_s), default=None)

    def stats(self) -> dict[str, int]:
        with self._lock:
            return {"gaps": len(self._closed) + len(self._open), "not_back": len(self._open),
                "missed": sum(g.missed for g in self._losses)}


def note(gaps: list[Gap], now: float | None = None) -> str:
    """What an answer adds about the holes in what the node heard while the task ran ("" when there were none):
    gaps that overlap are one hole; "the robot" when nothing else of it was heard meanwhile, else whom."""
    if not gaps:
        return ""
    now = time.time() if now is None else now
    holes: list[tuple[float, float | None, list[Gap]]] = []
    for g in sorted(gaps, key=lambda g: g.since):
        if holes and (holes[-1][1] is None or g.since <= holes[-1][1]):
            since, until, members = holes[-1]
            ends = None if until is None or g.until is None else max(until, g.until)
            holes[-1] = (since, ends, [*members, g])
        else:
            holes.append((g.since, g.until, [g]))
    parts = []
    for since, until, members in holes:
        dropped = [g for g in members if not g.missed]
        missed, topics = sum(g.missed for g in members), sorted({g.who for g in members if g.missed})
        lost = f"{missed} message{'s' if missed > 1 else ''}"
        if not dropped:
            parts.append(f"{lost} the robot sent on {', '.join(topics)} from {_clock(since)} to {_clock(until)} "
                         "never reached me")
            continue
        who = "the robot" if all(g.alone for g in dropped) else _names(dropped)
        part = (f"I have not heard from {who} since {_clock(since)} ({now - since:.0f} s)" if until is None else
                f"I heard nothing from {who} from {_clock(since)} to {_clock(until)} ({until - since:.0f} s)")
        parts.append(part + (f", and {lost} it sent on {', '.join(topics)} never reached me" if missed else ""))
    return "; ".join(parts) + ", so I may have missed what happened then."


def annotate(result: dict[str, Any], tasks: Iterable[Task], contact: Contact) -> None:
    """Add to an answer about a task the holes in what the node heard while it ran (`contact` in the result, and
    the answer's last sentence), so a lost /task_info update is not taken for a task still running."""
    task = next((t for t in tasks if t.task_id == result.get("task_id")), None)
    if task is None or not result.get("answer"):
        return
    gaps = contact.gaps(task.created, task.last_update if task.outcome in ENDED else None)
    if gaps:
        said = note(gaps)
        running = next((r for r in task.skills if r.state == "running"), None)
        if running is not None and task.outcome not in ENDED:
            from hexar.explainers.recorded import step_ref

            said += f" The last I heard, I was still at {step_ref(running)}."
        # an answer that could not tell what happened starts with why: the node did not hear it
        told = (result["answer"], said) if result.get("causes") else (said, result["answer"])
        result["answer"] = " ".join(told)
        result["contact"] = [g.as_dict() for g in gaps]


def _names(gaps: list[Gap]) -> str:
    """The nodes of the processes that went quiet, or how many of the robot's processes where a transport could
    not name them (a GUID is for the log, not for a person)."""
    names = sorted({name for g in gaps if g.named for name in g.who.split(", ")})
    said = ", ".join(names[:3]) + (f" and {len(names) - 3} more" if len(names) > 3 else "")
    unnamed = sum(not g.named for g in gaps)
    if not unnamed:
        return said
    others = f"{'one' if unnamed == 1 else unnamed}{' other' if said else ''} of the robot's processes"
    return f"{said} and {others}" if said else others


__all__ = ["Contact", "Gap", "annotate", "note", "participant_of"]
