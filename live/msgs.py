"""The ROS 2 message types HEXAR reads and writes, as DDS sees them from rmw_cyclonedds and rmw_fastrtps.

Both RMWs name a ROS type `<pkg>::msg::dds_::<Type>_` and a topic `rt/<topic>` and send plain CDR (XCDR1) of
final structs. Each field has the IDL type rosidl gives it: `byte` is an octet, `uint8` a uint8, fixed arrays
(`float64[36]`, `uint8[16]`) are arrays, `T[]` unbounded sequences. The field order is the .msg field order
(the project's shared reference msg_definitions.md: rcl_interfaces/Log, builtin_interfaces/Time,
std_msgs/String|Bool|Header, geometry_msgs/PoseWithCovarianceStamped, diagnostic_msgs/DiagnosticArray,
geometry_msgs/Twist|Vector3|PoseStamped, action_msgs/GoalStatusArray|GoalStatus|GoalInfo,
unique_identifier_msgs/UUID; nav_msgs/Odometry, nav_msgs/OccupancyGrid, nav_msgs/MapMetaData and
geometry_msgs/TwistWithCovariance and rcl_interfaces/ParameterEvent|Parameter|ParameterValue as rosbags' Humble
type store defines them). A test checks each against the
Kilted rclpy message classes (tests/live/test_msgs.py).
"""

# No `from __future__ import annotations` here: cyclonedds resolves field annotations by name in this
# module, and builtins such as `str` are not found that way.
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from cyclonedds.idl import IdlStruct
from cyclonedds.idl.types import array, byte, float32, float64, int8, int32, int64, sequence, uint8, uint32


def _dds(ros_type: str) -> str:
    """`rcl_interfaces/msg/Log` -> `rcl_interfaces::msg::dds_::Log_`."""
    pkg, kind, name = ros_type.split("/")
    return f"{pkg}::{kind}::dds_::{name}_"


@dataclass
class Time(IdlStruct, typename=_dds("builtin_interfaces/msg/Time")):
    sec: int32 = 0
    nanosec: uint32 = 0


@dataclass
class Log(IdlStruct, typename=_dds("rcl_interfaces/msg/Log")):
    stamp: Time = field(default_factory=Time)
    level: uint8 = 20
    name: str = ""
    msg: str = ""
    file: str = ""
    function: str = ""
    line: uint32 = 0


@dataclass
class String(IdlStruct, typename=_dds("std_msgs/msg/String")):
    data: str = ""


@dataclass
class Bool(IdlStruct, typename=_dds("std_msgs/msg/Bool")):
    data: bool = False


@dataclass
class Header(IdlStruct, typename=_dds("std_msgs/msg/Header")):
    stamp: Time = field(default_factory=Time)
    frame_id: str = ""


@dataclass
class Point(IdlStruct, typename=_dds("geometry_msgs/msg/Point")):
    x: float64 = 0.0
    y: float64 = 0.0
    z: float64 = 0.0


@dataclass
class Quaternion(IdlStruct, typename=_dds("geometry_msgs/msg/Quaternion")):
    x: float64 = 0.0
    y: float64 = 0.0
    z: float64 = 0.0
    w: float64 = 1.0


@dataclass
class Pose(IdlStruct, typename=_dds("geometry_msgs/msg/Pose")):
    position: Point = field(default_factory=Point)
    orientation: Quaternion = field(default_factory=Quaternion)


# mypy sees plain lists; cyclonedds needs its own array/sequence markers to lay out the CDR
if TYPE_CHECKING:
    Covariance = list[float]
else:
    Covariance = array[float64, 36]


@dataclass
class PoseWithCovariance(IdlStruct, typename=_dds("geometry_msgs/msg/PoseWithCovariance")):
    pose: Pose = field(default_factory=Pose)
    covariance: Covariance = field(default_factory=lambda: [0.0] * 36)


@dataclass
class PoseWithCovarianceStamped(IdlStruct, typename=_dds("geometry_msgs/msg/PoseWithCovarianceStamped")):
    header: Header = field(default_factory=Header)
    pose: PoseWithCovariance = field(default_factory=PoseWithCovariance)


@dataclass
class KeyValue(IdlStruct, typename=_dds("diagnostic_msgs/msg/KeyValue")):
    key: str = ""
    value: str = ""


if TYPE_CHECKING:
    KeyValues = list[KeyValue]
else:
    KeyValues = sequence[KeyValue]


@dataclass
class DiagnosticStatus(IdlStruct, typename=_dds("diagnostic_msgs/msg/DiagnosticStatus")):
    level: byte = 0  # `byte` in the .msg: an IDL octet (XTypes TK_BYTE), not uint8 (TK_UINT8)
    name: str = ""
    message: str = ""
    hardware_id: str = ""
    values: KeyValues = field(default_factory=list)


if TYPE_CHECKING:
    Statuses = list[DiagnosticStatus]
else:
    Statuses = sequence[DiagnosticStatus]


@dataclass
class DiagnosticArray(IdlStruct, typename=_dds("diagnostic_msgs/msg/DiagnosticArray")):
    header: Header = field(default_factory=Header)
    status: Statuses = field(default_factory=list)


