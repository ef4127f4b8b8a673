"""Typed records of the HEXAR topic contract.

Every time is an integer count of nanoseconds since the epoch, taken from the message itself (log stamp,
header stamp) or from the bag's receive time for message types without a stamp.
"""

from __future__ import annotations

import math
import zlib
from dataclasses import dataclass, field
from datetime import UTC, datetime

DEBUG, INFO, WARN, ERROR, FATAL = 10, 20, 30, 40, 50
# CPython's traceback header: a log line holding it after its first line is a Python exception its process died of
# (events/console.py writes such records, explainers/stack/thrown.py reads them)
TRACEBACK = "Traceback (most recent call last):"
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


def hms(t: int) -> str:
    """A time of day to the second (the recording's stamps are UTC)."""
    return clock(t).split(".")[0]


def duration(ns: int) -> str:
    """A span as said: "less than a second", "36 s", "1 min 5 s"."""
    s = round(max(ns, 0) / 1e9)
    if s == 0:
        return "less than a second"
    if s < 60:
        return f"{s} s"
    m, s = divmod(s, 60)
    return f"{m} min {s} s" if s else f"{m} min"


# Before 2000 on a robot's clock: a simulator's time, which starts at zero, so no calendar day.
SIM_CLOCK_NS = 946_684_800 * 1_000_000_000


def calendar_day(t: int) -> str | None:
    """"Monday 10 March 2025": the day (UTC) of a nanosecond stamp (any int64 one is before 2263); None on a
    simulator's clock."""
    if t < SIM_CLOCK_NS:
        return None
    d = datetime.fromtimestamp(t / 1e9, tz=UTC)
    return f"{d:%A} {d.day} {d:%B %Y}"


@dataclass(frozen=True, slots=True)
class LogLine:
    """One `/rosout` line (rcl_interfaces/msg/Log), or one line of launch's log file (origin "launch.log",
    events/roslog.py: a line the recording's /rosout never carried)."""

    t: int
    level: int
    name: str
    msg: str
    origin: str = "/rosout"

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


@dataclass(frozen=True, slots=True)
class Grid:
    """One occupancy grid (`/map` or `/global_costmap/costmap`, nav_msgs/msg/OccupancyGrid). The cells are kept
    zlib-compressed: a costmap published every second for an hour is mostly the same few obstacles."""

    t: int
    topic: str
    frame: str
    resolution: float
    width: int
    height: int
    origin_x: float
    origin_y: float
    origin_yaw: float
    packed: bytes  # zlib of the int8 cells, row-major from the origin's corner

    def index(self, x: float, y: float) -> tuple[int, int] | None:
        """(column, row) of the cell holding the point (x, y) of the grid's frame, None outside the grid."""
        dx, dy = x - self.origin_x, y - self.origin_y
        cos, sin = math.cos(self.origin_yaw), math.sin(self.origin_yaw)
        col = math.floor((cos * dx + sin * dy) / self.resolution)
        row = math.floor((-sin * dx + cos * dy) / self.resolution)
        return (col, row) if 0 <= col < self.width and 0 <= row < self.height else None

    def cells(self) -> bytes:
        return zlib.decompress(self.packed)

    def value(self, x: float, y: float, cells: bytes | None = None) -> int | None:
        """The cell's value at (x, y) (-1 unknown, 0 free ... 100 occupied), None outside the grid. `cells`: this
        grid's cells() when already unpacked, so that several look-ups unpack it once."""
        at = self.index(x, y)
        if at is None:
            return None
        byte = (cells if cells is not None else self.cells())[at[1] * self.width + at[0]]
        return byte - 256 if byte > 127 else byte

    def corners(self) -> tuple[float, float, float, float]:
        """x from, x to, y from, y to of an unrotated grid (the usual map and costmap)."""
        return (self.origin_x, self.origin_x + self.width * self.resolution,
                self.origin_y, self.origin_y + self.height * self.resolution)


# rcl_interfaces/msg/ParameterValue's type field: what each value holds (0 is PARAMETER_NOT_SET)
PARAMETER_TYPES = {1: "bool", 2: "integer", 3: "double", 4: "string", 5: "byte_array", 6: "bool_array",
                   7: "integer_array", 8: "double_array", 9: "string_array"}
ParameterValue = bool | int | float | str | tuple[bool | int | float | str, ...] | None


@dataclass(frozen=True, slots=True)
class ParameterSample:
    """One parameter of a node as its /parameter_events (rcl_interfaces/msg/ParameterEvent) announced it: declared
    ("new", with the value it started with), set ("changed") or undeclared ("deleted", no value)."""

    t: int
    node: str
    name: str
    value: ParameterValue
    change: str  # "new", "changed" or "deleted"

    @property
    def said(self) -> str:
        """The value as a launch or parameter file writes it: true, 0.3, 'map', [0.1, 0.2]."""
        return said_value(self.value)


def said_value(value: ParameterValue) -> str:
    if value is None:
        return "not set"
    if isinstance(value, tuple):
        return "[" + ", ".join(said_value(v) for v in value) + "]"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return repr(value)
    return str(value)


# any one record of the event log: what a recording's reader and the live node's converter make of one message
Record = (LogLine | TaskUpdate | PoseSample | BoolSample | StatusRecord | TwistSample | OdomSample | GoalPose
          | GoalStatus | Grid | ParameterSample)
