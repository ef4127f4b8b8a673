"""The page's live run: a read-only DDS subscription to the robot, kept in a LiveLog and shown like a recording.

The page is a viewer. Unlike `hexar serve` it creates no DDS writer at all (not even /hexar/answer), so it can
run beside a live node on the robot's network without a second voice answering questions.
"""

from __future__ import annotations

import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from hexar.events.log import EventLog
from hexar.events.tasks import Task
from hexar.live.limits import Limits
from hexar.live.log import LiveLog
from hexar.web.pagedata import Findings

if TYPE_CHECKING:
    from hexar.live.launch_log import LaunchLogFollower

LIVE = "live"  # the live run's name in the runs list and the page's address
REBUILD_S = 0.5  # a snapshot copies every kept record: at most one rebuild per this long, however many polls


class DdsWatcher:
    """Readers on the robot's topics (the ones `hexar serve` reads, with the same QoS), feeding a LiveLog."""

    def __init__(self, domain_id: int) -> None:
        from hexar.live.dds import DdsEndpoint  # raises the one-line error when cyclonedds cannot load

        self.endpoint = DdsEndpoint(domain_id)
        self.domain_id = domain_id
        self.errors = 0
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None

    def writer_topics(self) -> list[str]:
        """Every topic this viewer can write: none. A test checks it from DDS discovery."""
        return sorted(self.endpoint.writers)

    def start(self, log: LiveLog) -> None:
        from hexar.live.graph_info import DISCOVERY_TOPIC
        from hexar.live.topics import SUBSCRIBED

        readers = [(t.topic, self.endpoint.reader(t.topic, t.type, t.qos)) for t in SUBSCRIBED]
        readers.append((DISCOVERY_TOPIC, self.endpoint.graph_reader()))
        self._thread = threading.Thread(target=self._loop, args=(readers, log), name="hexar-web-dds", daemon=True)
        self._thread.start()

    def _loop(self, readers: list[tuple[str, Any]], log: LiveLog) -> None:
        """As `hexar serve`'s DDS transport reads the robot, with who wrote what (live/contact.py): the page's chat
        tells the holes a lost link left in what it heard."""
        from hexar.live.convert import to_records
        from hexar.live.dds import RobotContact, take_loop
        from hexar.live.graph_info import DISCOVERY_TOPIC

        log.contact.speaker = "hexar web"
        robot = RobotContact(self.endpoint.participant,
                             {topic: r for topic, r in readers if topic != DISCOVERY_TOPIC}, log.contact)

        def handle(topic: str, sample: Any, t: int) -> None:
            if not robot.graph(topic, sample):
                log.extend(to_records(topic, sample, t))
                robot.heard(topic, sample)

        take_loop(self.endpoint.participant, readers, self._stop, handle, self._report, robot.idle)

    def _report(self, line: str) -> None:
        self.errors += 1
        print(f"hexar web: {line}", file=sys.stderr)

    def close(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=2.0)
        self.endpoint.close()


class RclpyWatcher:
    """The same read-only subscription as a node of rclpy (`hexar_web`), where cyclonedds is missing (CPython 3.14)
    or `--transport rclpy` asks for it: the robot's topics, as `hexar serve --transport rclpy` reads them; nothing
    written but /parameter_events, which rclpy creates for every node."""

    def __init__(self, domain_id: int) -> None:
        from hexar.live.ros import RclpyTransport

        self.transport = RclpyTransport(domain_id, node_name="hexar_web", answers=False, speaker="hexar web")
        self.domain_id = domain_id

    @property
    def errors(self) -> int:
        return self.transport.errors

    def writer_topics(self) -> list[str]:
        return self.transport.writer_topics()

    def start(self, log: LiveLog) -> None:
        log.contact.speaker = "hexar web"
        self.transport.start(log, lambda record: None, lambda question: None)

    def close(self) -> None:
        self.transport.close()


Watcher = DdsWatcher | RclpyWatcher


@dataclass(frozen=True)
class Snapshot:
    """One state of the live run: its event log, its version and the explainers' findings on that log."""

    log: EventLog
    version: int
    findings: Findings
    views: dict[str, dict[str, Any]] = field(default_factory=dict)  # the page's JSON per task, built once

    def explain(self, task: Task) -> list[dict[str, Any]]:
        return self.findings.get(LIVE, self.log, task)


class LiveSource:
    """The live run as the page reads it: the latest snapshot, rebuilt only when records arrived (and not more
    often than REBUILD_S), so page polls between arrivals cost nothing."""

    def __init__(self, log: LiveLog, watcher: Watcher | None = None,
                 follower: LaunchLogFollower | None = None) -> None:
        self.log = log
        self.watcher = watcher
        self.follower = follower  # launch's log on this computer, read at each snapshot (live/launch_log.py)
        self._lock = threading.Lock()
        self._snap: Snapshot | None = None
        self._built = 0.0
        self.shared = Findings()  # the page's: explainers run one at a time across every run (Findings says why)

    @classmethod
    def over_dds(cls, domain_id: int, limits: Limits | None = None, launch_log: Path | None = None,
                 transport: str = "dds") -> LiveSource:
        """Follow the robot on `domain_id` over `transport` ("dds": cyclonedds, "rclpy": a node of rclpy)."""
        from hexar.live.launch_log import follower

        watcher: Watcher = RclpyWatcher(domain_id) if transport == "rclpy" else DdsWatcher(domain_id)
        log = LiveLog(limits, name=f"live (DDS domain {domain_id})")
        watcher.start(log)
        # as `hexar serve` does: the newest launch's log, when launch writes on this computer (or where it is told)
        return cls(log, watcher, follower(launch_log, log.limits.horizon_s))

    def _kept(self) -> int:
        # read under the log's lock, so a record counted is a record a snapshot taken after this holds; counts
        # only grow, and a clock jump drops records but is counted, so the version still moves
        s = self.log.stats()
        return s["received"] - s["duplicates"] + s["clock_jumps"]

    def snapshot(self, fresh: bool = False) -> Snapshot:
        """The latest snapshot; its version changes whenever the kept records changed. `fresh`: whatever
        arrived until now, however recently the last one was built (a chat answer must see it)."""
        with self._lock:
            if self.follower is not None:
                self.log.extend(self.follower.poll())
            kept = self._kept()
            snap = self._snap
            if snap is None or (kept != snap.version and (fresh or time.monotonic() - self._built >= REBUILD_S)):
                # findings are per snapshot: a running task's explanation changes as its records arrive
                snap = self._snap = Snapshot(self.log.snapshot(), kept, Findings(self.shared))
                self._built = time.monotonic()
            return snap

    def close(self) -> None:
        if self.watcher is not None:
            self.watcher.close()
