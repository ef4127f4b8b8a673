"""The live node's work, bounded: its jobs (a failure to explain, a question, a second look at an answer), a job
queue that keeps only the newest few questions and failures, and a per-source rate for questions.

Anyone on the robot's DDS domain can publish on /hexar/question. Unbounded, a flood of 10,000 questions queued
10,000 agent runs, and a person's real question after it waited behind all of them. Here a source (the
conversation thread a question names, or the plain-text topic as one source) gets a few questions at once and
then one a second; past the queue's limit the oldest waiting question is dropped, since its asker has given
up long before it would be answered, while the newest (a person's, after a flood) is kept.
"""

from __future__ import annotations

import threading
import time
from collections import OrderedDict, deque
from dataclasses import dataclass, field
from typing import Generic, Literal, Protocol, TypeVar

from hexar.events.records import TaskUpdate

MAX_QUESTIONS = 4  # waiting questions; a fifth drops the oldest
MAX_FAILURES = 32  # waiting proactive explanations (each failure is explained once, see LiveNode._explained)
# Unasked explanations spoken: two at once, then one every 10 s, and none that waited longer than 10 s; the rest
# are published only. A robot that fails over and over (or a publisher that floods /task_info) must not talk on
# and on about it, and a stale failure is no news to say out loud.
SPEAK_BURST, SPEAK_EVERY_S, SPEAK_STALE_S = 2, 10.0, 10.0
BURST = 3  # questions a source may ask at once
PER_SECOND = 1.0  # and then one a second
MAX_SOURCES = 1024  # sources remembered (the least recent are forgotten, and start afresh)


class Kinded(Protocol):
    @property
    def kind(self) -> str: ...


J = TypeVar("J", bound=Kinded)


class Bucket:
    """A token bucket: `take()` is True when the source may ask now."""

    def __init__(self, burst: float, rate: float, now: float) -> None:
        self.burst, self.rate, self.tokens, self.t = burst, rate, burst, now

    def take(self, now: float) -> bool:
        self.tokens = min(self.burst, self.tokens + (now - self.t) * self.rate)
        self.t = now
        if self.tokens < 1.0:
            return False
        self.tokens -= 1.0
        return True


class RateLimit:
    """A bucket per source (at most MAX_SOURCES remembered). There is no bucket for everybody: a flood would
    empty it and refuse the person asking right after; made-up sources are bounded by the queue instead, which
    keeps the newest questions."""

    def __init__(self, burst: float = BURST, rate: float = PER_SECOND) -> None:
        self.burst, self.rate = burst, rate
        self._sources: OrderedDict[str, Bucket] = OrderedDict()
        self._lock = threading.Lock()

    def allow(self, source: str) -> bool:
        now = time.monotonic()
        with self._lock:
            bucket = self._sources.get(source)
            if bucket is None:
                bucket = self._sources[source] = Bucket(self.burst, self.rate, now)
                while len(self._sources) > MAX_SOURCES:
                    self._sources.popitem(last=False)
            self._sources.move_to_end(source)
            return bucket.take(now)


class JobQueue(Generic[J]):
    """FIFO of jobs with a limit per kind: over it, the oldest job of that kind is dropped (and counted). Jobs of
    the `first` kinds go before the others (a person's question before a backlog of unasked explanations)."""

    def __init__(self, limits: dict[str, int], first: tuple[str, ...] = ()) -> None:
        self.limits = limits
        self.first = first
        self.dropped = 0
        self._jobs: deque[J] = deque()
        self._ready = threading.Condition()

    def put(self, job: J) -> None:
        with self._ready:
            limit = self.limits.get(job.kind)
            if limit is not None and sum(1 for j in self._jobs if j.kind == job.kind) >= limit:
                oldest = next(j for j in self._jobs if j.kind == job.kind)
                self._jobs.remove(oldest)
                self.dropped += 1
            self._jobs.append(job)
            self._ready.notify()

    def get(self, timeout: float | None = None) -> J | None:
        """The oldest job of a `first` kind, else the oldest job; None when `timeout` seconds passed without one."""
        with self._ready:
            if not self._ready.wait_for(lambda: bool(self._jobs), timeout=timeout):
                return None
            urgent = next((j for j in self._jobs if j.kind in self.first), None) if self.first else None
            if urgent is None:
                return self._jobs.popleft()
            self._jobs.remove(urgent)
            return urgent

    def __len__(self) -> int:
        with self._ready:
            return len(self._jobs)


@dataclass
class Job:
    kind: Literal["failure", "question", "stop"]
    text: str = ""
    task_id: str = ""
    t: int = 0
    thread: str | None = None
    received: float = field(default_factory=time.monotonic)


@dataclass(frozen=True)
class Look:
    """A second look at an unasked explanation (live/recheck.py): its failure's job, the causes last published and
    when the first answer went out, when the log last read was taken, which look this is, whether the first
    answer was said aloud (so that its correction is said too), and how many holes in what was heard it told."""

    job: Job
    causes: tuple[str, ...]
    answered: float
    since: float
    n: int = 0
    spoken: bool = False
    holes: int = 0


def failure_key(update: TaskUpdate) -> str | None:
    """What failed in this update (an invalid plan, or a skill by its index), or None."""
    if not update.valid:
        return f"{update.task_id}:invalid"
    for i, step in enumerate(update.skills):
        if step.state == "failed":
            return f"{update.task_id}:{i}:{step.skill}"
    return None
