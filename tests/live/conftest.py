"""Live tests run on both transports, over loopback only.

The DDS settings below are for the tests, not for users: Cyclone on 127.0.0.1 with unicast discovery to local
peers (ParticipantIndex auto, so several participants share the machine), and rmw_fastrtps limited to the host
(ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST). With them a Fast DDS node (rclpy) and a Cyclone participant find each
other on a machine whose only route is loopback, or where multicast is filtered. They are set before any
participant exists, so the subprocesses (`hexar serve`, `hexar replay`) inherit them.
"""

from __future__ import annotations

import os

import pytest

from hexar.live.ros import rclpy_available
from tests.live.dds_helpers import NO_DDS

LOOPBACK_CYCLONE = (
    '<General><Interfaces><NetworkInterface address="127.0.0.1"/></Interfaces>'
    "<AllowMulticast>false</AllowMulticast></General>"
    "<Discovery><ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>60</MaxAutoParticipantIndex>"
    '<Peers><Peer address="127.0.0.1"/></Peers></Discovery>'
)
os.environ["CYCLONEDDS_URI"] = LOOPBACK_CYCLONE
os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"

NO_RCLPY = pytest.mark.skipif(not rclpy_available(), reason="rclpy (the `ros` extra) exists for Linux x86_64 only")
TRANSPORTS = [pytest.param("dds", marks=NO_DDS), pytest.param("rclpy", marks=NO_RCLPY)]


@pytest.fixture(params=TRANSPORTS)
def transport(request: pytest.FixtureRequest) -> str:
    """The node's transport; the robot stand-in uses the other one where rclpy exists (tests.live.dds_helpers.other),
    so each run also crosses DDS vendors."""
    return str(request.param)

