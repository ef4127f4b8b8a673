"""The rclpy transport: a normal ROS 2 node `hexar` on the robot. Import-guarded: rclpy comes from a ROS 2
install, which cannot be installed here, so this file is not exercised by the tests (the DDS transport shares
everything but the subscription code and is tested with real traffic).
"""

from __future__ import annotations

import importlib
import threading
import time
from collections.abc import Callable
from typing import Any

from hexar.events import contract as c
from hexar.live.convert import to_records
from hexar.live.errors import BadOptionError, TransportUnavailableError
from hexar.live.log import LiveLog
from hexar.live.topics import ANSWER, ANSWER_QOS, HEXAR_PREFIX, QUESTION, QUESTION_QOS, SUBSCRIBED, TTS_QOS, TopicQos

ROS_TYPES = {
    c.LOG_TYPE: ("rcl_interfaces.msg", "Log"), c.STRING_TYPE: ("std_msgs.msg", "String"),
    c.BOOL_TYPE: ("std_msgs.msg", "Bool"), c.POSE_COV_TYPE: ("geometry_msgs.msg", "PoseWithCovarianceStamped"),
    c.DIAG_TYPE: ("diagnostic_msgs.msg", "DiagnosticArray"), c.TWIST_TYPE: ("geometry_msgs.msg", "Twist"),
    c.ODOM_TYPE: ("nav_msgs.msg", "Odometry"), c.POSE_STAMPED_TYPE: ("geometry_msgs.msg", "PoseStamped"),
    c.GOAL_STATUS_TYPE: ("action_msgs.msg", "GoalStatusArray"),
}


def rclpy_available() -> bool:
    try:
        importlib.import_module("rclpy")
    except ImportError:
        return False
    return True


class RobotClock:
    """Dates unstamped messages on the robot's clock when only the receive time is known.

    rclpy (Humble) hands a subscription callback the message without its source timestamp, so `/task_info` is
    dated from the newest stamped message (`/rosout`, `/amcl_pose`) plus the time received since; with no stamped
    message in the last few seconds the receive time itself is used (the node runs on the robot's clock).
    """

    def __init__(self, fresh_s: float = 5.0) -> None:
        self.fresh_ns = int(fresh_s * 1e9)
        self._stamp = 0
        self._recv = 0

    def stamped(self, stamp: int, recv: int) -> None:
        if stamp >= self._stamp:
            self._stamp, self._recv = stamp, recv

    def now(self, recv: int) -> int:
        if self._stamp and recv - self._recv <= self.fresh_ns:
            return self._stamp + max(recv - self._recv, 0)
        return recv


def _msg_class(ros_type: str) -> Any:
    module, name = ROS_TYPES[ros_type]
    try:
        return getattr(importlib.import_module(module), name)
    except ImportError as err:
        raise TransportUnavailableError(f"the rclpy transport needs the ROS 2 package {module}") from err


def _profile(q: TopicQos) -> Any:
    qos: Any = importlib.import_module("rclpy.qos")
    return qos.QoSProfile(
        depth=q.depth,
        reliability=qos.ReliabilityPolicy.RELIABLE if q.reliable else qos.ReliabilityPolicy.BEST_EFFORT,
        durability=(qos.DurabilityPolicy.TRANSIENT_LOCAL if q.durability == "transient_local"
                    else qos.DurabilityPolicy.VOLATILE),
    )


class RclpyTransport:  # pragma: no cover -- needs a ROS 2 install
    name = "rclpy"

    def __init__(self, tts_topic: str | None = None, node_name: str = "hexar") -> None:
        try:
            self._rclpy: Any = importlib.import_module("rclpy")
        except ImportError as err:
            raise TransportUnavailableError(
                "--transport rclpy needs a ROS 2 install (source /opt/ros/<distro>/setup.bash); "
                "without one use --transport dds") from err
        if not self._rclpy.ok():
            self._rclpy.init()
        self.node = self._rclpy.create_node(node_name)
        self.tts_topic = tts_topic
        self.clock = RobotClock()
        self._string = _msg_class(c.STRING_TYPE)
        self._pubs: dict[str, Any] = {ANSWER: self.node.create_publisher(self._string, ANSWER, _profile(ANSWER_QOS))}
        if tts_topic:
            self._pubs[tts_topic] = self.node.create_publisher(self._string, tts_topic, _profile(TTS_QOS))
        self._executor: Any = None
        self._thread: threading.Thread | None = None

    def writer_topics(self) -> list[str]:
        return sorted(self._pubs)

    def start(self, log: LiveLog, on_record: Callable[[Any], None], on_question: Callable[[str], None]) -> None:
        for spec in SUBSCRIBED:
            self.node.create_subscription(_msg_class(spec.type), spec.topic,
                                          self._callback(spec.topic, log, on_record), _profile(spec.qos))
        self.node.create_subscription(self._string, QUESTION, lambda m: on_question(str(m.data)),
                                      _profile(QUESTION_QOS))
        executors: Any = importlib.import_module("rclpy.executors")
        self._executor = executors.SingleThreadedExecutor()
        self._executor.add_node(self.node)
        self._thread = threading.Thread(target=self._executor.spin, name="hexar-rclpy", daemon=True)
        self._thread.start()

    def _callback(self, topic: str, log: LiveLog, on_record: Callable[[Any], None]) -> Callable[[Any], None]:
        stamped = topic in {c.ROSOUT, c.AMCL_POSE, c.ODOM, c.GOAL_POSE} or c.TYPE_OF.get(topic) == c.DIAG_TYPE

        def handle(msg: Any) -> None:
            recv = time.time_ns()
            records = to_records(topic, msg, self.clock.now(recv))
            for record in records:
                if stamped:
                    self.clock.stamped(record.t, recv)
                if log.add(record):
                    on_record(record)

        return handle

    def publish(self, topic: str, text: str) -> None:
        if topic not in self._pubs:
            raise BadOptionError(f"HEXAR writes only on {HEXAR_PREFIX}* and its TTS topic, not on {topic}")
        self._pubs[topic].publish(self._string(data=text))

    def close(self) -> None:
        if self._executor is not None:
            self._executor.shutdown(timeout_sec=2.0)
        self.node.destroy_node()


class RclpyReplayer:  # pragma: no cover -- needs a ROS 2 install
    """Publishes a recording's raw CDR through rclpy publishers (rclpy accepts serialized bytes)."""

    wants_dds = False

    def __init__(self) -> None:
        from hexar.live.replay import QOS_OF

        try:
            self._rclpy: Any = importlib.import_module("rclpy")
        except ImportError as err:
            raise TransportUnavailableError("--transport rclpy needs a ROS 2 install; use --transport dds") from err
        if not self._rclpy.ok():
            self._rclpy.init()
        self.node = self._rclpy.create_node("hexar_replay")
        self._qos = QOS_OF
        self._pubs: dict[str, Any] = {}

    def prepare(self) -> None:
        for topic, qos in self._qos.items():
            self._pubs[topic] = self.node.create_publisher(_msg_class(c.TYPE_OF[topic]), topic, _profile(qos))

    def write(self, topic: str, msgtype: str, msg: Any, t: int) -> None:
        from hexar.events.reader import _humble

        if msgtype != c.TYPE_OF[topic]:
            return  # a ROS 1 log or a TwistStamped has no publisher of its type here
        self._pubs[topic].publish(_humble().serialize_cdr(msg, msgtype))

    def close(self) -> None:
        self.node.destroy_node()
