"""Collects what a simulated robot publishes and writes it as a real rosbag2 recording with rosbags."""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

from rosbags.rosbag2 import StoragePlugin, Writer

from hexar.events import contract as c
from hexar.events.humble import humble

Storage = Literal["sqlite3", "mcap"]
NS = 1_000_000_000
TYPESTORE = humble()
_T = TYPESTORE.types


def sec_ns(seconds: float) -> int:
    return round(seconds * NS)


def _time(t: int) -> Any:
    return _T["builtin_interfaces/msg/Time"](sec=t // NS, nanosec=t % NS)


def _header(t: int, frame: str) -> Any:
    return _T["std_msgs/msg/Header"](stamp=_time(t), frame_id=frame)


def parameter(name: str, value: Any) -> Any:
    """An rcl_interfaces/msg/Parameter with its ParameterValue's type set from the Python value (None: not set)."""
    import numpy as np

    fields: dict[str, Any] = {"bool_value": False, "integer_value": 0, "double_value": 0.0, "string_value": "",
                              "byte_array_value": np.array([], dtype=np.uint8),
                              "bool_array_value": np.array([], dtype=np.bool_),
                              "integer_array_value": np.array([], dtype=np.int64),
                              "double_array_value": np.array([], dtype=np.float64), "string_array_value": []}
    kind = 0
    if isinstance(value, bool):
        kind, fields["bool_value"] = 1, value
    elif isinstance(value, int):
        kind, fields["integer_value"] = 2, value
    elif isinstance(value, float):
        kind, fields["double_value"] = 3, value
    elif isinstance(value, str):
        kind, fields["string_value"] = 4, value
    elif isinstance(value, list) and value and all(isinstance(v, str) for v in value):
        kind, fields["string_array_value"] = 9, value
    elif isinstance(value, list) and all(isinstance(v, float) for v in value):
        kind, fields["double_array_value"] = 8, np.array(value, dtype=np.float64)
    elif isinstance(value, list):
        kind, fields["integer_array_value"] = 7, np.array(value, dtype=np.int64)
    return _T["rcl_interfaces/msg/Parameter"](name=name, value=_T["rcl_interfaces/msg/ParameterValue"](
        type=kind, **fields))


@dataclass
class BagBuilder:
    """Messages in publication order; `t` values are integer nanoseconds since the epoch.

    `receive_lag` models that a bag stamps a message when the recorder receives it, a little after the
    publisher's own stamp.
    """

    messages: list[tuple[int, str, str, Any]] = field(default_factory=list)
    receive_lag: int = 2_000_000

    def log(self, t: int, name: str, level: int, msg: str, file: str = "", function: str = "", line: int = 0) -> None:
        m = _T["rcl_interfaces/msg/Log"](
            stamp=_time(t), level=level, name=name, msg=msg, file=file, function=function, line=line
        )
        self.messages.append((t + self.receive_lag, c.ROSOUT, c.LOG_TYPE, m))

    def task_info(self, t: int, payload: dict[str, Any]) -> None:
        m = _T["std_msgs/msg/String"](data=json.dumps(payload))
        self.messages.append((t, c.TASK_INFO, c.STRING_TYPE, m))

    def pose(self, t: int, x: float, y: float, yaw: float, cov_x: float, cov_y: float, cov_yaw: float) -> None:
        cov = [0.0] * 36
        cov[0], cov[7], cov[35] = cov_x, cov_y, cov_yaw
        import numpy as np

        pose = _T["geometry_msgs/msg/Pose"](
            position=_T["geometry_msgs/msg/Point"](x=x, y=y, z=0.0),
            orientation=_T["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=math.sin(yaw / 2), w=math.cos(yaw / 2)),
        )
        m = _T["geometry_msgs/msg/PoseWithCovarianceStamped"](
            header=_header(t, "map"),
            pose=_T["geometry_msgs/msg/PoseWithCovariance"](pose=pose, covariance=np.array(cov, dtype=np.float64)),
        )
        self.messages.append((t + self.receive_lag, c.AMCL_POSE, c.POSE_COV_TYPE, m))

    def flag(self, t: int, topic: str, value: bool) -> None:
        self.messages.append((t, topic, c.BOOL_TYPE, _T["std_msgs/msg/Bool"](data=value)))

    def status(
        self,
        t: int,
        topic: str,
        name: str,
        message: str,
        values: Sequence[tuple[str, str]],
        level: int = 0,
        hardware_id: str = "",
    ) -> None:
        kvs = [_T["diagnostic_msgs/msg/KeyValue"](key=k, value=v) for k, v in values]
        status = _T["diagnostic_msgs/msg/DiagnosticStatus"](
            level=level, name=name, message=message, hardware_id=hardware_id, values=kvs
        )
        m = _T["diagnostic_msgs/msg/DiagnosticArray"](header=_header(t, ""), status=[status])
        self.messages.append((t + self.receive_lag, topic, c.DIAG_TYPE, m))

    def parameters(self, t: int, node: str, new: dict[str, Any] | None = None,
                   changed: dict[str, Any] | None = None, deleted: Sequence[str] = ()) -> None:
        """One rcl_interfaces/msg/ParameterEvent of `node`, as rclcpp publishes it when parameters are declared
        (`new`), set (`changed`) or undeclared (`deleted`)."""
        m = _T[c.PARAMETER_EVENT_TYPE](
            stamp=_time(t), node=node, new_parameters=[parameter(k, v) for k, v in (new or {}).items()],
            changed_parameters=[parameter(k, v) for k, v in (changed or {}).items()],
            deleted_parameters=[parameter(k, None) for k in deleted])
        self.messages.append((t + self.receive_lag, c.PARAMETER_EVENTS, c.PARAMETER_EVENT_TYPE, m))

    def raw(self, t: int, topic: str, msgtype: str, msg: Any) -> None:
        self.messages.append((t, topic, msgtype, msg))

    def write(self, out: Path, storage: Storage = "sqlite3") -> Path:
        plugin = StoragePlugin.MCAP if storage == "mcap" else StoragePlugin.SQLITE3
        out = Path(out)
        with Writer(out, version=9, storage_plugin=plugin) as writer:
            conns: dict[tuple[str, str], Any] = {}
            for t, topic, msgtype, msg in sorted(self.messages, key=lambda m: m[0]):
                key = (topic, msgtype)
                if key not in conns:
                    conns[key] = writer.add_connection(topic, msgtype, typestore=TYPESTORE)
                writer.write(conns[key], t, TYPESTORE.serialize_cdr(msg, msgtype))
        return out


@dataclass(frozen=True)
class SkillResult:
    """How a simulated skill execution ended: when, whether it succeeded, and the skill's error message."""

    end: int
    succeeded: bool
    error_msg: str = ""
