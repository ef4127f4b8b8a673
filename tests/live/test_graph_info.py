"""The robot's processes named by their nodes on the DDS transport (live/graph_info.py): ROS 2's own
`ros_discovery_info`, read from a real rclpy/Fast DDS robot, in both Gid layouts (Humble's 24 bytes, 16 since
Iron); a process nobody could name is never said aloud by its GUID."""

from __future__ import annotations

import subprocess
import sys
import textwrap
import time
from typing import Any

import pytest

# cyclonedds has no wheel for CPython 3.14 (the lock installs it only below); these tests are of the DDS transport
pytest.importorskip("cyclonedds", reason="cyclonedds (the `live` extra) has no wheel for this Python")

from hexar.live.contact import Contact, Gap, note
from hexar.live.graph_info import (
    Gid,
    HumbleGid,
    HumbleNodeEntitiesInfo,
    HumbleParticipantEntitiesInfo,
    NodeEntitiesInfo,
    ParticipantEntitiesInfo,
    participant_nodes,
)
from tests.live.conftest import NO_RCLPY
from tests.live.dds_helpers import fresh_domain, live_node

GUID = bytes(range(1, 13)) + b"\x00\x00\x01\xc1"


def _info(kind: type, gid: type, node: type, size: int, *nodes: tuple[str, str]) -> Any:
    """A ParticipantEntitiesInfo of one layout; each node writes one topic (its gid: the participant's)."""
    def me() -> Any:
        return gid(data=list(GUID) + [0] * (size - 16))

    return kind(gid=me(), node_entities_info_seq=[node(node_namespace=ns, node_name=name, reader_gid_seq=[],
                                                       writer_gid_seq=[me()]) for ns, name in nodes])


def test_both_gid_layouts_decode_to_the_participant_and_its_nodes() -> None:
    newer = _info(ParticipantEntitiesInfo, Gid, NodeEntitiesInfo, 16, ("/", "bt_navigator"), ("/robot1", "amcl"))
    humble = _info(HumbleParticipantEntitiesInfo, HumbleGid, HumbleNodeEntitiesInfo, 24, ("/", "controller_server"))
    for sample, nodes in ((newer, "amcl, bt_navigator"), (humble, "controller_server")):
        decoded = ParticipantEntitiesInfo.deserialize(sample.serialize())
        assert type(decoded) is type(sample)
        assert participant_nodes(decoded) == (GUID[:12], nodes)
    # Humble's bytes read with the newer layout would seem a participant without nodes: that layout is not taken
    assert ParticipantEntitiesInfo.__idl__.deserialize(humble.serialize()).node_entities_info_seq == []
    with pytest.raises(ValueError, match="neither layout"):
        ParticipantEntitiesInfo.deserialize(newer.serialize()[:-6])


def test_a_process_nobody_named_is_not_said_by_its_guid() -> None:
    lines: list[str] = []
    contact = Contact(lambda: 0, report=lines.append)
    quiet, talking = b"\x01" * 12, b"\x02" * 12
    contact.heard(quiet)
    contact.heard(talking)
    contact.seen({quiet: "", talking: ""})
    time.sleep(1.1)
    contact.heard(talking)  # the rest of the robot goes on: not its link
    contact.seen({talking: ""})
    gap, = contact.gaps(0, None)
    assert gap.who == "participant 01010101" and not gap.named  # for the log and the JSON answer
    said = note([gap])
    assert said.startswith("I have not heard from one of the robot's processes since ")
    assert "0101" not in said and "participant" not in said
    # names that come after the gap opened name it; a process that destroyed its nodes as it ended keeps them
    contact.named(quiet, "")
    assert not contact.gaps(0, None)[0].named
    contact.named(quiet, "amcl")
    contact.named(quiet, "")
    assert [(g.who, g.named) for g in contact.gaps(0, None)] == [("amcl", True)]
    now = time.time()
    amcl = Gap("amcl", now - 5, 0, alone=False)
    others = [Gap(f"participant {i:08x}", now - 5, 0, alone=False, named=False) for i in (1, 2)]
    assert note([amcl, others[0]], now=now).startswith("I have not heard from amcl and one other of the robot's "
                                                       "processes since ")
    assert note(others, now=now).startswith("I have not heard from 2 of the robot's processes since ")


ROBOT = textwrap.dedent("""
    import sys, time, rclpy
    rclpy.init(domain_id=int(sys.argv[1]))
    nodes = [rclpy.create_node(name) for name in sys.argv[3].split(",")]
    end = time.monotonic() + float(sys.argv[2])
    while time.monotonic() < end:
        for node in nodes:
            node.get_logger().info("working")
        time.sleep(0.2)
    for node in nodes:
        node.destroy_node()
    rclpy.shutdown()
""")


@NO_RCLPY
def test_the_dds_transport_names_a_real_rclpy_process_that_ended_by_its_nodes() -> None:
    """Two processes of a robot on rclpy/Fast DDS log on /rosout; the one holding amcl and bt_navigator ends while
    the other goes on. The DDS transport (Cyclone) names it by its nodes, from ros_discovery_info."""
    domain = fresh_domain()
    with live_node(domain, transport="dds") as node:
        cmd = [sys.executable, "-c", ROBOT, str(domain)]
        # longer than Fast DDS's 3 s heartbeat, which brings the graph topic's history to a new reader
        localisation = subprocess.Popen([*cmd, "5", "amcl,bt_navigator"], stderr=subprocess.PIPE, text=True)
        skills = subprocess.Popen([*cmd, "14", "skill_navigate_to_zone"], stderr=subprocess.PIPE, text=True)
        try:
            deadline = time.monotonic() + 30
            gaps = []
            while not gaps and time.monotonic() < deadline:
                gaps = node.log.contact.gaps(0, None)
                time.sleep(0.2)
            assert localisation.wait(timeout=10) == 0
            time.sleep(1.5)  # the other process goes on: this is not the robot's link
            gaps = node.log.contact.gaps(0, None)
        finally:
            skills.kill()
            skills.communicate()
    gap, = gaps
    assert (gap.who, gap.named) == ("amcl, bt_navigator", True)
    assert note([gap]).startswith("I have not heard from amcl, bt_navigator since ")
