"""The DDS transport: the `cyclonedds` binding speaking what rmw_cyclonedds speaks, so HEXAR joins a ROS 2
robot's network without a ROS install (and the tests drive it with real DDS traffic on loopback)."""

from __future__ import annotations

import os
import re
import sys
import threading
from collections.abc import Callable
from pathlib import Path
from typing import Any

from hexar.events import contract as c
from hexar.live.clock import CLOCK, CLOCK_TYPE, Timeline, add_all
from hexar.live.contact import Contact, participant_of
from hexar.live.discovery import ros_discovery
from hexar.live.errors import BadOptionError, TransportUnavailableError
from hexar.live.log import LiveLog
from hexar.live.topics import (
    ANSWER,
    ANSWER_QOS,
    CLOCK_QOS,
    HEXAR_PREFIX,
    QUESTION,
    QUESTION_QOS,
    READ_ORDER,
    SUBSCRIBED,
    TTS_QOS,
    TopicQos,
    dds_name,
)

NO_CYCLONEDDS = ("the DDS transport needs the cyclonedds binding: pip install 'hexar[live]'"
                 if sys.version_info < (3, 14) else
                 "the DDS transport needs the cyclonedds binding, which has no wheel for this Python: use "
                 "--transport rclpy (the `ros` extra)")

try:
    from cyclonedds.core import InstanceState, Policy, Qos, ReadCondition, SampleState, ViewState, WaitSet
    from cyclonedds.domain import Domain, DomainParticipant
    from cyclonedds.pub import DataWriter
    from cyclonedds.sub import DataReader
    from cyclonedds.topic import Topic

    from hexar.live import msgs
    from hexar.live.graph_info import DISCOVERY_TOPIC, ParticipantEntitiesInfo, participant_nodes
except ImportError as err:  # cyclonedds is in the `live` extra, which has no wheel for CPython 3.14
    raise TransportUnavailableError(NO_CYCLONEDDS) from err

TakeBatch = 256
# This participant's lease unless CYCLONEDDS_URI sets one: Cyclone DDS's default (docs/manual/options.md,
# Discovery/LeaseDuration). A robot that hears nothing from the node for this long drops it, and then resends
# nothing of what it published meanwhile.
LEASE_S = 10.0
_LEASE = re.compile(r"<LeaseDuration>\s*([0-9.]+)\s*(ns|us|ms|s|min|hr|day)?\s*</LeaseDuration>", re.IGNORECASE)
_UNIT_S = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0, "min": 60.0, "hr": 3600.0, "day": 86400.0}


def own_lease_s(uri: str | None = None) -> float:
    """The lease this participant announces: the last LeaseDuration in CYCLONEDDS_URI (inline XML, or the files
    it names, read as Cyclone merges them: later over earlier), else Cyclone's default."""
    uri = os.environ.get("CYCLONEDDS_URI", "") if uri is None else uri
    lease = LEASE_S
    for part in uri.split(","):
        text = part.strip()
        if text.startswith("file://"):
            try:
                text = Path(text.removeprefix("file://")).read_text(errors="replace")
            except OSError:
                continue  # Cyclone itself refuses a file it cannot read, before this runs
        for value, unit in _LEASE.findall(text):
            try:
                lease = float(value) * _UNIT_S[(unit or "s").lower()]
            except ValueError:
                continue
    return lease
