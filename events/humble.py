"""The standard (ROS 2 Humble) message definitions: the store rosbags builds for them, and their hashes.

Building rosbags' Humble typestore imports its whole chain of distro stores (Dashing to Humble, hundreds of
message classes): about a tenth of a second on a cold start. A recording that stores its own definitions never
needs it to be decoded, only to be compared with it, so the type hashes of the types HEXAR decodes are kept here
(RIHS01, as rosidl and rosbags compute them; tests/events/test_humble.py checks them against rosbags) and the
store is built only when a recording stores no definitions or one of another type must be read.
"""

from __future__ import annotations

from rosbags.typesys import Stores, get_typestore
from rosbags.typesys.store import Typestore

# RIHS01 hash of the Humble definition of every type a HEXAR topic accepts (events.contract.ACCEPTED_TYPES);
# rosgraph_msgs/msg/Log is ROS 1's and has none.
RIHS01: dict[str, str] = {
    "action_msgs/msg/GoalStatusArray": "RIHS01_6c1684b00f177d37438febe6e709fc4e2b0d4248dca4854946f9ed8b30cda83e",
    "diagnostic_msgs/msg/DiagnosticArray": "RIHS01_5a8a36efb05fb25070fa0fb3810290c0e6cd4862b54a8fb975a1ee8dc55a333e",
    "geometry_msgs/msg/PoseStamped": "RIHS01_10f3786d7d40fd2b54367835614bff85d4ad3b5dab62bf8bca0cc232d73b4cd8",
    "geometry_msgs/msg/PoseWithCovarianceStamped":
        "RIHS01_26432f9803e43727d3c8f668d1fdb3c630f548af631e2f4e31382371bfea3b6e",
    "geometry_msgs/msg/Twist": "RIHS01_9c45bf16fe0983d80e3cfe750d6835843d265a9a6c46bd2e609fcddde6fb8d2a",
    "geometry_msgs/msg/TwistStamped": "RIHS01_5f0fcd4f81d5d06ad9b4c4c63e3ea51b82d6ae4d0558f1d475229b1121db6f64",
    "nav_msgs/msg/OccupancyGrid": "RIHS01_8d348150c12913a31ee0ec170fbf25089e4745d17035792a1ba94d6f0bc0cfc7",
    "nav_msgs/msg/Odometry": "RIHS01_3cc97dc7fb7502f8714462c526d369e35b603cfc34d946e3f2eda2766dfec6e0",
    "rcl_interfaces/msg/Log": "RIHS01_e28ce254ca8abc06abf92773b74602cdbf116ed34fbaf294fb9f81da9f318eac",
    "rcl_interfaces/msg/ParameterEvent": "RIHS01_043e627780fcad87a22d225bc2a037361dba713fca6a6b9f4b869a5aa0393204",
    "std_msgs/msg/Bool": "RIHS01_feb91e995ff9ebd09c0cb3d2aed18b11077585839fb5db80193b62d74528f6c9",
    "std_msgs/msg/String": "RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18",
}

_STORE: Typestore | None = None


def humble() -> Typestore:
    """rosbags' Humble typestore, built on first use and shared."""
    global _STORE
    if _STORE is None:
        _STORE = get_typestore(Stores.ROS2_HUMBLE)
    return _STORE


def is_humble(store: Typestore) -> bool:
    """Whether `store` is the shared Humble store (without building it)."""
    return _STORE is not None and store is _STORE


def humble_hash(msgtype: str) -> str:
    """The RIHS01 hash of the Humble definition of `msgtype` (KeyError and rosbags' errors for a type it lacks)."""
    known = RIHS01.get(msgtype)
    return known if known is not None else humble().hash_rihs01(msgtype)


def has_standard(msgtype: str) -> bool:
    """Whether Humble defines `msgtype`."""
    return msgtype in RIHS01 or msgtype in humble().fielddefs
