"""A robot's node declares its parameters and changes one: rcl itself announces them on /parameter_events (the
real rclpy publisher over Fast DDS, no recording in between), and both transports hear them, so a live question
about a setting is answered with the value the node holds. HEXAR's own rclpy node announces parameters too; they
are not the robot's and are not kept."""

from __future__ import annotations

import time

import pytest

from hexar.live.log import LiveLog
from tests.live.dds_helpers import NO_DDS, fresh_domain, make_transport

pytest.importorskip("rclpy")


@pytest.mark.parametrize("node", [pytest.param("dds", marks=NO_DDS), "rclpy"])
def test_a_robot_nodes_own_parameter_events_are_heard(node: str) -> None:
    from rclpy.parameter import Parameter

    from hexar.live.ros import RosNode

    domain = fresh_domain()
    transport, log = make_transport(node, domain), LiveLog()
    transport.start(log, lambda r: None, lambda q: None)
    robot = RosNode("amcl", domain)
    try:
        deadline = time.monotonic() + 15.0
        # the topic is volatile: what the node announced before HEXAR matched it is not resent, so a probe is set
        # until HEXAR hears it
        robot.node.declare_parameter("probe", 0)
        k = 0
        while time.monotonic() < deadline and not any(p.name == "probe" for p in log.snapshot().parameters):
            k += 1
            robot.node.set_parameters([Parameter("probe", value=k)])
            time.sleep(0.1)
        robot.node.declare_parameter("max_particles", 2000)
        robot.node.declare_parameter("base_frame_id", "base_footprint")
        robot.node.declare_parameter("laser_likelihood_max_dist", 2.0)
        robot.node.set_parameters([Parameter("laser_likelihood_max_dist", value=3.5)])
        while time.monotonic() < deadline and not any(p.change == "changed" and p.name == "laser_likelihood_max_dist"
                                                      for p in log.snapshot().parameters):
            time.sleep(0.05)
        time.sleep(0.3)
    finally:
        robot.close()
        transport.close()
    asked = {"max_particles", "base_frame_id", "laser_likelihood_max_dist"}
    heard = [(p.name, p.said, p.change) for p in log.snapshot().parameters if p.name in asked]
    assert heard == [("max_particles", "2000", "new"), ("base_frame_id", "'base_footprint'", "new"),
                     ("laser_likelihood_max_dist", "2.0", "new"), ("laser_likelihood_max_dist", "3.5", "changed")]
    assert {p.node for p in log.snapshot().parameters} == {"/amcl"}  # none of HEXAR's own node
