"""The HEXAR topic contract: what a compatible robot records, and what the event log decodes.

The first seven topics are those of the original HEXAR release; the two skill topics are ours (README,
"Topic contract"); the rest are ordinary Nav2 and MoveIt topics that most robots record anyway (README, "What a
robot must record"), the two occupancy grids included.
"""

from __future__ import annotations

from dataclasses import dataclass

ROSOUT = "/rosout"
# ROS 2 launch's log file copied beside a recording (events/roslog.py): log lines that never reached /rosout
LAUNCH_LOG = "launch.log"
LOG_SOURCES = frozenset({ROSOUT, LAUNCH_LOG})
TASK_INFO = "/task_info"
AMCL_POSE = "/amcl_pose"
JOY_PRIORITY = "/joy_priority"
IS_CHARGING = "/power/is_charging"
EPISODIC_MEMORY = "/episodic_memory"
DIAGNOSTICS = "/diagnostics"
SAY_EVENTS = "/skills/say/events"
PIZZA_EVENTS = "/skills/recommend_pizza/events"
# Ordinary Nav2 topics (no HEXAR contract needed): motion, goals and the NavigateToPose action's status.
CMD_VEL = "/cmd_vel"
ODOM = "/odom"
GOAL_POSE = "/goal_pose"
NAV_STATUS = "/navigate_to_pose/_action/status"
# The maps the planner plans on: map_server's static map and the global costmap (Costmap2DPublisher's topic).
MAP = "/map"
GLOBAL_COSTMAP = "/global_costmap/costmap"
# A keepout filter's mask, as nav2_bringup's keepout_zone_launch.py has map_server serve it (100 in a zone)
KEEPOUT_MASK = "/keepout_filter_mask"
# MoveIt's and the arm controllers' action statuses: arm tasks are derived from them (events/arm_goals.py).
MOVE_ACTION_STATUS = "/move_action/_action/status"
EXECUTE_TRAJECTORY_STATUS = "/execute_trajectory/_action/status"
# Every controller has its own: /<controller>/follow_joint_trajectory/_action/status, read under this one key.
FJT_STATUS = "/*/follow_joint_trajectory/_action/status"
_FJT_SUFFIX = "/follow_joint_trajectory/_action/status"

# Every rclcpp and rclpy node announces the parameters it declares and every later change on this topic: a
# recording that starts before the bring-up holds each node's settings.
PARAMETER_EVENTS = "/parameter_events"

LOG_TYPE = "rcl_interfaces/msg/Log"
STRING_TYPE = "std_msgs/msg/String"
BOOL_TYPE = "std_msgs/msg/Bool"
POSE_COV_TYPE = "geometry_msgs/msg/PoseWithCovarianceStamped"
DIAG_TYPE = "diagnostic_msgs/msg/DiagnosticArray"
TWIST_TYPE = "geometry_msgs/msg/Twist"
TWIST_STAMPED_TYPE = "geometry_msgs/msg/TwistStamped"
ODOM_TYPE = "nav_msgs/msg/Odometry"
POSE_STAMPED_TYPE = "geometry_msgs/msg/PoseStamped"
GOAL_STATUS_TYPE = "action_msgs/msg/GoalStatusArray"
GRID_TYPE = "nav_msgs/msg/OccupancyGrid"
PARAMETER_EVENT_TYPE = "rcl_interfaces/msg/ParameterEvent"

ASK_HUMAN_STATUS_NAME = "/skills/skill_ask_human_for_help"
SAY_STATUS_NAME = "/skills/skill_say"
PIZZA_STATUS_NAME = "/skills/skill_recommend_pizza"


@dataclass(frozen=True)
class TopicSpec:
    topic: str
    type: str
    fields: str
    conventions: str


