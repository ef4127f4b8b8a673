"""The live topics, their ROS types and the QoS a subscriber must request to match what the robot offers.

A DDS reader matches a writer only if it asks for no more than the writer offers (reliable <= reliable,
transient-local <= transient-local). So: /rosout and /amcl_pose are read transient-local, because rcl's rosout
publisher (`rcl_qos_profile_rosout_default`: reliable, transient-local, depth 1000, lifespan 10 s) and AMCL offer
it, and a node that joins late then receives their recent history; /joy_priority is latched (transient-local,
depth 1) on TIAGo. Topics published with ROS' default profile (reliable, volatile, depth 10) are read
reliable + volatile, which also matches a transient-local writer: /cmd_vel (Nav2's controller and velocity
smoother), /odom, /goal_pose (RViz's Nav2 Goal tool). An action server's status topic is offered with
`rcl_action_qos_profile_status_default` (keep-last 1, reliable, transient-local: ros2/rcl,
rcl_action/include/rcl_action/default_qos.h), so /navigate_to_pose/_action/status (and the arm's action status
topics) is read transient-local and a late joiner still gets the status array of the goals the server tracks.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from hexar.events import contract as c

Durability = Literal["volatile", "transient_local"]

QUESTION = "/hexar/question"
ANSWER = "/hexar/answer"
HEXAR_PREFIX = "/hexar/"


@dataclass(frozen=True)
class TopicQos:
    reliable: bool = True
    durability: Durability = "volatile"
    depth: int = 10


@dataclass(frozen=True)
class LiveTopic:
    topic: str
    type: str
    qos: TopicQos


def dds_name(topic: str) -> str:
    """rmw_cyclonedds prefixes ROS topics with `rt` (`/rosout` -> `rt/rosout`)."""
    return "rt" + (topic if topic.startswith("/") else "/" + topic)


ARM_CONTROLLERS = ("arm_controller", "joint_trajectory_controller", "scaled_joint_trajectory_controller",
                   "panda_arm_controller")
SUBSCRIBED: tuple[LiveTopic, ...] = (
    LiveTopic(c.ROSOUT, c.LOG_TYPE, TopicQos(durability="transient_local", depth=1000)),
    LiveTopic(c.TASK_INFO, c.STRING_TYPE, TopicQos(depth=100)),
    LiveTopic(c.AMCL_POSE, c.POSE_COV_TYPE, TopicQos(durability="transient_local", depth=50)),
    LiveTopic(c.JOY_PRIORITY, c.BOOL_TYPE, TopicQos(durability="transient_local", depth=1)),
    LiveTopic(c.IS_CHARGING, c.BOOL_TYPE, TopicQos(depth=10)),
    LiveTopic(c.EPISODIC_MEMORY, c.DIAG_TYPE, TopicQos(depth=100)),
    LiveTopic(c.DIAGNOSTICS, c.DIAG_TYPE, TopicQos(depth=100)),
    LiveTopic(c.SAY_EVENTS, c.DIAG_TYPE, TopicQos(depth=100)),
    LiveTopic(c.PIZZA_EVENTS, c.DIAG_TYPE, TopicQos(depth=100)),
    # The ordinary Nav2 topics. /cmd_vel is read as geometry_msgs/Twist, Humble's type for it (a DDS topic has
    # one type; a Jazzy robot publishing TwistStamped there is not matched). The robot offers depth 10; depth is
    # no matching rule, and the reader keeps 100 so that 20-50 Hz odometry (x10 in a replay) survives a reader
    # thread that is late by a few hundred milliseconds: keep-last drops the oldest unread samples.
    LiveTopic(c.CMD_VEL, c.TWIST_TYPE, TopicQos(depth=100)),
    LiveTopic(c.ODOM, c.ODOM_TYPE, TopicQos(depth=100)),
    LiveTopic(c.GOAL_POSE, c.POSE_STAMPED_TYPE, TopicQos(depth=10)),
    LiveTopic(c.NAV_STATUS, c.GOAL_STATUS_TYPE, TopicQos(durability="transient_local", depth=10)),
    # The maps the planner plans on, and a keepout filter's mask: map_server and nav2_costmap_2d's publisher offer
    # them latched (nav2::qos::LatchedPublisherQoS: reliable, transient-local, keep-last 1), so a node that joins
    # late gets them.
    *(LiveTopic(topic, c.GRID_TYPE, TopicQos(durability="transient_local", depth=1))
      for topic in (c.MAP, c.GLOBAL_COSTMAP, c.KEEPOUT_MASK)),
    # The arm's actions (MoveIt's move_action and execute_trajectory, a joint trajectory controller's
    # follow_joint_trajectory): their status topics, so a robot without /task_info gets arm tasks and an aborted
    # arm goal is explained unasked. A controller's status topic carries its own name, and a DDS reader needs the
    # exact one: ARM_CONTROLLERS names the usual ones (TIAGo's arm_controller, ros2_control's and the UR
    # driver's joint trajectory controllers, MoveIt's tutorial Panda).
    *(LiveTopic(topic, c.GOAL_STATUS_TYPE, TopicQos(durability="transient_local", depth=10))
      for topic in (c.MOVE_ACTION_STATUS, c.EXECUTE_TRAJECTORY_STATUS)),
    *(LiveTopic(f"/{name}/follow_joint_trajectory/_action/status", c.GOAL_STATUS_TYPE,
                TopicQos(durability="transient_local", depth=10)) for name in ARM_CONTROLLERS),
    # Every node's parameters as it declares them, and each change. rcl offers them with
    # rmw_qos_profile_parameter_events (reliable, volatile, keep-last 1000): volatile, so only a node that starts
    # after HEXAR is heard declaring its values; a change is heard whenever it comes.
    LiveTopic(c.PARAMETER_EVENTS, c.PARAMETER_EVENT_TYPE, TopicQos(depth=1000)),
)
ARM_STATUS: frozenset[str] = frozenset(t.topic for t in SUBSCRIBED if c.topic_key(t.topic) in c.ARM_STATUS_TOPICS)

# The order a transport reads its topics in: the evidence first, the triggers (a failing /task_info, an aborted
# goal) last. A transport takes what arrived on each topic in turn, so a failure is seen only after the log
# lines and skill events that arrived with it, and the explanation that it triggers already has them.
TRIGGERS = frozenset({c.TASK_INFO, c.NAV_STATUS, *ARM_STATUS})
READ_ORDER: tuple[LiveTopic, ...] = tuple(sorted(SUBSCRIBED, key=lambda t: t.topic in TRIGGERS))

# What the node and the replayer offer. Answers are transient-local so a display that starts later still
# gets the last few; the question topic is an ordinary ROS default publisher's.
QUESTION_QOS = TopicQos(depth=100)  # keep-last: a burst of questions must not push earlier ones out
ANSWER_QOS = TopicQos(durability="transient_local", depth=10)
TTS_QOS = TopicQos(depth=10)
# /clock: read best-effort, which matches what rclcpp's ClockQoS (best effort) and a reliable publisher offer
CLOCK_QOS = TopicQos(reliable=False, depth=10)
# The replayer offers what the robot's publishers offer, so a reader that matches it matches the robot.
PUBLISHED_BY_ROBOT: dict[str, TopicQos] = {
    c.ROSOUT: TopicQos(durability="transient_local", depth=1000),
    c.AMCL_POSE: TopicQos(durability="transient_local", depth=1),
    c.JOY_PRIORITY: TopicQos(durability="transient_local", depth=1),
    c.CMD_VEL: TopicQos(depth=10),
    c.ODOM: TopicQos(depth=10),
    c.GOAL_POSE: TopicQos(depth=10),
    c.NAV_STATUS: TopicQos(durability="transient_local", depth=1),  # rcl_action_qos_profile_status_default
    c.MAP: TopicQos(durability="transient_local", depth=1),
    c.GLOBAL_COSTMAP: TopicQos(durability="transient_local", depth=1),
    c.KEEPOUT_MASK: TopicQos(durability="transient_local", depth=1),
    **{topic: TopicQos(durability="transient_local", depth=1) for topic in ARM_STATUS},
    c.PARAMETER_EVENTS: TopicQos(depth=1000),
}
