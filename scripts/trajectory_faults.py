"""Real console output of ros2_control following a trajectory as a script sends it (controller_manager,
joint_state_broadcaster, joint_trajectory_controller on mock_components/GenericSystem: set 33's arm), each run with
one mistake in the FollowJointTrajectory goal: times that do not increase, a point with one position for two joints,
no points, a last point still moving, a stamp that puts the whole trajectory in the past, points with no positions,
a motion faster than the joints' velocity limits; and three runs that went well (one stamped 2 s ahead, one with
velocities on every point).

A run is set 33's bring-up (a robot_description publisher, ros2_control_node, the spawners one after the other,
started by ros2launch); from outside the console a script waits for the controller's action (30 s at most) and sends
one control_msgs/FollowJointTrajectory goal built as its fault says. The trajectory succeeded when its goal did
(SUCCEEDED, error code SUCCESSFUL). Ctrl-C follows two seconds after the result. The cause of each run is the fault
injected, written here before any run was made, by the rule of control_faults.label(). Output is kept as printed,
less ANSI colours, with this machine's folders replaced by fixed names. Writes real_modules-format excerpts
(evals/data/real_modules/README.md).

Run inside a ROS 2 environment with ros2_control and ros2_controllers (e.g. `source /opt/ros/kilted/setup.bash`):

    python3 scripts/trajectory_faults.py --out FILE.yaml [--only ID ...]
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from control_faults import (
    CONFIG,
    JOINTS,
    NOMINAL,
    RUN_S,
    TOLERANCE,
    TRAJECTORY_CLIENT,
    TRAJECTORY_RESULT,
    WAIT_S,
    label,
    module_set,
    setup,
)
from control_faults import Fault as Bringup
from launch_runs import run_launch

# (seconds from start, positions, velocities or None): set 30's trajectory, half way and all the way in 2 s
GOOD = ((1.0, (0.5, -0.5), None), (2.0, (1.0, -1.0), None))


@dataclass(frozen=True)
class Fault:
    id: str
    cause: str  # the cause when the trajectory fails; label() says what a trajectory that succeeded is
    quote: str  # what was wrong, as the cause_quote
    points: tuple[tuple[float, tuple[float, ...], tuple[float, ...] | None], ...] = GOOD
    stamp_s: float | None = None  # the goal header's stamp, seconds from now (None: zero, "start now")
    silent: bool = False  # logs_show_cause false: nothing in any process's console could show it
    extra: dict[str, Any] = field(default_factory=dict)  # the trajectory controller's parameters beyond set 33's


FAULTS = (
    Fault("traj-nominal", NOMINAL, "Nothing was wrong: the trajectory's two points reached both joints in 2 s."),
    Fault("traj-stamp-ahead", NOMINAL, "Nothing was wrong: the trajectory was stamped 2 s ahead, so it began 2 s "
          "after it was received.", stamp_s=2.0),
    Fault("traj-velocities", NOMINAL, "Nothing was wrong: every point gave velocities too, zero at the last.",
          points=((1.0, (0.5, -0.5), (0.5, -0.5)), (2.0, (1.0, -1.0), (0.0, 0.0)))),
    Fault("traj-time-not-increasing", CONFIG, "The trajectory's second point came 1 s from the start, before its "
          "first (2 s): its times did not increase.",
          points=((2.0, (0.5, -0.5), None), (1.0, (1.0, -1.0), None))),
    Fault("traj-one-position", CONFIG, "The trajectory's first point gave one position for its two joints.",
          points=((1.0, (0.5,), None), (2.0, (1.0, -1.0), None))),
    Fault("traj-empty", CONFIG, "The trajectory named its joints and had no points.", points=()),
    Fault("traj-last-moving", CONFIG, "The trajectory's last point still had velocity (0.5 rad/s), while the "
          "controller requires it to stop there.",
          points=((1.0, (0.5, -0.5), (0.5, -0.5)), (2.0, (1.0, -1.0), (0.5, -0.5)))),
    Fault("traj-stamp-past", CONFIG, "The trajectory was stamped 10 s in the past (a goal built earlier and sent "
          "late), so all of it ended before it was received.", stamp_s=-10.0),
    Fault("traj-no-positions", CONFIG, "The trajectory's points gave times and no positions, velocities or "
          "accelerations.", points=((1.0, (), None), (2.0, (), None))),
    Fault("traj-too-fast", TOLERANCE, "The trajectory asked both joints to move 3 rad in 0.2 s (15 rad/s), faster "
          "than their 2 rad/s velocity limit, so they lagged behind it.",
          points=((0.2, (3.0, -3.0), None),)),
)


SEND = TRAJECTORY_CLIENT + """\
    from rclpy.duration import Duration as Span
    joints, points, stamp_s = sys.argv[4].split(','), json.loads(sys.argv[5]), json.loads(sys.argv[6])
    goal.trajectory.joint_names = joints
    if stamp_s is not None:
        goal.trajectory.header.stamp = (node.get_clock().now() + Span(seconds=stamp_s)).to_msg()
    for t, positions, velocities in points:
        point = JointTrajectoryPoint(positions=positions, time_from_start=Duration(sec=int(t),
                                                                                   nanosec=int(t % 1 * 1e9)))
        if velocities is not None:
            point.velocities = velocities
        goal.trajectory.points.append(point)
    done = send_goal(node, client, goal, [], '', run_s, result)
""" + TRAJECTORY_RESULT


def run(fault: Fault, work: Path, launch_path: list[Path]) -> tuple[str, dict[str, Any]]:
    """Set 33's bring-up, the trajectory sent from outside it, Ctrl-C two seconds after the result."""
    launch, prefix = setup(Bringup(fault.id, fault.cause, fault.quote, controller=fault.extra, chained=True), work)
    result_file = work / "result.json"
    points = [[t, list(p), list(v) if v is not None else None] for t, p, v in fault.points]
    argv = [str(WAIT_S), str(RUN_S), str(result_file), ",".join(JOINTS), json.dumps(points), json.dumps(fault.stamp_s)]
    return run_launch(launch, prefix, work, launch_path, (SEND, argv), result_file, WAIT_S + 3 * RUN_S)


HEADER = """\
# Held-out set 36 of real console excerpts (issue 23's format): printed by ros2_control {version} (controller_manager,
# joint_state_broadcaster, joint_trajectory_controller, mock_components/GenericSystem), built from source on ROS 2
# Kilted's rclpy, rcl and Fast DDS from PyPI, each run with one mistake in a FollowJointTrajectory goal as a script
# sends it and started by the real ros2launch: written by scripts/trajectory_faults.py, whose faults and labelling rule
# were committed before any of them was run. Output is kept as printed, less ANSI colours, with this machine's folders
# replaced by fixed names. Frozen and measured once before anything was tuned on it.
# Regenerate inside a ROS 2 environment with ros2_control: python3 scripts/trajectory_faults.py --out FILE
"""


def main() -> int:
    return module_set(__doc__, FAULTS, run, "trajectory_faults.py", HEADER, label,
                      lambda result: result.get("status") == 4 and result.get("error_code") == 0,
                      lambda result: f"Trajectory of {len(JOINTS)} joints: {json.dumps(result)}.")


if __name__ == "__main__":
    raise SystemExit(main())
