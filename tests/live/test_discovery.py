"""ROS 2's discovery variables on the DDS transport (live/discovery.py), and what `hexar serve` says when it hears
nothing: a robot on a network without multicast is heard through ROS_STATIC_PEERS, as a ROS node would hear it."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from hexar.live.commands import SILENT_HINT_S
from hexar.live.discovery import ros_discovery
from tests.live.dds_helpers import NO_DDS, fresh_domain
from tests.live.test_replay_explains import expected

# loopback only, no multicast, and not localhost as a peer (Cyclone adds it when no interface has multicast): two
# computers on a network that drops multicast, neither knowing the other's address
NO_MULTICAST = ('<General><Interfaces><NetworkInterface address="127.0.0.1"/></Interfaces>'
                "<AllowMulticast>false</AllowMulticast></General>"
                '<Discovery><Peers AddLocalhost="false"/></Discovery>')


def test_the_ranges_map_as_rmw_cyclonedds_maps_them() -> None:
    subnet = ros_discovery({"ROS_STATIC_PEERS": "192.168.1.20; robot.local;"})
    assert (subnet.range, subnet.peers) == ("SUBNET", ("192.168.1.20", "robot.local"))
    fragment = subnet.cyclone_fragment()
    assert '<Peer address="192.168.1.20"/><Peer address="robot.local"/>' in fragment
    assert "AllowMulticast" not in fragment  # the subnet keeps multicast; the peers come on top
    local = ros_discovery({"ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST", "ROS_STATIC_PEERS": "10.0.0.7"})
    assert '<Peer address="localhost"/><Peer address="10.0.0.7"/>' in local.cyclone_fragment()
    assert "<AllowMulticast>false</AllowMulticast>" in local.cyclone_fragment()
    off = ros_discovery({"ROS_AUTOMATIC_DISCOVERY_RANGE": "OFF", "ROS_STATIC_PEERS": "10.0.0.7"})
    assert off.peers == () and "ignored" in off.notes[0]
    assert "<Tag>ros_discovery_off_42</Tag>" in off.cyclone_fragment(pid=42) and "Peer" not in off.cyclone_fragment()
    assert ros_discovery({"ROS_AUTOMATIC_DISCOVERY_RANGE": "SYSTEM_DEFAULT"}).cyclone_fragment() == ""
    typo = ros_discovery({"ROS_AUTOMATIC_DISCOVERY_RANGE": "subnet"})  # rcl compares case-sensitively
    assert typo.range == "LOCALHOST" and "invalid" in typo.notes[0]
    assert "ignored" in ros_discovery({"ROS_LOCALHOST_ONLY": "1"}).notes[0]
    assert ros_discovery({"ROS_LOCALHOST_ONLY": "1"}).range == "SUBNET"


def _serve_and_replay(run: Path, static_peers: str | None) -> tuple[list[dict[str, object]], str]:
    """`hexar serve --transport dds` and a robot (`hexar replay` on Cyclone) on a loopback without multicast, the
    robot not knowing the node's address; the node's answers and its stderr."""
    domain = fresh_domain()
    env = {k: v for k, v in os.environ.items() if k != "ROS_STATIC_PEERS"}
    env.update(CYCLONEDDS_URI=NO_MULTICAST, ROS_AUTOMATIC_DISCOVERY_RANGE="SUBNET")
    serve_env = {**env, **({"ROS_STATIC_PEERS": static_peers} if static_peers else {})}
    serve = subprocess.Popen([sys.executable, "-m", "hexar", "serve", "--transport", "dds", "--domain", str(domain),
                              "--no-follow-launch-log"], env=serve_env, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
    started = time.monotonic()
    try:
        assert serve.stderr is not None and "listening" in serve.stderr.readline()
        robot = subprocess.run([sys.executable, "-m", "hexar", "replay", str(run), "--rate", "10", "--transport",
                                "dds", "--domain", str(domain)], env=env, capture_output=True, text=True,
                               timeout=120)
        assert robot.returncode == 0, robot.stderr
        time.sleep(max(3.0, SILENT_HINT_S + 1.0 - (time.monotonic() - started)))
    finally:
        serve.send_signal(signal.SIGTERM)
        out, err = serve.communicate(timeout=60)
    assert serve.returncode == 0, err
    return [json.loads(line) for line in out.splitlines() if line.startswith("{")], err


@pytest.mark.parametrize("peers", [None, "127.0.0.1"])
@NO_DDS  # Cyclone's static peers
def test_a_robot_without_multicast_is_heard_through_static_peers(suite: Path, peers: str | None) -> None:
    run = suite / "bagfile_5_1"
    answers, err = _serve_and_replay(run, peers)
    if peers is None:
        assert answers == [] and "received 0 records" in err
        assert "nothing heard from a robot" in err and "ROS_STATIC_PEERS" in err  # the user learns what to check
        return
    failures, _ = expected(run)
    assert {a["task_id"]: a["causes"] for a in answers if a.get("trigger") == "failure"} == failures
    assert "nothing heard" not in err
