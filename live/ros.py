"""The rclpy transport and replayer: a normal ROS 2 node `hexar` on the robot.

rclpy comes from a ROS 2 install or, on Linux x86_64, from the `ros` extra (the ROS 2 Kilted Python wheels,
Fast DDS). The node subscribes raw: each message arrives as its CDR bytes and is decoded with the same Humble
type store as a recording (rosbags), so a live record and the recording's record are decoded by one code path,
and the DDS source timestamp comes with it (rclpy's MessageInfo). Each transport has its own rclpy Context,
initialised without rclpy's signal handlers (the CLI handles SIGINT/SIGTERM) and shut down on close, which
ends the DDS participant cleanly: no "terminate called without an active exception", no Fast DDS shared-memory
files left in /dev/shm.
"""

from __future__ import annotations

import importlib
import os
import sys
import threading
from collections.abc import Callable
from typing import Any

from hexar.events import contract as c
from hexar.live.clock import CLOCK, CLOCK_TYPE, Timeline, add_all
from hexar.live.contact import participant_of
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
)

ROS_TYPES = {
    c.LOG_TYPE: ("rcl_interfaces.msg", "Log"), c.STRING_TYPE: ("std_msgs.msg", "String"),
    c.BOOL_TYPE: ("std_msgs.msg", "Bool"), c.POSE_COV_TYPE: ("geometry_msgs.msg", "PoseWithCovarianceStamped"),
    c.DIAG_TYPE: ("diagnostic_msgs.msg", "DiagnosticArray"), c.TWIST_TYPE: ("geometry_msgs.msg", "Twist"),
    c.ODOM_TYPE: ("nav_msgs.msg", "Odometry"), c.POSE_STAMPED_TYPE: ("geometry_msgs.msg", "PoseStamped"),
    c.GOAL_STATUS_TYPE: ("action_msgs.msg", "GoalStatusArray"), CLOCK_TYPE: ("rosgraph_msgs.msg", "Clock"),
    c.GRID_TYPE: ("nav_msgs.msg", "OccupancyGrid"), c.PARAMETER_EVENT_TYPE: ("rcl_interfaces.msg", "ParameterEvent"),
}
BARE_DDS = "_CREATED_BY_BARE_DDS_APP_"  # the name rmw gives a writer of a plain DDS program (no ROS node)
TAKE_BATCH = 256  # at most this many more messages of one topic per callback
NO_ROS = ("--transport rclpy needs rclpy: on Linux x86_64 pip install 'hexar[ros]' (the ROS 2 Kilted wheels); "
          "elsewhere source a ROS 2 install (source /opt/ros/<distro>/setup.bash), or use --transport dds")


def _bootstrap_paths() -> str | None:
    """The LD_LIBRARY_PATH the Kilted wheels need, when they are installed but this process started without it
    (their ros_wheels_bootstrapper re-executes every Python start to set it, unless
    _ROS_WHEELS_BOOTSTRAP_COMPLETE is set, which keeps `hexar ask` from paying for the re-execution)."""
    try:
        boot: Any = importlib.import_module("ros_wheels_bootstrapper")
    except ImportError:
        return None
    paths = str(boot.get_ros_paths())
    have = set(os.environ.get("LD_LIBRARY_PATH", "").split(os.pathsep))
    return None if set(paths.split(os.pathsep)) <= have else paths


def import_rclpy() -> Any:
    """rclpy, or a one-line TransportUnavailableError. When the wheels' libraries are not on the library path
    (the bootstrap was skipped), this process re-executes itself once with them, as the wheels' own .pth would
    have done at start-up."""
    try:
        return importlib.import_module("rclpy")
    except ImportError as err:
        paths = _bootstrap_paths()
        if paths is not None and not os.environ.get("_HEXAR_ROS_REEXEC"):
            env = dict(os.environ, LD_LIBRARY_PATH=paths, _ROS_WHEELS_BOOTSTRAP_COMPLETE="1", _HEXAR_ROS_REEXEC="1")
            sys.stdout.flush()
            sys.stderr.flush()
            os.execve(sys.executable, sys.orig_argv, env)
        raise TransportUnavailableError(f"{NO_ROS} ({err})") from err