CONTRACT: tuple[TopicSpec, ...] = (
    TopicSpec(ROSOUT, LOG_TYPE, "stamp, level, name, msg",
              "time = log stamp; Nav2 loggers as in Nav2 Humble; levels 10/20/30/40/50"),
    TopicSpec(TASK_INFO, STRING_TYPE, "data (JSON: instruction, task_id, task_status, task_error_msg, "
              "skill_sequence[skill, params, status, error_msg])",
              "time = bag receive time; status waiting -> Running -> succeeded|failed (any case); "
              "task_status valid|invalid"),
    TopicSpec(AMCL_POSE, POSE_COV_TYPE, "header.stamp, pose.pose, pose.covariance[0], [7], [35]",
              "poor localisation: mean(cov[0], cov[7]) or cov[35] above 0.2 for more than 5 poses"),
    TopicSpec(JOY_PRIORITY, BOOL_TYPE, "data", "True = joystick (manual) mode holds the base"),
    TopicSpec(IS_CHARGING, BOOL_TYPE, "data", "True = docked and charging"),
    TopicSpec(EPISODIC_MEMORY, DIAG_TYPE, "header.stamp, status[].name/message/values",
              "one status per step, name /skills/skill_ask_human_for_help, values "
              "[(Module name, skill_ask_human_for_help), (key, str(value))]"),
    TopicSpec(DIAGNOSTICS, DIAG_TYPE, "header.stamp, status[].level/name/message/values",
              "1 Hz status of each node"),
    TopicSpec(SAY_EVENTS, DIAG_TYPE, "header.stamp, status[].message/values",
              "name /skills/skill_say; message started|finished|timed_out; values text, timeout_s, "
              "words_per_minute (on start), spoken_s (on end)"),
    TopicSpec(PIZZA_EVENTS, DIAG_TYPE, "header.stamp, status[].message/values",
              "name /skills/skill_recommend_pizza; message request|recommendation; values "
              "available_ingredients (JSON list), recommended_pizza"),
    TopicSpec(CMD_VEL, TWIST_TYPE, "linear.x, linear.y, angular.z (or TwistStamped's twist)",
              "what the controller commanded; with /odom it shows commands that do not reach the base"),
    TopicSpec(ODOM, ODOM_TYPE, "header.stamp, pose.pose.position, twist.twist.linear.x, angular.z",
              "how the base moved"),
    TopicSpec(GOAL_POSE, POSE_STAMPED_TYPE, "header.stamp, header.frame_id, pose.position",
              "a navigation goal (RViz's Nav2 Goal); tasks are derived from goals when /task_info is absent"),
    TopicSpec(NAV_STATUS, GOAL_STATUS_TYPE, "status_list[goal_info.goal_id, goal_info.stamp, status]",
              "NavigateToPose goals and how they ended (4 succeeded, 5 canceled, 6 aborted)"),
    TopicSpec(MAP, GRID_TYPE, "header.frame_id, info.resolution/width/height/origin, data",
              "map_server's map (trinary: 100 occupied, 0 free, -1 unknown); where a goal or the robot lay on it"),
    TopicSpec(GLOBAL_COSTMAP, GRID_TYPE, "header.frame_id, info.resolution/width/height/origin, data",
              "the planner's costmap as nav2_costmap_2d's publisher translates it: 100 lethal, 99 inscribed, 1-98 "
              "cost, 0 free, -1 unknown"),
    TopicSpec(KEEPOUT_MASK, GRID_TYPE, "header.frame_id, info.resolution/width/height/origin, data",
              "a keepout filter's mask (100 in a zone, 0 outside): whether a goal or the robot lay in a zone"),
    TopicSpec(MOVE_ACTION_STATUS, GOAL_STATUS_TYPE, "status_list[goal_info.goal_id, goal_info.stamp, status]",
              "MoveIt's MoveGroup (plan and execute) goals; arm tasks are derived from them"),
    TopicSpec(EXECUTE_TRAJECTORY_STATUS, GOAL_STATUS_TYPE, "status_list[goal_info.goal_id, goal_info.stamp, status]",
              "MoveIt's ExecuteTrajectory goals"),
    TopicSpec(FJT_STATUS, GOAL_STATUS_TYPE, "status_list[goal_info.goal_id, goal_info.stamp, status]",
              "each joint trajectory controller's FollowJointTrajectory goals (any controller name)"),
    TopicSpec(PARAMETER_EVENTS, PARAMETER_EVENT_TYPE, "stamp, node, new_parameters, changed_parameters, "
              "deleted_parameters[name, value]",
              "each node's parameters as declared at start-up and as set later: the settings a question names"),
)


def topic_key(topic: str) -> str:
    """The contract's name for a recorded topic: a controller's own follow_joint_trajectory status reads as
    FJT_STATUS; every other topic is its own key."""
    return FJT_STATUS if topic.endswith(_FJT_SUFFIX) and topic != _FJT_SUFFIX else topic


TYPE_OF: dict[str, str] = {spec.topic: spec.type for spec in CONTRACT}
# ROS 1 recordings carry /rosout as rosgraph_msgs/Log (levels 1/2/4/8/16), accepted as well.
ROS1_LOG_TYPE = "rosgraph_msgs/msg/Log"
ROS1_LEVELS = {1: 10, 2: 20, 4: 30, 8: 40, 16: 50}
ACCEPTED_TYPES: dict[str, frozenset[str]] = {
    topic: frozenset({typ, ROS1_LOG_TYPE}) if topic == ROSOUT else frozenset({typ})
    for topic, typ in TYPE_OF.items()
}
ACCEPTED_TYPES[CMD_VEL] = frozenset({TWIST_TYPE, TWIST_STAMPED_TYPE})
ALL_TOPICS: frozenset[str] = frozenset(TYPE_OF)
# The ordinary Nav2 topics: optional; another type under one of these names is skipped with a warning.
NAV2_TOPICS: frozenset[str] = frozenset({CMD_VEL, ODOM, GOAL_POSE, NAV_STATUS})
# The grids a planner failure is checked on: optional like the ordinary Nav2 topics.
GRID_TOPICS: frozenset[str] = frozenset({MAP, GLOBAL_COSTMAP, KEEPOUT_MASK})
# Optional like them: another type under one of these names is skipped with a warning, not refused.
OPTIONAL_TOPICS: frozenset[str] = NAV2_TOPICS | GRID_TOPICS | frozenset({PARAMETER_EVENTS})
# What deriving tasks from Nav2 goals reads (recordings without /task_info).
NAV_GOAL_TOPICS: frozenset[str] = frozenset({ROSOUT, NAV_STATUS, GOAL_POSE})
ARM_STATUS_TOPICS: frozenset[str] = frozenset({MOVE_ACTION_STATUS, EXECUTE_TRAJECTORY_STATUS, FJT_STATUS})
# What deriving tasks reads without /task_info: Nav2 goals and MoveIt's and the controllers' goals.
GOAL_TOPICS: frozenset[str] = NAV_GOAL_TOPICS | ARM_STATUS_TOPICS
