"""Which nodes each DDS participant of the robot holds, from ROS 2's own graph topic, for the DDS transport.

Every ROS 2 process publishes its participant's nodes on the DDS topic `ros_discovery_info` (no `rt/` prefix:
the RMWs create it with avoid_ros_namespace_conventions) as `rmw_dds_common/msg/ParticipantEntitiesInfo`,
reliable, transient-local, keep-last 1 (ros2/rmw_fastrtps `rmw_fastrtps_cpp/src/init_rmw_context_impl.cpp`,
ros2/rmw_cyclonedds `rmw_cyclonedds_cpp/src/rmw_node.cpp`); it is what `ros2 node list` reads. rclpy names a
participant's nodes from it; the DDS transport reads it too, so that a robot process that went quiet is named by
its nodes ("amcl, bt_navigator"), not by a GUID.

`rmw_dds_common/msg/Gid` is `char[24] data` up to Humble and `char[16] data` from Iron on (ros2/rmw_dds_common,
branches humble and jazzy), under one DDS type name: a sample is decoded with the layout that re-encodes to its
own length.
"""

# No `from __future__ import annotations` (live/msgs.py says why).
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from cyclonedds.idl import IdlStruct
from cyclonedds.idl.types import array, sequence, uint8

DISCOVERY_TOPIC = "ros_discovery_info"
TYPENAME = "rmw_dds_common::msg::dds_::ParticipantEntitiesInfo_"

if TYPE_CHECKING:
    Bytes16 = list[int]
    Bytes24 = list[int]
else:
    Bytes16 = array[uint8, 16]
    Bytes24 = array[uint8, 24]


@dataclass
class Gid(IdlStruct, typename="rmw_dds_common::msg::dds_::Gid_"):
    data: Bytes16 = field(default_factory=lambda: [0] * 16)


@dataclass
class HumbleGid(IdlStruct, typename="rmw_dds_common::msg::dds_::HumbleGid_"):
    data: Bytes24 = field(default_factory=lambda: [0] * 24)


if TYPE_CHECKING:
    Gids = list[Gid]
    HumbleGids = list[HumbleGid]
else:
    Gids = sequence[Gid]
    HumbleGids = sequence[HumbleGid]


@dataclass
class NodeEntitiesInfo(IdlStruct, typename="rmw_dds_common::msg::dds_::NodeEntitiesInfo_"):
    node_namespace: str = ""
    node_name: str = ""
    reader_gid_seq: Gids = field(default_factory=list)
    writer_gid_seq: Gids = field(default_factory=list)


@dataclass
class HumbleNodeEntitiesInfo(IdlStruct, typename="rmw_dds_common::msg::dds_::HumbleNodeEntitiesInfo_"):
    node_namespace: str = ""
    node_name: str = ""
    reader_gid_seq: HumbleGids = field(default_factory=list)
    writer_gid_seq: HumbleGids = field(default_factory=list)


if TYPE_CHECKING:
    Nodes = list[NodeEntitiesInfo]
    HumbleNodes = list[HumbleNodeEntitiesInfo]
else:
    Nodes = sequence[NodeEntitiesInfo]
    HumbleNodes = sequence[HumbleNodeEntitiesInfo]


@dataclass
class HumbleParticipantEntitiesInfo(IdlStruct, typename="rmw_dds_common::msg::dds_::HumbleParticipantEntitiesInfo_"):
    gid: HumbleGid = field(default_factory=HumbleGid)
    node_entities_info_seq: HumbleNodes = field(default_factory=list)


@dataclass
class ParticipantEntitiesInfo(IdlStruct, typename=TYPENAME):
    gid: Gid = field(default_factory=Gid)
    node_entities_info_seq: Nodes = field(default_factory=list)

    @classmethod
    def deserialize(cls, data: bytes, has_header: bool = True, use_version_2: bool | None = None) -> Any:
        """The Iron-and-later layout, or Humble's where that is the one that re-encodes to as many bytes (a
        Humble sample read with the newer layout takes 8 bytes of its GID for the node count, and seems empty)."""
        kinds: tuple[type[IdlStruct], ...] = (cls, HumbleParticipantEntitiesInfo)
        for kind in kinds:
            try:
                sample: Any = kind.__idl__.deserialize(data, has_header, use_version_2)  # type: ignore[arg-type]
            except Exception:  # a layout that does not fit: try the other one
                continue
            if _same(sample.serialize(), data):
                return sample
        raise ValueError(f"a {DISCOVERY_TOPIC} sample of neither layout ({len(data)} bytes)")


def _same(encoded: bytes, data: bytes) -> bool:
    """Whether `data` is as long as `encoded`, give or take up to 3 bytes of padding at the end. Only the length:
    Fast DDS leaves the bytes it skips to align a field as they were (seen: a string's padding "d3ef")."""
    return 0 <= len(data) - len(encoded) < 4


def participant_nodes(sample: Any) -> tuple[bytes, str]:
    """(the participant's GUID prefix, its nodes' names, "amcl, bt_navigator": said to a person, so without
    their namespaces)."""
    return bytes(sample.gid.data[:12]), ", ".join(sorted({n.node_name for n in sample.node_entities_info_seq
                                                          if n.node_name}))


__all__ = ["DISCOVERY_TOPIC", "ParticipantEntitiesInfo", "participant_nodes"]
