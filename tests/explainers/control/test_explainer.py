"""The control explainer on real rosbag2 recordings of ros2_control's own lines (controller_manager, spawner,
resource manager, joint_trajectory_controller: texts of ros2_control_catalogue.json)."""

from __future__ import annotations

from pathlib import Path

from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events import read_recording
from hexar.events.records import ERROR, FATAL, INFO
from hexar.explainers.base import Context, Explanation
from hexar.explainers.registry import Registry

T0 = 1_700_000_000_000_000_000


def _explain(tmp_path: Path, lines: list[tuple[float, str, int, str]]) -> Explanation:
    b = BagBuilder()
    for s, name, level, msg in lines:
        b.log(T0 + sec_ns(s), name, level, msg)
    log = read_recording(b.write(tmp_path / "run"))
    registry = Registry.load()
    task = log.task()
    assert task.derived and task.skills[0].skill == "follow_joint_trajectory"
    return registry.get("control").explain("Why didn't the arm move?", Context.for_task(log, task, registry))


def test_the_controller_managers_line_is_the_cause_and_the_spawners_its_symptom(tmp_path: Path) -> None:
    found = _explain(tmp_path, [
        (0, "controller_manager", INFO, "Loading controller 'joint_state_broadcaster'"),
        (0.1, "controller_manager", ERROR, "Loader for controller 'joint_state_broadcaster' (type "
                                            "'joint_state_broadcaster/JointStateBroadcaster') not found."),
        (0.2, "spawner_joint_state_broadcaster", FATAL, "Failed loading controller joint_state_broadcaster")])
    assert found.causes == ["control.controller_load_failed"]
    assert found.evidence[0].item.startswith("[controller_manager] ERROR Loader for controller")
    assert "could not load it" in found.text and "package.xml" in (found.fix or "")


def test_switch_timeout_is_an_activation_failure(tmp_path: Path) -> None:
    found = _explain(tmp_path, [
        (0, "controller_manager", ERROR, "Switch controller timed out after 5.000000 seconds!"),
        (0.1, "spawner_joint_state_broadcaster", ERROR, "Failed to activate controller")])
    assert found.causes == ["control.controller_activation_failed"]
    assert "could not be activated" in found.text


def test_a_hardware_exception_while_configuring_is_a_hardware_failure(tmp_path: Path) -> None:
    found = _explain(tmp_path, [
        (0, "controller_manager.resource_manager", ERROR,
         "Exception of type : N9LibSerial10OpenFailedE occurred while configuring hardware 'RobotSystem': "
         "Bad file descriptor")])
    assert found.causes == ["control.hardware_failure"]
