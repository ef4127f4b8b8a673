"""The home robot with an arm: a fetch task (drive to the kitchen, pick the object up, bring it back, put it down)
whose pick step runs MoveIt 2 and a joint trajectory controller, logged with their real strings.

Every line below is a text of the mined catalogues (explainers/manipulation/moveit_catalogue.json,
explainers/control/ros2_control_catalogue.json), with the loggers MoveIt and ros2_control use, filled with this
robot's values; nothing of the situation (its name, a cause) is written into the recording. These recordings are
not among the paper's 20 scenarios: `hexar simulate --arm` writes them as `armfile_<situation>_<variant>`.

Situations of the pick step: nominal; controllers_not_found (no controller for the arm's joints); tolerance (the
arm controller aborts on a path tolerance, MoveIt reports the controller's failure); out_of_reach (the base
arrives badly localised and the planner finds no motion); stale_state (MoveIt asks for a wall-clock time while
the joint states carry simulated time).
"""

from __future__ import annotations

import random
import shutil
from collections.abc import Callable
from pathlib import Path
from typing import Any

from hexar.evals.scenarios.bag import BagBuilder, SkillResult, Storage, sec_ns

INFO, WARN, ERROR = 20, 30, 40
SITUATIONS = ("nominal", "controllers_not_found", "tolerance", "out_of_reach", "stale_state")
OBJECTS = ("cup", "apple", "bottle")
MGI = "move_group_interface"
MOVE = "moveit_move_group_default_capabilities.move_action_capability"
STATE = "moveit_ros.current_state_monitor"
OMPL = "moveit.ompl_planning.model_based_planning_context"
TEM = "moveit.ros.trajectory_execution_manager"
HANDLE = "moveit.simple_controller_manager.follow_joint_trajectory_controller_handle"
CONTROLLER = "arm_controller"
JOINTS = tuple(f"arm_{i}_joint" for i in range(1, 8))


class _Log:
    def __init__(self, b: BagBuilder, rng: random.Random, t: int) -> None:
        self.b, self.rng, self.t = b, rng, t

    def __call__(self, name: str, level: int, msg: str, after: float = 0.05) -> None:
        self.t += sec_ns(after * self.rng.uniform(0.6, 1.4))
        self.b.log(self.t, name, level, msg)


def simulate_arm(b: BagBuilder, rng: random.Random, start: int, skill: str, obj: str, situation: str = "nominal",
                 wall_clock_s: float = 0.0) -> SkillResult:
    """One pick or place: MoveGroupInterface's plan-and-execute goal and what move_group and the controller log."""
    log = _Log(b, rng, start)
    log(f"skill_{skill}", INFO, f"{'Picking up' if skill == 'pick' else 'Putting down'} the {obj}")
    log(MGI, INFO, "Ready to take commands for planning group arm.")
    if situation == "stale_state":
        requested = wall_clock_s + (log.t - start) / 1e9
        log(STATE, INFO, "Didn't receive robot state (joint angles) with recent timestamp within 1.000000 seconds. "
            f"Requested time {requested:.6f}, but latest received state has time {rng.uniform(300, 900):.6f}.\n"
            "Check clock synchronization if your are running ROS across multiple machines!", after=1.0)
        log(MGI, ERROR, "Failed to fetch current robot state")
        return SkillResult(log.t + sec_ns(0.1), False, "The skill has been aborted")
    log(MOVE, INFO, "Received request")
    log(MOVE, INFO, "executing..")
    log(MGI, INFO, "Plan and Execute request accepted")
    log(MOVE, INFO, "Combined planning and execution request received for MoveGroup action. Forwarding to planning "
        "and execution pipeline.")
    log("moveit.ros.plan_execution", INFO, "Planning attempt 1 of at most 1")
    if situation == "out_of_reach":
        log(OMPL, ERROR, "Unable to solve the planning problem", after=5.0)
        return _aborted(log)
    log(OMPL, INFO, "Planner configuration 'arm[RRTConnectkConfigDefault]' will use planner "
        "'geometric::RRTConnect'. Additional configuration parameters will be set when the planner is constructed.")
    if situation == "controllers_not_found":
        log(TEM, ERROR, f"Unable to identify any set of controllers that can actuate the specified joints: "
            f"[ {' '.join(JOINTS)} ]", after=0.4)
        log(TEM, ERROR, "Known controllers and their joints:\n")
        return _aborted(log)
    log(HANDLE, INFO, f"sending trajectory to {CONTROLLER}", after=0.4)
    log(CONTROLLER, INFO, "Received new action goal")
    log(CONTROLLER, INFO, "Accepted new action goal")
    log(HANDLE, INFO, f"{CONTROLLER} started execution")
    log(HANDLE, INFO, "Goal request accepted!")
    if situation == "tolerance":
        joint = rng.choice(JOINTS)
        log(CONTROLLER, ERROR, f"State tolerances failed for joint {JOINTS.index(joint) + 1}:", after=1.5)
        log(CONTROLLER, ERROR, f"Position Error: {rng.uniform(0.1, 0.3):.6f}, Position Tolerance: 0.100000")
        log(CONTROLLER, WARN, "Aborted due to state tolerance violation")
        log(HANDLE, WARN, f"Controller '{CONTROLLER}' failed with error PATH_TOLERANCE_VIOLATED: ")
        return _aborted(log)
    log(CONTROLLER, INFO, "Goal reached, success!", after=rng.uniform(3.0, 5.0))
    log(HANDLE, INFO, f"Controller '{CONTROLLER}' successfully finished")
    log(MGI, INFO, "Plan and Execute request complete!")
    return SkillResult(log.t + sec_ns(0.1), True)


