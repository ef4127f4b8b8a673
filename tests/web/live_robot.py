"""A robot's traffic over real DDS for the live page: /task_info updates, real Nav2 /rosout lines (the strings of
nav2_log_messages.md in the project's reference notes) and /amcl_pose, each on its own writer with the robot's QoS
(the replayer's writers: cyclonedds, or rclpy's Fast DDS), and the page's server with `--live` in-process on a free
port."""

from __future__ import annotations

import json
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np

from hexar.events import contract as c
from hexar.events.humble import humble
from hexar.live.replay import to_dds
from tests.live.dds_helpers import DEFAULT, make_replayer, wait_matched

NS = 1_000_000_000
NAV = "navigate_to_zone"
BLOCKED_LINES = [  # controller and planner give up on a path that an obstacle closed (Nav2 Humble strings)
    ("controller_server", 40, "Failed to make progress"),
    ("controller_server", 30, "[follow_path] [ActionServer] Aborting handle."),
    ("planner_server", 30, "GridBased: failed to create plan with tolerance 0.50."),
    ("planner_server", 30, "Planning algorithm GridBased failed to generate a valid path to (4.20, 2.10)"),
    ("planner_server", 30, "[compute_path_to_pose] [ActionServer] Aborting handle."),
    ("planner_server", 30, "GridBased: failed to create plan with tolerance 0.50."),
    ("planner_server", 30, "Planning algorithm GridBased failed to generate a valid path to (4.20, 2.10)"),
    ("planner_server", 30, "[compute_path_to_pose] [ActionServer] Aborting handle."),
    ("behavior_server", 20, "Running spin"),
    ("planner_server", 30, "GridBased: failed to create plan with tolerance 0.50."),
    ("planner_server", 30, "Planning algorithm GridBased failed to generate a valid path to (4.20, 2.10)"),
    ("planner_server", 30, "[compute_path_to_pose] [ActionServer] Aborting handle."),
    ("bt_navigator", 40, "Goal failed"),
    ("bt_navigator", 30, "[navigate_to_pose] [ActionServer] Aborting handle."),
]


class Robot:
    """The robot's publishers on one DDS domain; stamps follow the robot's clock, which starts now."""

    def __init__(self, domain: int, transport: str = DEFAULT) -> None:
        self.writer = make_replayer(transport, domain)
        self.writer.prepare()
        self.types = humble().types
        self._matched: set[str] = set()
        self.t = time.time_ns()
        self.sent = 0  # messages written; each is one record of the page's live log

    def tick(self, seconds: float) -> int:
        """The next message's stamp; the first waits until the page's readers matched (across DDS vendors discovery
        takes a second more than the writer's side shows, and a volatile topic's early messages would be lost)."""
        if not self._matched:
            self._matched = {c.TASK_INFO, c.ROSOUT, c.AMCL_POSE}
            wait_matched(self.writer, self._matched, settle_s=2.0)
            self.t = max(self.t, time.time_ns())
        self.t += int(seconds * NS)
        self.sent += 1
        if not self.writer.wants_dds:
            # rclpy stamps each message's source time with the time of publishing, as `ros2 bag play` does, and a
            # String (/task_info) has no stamp of its own: the robot's clock keeps to the wall clock, as a real one
            time.sleep(max(0.0, (self.t - time.time_ns()) / NS))
        return self.t

    def heard_by(self, store: Any, timeout: float = 10.0) -> None:
        """Wait until the page's live log received every message written so far: DDS keeps each writer's order,
        not the order across topics, so the failing /task_info update can overtake the last /rosout lines."""
        deadline = time.monotonic() + timeout
        while store.live.log.stats()["received"] < self.sent and time.monotonic() < deadline:
            time.sleep(0.02)
        assert store.live.log.stats()["received"] == self.sent, (store.live.log.stats(), self.sent)

    def task(self, task_id: str, instruction: str, status: str, error: str = "") -> None:
        step = {"skill": NAV, "params": {"location": "kitchen"}, "status": status, "error_msg": error}
        raw = json.dumps({"instruction": instruction, "task_id": task_id, "task_status": "valid",
                          "task_error_msg": "", "skill_sequence": [step]})
        self._write(c.TASK_INFO, c.STRING_TYPE, self.types[c.STRING_TYPE](data=raw), self.tick(0.1))

    def _write(self, topic: str, msgtype: str, msg: Any, t: int) -> None:
        """A rosbags message of `msgtype`, as the replayer's transport writes it."""
        self.writer.write(topic, msgtype, to_dds(msgtype, msg) if self.writer.wants_dds else msg, t)

    def _stamp(self, t: int) -> Any:
        return self.types["builtin_interfaces/msg/Time"](sec=t // NS, nanosec=t % NS)

    def log(self, name: str, level: int, text: str) -> None:
        t = self.tick(0.1)
        msg = self.types[c.LOG_TYPE](stamp=self._stamp(t), level=level, name=name, msg=text, file="", function="",
                                     line=0)
        self._write(c.ROSOUT, c.LOG_TYPE, msg, t)

    def pose(self, x: float, y: float) -> None:
        t = self.tick(0.1)
        cov = np.zeros(36)
        cov[0] = cov[7] = 0.02
        cov[35] = 0.01
        ty = self.types
        pose = ty["geometry_msgs/msg/Pose"](position=ty["geometry_msgs/msg/Point"](x=x, y=y, z=0.0),
                                            orientation=ty["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0))
        msg = ty[c.POSE_COV_TYPE](header=ty["std_msgs/msg/Header"](stamp=self._stamp(t), frame_id="map"),
                                  pose=ty["geometry_msgs/msg/PoseWithCovariance"](pose=pose, covariance=cov))
        self._write(c.AMCL_POSE, c.POSE_COV_TYPE, msg, t)

    def blocked_trip(self, task_id: str, instruction: str) -> None:
        """A navigation task that fails because the path is blocked, with its poses and Nav2 lines."""
        self.task(task_id, instruction, "waiting")
        self.task(task_id, instruction, "Running")
        self.log("skill_navigate_to_zone", 20, "Navigating to kitchen at (4.20, 2.10)")
        self.log("bt_navigator", 20, "Begin navigating from current location (-1.80, 0.60) to (4.20, 2.10)")
        self.log("controller_server", 20, "Received a goal, begin computing control effort.")
        for i in range(10):
            self.pose(-1.8 + 0.2 * i, 0.6 + 0.05 * i)
            self.log("controller_server", 20, "Passing new path to controller.")
        for name, level, text in BLOCKED_LINES:
            self.log(name, level, text)
        self.log("skill_navigate_to_zone", 40, "Navigation to kitchen failed")
        self.task(task_id, instruction, "failed", "Navigation to kitchen failed")

    def close(self) -> None:
        self.writer.close()


@contextmanager
def live_page(domain: int, checkpoints: Path, root: Path | None = None, launch_log: Path | None = None,
              transport: str = "auto") -> Iterator[tuple[str, Any]]:
    """`hexar web [root] --live --domain N [--launch-log DIR] [--transport T]` in this process on a free loopback
    port: its address and store."""
    from hexar.web.server import live_source, make_server
    from hexar.web.store import Store

    store = Store(root, "none", checkpoints, live_source(True, domain, launch_log, transport))
    server = make_server(store, "127.0.0.1", 0)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}/", store
    finally:
        server.shutdown()
        server.server_close()
        store.close()