@dataclass
class PoseStamped(IdlStruct, typename=_dds("geometry_msgs/msg/PoseStamped")):
    header: Header = field(default_factory=Header)
    pose: Pose = field(default_factory=Pose)


@dataclass
class Vector3(IdlStruct, typename=_dds("geometry_msgs/msg/Vector3")):
    x: float64 = 0.0
    y: float64 = 0.0
    z: float64 = 0.0


@dataclass
class Twist(IdlStruct, typename=_dds("geometry_msgs/msg/Twist")):
    linear: Vector3 = field(default_factory=Vector3)
    angular: Vector3 = field(default_factory=Vector3)


@dataclass
class TwistWithCovariance(IdlStruct, typename=_dds("geometry_msgs/msg/TwistWithCovariance")):
    twist: Twist = field(default_factory=Twist)
    covariance: Covariance = field(default_factory=lambda: [0.0] * 36)


@dataclass
class Odometry(IdlStruct, typename=_dds("nav_msgs/msg/Odometry")):
    header: Header = field(default_factory=Header)
    child_frame_id: str = ""
    pose: PoseWithCovariance = field(default_factory=PoseWithCovariance)
    twist: TwistWithCovariance = field(default_factory=TwistWithCovariance)


if TYPE_CHECKING:
    Uuid16 = list[int]
else:
    Uuid16 = array[uint8, 16]


@dataclass
class UUID(IdlStruct, typename=_dds("unique_identifier_msgs/msg/UUID")):
    uuid: Uuid16 = field(default_factory=lambda: [0] * 16)


@dataclass
class GoalInfo(IdlStruct, typename=_dds("action_msgs/msg/GoalInfo")):
    goal_id: UUID = field(default_factory=UUID)
    stamp: Time = field(default_factory=Time)


@dataclass
class GoalStatus(IdlStruct, typename=_dds("action_msgs/msg/GoalStatus")):
    goal_info: GoalInfo = field(default_factory=GoalInfo)
    status: int8 = 0  # 1 accepted, 2 executing, 3 canceling, 4 succeeded, 5 canceled, 6 aborted


if TYPE_CHECKING:
    GoalStatuses = list[GoalStatus]
else:
    GoalStatuses = sequence[GoalStatus]


@dataclass
class GoalStatusArray(IdlStruct, typename=_dds("action_msgs/msg/GoalStatusArray")):
    status_list: GoalStatuses = field(default_factory=list)


@dataclass
class MapMetaData(IdlStruct, typename=_dds("nav_msgs/msg/MapMetaData")):
    map_load_time: Time = field(default_factory=Time)
    resolution: float32 = 0.0
    width: uint32 = 0
    height: uint32 = 0
    origin: Pose = field(default_factory=Pose)


if TYPE_CHECKING:
    Cells = list[int]
else:
    Cells = sequence[int8]


@dataclass
class OccupancyGrid(IdlStruct, typename=_dds("nav_msgs/msg/OccupancyGrid")):
    header: Header = field(default_factory=Header)
    info: MapMetaData = field(default_factory=MapMetaData)
    data: Cells = field(default_factory=list)


@dataclass
class Clock(IdlStruct, typename=_dds("rosgraph_msgs/msg/Clock")):
    clock: Time = field(default_factory=Time)


if TYPE_CHECKING:
    Bytes = list[int]
    Bools = list[bool]
    Int64s = list[int]
    Float64s = list[float]
    Strings = list[str]
else:
    Bytes = sequence[byte]
    Bools = sequence[bool]
    Int64s = sequence[int64]
    Float64s = sequence[float64]
    Strings = sequence[str]


@dataclass
class ParameterValue(IdlStruct, typename=_dds("rcl_interfaces/msg/ParameterValue")):
    type: uint8 = 0  # 1 bool, 2 integer, 3 double, 4 string, 5-9 arrays of byte, bool, integer, double, string
    bool_value: bool = False
    integer_value: int64 = 0
    double_value: float64 = 0.0
    string_value: str = ""
    byte_array_value: Bytes = field(default_factory=list)
    bool_array_value: Bools = field(default_factory=list)
    integer_array_value: Int64s = field(default_factory=list)
    double_array_value: Float64s = field(default_factory=list)
    string_array_value: Strings = field(default_factory=list)


@dataclass
class Parameter(IdlStruct, typename=_dds("rcl_interfaces/msg/Parameter")):
    name: str = ""
    value: ParameterValue = field(default_factory=ParameterValue)


if TYPE_CHECKING:
    Parameters = list[Parameter]
else:
    Parameters = sequence[Parameter]


@dataclass
class ParameterEvent(IdlStruct, typename=_dds("rcl_interfaces/msg/ParameterEvent")):
    stamp: Time = field(default_factory=Time)
    node: str = ""
    new_parameters: Parameters = field(default_factory=list)
    changed_parameters: Parameters = field(default_factory=list)
    deleted_parameters: Parameters = field(default_factory=list)


def time_of(t: int) -> Time:
    return Time(sec=t // 1_000_000_000, nanosec=t % 1_000_000_000)
