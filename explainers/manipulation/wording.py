"""The manipulation explainer's sentences (explainers/module_wording.py): each fix fits its cause.

Phrasings use the words of their own cause in hexar/causes.yaml and avoid those of the others (no "path", no
"misconfigured", no "timed out", no "clock"), so the graders and the guard read exactly the cause found.
"""

from __future__ import annotations

from hexar.explainers.module_wording import Worded, Wording

CLAUSES = {
    "manipulation.planning_failed": (
        "my motion planner found no solution for my arm in the time it had.",
        "Check that the goal is within the arm's reach and free of obstacles in the planning scene, or give the "
        "planner more time or attempts."),
    "manipulation.ik_failed": (
        "inverse kinematics found no joint configuration of my arm that reaches the requested pose.",
        "Check that the pose is within the arm's reach (and that my base stopped where it should), and the IK "
        "solver's timeout and tip frame."),
    "manipulation.start_state_in_collision": (
        "my arm's start state was {meaning}, so planning could not begin.",
        "Look at what the quoted line names: the contacts MoveIt reports (an object attached or added where the arm "
        "is, or the self-collision matrix of the SRDF), or a joint outside its limits (where the robot was spawned "
        "or calibrated, or the limits in its description), and start from a valid state."),
    "manipulation.goal_state_invalid": (
        "the arm goal itself was invalid: {meaning}.",
        "Choose a goal pose clear of obstacles and within the joint limits and constraints."),
    "manipulation.no_joint_states": (
        "my motion planning never received my arm's joint states, so it did not know where my arm was.",
        "Check that joint_states is published (joint_state_broadcaster active) and reaches move_group under the "
        "topic and namespace it listens to."),
    "manipulation.stale_robot_state": (
        "the joint states MoveIt received were older than the time it asked for: simulated time and wall-clock "
        "time were mixed, so it saw an out of date robot state.",
        "Give every node the same use_sim_time (move_group, your MoveGroupInterface node and the simulator), or "
        "synchronise the machines' clocks."),
    "manipulation.execution_failed": (
        "executing the planned arm trajectory failed.",
        "Read the arm controller's own log around that time (tolerances, goal rejected, hardware)."),
    "manipulation.controllers_not_found": (
        "MoveIt found no controllers for my arm's joints{meaning}.",
        "Declare the arm controller in moveit_controllers.yaml (controller_names, action_ns, joints) and check "
        "that it is loaded and active (ros2 control list_controllers)."),
    "manipulation.configuration_error": (
        "my motion planning system was not set up correctly: part of its set-up (a planning pipeline, planner "
        "plugin, controller settings or robot description) did not load.",
        "Fix the set-up named in the quoted line and pass the MoveIt config (moveit_configs_utils to_dict()) to "
        "move_group."),
    "bringup.configuration_error": (
        "a parameter my arm software needs never reached the node that uses it.",
        "Pass the robot description, SRDF and kinematics.yaml parameters to that node (e.g. "
        "MoveItConfigsBuilder(...).to_dict() in its launch file)."),
}


def _nominal(what: str) -> Worded:
    during = f", {what}" if what.startswith(("picking", "putting")) else ""
    return (f"I moved my arm as asked without any problem{during}.", None,
            ["My MoveIt logs show the goal accepted and completed, with no error."])


# a start or goal state is told in the words of the line that showed it (in collision, a joint outside its limits,
# a goal pose in a frame the planner refuses); these when the line says no more
MEANINGS = {"manipulation.start_state_in_collision": "already in collision in my planning scene",
            "manipulation.goal_state_invalid": "in collision or against its constraints",
            "manipulation.controllers_not_found": ""}
# a controller left out of MoveIt's list is said with what its settings lack (a refinement's note); the other lines
# of this cause mean what the clause says already
NOTES_ONLY = frozenset({"manipulation.controllers_not_found"})

template = Wording("I couldn't finish {what} because", "MoveIt", CLAUSES, meanings=MEANINGS, nominal=_nominal,
                   notes_only=NOTES_ONLY)