IDL: dict[str, type[Any]] = {
    c.LOG_TYPE: msgs.Log, c.STRING_TYPE: msgs.String, c.BOOL_TYPE: msgs.Bool,
    c.POSE_COV_TYPE: msgs.PoseWithCovarianceStamped, c.DIAG_TYPE: msgs.DiagnosticArray,
    c.TWIST_TYPE: msgs.Twist, c.ODOM_TYPE: msgs.Odometry, c.POSE_STAMPED_TYPE: msgs.PoseStamped,
    c.GOAL_STATUS_TYPE: msgs.GoalStatusArray, CLOCK_TYPE: msgs.Clock, c.GRID_TYPE: msgs.OccupancyGrid,
    c.PARAMETER_EVENT_TYPE: msgs.ParameterEvent,
}
# Match ROS 2 peers on topic and type name, as ROS 2's RMWs do (rmw_cyclonedds sends no type information at
# all: "not yet providing type discovery, assignability checking", ros2/rmw_cyclonedds
# rmw_cyclonedds_cpp/src/serdata.cpp:646@rolling). The binding always attaches XTypes type information to a
# topic, and Fast DDS (vendor 1.15) sends its own: Cyclone rejects Fast DDS's plain sequence and array type
# identifiers (their element flags have both try-construct bits 0, which Cyclone's validation refuses unless
# Compatibility/AllowInvalidTryConstruct is set, ddsi_typewrap.c xt_valid_member_flags@11.0.1) and, accepting
# them, still finds the two vendors' type objects of e.g. Odometry not assignable, so every type with a
# sequence or an array never matched. Cyclone ignores the type information of the vendors listed below and
# matches their endpoints by type name: eProsima Fast DDS (1.15, rmw_fastrtps) and RTI Connext (1.1,
# rmw_connextdds). The user's CYCLONEDDS_URI still applies; this fragment is added after it.
ROS_COMPATIBILITY = "<Compatibility><IgnoreTypeInformation>1.1,1.15</IgnoreTypeInformation></Compatibility>"
# Cyclone announces a participant to its peers every 30 s by default: on a lossy link, a lost announcement leaves two
# participants strangers for up to half a minute (measured here: a robot whose Cyclone drops a fifth of its packets
# was not matched within 30 s on 3 runs of 8). Announced every 2 s, as a small packet, unless the user's
# CYCLONEDDS_URI, read after this, sets another interval.
DISCOVERY = "<Discovery><SPDPInterval>2 s</SPDPInterval></Discovery>"
_DOMAINS: dict[int, Any] = {}  # a Domain deletes its participants when collected: kept for the process
_DOMAINS_LOCK = threading.Lock()
MAX_BLOCKING_NS = 100_000_000  # rmw_cyclonedds' default for reliable writers
UNLIMITED = -1  # DDS_LENGTH_UNLIMITED


def dds_qos(q: TopicQos) -> Qos:
    """The QoS as DDS policies; data representation XCDR1, which is what ROS 2 (Humble) types use."""
    reliability = Policy.Reliability.Reliable(MAX_BLOCKING_NS) if q.reliable else Policy.Reliability.BestEffort
    durability = Policy.Durability.TransientLocal if q.durability == "transient_local" else Policy.Durability.Volatile
    policies: list[Any] = [reliability, durability, Policy.History.KeepLast(q.depth),
                           Policy.DataRepresentation(use_cdrv0_representation=True)]
    if q.durability == "transient_local":
        # Cyclone keeps a late joiner's history by the durability-service history (default: 1 sample), not the
        # writer's; rmw_cyclonedds sets it to the history for transient-local (rmw_node.cpp, create_readwrite_qos),
        # so /rosout offers its last 1000 lines and HEXAR's answers their last 10, as on a ROS 2 robot.
        policies.append(Policy.DurabilityService(0, Policy.History.KeepLast(q.depth), UNLIMITED, UNLIMITED,
                                                 UNLIMITED))
    return Qos(*policies)


def take_loop(participant: Any, readers: list[tuple[str, Any]], stop: threading.Event,
              handle: Callable[[str, Any, int], None], report: Callable[[str], None],
              idle: Callable[[], None] | None = None) -> None:
    """Wait on every reader and hand each valid sample to `handle(topic, sample, source_stamp_ns)` until `stop`;
    a sample the binding cannot decode, or one `handle` fails on, is reported and skipped, never a traceback.
    `idle` runs after every wait (at least every 50 ms)."""
    ws = WaitSet(participant)
    mask = SampleState.Any | ViewState.Any | InstanceState.Any
    conditions = [ReadCondition(r, mask) for _, r in readers]
    for cond in conditions:
        ws.attach(cond)
    while not stop.is_set():
        ws.wait(50_000_000)
        if idle is not None:
            try:
                idle()
            except Exception as err:
                report(f"{type(err).__name__}: {err}")
        for (topic, reader), cond in zip(readers, conditions, strict=True):
            try:
                samples = reader.take(TakeBatch, condition=cond)
            except Exception as err:  # a sample the binding cannot decode must not stop the reading
                report(f"cannot read {topic}: {err}")
                continue
            for sample in samples:
                info = getattr(sample, "sample_info", None)
                if info is not None and not info.valid_data:
                    continue  # a writer went away (dispose/unregister): no data
                try:
                    handle(topic, sample, int(info.source_timestamp) if info is not None else 0)
                except Exception as err:  # one bad message is reported and skipped
                    report(f"skipped a message on {topic}: {type(err).__name__}: {err}")


