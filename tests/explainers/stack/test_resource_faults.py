"""A machine or network short of something, read from the lines the real stack printed here with one fault each
(Cyclone DDS 11.0.1's core through cyclonedds, rclpy 9.1.2 on Fast DDS; scripts/resource_faults.py, the spent held-out
set 28), written as recordings with rosbags: no task and no goal, so the robot's start is derived from them."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.explainers.helpers import claimed, console_lines, derived_start, printed


@pytest.mark.parametrize(("ident", "said", "fix"), [
    ("kilted-cyclone-network-not-up", 'found no network interface up for its transport ("udp")',
     "network-online.target"),
    ("kilted-cyclone-port-held-by-another-program", "could not open its unicast ports (17910, 17911)", "ss -ulpn"),
    ("kilted-cyclone-receive-buffer-min-too-large", "requires a socket receive buffer of at least 67108864 bytes and "
     "the operating system gives 8388608", "net.core.rmem_max"),
    ("kilted-cyclone-link-down-mid-run", "could not send to udp/192.168.1.11:49304: the network link or interface",
     "ip link"),
    ("kilted-cyclone-sample-larger-than-allowed", "at 400012 bytes it was larger than the most it is set to carry "
     "(65536 bytes)", "MaxMessageSize"),
])
def test_dds_that_could_not_start_or_send_is_the_network_not_the_process_that_died(
        tmp_path: Path, ident: str, said: str, fix: str) -> None:
    # each but the link going down ends in a DDSException traceback: the middleware's own line before it says why
    found = derived_start(tmp_path, console_lines(printed("real-modules-heldout28", ident)))
    assert found.causes == ["system.network"] and claimed(found) == {"system.network"}
    assert said in found.text and fix in (found.fix or "")
    assert "died" not in found.text
