"""The faults of held-out module set 31, run by scripts/control_faults.py (`--set 31`): the same arm on ros2_control's
mock hardware, its spawners now started one after the other as ros2_control's demos start them, with one fault each
of the joint limits, the trajectory controller's tolerances and interfaces, a second controller on the same joints,
a controller left inactive, a spawner's parameters file, the control loop's rate and the state's initial values; and
two runs with nothing wrong. Written, with their causes and the labelling rule of control_faults.label(), before any
of them was run.
"""

from __future__ import annotations

from control_faults import CONFIG, JOINTS, LAUNCH_ARG, NOMINAL, TOLERANCE, Fault

ACTIVATION = "control.controller_activation_failed"
FAULTS31 = (
    Fault("chained-nominal", NOMINAL, "Nothing was wrong: the spawners started one after the other and the arm "
          "followed the trajectory.", chained=True),
    Fault("position-state-only", NOMINAL, "Nothing was wrong: the trajectory controller read only the position "
          "states (no velocity), which it can work with.", controller={"state_interfaces": ["position"]},
          chained=True),
    Fault("joint-limits-tight", CONFIG, "The robot description limited both joints to +-0.5 rad, while the "
          "trajectory went to 1.0 rad, so the controller manager held the commands at the limit.", limit=0.5,
          chained=True),
    Fault("path-tolerance-tight", TOLERANCE, "The trajectory controller allowed 0.01 rad off its path while the "
          "hardware reported each joint 0.05 rad from its command.",
          controller={"constraints": {"goal_time": 1.0, "stopped_velocity_tolerance": 0.05,
                                      **{j: {"goal": 0.1, "trajectory": 0.01} for j in JOINTS}}},
          hardware={"position_state_following_offset": "0.05"}, chained=True),
    Fault("interface-claimed", ACTIVATION, "A forward_command_controller on the same joints' position commands was "
          "spawned and activated before the trajectory controller, which could then not claim them.", blocker=True,
          spawns=(("joint_state_broadcaster", ()), ("position_forward", ()), ("arm_controller", ())), chained=True),
    Fault("spawned-inactive", ACTIVATION, "The trajectory controller's spawner was given --inactive, so the "
          "controller was loaded and configured but never activated.",
          spawns=(("joint_state_broadcaster", ()), ("arm_controller", ("--inactive",))), chained=True),
    Fault("spawner-param-file-missing", LAUNCH_ARG, "The trajectory controller's spawner was given --param-file "
          "config/arm_controllers.yaml, a file that is not there.",
          spawns=(("joint_state_broadcaster", ()), ("arm_controller", ("--param-file", "config/arm_controllers.yaml"))),
          chained=True),
    Fault("update-rate-2hz", TOLERANCE, "The controller manager's update_rate was 2 Hz, so the trajectory "
          "controller sampled a 2 s trajectory four times.", update_rate=2, chained=True),
    Fault("state-no-initial-value", CONFIG, "The robot description gave the position state interfaces no "
          "initial_value, so the mock hardware reported NaN positions until commanded.", initial=False,
          chained=True),
    Fault("broadcaster-not-spawned", NOMINAL, "The launch file spawned no joint_state_broadcaster; the trajectory "
          "controller itself needs none.", spawns=(("arm_controller", ()),), chained=True),
)

HEADER31 = """\
# Held-out set 31 of real console excerpts (issue 23's format): printed by ros2_control {version} (controller_manager,
# joint_state_broadcaster, joint_trajectory_controller, forward_command_controller, mock_components/GenericSystem),
# built from source on ROS 2 Kilted's rclpy, rcl and Fast DDS from PyPI, each run with one fault of an arm's control
# bring-up and started by the real ros2launch: written by scripts/control_faults.py --set 31, whose faults
# (scripts/control_faults31.py) and labelling rule were committed before any of them was run. Output is kept as
# printed, less ANSI colours, with this machine's folders replaced by fixed names. Frozen and measured once before
# anything was tuned on it.
# Regenerate inside a ROS 2 environment with ros2_control: python3 scripts/control_faults.py --set 31 --out FILE
"""
