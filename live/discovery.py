"""ROS 2's discovery settings for the DDS transport, as a ROS node on this computer would apply them.

A computer set up for ROS 2 says whom to discover in two variables that rcl reads and hands to the middleware
(ros2/rcl, rcl/src/rcl/discovery_options.c@9.2.0): `ROS_AUTOMATIC_DISCOVERY_RANGE` (SUBNET, the default;
LOCALHOST; OFF; SYSTEM_DEFAULT) and `ROS_STATIC_PEERS` (addresses separated by ';', for networks where multicast
does not reach the robot). The DDS transport runs Cyclone DDS without rcl, so it reads them itself and gives Cyclone
the configuration rmw_cyclonedds builds from them (ros2/rmw_cyclonedds, rmw_cyclonedds_cpp/src/rmw_node.cpp
check_create_domain@3.2.0): otherwise `hexar serve --transport dds` would not hear a robot that every ROS tool on
the same computer hears.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import dataclass, field

RANGES = ("SUBNET", "LOCALHOST", "OFF", "SYSTEM_DEFAULT")


@dataclass(frozen=True)
class Discovery:
    range: str = "SUBNET"
    peers: tuple[str, ...] = ()
    notes: tuple[str, ...] = field(default=(), compare=False)  # what rcl would warn about these settings

    def cyclone_fragment(self, pid: int | None = None) -> str:
        """The Cyclone DDS configuration rmw_cyclonedds gives a node with these settings ("" for SYSTEM_DEFAULT).
        A participant index of its own (auto, at most 32) puts its unicast discovery port where a peer that lists
        this computer in its ROS_STATIC_PEERS looks for it."""
        if self.range == "SYSTEM_DEFAULT":
            return ""
        multicast = "" if self.range == "SUBNET" else "<General><AllowMulticast>false</AllowMulticast></General>"
        if self.range == "OFF":
            # a tag no other participant has: nothing is discovered, as rmw_cyclonedds does for OFF
            return (f"{multicast}<Discovery><ParticipantIndex>none</ParticipantIndex>"
                    f"<Tag>ros_discovery_off_{os.getpid() if pid is None else pid}</Tag></Discovery>")
        peers = ("localhost",) * (self.range == "LOCALHOST") + self.peers
        listed = "".join(f'<Peer address="{_xml_attr(peer)}"/>' for peer in peers)
        return (f"{multicast}<Discovery><ParticipantIndex>auto</ParticipantIndex>"
                f"<MaxAutoParticipantIndex>32</MaxAutoParticipantIndex>"
                f"{f'<Peers>{listed}</Peers>' if listed else ''}</Discovery>")


def ros_discovery(env: Mapping[str, str] | None = None) -> Discovery:
    """The discovery range and static peers rcl would take from `env` (default: this process's environment)."""
    env = os.environ if env is None else env
    notes: list[str] = []
    if env.get("ROS_LOCALHOST_ONLY", "") == "1":  # Kilted's rcl no longer reads it (Jazzy's still did)
        notes.append("ROS_LOCALHOST_ONLY is ignored, as ROS 2 Kilted ignores it: set "
                     "ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST to stay on this computer")
    wanted = env.get("ROS_AUTOMATIC_DISCOVERY_RANGE", "")
    rng = wanted or "SUBNET"
    if rng not in RANGES:
        notes.append(f"invalid ROS_AUTOMATIC_DISCOVERY_RANGE {wanted!r}: discovery stays on this computer, as rcl "
                     "assumes (use SUBNET, LOCALHOST, OFF or SYSTEM_DEFAULT)")
        rng = "LOCALHOST"
    peers = tuple(p.strip() for p in env.get("ROS_STATIC_PEERS", "").split(";") if p.strip())
    if peers and rng in ("OFF", "SYSTEM_DEFAULT"):
        notes.append(f"ROS_STATIC_PEERS is ignored with ROS_AUTOMATIC_DISCOVERY_RANGE={rng}")
        peers = ()
    return Discovery(rng, peers, tuple(notes))


def _xml_attr(text: str) -> str:
    return text.replace("&", "&amp;").replace('"', "&quot;").replace("<", "&lt;")