def importable(name: str) -> bool:
    """Whether module `name` can be imported here, without importing it (a module set to None, as a test does to
    stand for a machine without it, is not)."""
    if name in sys.modules:
        return sys.modules[name] is not None
    try:
        return importlib.util.find_spec(name) is not None
    except (ImportError, ValueError):
        return False


def rclpy_available() -> bool:
    """Whether rclpy can be imported here (importing it costs a quarter of a second)."""
    return importable("rclpy")


def msg_class(ros_type: str) -> Any:
    module, name = ROS_TYPES[ros_type]
    try:
        return getattr(importlib.import_module(module), name)
    except ImportError as err:
        raise TransportUnavailableError(f"the rclpy transport needs the ROS 2 package {module}") from err


def qos_profile(q: TopicQos) -> Any:
    qos: Any = importlib.import_module("rclpy.qos")
    return qos.QoSProfile(
        depth=q.depth,
        reliability=qos.ReliabilityPolicy.RELIABLE if q.reliable else qos.ReliabilityPolicy.BEST_EFFORT,
        durability=(qos.DurabilityPolicy.TRANSIENT_LOCAL if q.durability == "transient_local"
                    else qos.DurabilityPolicy.VOLATILE),
    )


class RosNode:
    """An rclpy node in its own context on `domain_id`, and the thread that spins it."""

    def __init__(self, name: str, domain_id: int, **node_options: Any) -> None:
        if not 0 <= domain_id <= 232:
            raise BadOptionError(f"DDS domain id {domain_id} is out of range (0-232, as ROS_DOMAIN_ID)")
        self.rclpy = import_rclpy()
        signals: Any = importlib.import_module("rclpy.signals")
        self.context = importlib.import_module("rclpy.context").Context()
        try:
            self.rclpy.init(context=self.context, domain_id=domain_id,
                            signal_handler_options=signals.SignalHandlerOptions.NO)
            self.node = self.rclpy.create_node(name, context=self.context, **node_options)
        except Exception as err:  # rclpy raises RCLError on a bad RMW or middleware configuration
            self.context.try_shutdown()
            raise TransportUnavailableError(f"cannot start the ROS 2 node {name}: {err}") from err
        self.domain_id = domain_id
        self._executor: Any = None
        self._thread: threading.Thread | None = None
        self._stop = threading.Event()

    def spin(self, report: Callable[[str], None], idle: Callable[[], None] | None = None,
             done: Callable[[], None] | None = None) -> None:
        executors: Any = importlib.import_module("rclpy.executors")
        self._executor = executors.SingleThreadedExecutor(context=self.context)
        self._executor.add_node(self.node)

        def loop() -> None:
            while not self._stop.is_set():
                try:
                    self._executor.spin_once(timeout_sec=0.05)
                    if idle is not None:
                        idle()
                except (executors.ExternalShutdownException, executors.ShutdownException):
                    break
                except Exception as err:  # never let the receive thread die: report and go on
                    report(f"{type(err).__name__}: {err}")
            if done is not None:
                done()

        self._thread = threading.Thread(target=loop, name=f"hexar-rclpy-{self.node.get_name()}", daemon=True)
        self._thread.start()

    def close(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=5.0)
        if self._executor is not None:
            self._executor.shutdown(timeout_sec=2.0)
        self.node.destroy_node()
        self.context.try_shutdown()


