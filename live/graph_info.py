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
from typing import Any

from cyclonedds.idl import IdlStruct, make_idl_struct
from cyclonedds.idl.types import array, sequence, uint8

DISCOVERY_TOPIC = "ros_discovery_info"
_NS = "rmw_dds_common::msg::dds_::"
# the binding's type constructors, indexed at run time (mypy sees no generics in them)
_array: Any = array
_sequence: Any = sequence


def _either_layout(cls: type, data: bytes, has_header: bool = True, use_version_2: bool | None = None) -> Any:
    """The Iron-and-later layout, or Humble's where that is the one that re-encodes to as many bytes (a Humble
    sample read with the newer layout takes 8 bytes of its GID for the node count, and seems empty)."""
    for kind in (ParticipantEntitiesInfo, HumbleParticipantEntitiesInfo):
        try:  # the binding reads short data leniently (a short GID) and then cannot encode what it read
            sample: Any = kind.__idl__.deserialize(data, has_header, use_version_2)  # type: ignore[arg-type]
            if _same(sample.serialize(), data):
                return sample
        except Exception:  # a layout that does not fit: try the other one
            continue
    raise ValueError(f"a {DISCOVERY_TOPIC} sample of neither layout ({len(data)} bytes)")


def _layout(gid_bytes: int, tag: str = "") -> tuple[type[IdlStruct], ...]:
    """rmw_dds_common's Gid, NodeEntitiesInfo and ParticipantEntitiesInfo with a Gid of `gid_bytes`; `tag` names
    a layout that is only ever decoded by hand, never offered on the wire under its own type name."""
    gid = make_idl_struct(f"{tag}Gid", f"{_NS}{tag}Gid_", {"data": _array[uint8, gid_bytes]})
    node = make_idl_struct(f"{tag}NodeEntitiesInfo", f"{_NS}{tag}NodeEntitiesInfo_", {
        "node_namespace": str, "node_name": str, "reader_gid_seq": _sequence[gid], "writer_gid_seq": _sequence[gid]})
    info = make_idl_struct(f"{tag}ParticipantEntitiesInfo", f"{_NS}{tag}ParticipantEntitiesInfo_",
                           {"gid": gid, "node_entities_info_seq": _sequence[node]})
    return gid, node, info


Gid, NodeEntitiesInfo, ParticipantEntitiesInfo = _layout(16)
HumbleGid, HumbleNodeEntitiesInfo, HumbleParticipantEntitiesInfo = _layout(24, "Humble")
# the reader decodes each sample with its type's `deserialize`: this one tries both layouts
setattr(ParticipantEntitiesInfo, "deserialize", classmethod(_either_layout))  # noqa: B010


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
