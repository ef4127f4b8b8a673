"""/cmd_vel (Twist or TwistStamped) and /odom decoding, fast path and rosbags' agree; an ordinary topic name
carrying another type is skipped with a warning, never an error."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from hexar.evals.scenarios.bag import TYPESTORE, BagBuilder
from hexar.events.cdr import decode_odom, decode_twist
from hexar.events.reader import read_recording
from tests.events.helpers import T0

TY = TYPESTORE.types


def _header(t: int) -> object:
    return TY["std_msgs/msg/Header"](stamp=TY["builtin_interfaces/msg/Time"](sec=t // 10**9, nanosec=t % 10**9),
                                     frame_id="base_link")


def _twist(vx: float, wz: float) -> object:
    v3 = TY["geometry_msgs/msg/Vector3"]
    return TY["geometry_msgs/msg/Twist"](linear=v3(x=vx, y=0.0, z=0.0), angular=v3(x=0.0, y=0.0, z=wz))


def _odom(t: int, x: float, y: float, child: str = "base_footprint") -> object:
    pose = TY["geometry_msgs/msg/Pose"](position=TY["geometry_msgs/msg/Point"](x=x, y=y, z=0.0),
                                        orientation=TY["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0))
    return TY["nav_msgs/msg/Odometry"](
        header=_header(t), child_frame_id=child,
        pose=TY["geometry_msgs/msg/PoseWithCovariance"](pose=pose, covariance=np.arange(36, dtype=np.float64)),
        twist=TY["geometry_msgs/msg/TwistWithCovariance"](twist=_twist(0.25, -0.5), covariance=np.ones(36)))


@pytest.mark.parametrize("child", ["b", "base_footprint", "odd_len_frame"])
def test_fast_decoders_read_what_rosbags_wrote(child: str) -> None:
    raw = bytes(TYPESTORE.serialize_cdr(_odom(T0 + 7, 1.5, -2.25, child), "nav_msgs/msg/Odometry"))
    assert decode_odom(raw) == (T0 + 7, 1.5, -2.25, 0.25, -0.5)
    stamped = TY["geometry_msgs/msg/TwistStamped"](header=_header(T0 + 9), twist=_twist(0.1, 0.2))
    got = decode_twist(bytes(TYPESTORE.serialize_cdr(stamped, "geometry_msgs/msg/TwistStamped")), True)
    assert got == (T0 + 9, (0.1, 0.0, 0.0, 0.0, 0.0, 0.2))
    assert decode_twist(bytes(TYPESTORE.serialize_cdr(_twist(0.3, 0.0), "geometry_msgs/msg/Twist")), False) == (
        0, (0.3, 0.0, 0.0, 0.0, 0.0, 0.0))


@pytest.mark.parametrize("storage", ["sqlite3", "mcap"])
def test_cmd_vel_and_odom_are_decoded_in_both_storages(tmp_path: Path, storage: str) -> None:
    b = BagBuilder()
    b.raw(T0, "/cmd_vel", "geometry_msgs/msg/TwistStamped",
          TY["geometry_msgs/msg/TwistStamped"](header=_header(T0), twist=_twist(0.2, 0.1)))
    b.raw(T0 + 1, "/odom", "nav_msgs/msg/Odometry", _odom(T0 + 1, 3.0, 4.0))
    log = read_recording(b.write(tmp_path / "bag", storage=storage))  # type: ignore[arg-type]
    (cmd,) = log.twists
    (odom,) = log.odometry
    assert (cmd.t, cmd.vx, cmd.wz) == (T0, 0.2, 0.1)
    assert (odom.t, odom.x, odom.y, odom.vx, odom.wz) == (T0 + 1, 3.0, 4.0, 0.25, -0.5)


def test_another_type_on_an_ordinary_topic_name_is_skipped(tmp_path: Path) -> None:
    b = BagBuilder()
    b.raw(T0, "/odom", "geometry_msgs/msg/Twist", _twist(0.2, 0.0))
    log = read_recording(b.write(tmp_path / "bag"))
    assert log.odometry == [] and any("skipped /odom" in w for w in log.warnings)