def _configure(domain_id: int) -> None:
    """Create the process's Domain for `domain_id` once: DISCOVERY, what ROS 2's discovery variables ask of it (as
    rmw_cyclonedds applies them, live/discovery.py), the user's configuration, ROS_COMPATIBILITY."""
    with _DOMAINS_LOCK:
        if domain_id not in _DOMAINS:
            ros = ros_discovery()
            for note in ros.notes:
                print(f"hexar: {note}", file=sys.stderr, flush=True)
            user = os.environ.get("CYCLONEDDS_URI", "").strip()
            config = (DISCOVERY, ros.cyclone_fragment(), user, ROS_COMPATIBILITY)
            _DOMAINS[domain_id] = Domain(domain_id, ",".join(filter(None, config)))


class DdsEndpoint:
    """A domain participant with lazily created topics, readers and writers."""

    def __init__(self, domain_id: int = 0) -> None:
        if not 0 <= domain_id <= 232:
            raise BadOptionError(f"DDS domain id {domain_id} is out of range (0-232, as ROS_DOMAIN_ID)")
        try:
            _configure(domain_id)
            self.participant = DomainParticipant(domain_id)
        except Exception as err:  # cyclonedds raises DDSException on a bad CYCLONEDDS_URI or no interface
            raise TransportUnavailableError(f"cannot join DDS domain {domain_id}: {err}") from err
        self.domain_id = domain_id
        self._topics: dict[str, Any] = {}
        self.writers: dict[str, Any] = {}

    def topic(self, ros_topic: str, ros_type: str) -> Any:
        if ros_topic not in self._topics:
            self._topics[ros_topic] = Topic(self.participant, dds_name(ros_topic), IDL[ros_type])
        return self._topics[ros_topic]

    def reader(self, ros_topic: str, ros_type: str, qos: TopicQos) -> Any:
        return DataReader(self.participant, self.topic(ros_topic, ros_type), dds_qos(qos))

    def graph_reader(self) -> Any:
        """A reader of ROS 2's graph topic, which names each participant's nodes (live/graph_info.py): reliable
        and transient-local like its writers, deep enough for every process of a robot."""
        topic = Topic(self.participant, DISCOVERY_TOPIC, ParticipantEntitiesInfo)
        return DataReader(self.participant, topic, dds_qos(TopicQos(durability="transient_local", depth=1000)))

    def writer(self, ros_topic: str, ros_type: str, qos: TopicQos) -> Any:
        if ros_topic not in self.writers:
            self.writers[ros_topic] = DataWriter(self.participant, self.topic(ros_topic, ros_type), dds_qos(qos))
        return self.writers[ros_topic]

    def close(self) -> None:
        self.writers.clear()
        self._topics.clear()
        self.participant = None  # type: ignore[assignment]  # the binding deletes entities when collected


class Writers:
    """Which participant wrote a sample, and which write the robot's topics now, from the readers' matched
    writers (their GUID prefixes; the node's own participant left out)."""

    def __init__(self, participant: Any, readers: dict[str, Any]) -> None:
        self._own = participant_of(participant.guid.bytes)
        self._readers = readers
        self._of: dict[int, bytes] = {}  # writer instance handle -> its participant

    def of(self, topic: str, handle: int) -> bytes:
        if handle not in self._of:
            try:
                self._of[handle] = participant_of(self._readers[topic].get_matched_publication_data(handle)
                                                  .participant_key.bytes)
            except Exception:  # the writer is already gone (its last samples come after): nobody to name
                return b""
        return self._of[handle]

    def present(self) -> dict[bytes, str] | None:
        """None when the binding could not list them this time (a writer matched or left while it counted)."""
        try:
            handles = {h: topic for topic, reader in self._readers.items() for h in reader.get_matched_publications()}
        except Exception:  # cyclonedds raises IndexError when the count changes between its two calls
            return None
        for gone in self._of.keys() - handles.keys():
            del self._of[gone]
        found = {self.of(topic, h) for h, topic in handles.items()}
        # their names come to contact as the graph topic is read (RobotContact.graph), not with this list
        return dict.fromkeys((p for p in found if p and p != self._own), "")