def _aborted(log: _Log) -> SkillResult:
    log(MGI, INFO, "Plan and Execute request aborted")
    log(MGI, ERROR, "MoveGroupInterface::move() failed or timeout reached")
    return SkillResult(log.t + sec_ns(0.1), False, "The skill has been aborted")


def announce_parameters(b: BagBuilder, t: int, situation: str) -> None:
    """What the arm's nodes announce on /parameter_events as they start: use_sim_time (move_group's false where it
    asks for wall-clock time while the rest run on the simulator's), and the joint trajectory controller's joints
    and tolerances (ros2_controllers' parameter names; its path tolerance is the 0.1 the tolerance abort quotes)."""
    b.parameters(t, "/robot_state_publisher", new={"use_sim_time": True})
    b.parameters(t + sec_ns(0.2), "/controller_manager", new={"use_sim_time": True, "update_rate": 100})
    b.parameters(t + sec_ns(0.4), "/arm_controller", new={
        "use_sim_time": True, "joints": list(JOINTS), "constraints.goal_time": 0.0,
        "constraints.stopped_velocity_tolerance": 0.01,
        **{f"constraints.{j}.{kind}": value for j in JOINTS for kind, value in (("trajectory", 0.1), ("goal", 0.05))}})
    b.parameters(t + sec_ns(0.8), "/move_group", new={"use_sim_time": situation != "stale_state"})


def plan(obj: str) -> list[tuple[str, dict[str, Any]]]:
    return [("navigate_to_zone", {"location": "kitchen"}), ("pick", {"object": obj}),
            ("navigate_to_zone", {"location": "dining_room"}), ("place", {"object": obj}),
            ("say", {"input": f"Here is your {obj}."})]


def record_arm(situation: str, variant: int, seed: int = 0) -> BagBuilder:
    """One fetch task with `situation` in its pick step (and, for out_of_reach, a badly localised trip first)."""
    from hexar.evals.scenarios import nav
    from hexar.evals.scenarios.suite import EPOCH, ROOMS, Robot

    k = SITUATIONS.index(situation)
    rng = random.Random(seed * 10_000 + 5_000 + k * 10 + variant)
    obj = OBJECTS[variant - 1]
    b = BagBuilder()
    start = sec_ns(EPOCH + 30 * 3600 + k * 600 + variant * 60 + rng.uniform(0, 30))
    home = ROOMS["dining_room"]
    robot = Robot(b, rng, 0, variant, start + sec_ns(rng.uniform(3, 6)), home)
    robot.arm_situation = situation
    announce_parameters(b, start, situation)
    if situation == "out_of_reach":
        robot.first_navigation = "poor_localisation"
    ok = robot.run_task(f"Bring me the {obj} from the kitchen", plan(obj))
    if not ok:
        robot.t += sec_ns(rng.uniform(1.0, 2.0))
        robot.run_task("", [("navigate_to_zone", {"location": "dining_room"}),
                            ("say", {"input": "Sorry, I could not complete the task."})])
    end = robot.t + sec_ns(rng.uniform(2, 4))
    nav.simulate_robot_state(b, rng, start, end, joystick=False, charging=False, pose=(home[0], home[1], 0.0))
    return b


def arm_recording_name(situation: str, variant: int) -> str:
    return f"armfile_{situation}_{variant}"


def simulate_arm_suite(out: Path, storage: Storage = "sqlite3", seed: int = 0,
                       only: Callable[[str, int], bool] | None = None) -> list[Path]:
    """Write the arm recordings (5 situations x 3 objects) as `out/armfile_<situation>_<variant>/`."""
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for situation in SITUATIONS:
        for variant in range(1, len(OBJECTS) + 1):
            if only is not None and not only(situation, variant):
                continue
            path = out / arm_recording_name(situation, variant)
            if path.exists():
                shutil.rmtree(path)
            record_arm(situation, variant, seed).write(path, storage)
            written.append(path)
    return written