class RclpyTransport:
    name = "rclpy"

    def __init__(self, domain_id: int = 0, tts_topic: str | None = None, node_name: str = "hexar",
                 recorder: Any = None, answers: bool = True, speaker: str = "hexar serve") -> None:
        """`answers=False` is the page's viewer: no /hexar/answer, no TTS, no /hexar/question, only the robot's
        topics read; rclpy itself still writes /parameter_events, as every rclpy node does."""
        # nor does the viewer log to /rosout (a topic the robot writes and HEXAR reads) or serve parameters
        viewer = {} if answers else {"enable_rosout": False, "start_parameter_services": False}
        self.ros = RosNode(node_name, domain_id, **viewer)
        self.domain_id = domain_id
        self.speaker = speaker
        self.answers = answers
        self.node = self.ros.node
        self.tts_topic = tts_topic
        self.recorder = recorder
        self.timeline = Timeline(on_dated=self._record)
        self.errors = 0
        self._humble: Any = None
        self._own: bytes | None = None  # this node's participant (GUID prefix), found once the graph shows it
        self._string = msg_class(c.STRING_TYPE)
        self._pubs: dict[str, Any] = {}
        if answers:
            self._pubs[ANSWER] = self.node.create_publisher(self._string, ANSWER, qos_profile(ANSWER_QOS))
        if answers and tts_topic:
            self._pubs[tts_topic] = self.node.create_publisher(self._string, tts_topic, qos_profile(TTS_QOS))

    def writer_topics(self) -> list[str]:
        return sorted(self._pubs)

    def start(self, log: LiveLog, on_record: Callable[[Any], None], on_question: Callable[[str], None]) -> None:
        from hexar.events.humble import humble

        self._humble = humble()
        # rclpy's executor hands over one message per ready subscription per wait, in creation order: the
        # callback takes the rest of its topic's backlog itself, and the triggers come last (topics.READ_ORDER)
        for spec in READ_ORDER:
            holder: list[Any] = []
            holder.append(self.node.create_subscription(
                msg_class(spec.type), spec.topic, self._callback(spec.topic, spec.type, log, on_record, holder),
                qos_profile(spec.qos), raw=True))
        self.node.create_subscription(msg_class(CLOCK_TYPE), CLOCK, self._callback(CLOCK, CLOCK_TYPE, log, on_record),
                                      qos_profile(CLOCK_QOS), raw=True)

        def question(msg: Any) -> None:
            on_question(str(msg.data))

        if self.answers:
            self.node.create_subscription(self._string, QUESTION, question, qos_profile(QUESTION_QOS))

        def idle() -> None:
            add_all(self.timeline.flush(), log.add, on_record)
            if log.contact.due() and (writers := self._writers()) is not None:
                log.contact.seen(writers)

        def done() -> None:
            if self.recorder is not None:
                self.recorder.close()  # sqlite wants the thread that wrote the bag to close it

        self.ros.spin(self._report, idle, done)

    def _callback(self, topic: str, ros_type: str, log: LiveLog, on_record: Callable[[Any], None],
                  holder: list[Any] | None = None) -> Callable[[bytes, Any], None]:
        def one(raw: bytes, info: Any) -> None:
            try:
                msg = self._humble.deserialize_cdr(raw, ros_type)
                source = int(info["source_timestamp"])
                add_all(self.timeline.records(topic, msg, source), log.add, on_record)
            except Exception as err:  # one bad message is reported and skipped; the node keeps listening
                self._report(f"skipped a message on {topic}: {type(err).__name__}: {err}")
                return
            if topic != CLOCK and (gid := (info.get("publisher_gid") or {}).get("data")):
                log.contact.heard(participant_of(gid), topic)
                if (seq := info.get("publication_sequence_number")) is not None:
                    log.contact.sequence(bytes(gid), topic, int(seq))

        def handle(raw: bytes, info: Any) -> None:
            one(raw, info)
            if not holder:
                return
            sub: Any = holder[0]
            for _ in range(TAKE_BATCH):
                with sub.handle:
                    taken = sub.handle.take_message(sub.msg_type, True)
                if taken is None:
                    return
                one(*taken)

        return handle

    def _writers(self) -> dict[bytes, str] | None:
        """The participants that write the robot's topics now, as the ROS graph knows them, with their nodes' names;
        this node's own participant left out (None until the graph shows which that is)."""
        node, found = self.node, dict[bytes, set[str]]()
        try:
            if self._own is None:
                own = (node.get_publishers_info_by_topic(ANSWER) if self.answers
                       else node.get_subscriptions_info_by_topic(SUBSCRIBED[0].topic))
                mine = [i for i in own if i.node_name == node.get_name() and i.node_namespace == node.get_namespace()]
                if not mine:
                    return None
                self._own = participant_of(bytes(mine[0].endpoint_gid))
            infos = [node.get_publishers_info_by_topic(spec.topic) for spec in SUBSCRIBED]
        except Exception:  # the graph changed under the query: look again at the next poll, drop nobody now
            return None
        for found_on in infos:
            for info in found_on:
                participant = participant_of(bytes(info.endpoint_gid))
                if participant != self._own:
                    named = info.node_name not in ("", BARE_DDS)
                    found.setdefault(participant, set()).update({info.node_name} if named else ())
        return {p: ", ".join(sorted(names)) for p, names in found.items()}

    def _record(self, topic: str, msg: Any, t: int) -> None:
        """Into the rolling recording, on the robot's clock, as `ros2 bag record` on the robot stamps it."""
        if self.recorder is not None:
            ros_type = c.TYPE_OF[c.topic_key(topic)]
            self.recorder.write(topic, ros_type, bytes(self._humble.serialize_cdr(msg, ros_type)), t)

    def _report(self, line: str) -> None:
        self.errors += 1
        print(f"{self.speaker}: {line}", file=sys.stderr, flush=True)

    def publish(self, topic: str, text: str) -> None:
        if topic not in self._pubs:
            raise BadOptionError(f"HEXAR writes only on {HEXAR_PREFIX}* and its TTS topic, not on {topic}")
        self._pubs[topic].publish(self._string(data=text))

    def close(self) -> None:
        self.ros.close()
        if self.recorder is not None and self.ros._thread is None:
            self.recorder.close()