class RobotContact:
    """Contact with the robot as the DDS readers show it (live/contact.py): who wrote each sample, the names
    `ros_discovery_info` gives the robot's processes, and at each due time who is there; the silence that makes a
    hole is the node's own lease. Shared by `hexar serve --transport dds` and the web page's live run."""

    def __init__(self, participant: Any, robot: dict[str, Any], contact: Contact) -> None:
        self.who = Writers(participant, robot)
        self.contact = contact
        self._robot = robot
        contact.quiet_after(own_lease_s())

    def graph(self, topic: str, sample: Any) -> bool:
        """Whether the sample was the graph topic's (taken here: it names a participant's nodes)."""
        if topic != DISCOVERY_TOPIC:
            return False
        self.contact.named(*participant_nodes(sample))
        return True

    def heard(self, topic: str, sample: Any) -> None:
        if topic in self._robot and (participant := self.who.of(topic, sample.sample_info.publication_handle)):
            self.contact.heard(participant, topic)

    def idle(self) -> None:
        if self.contact.due() and (present := self.who.present()) is not None:
            self.contact.seen(present)


class DdsTransport:
    """Feeds a LiveLog from the robot's topics and carries the node's questions and answers."""

    name = "dds"

    def __init__(self, domain_id: int = 0, tts_topic: str | None = None, recorder: Any = None) -> None:
        self.endpoint = DdsEndpoint(domain_id)
        self.recorder = recorder  # a RollingRecorder, or None
        self.tts_topic = tts_topic
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self.errors = 0
        self.timeline = Timeline(on_dated=self._record)
        self._answer = self.endpoint.writer(ANSWER, c.STRING_TYPE, ANSWER_QOS)
        self._tts = self.endpoint.writer(tts_topic, c.STRING_TYPE, TTS_QOS) if tts_topic else None

    def writer_topics(self) -> list[str]:
        """Every topic this node can write: the read-only promise, checked by a test."""
        return sorted(self.endpoint.writers)

    def start(self, log: LiveLog, on_record: Callable[[Any], None], on_question: Callable[[str], None]) -> None:
        self._types = {t.topic: t.type for t in SUBSCRIBED}
        readers: list[tuple[str, Any]] = [(t.topic, self.endpoint.reader(t.topic, t.type, t.qos)) for t in READ_ORDER]
        readers.append((CLOCK, self.endpoint.reader(CLOCK, CLOCK_TYPE, CLOCK_QOS)))
        readers.append((QUESTION, self.endpoint.reader(QUESTION, c.STRING_TYPE, QUESTION_QOS)))
        readers.append((DISCOVERY_TOPIC, self.endpoint.graph_reader()))
        self._thread = threading.Thread(target=self._loop, args=(readers, log, on_record, on_question),
                                        name="hexar-dds", daemon=True)
        self._thread.start()

    def _loop(self, readers: list[tuple[str, Any]], log: LiveLog, on_record: Callable[[Any], None],
              on_question: Callable[[str], None]) -> None:
        robot = RobotContact(self.endpoint.participant,
                             {topic: reader for topic, reader in readers if topic in self._types}, log.contact)

        def handle(topic: str, sample: Any, t: int) -> None:
            if topic == QUESTION:
                on_question(str(sample.data))
            elif not robot.graph(topic, sample):
                add_all(self.timeline.records(topic, sample, t), log.add, on_record)
                robot.heard(topic, sample)

        def idle() -> None:
            add_all(self.timeline.flush(), log.add, on_record)
            robot.idle()

        take_loop(self.endpoint.participant, readers, self._stop, handle, self._report, idle)
        if self.recorder is not None:
            self.recorder.close()  # sqlite wants the thread that wrote the bag to close it

    def _record(self, topic: str, sample: Any, t: int) -> None:
        """Into the rolling recording, on the robot's clock, as `ros2 bag record` on the robot stamps it."""
        if self.recorder is not None:
            self.recorder.write(topic, c.TYPE_OF[c.topic_key(topic)], sample.serialize(), t)

    def _report(self, line: str) -> None:
        self.errors += 1
        print(f"hexar serve: {line}", file=sys.stderr)

    def publish(self, topic: str, text: str) -> None:
        if topic == ANSWER:
            self._answer.write(msgs.String(data=text))
        elif topic == self.tts_topic and self._tts is not None:
            self._tts.write(msgs.String(data=text))
        else:  # the node is read-only: it never writes on the robot's own topics
            raise BadOptionError(f"HEXAR writes only on {HEXAR_PREFIX}* and its TTS topic, not on {topic}")

    def close(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=2.0)
        if self.recorder is not None and self._thread is None:
            self.recorder.close()
        self.endpoint.close()
