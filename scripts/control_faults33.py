"""The faults of held-out module set 33, run by scripts/control_faults.py (`--set 33`): set 31's arm (spawners one
after the other) with one fault each of the trajectory a client sends (joint names the controller does not have, a
goal for one joint of two), of the control loop's load (1 kHz on this 2-core computer), of the spawners (the
trajectory controller spawned twice; spawners that wait 2 s for a controller manager whose robot description comes
8 s late); and a run with nothing wrong. Written, with their causes and the labelling rule of control_faults.label(),
before any of them was run.
"""

from __future__ import annotations

from control_faults import CONFIG, LAUNCH_ARG, NOMINAL, Fault

SHORT = ("--controller-manager-timeout", "2")
FAULTS33 = (
    Fault("goal-nominal", NOMINAL, "Nothing was wrong: the spawners started one after the other and the arm "
          "followed the trajectory.", chained=True),
    Fault("goal-joint-names-wrong", CONFIG, "The client's trajectory named its joints shoulder and elbow, while "
          "the trajectory controller's joints are shoulder_joint and elbow_joint.",
          goal_joints=("shoulder", "elbow"), chained=True),
    Fault("goal-partial-joints", CONFIG, "The client's trajectory named shoulder_joint only, while the trajectory "
          "controller does not take goals for some of its joints (allow_partial_joints_goal false, its default).",
          goal_joints=("shoulder_joint",), chained=True),
    Fault("manager-1khz", NOMINAL, "Nothing was wrong that stopped the arm: the controller manager's update_rate "
          "was 1000 Hz, more than this 2-core computer keeps.", update_rate=1000, chained=True),
    Fault("spawned-twice", NOMINAL, "Nothing was wrong that stopped the arm: the launch file spawned arm_controller "
          "twice, and the second spawner found it loaded already.",
          spawns=(("joint_state_broadcaster", ()), ("arm_controller", ()), ("arm_controller", ())), chained=True),
    Fault("spawner-timeout-short", LAUNCH_ARG, "The robot description was published 8 s after the start, and the "
          "spawners waited 2 s for the controller manager (--controller-manager-timeout 2), which offers its "
          "services only once it has the description, so they gave up before it could load anything.",
          spawns=(("joint_state_broadcaster", SHORT), ("arm_controller", SHORT)), describe_delay=8.0, chained=True),
)

HEADER33 = """\
# Held-out set 33 of real console excerpts (issue 23's format): printed by ros2_control {version} (controller_manager,
# joint_state_broadcaster, joint_trajectory_controller, mock_components/GenericSystem), built from source on ROS 2
# Kilted's rclpy, rcl and Fast DDS from PyPI, each run with one fault of an arm's trajectory, control loop or
# spawners and started by the real ros2launch: written by scripts/control_faults.py --set 33, whose faults
# (scripts/control_faults33.py) and labelling rule were committed before any of them was run. Output is kept as
# printed, less ANSI colours, with this machine's folders replaced by fixed names. Frozen and measured once before
# anything was tuned on it.
# Regenerate inside a ROS 2 environment with ros2_control: python3 scripts/control_faults.py --set 33 --out FILE
"""