class RclpyReplayer:
    """Publishes a recording's raw CDR through rclpy publishers, as `ros2 bag play` does: the source timestamps
    are the time of publishing, the stamps inside the messages the recording's."""

    wants_dds = False

    def __init__(self, domain_id: int = 0) -> None:
        from hexar.events.humble import humble
        from hexar.live.replay import QOS_OF

        self.ros = RosNode("hexar_replay", domain_id)
        self._humble = humble()
        self._qos = QOS_OF
        self._pubs: dict[str, Any] = {}

    def prepare(self) -> None:
        for topic, qos in self._qos.items():
            if topic in self._pubs:
                continue  # prepared before: a second publisher would have to be matched again
            ros_type = c.TYPE_OF[c.topic_key(topic)]
            self._pubs[topic] = self.ros.node.create_publisher(msg_class(ros_type), topic, qos_profile(qos))

    def matched(self, topic: str) -> int:
        return int(self._pubs[topic].get_subscription_count())

    def clock(self, t: int) -> None:
        if CLOCK not in self._pubs:
            self._pubs[CLOCK] = self.ros.node.create_publisher(msg_class(CLOCK_TYPE), CLOCK, qos_profile(CLOCK_QOS))
        stamp = self._humble.types["builtin_interfaces/msg/Time"](sec=t // 1_000_000_000, nanosec=t % 1_000_000_000)
        msg = self._humble.types[CLOCK_TYPE](clock=stamp)
        self._pubs[CLOCK].publish(bytes(self._humble.serialize_cdr(msg, CLOCK_TYPE)))

    def write(self, topic: str, msgtype: str, msg: Any, t: int) -> None:
        ros_type = c.TYPE_OF[c.topic_key(topic)]
        if msgtype == c.TWIST_STAMPED_TYPE:
            msg = msg.twist  # the live topic carries Humble's Twist; the header's stamp is not sent
        elif msgtype == c.ROS1_LOG_TYPE:
            msg = self._humble.types[c.LOG_TYPE](
                stamp=msg.header.stamp, level=c.ROS1_LEVELS.get(int(msg.level), int(msg.level)), name=msg.name,
                msg=msg.msg, file=msg.file, function=msg.function, line=int(msg.line))
        # rclpy publishes serialized messages given as bytes (a memoryview is refused)
        self._pubs[topic].publish(bytes(self._humble.serialize_cdr(msg, ros_type)))

    def close(self, linger_s: float = 2.0) -> None:
        """Wait (at most `linger_s`) until reliable readers acknowledged the tail, then leave the domain."""
        for pub in self._pubs.values():
            try:
                pub.wait_for_all_acked(importlib.import_module("rclpy.duration").Duration(seconds=linger_s))
            except Exception:  # an RMW without the call: the linger is best effort
                continue
        self.ros.close()

