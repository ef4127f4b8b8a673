"""A robot's traffic over real DDS for the live page: /task_info updates, real Nav2 /rosout lines (the strings of
nav2_log_messages.md in the project's reference notes) and /amcl_pose, each on its own writer with the robot's QoS
(the replayer's writers), and the page's server with `--live` in-process on a free port."""

from __future__ import annotations

import json
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from hexar.events import contract as c
from hexar.live import msgs
from hexar.live.replay import DdsReplayer

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

    def __init__(self, domain: int) -> None:
        self.writer = DdsReplayer(domain)
        self.writer.prepare()
        self.t = time.time_ns()
        self.sent = 0  # messages written; each is one record of the page's live log

    def tick(self, seconds: float) -> int:
        self.t += int(seconds * NS)
        self.sent += 1
        return self.t

    def heard_by(self, store: Any, timeout: float = 10.0) -> None:
        """Wait until the page's live log received every message written so far: DDS keeps each writer's order,
        not the order across topics, so the failing /task_info update can overtake the last /rosout lines."""
        deadline = time.monotonic() + timeout
        while store.live.log.stats()["received"] < self.sent and time.monotonic() < deadline:
            time.sleep(0.02)
        assert store.live.log.stats()["received"] == self.sent

    def task(self, task_id: str, instruction: str, status: str, error: str = "") -> None:
        step = {"skill": NAV, "params": {"location": "kitchen"}, "status": status, "error_msg": error}
        raw = json.dumps({"instruction": instruction, "task_id": task_id, "task_status": "valid",
                          "task_error_msg": "", "skill_sequence": [step]})
        self.writer.write(c.TASK_INFO, c.STRING_TYPE, msgs.String(data=raw), self.tick(0.1))

    def log(self, name: str, level: int, text: str) -> None:
        t = self.tick(0.1)
        self.writer.write(c.ROSOUT, c.LOG_TYPE, msgs.Log(stamp=msgs.time_of(t), level=level, name=name, msg=text), t)

    def pose(self, x: float, y: float) -> None:
        t = self.tick(0.1)
        cov = [0.0] * 36
        cov[0] = cov[7] = 0.02
        cov[35] = 0.01
        msg = msgs.PoseWithCovarianceStamped(header=msgs.Header(stamp=msgs.time_of(t), frame_id="map"),
                                             pose=msgs.PoseWithCovariance(pose=msgs.Pose(msgs.Point(x, y, 0.0)),
                                                                          covariance=cov))
        self.writer.write(c.AMCL_POSE, c.POSE_COV_TYPE, msg, t)

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
def live_page(domain: int, checkpoints: Path, root: Path | None = None,
              launch_log: Path | None = None) -> Iterator[tuple[str, Any]]:
    """`hexar web [root] --live --domain N [--launch-log DIR]` in this process on a free loopback port: its address
    and store."""
    from hexar.web.server import live_source, make_server
    from hexar.web.store import Store

    store = Store(root, "none", checkpoints, live_source(True, domain, launch_log))
    server = make_server(store, "127.0.0.1", 0)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}/", store
    finally:
        server.shutdown()
        server.server_close()
        store.close()
