"""Typed records of the HEXAR topic contract.

Every time is an integer count of nanoseconds since the epoch, taken from the message itself (log stamp,
header stamp) or from the bag's receive time for message types without a stamp.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from datetime import UTC, datetime

DEBUG, INFO, WARN, ERROR, FATAL = 10, 20, 30, 40, 50
LEVEL_NAMES = {DEBUG: "DEBUG", INFO: "INFO", WARN: "WARN", ERROR: "ERROR", FATAL: "FATAL"}


def stamp_ns(sec: int, nanosec: int) -> int:
    """Join a ROS time into integer nanoseconds (never a float from a "sec.nanosec" string)."""
    return int(sec) * 1_000_000_000 + int(nanosec)


def clock(t: int) -> str:
    """Wall-clock time (UTC) of a nanosecond stamp, to the millisecond (a stamp no calendar holds: the raw number)."""
    try:
        wall = datetime.fromtimestamp(t // 1_000_000_000, tz=UTC).strftime("%H:%M:%S")
    except (OverflowError, OSError, ValueError):
        return f"{t} ns"
    return wall + f".{t // 1_000_000 % 1000:03d}"


@dataclass(frozen=True, slots=True)
class LogLine:
    """One `/rosout` line (rcl_interfaces/msg/Log)."""

    t: int
    level: int
    name: str
    msg: str

    @property
    def level_name(self) -> str:
        return LEVEL_NAMES.get(self.level, str(self.level))

    def render(self) -> str:
        return f"[{self.name}] {self.level_name} {self.msg}"

    @property
    def speaker(self) -> str:
        """The node that logged the line, as an answer names it."""
        return self.name.strip("/") or "a node that gave no name"


@dataclass(frozen=True, slots=True)
class SkillStep:
    """One skill of a plan as published on `/task_info`."""

    skill: str
    params: dict[str, object]
    status: str
    error_msg: str = ""

    @property
    def state(self) -> str:
        """The status, lower-cased: the original publishes `Running` with a capital R."""
        return self.status.strip().lower()

    def label(self) -> str:
        args = ", ".join(f"{k}={v!r}" for k, v in self.params.items())
        return f"{self.skill}({args})"


@dataclass(frozen=True, slots=True)
class TaskUpdate:
    """One `/task_info` message (std_msgs/msg/String holding JSON)."""

    t: int
    task_id: str
    instruction: str
    task_status: str
    task_error_msg: str
    skills: tuple[SkillStep, ...]
    raw: str

    @property
    def valid(self) -> bool:
        return self.task_status.strip().lower() != "invalid"


@dataclass(frozen=True, slots=True)
class PoseSample:
    """One `/amcl_pose` (geometry_msgs/msg/PoseWithCovarianceStamped)."""

    t: int
    x: float
    y: float
    yaw: float
    cov_x: float
    cov_y: float
    cov_yaw: float

    @property
    def cov_xy(self) -> float:
        return (self.cov_x + self.cov_y) / 2.0


@dataclass(frozen=True, slots=True)
class BoolSample:
    """A std_msgs/msg/Bool flag (`/joy_priority`, `/power/is_charging`), stamped by the bag."""

    t: int
    topic: str
    value: bool


@dataclass(frozen=True, slots=True)
class StatusRecord:
    """One diagnostic_msgs/msg/DiagnosticStatus of a DiagnosticArray, with its values as pairs."""

    t: int
    topic: str
    level: int
    name: str
    message: str
    hardware_id: str
    values: tuple[tuple[str, str], ...] = field(default=())

    def get(self, key: str, default: str | None = None) -> str | None:
        for k, v in self.values:
            if k == key:
                return v
        return default

    def data_items(self) -> tuple[tuple[str, str], ...]:
        """The values without the `Module name` tag that every skill record carries."""
        return tuple((k, v) for k, v in self.values if k != "Module name")


@dataclass(frozen=True, slots=True)
class TwistSample:
    """A velocity command (`/cmd_vel`: geometry_msgs/msg/Twist or TwistStamped), stamped by the header or bag."""

    t: int
    topic: str
    vx: float
    vy: float
    wz: float


@dataclass(frozen=True, slots=True)
class OdomSample:
    """One `/odom` (nav_msgs/msg/Odometry): where the base says it is and how fast it moves."""

    t: int
    x: float
    y: float
    vx: float
    wz: float


@dataclass(frozen=True, slots=True)
class GoalStatus:
    """One goal of an action's status array (`/navigate_to_pose/_action/status`, action_msgs/msg/GoalStatus)."""

    t: int
    goal_id: str
    accepted: int
    status: int  # 1 accepted, 2 executing, 3 canceling, 4 succeeded, 5 canceled, 6 aborted
    topic: str = "/navigate_to_pose/_action/status"  # which action: Nav2's, MoveIt's or a controller's


@dataclass(frozen=True, slots=True)
class GoalPose:
    """A goal sent to Nav2 (`/goal_pose`, geometry_msgs/msg/PoseStamped)."""

    t: int
    x: float
    y: float
    frame: str
