"""A clock finding (MoveIt's out-of-date joint states, a transform extrapolated into the future) with the nodes'
use_sim_time as they announced it on /parameter_events: the nodes on each clock named where they differ, a note
where they agree, and nothing changed where the recording holds no parameters. Real excerpts written with rosbags,
with the parameter events a robot's nodes publish."""

from __future__ import annotations

from pathlib import Path

from hexar.events import read_recording
from hexar.explainers.base import Context, Explanation
from hexar.explainers.registry import Registry
from tests.agent.helpers import real_module_run, real_nav2_run, real_run_with_parameters

NAV2 = "nav2-3746-sim-time-extrapolation"
MOVEIT = "moveit2-3340-hello-moveit-without-sim-time"


def finding(run: Path, name: str) -> Explanation:
    log = read_recording(run)
    registry = Registry.load(None)
    task = log.task()
    return registry.get(name).explain("what happened?", Context.for_task(log, task, registry))


def test_nodes_on_different_clocks_are_named_beside_the_extrapolation(tmp_path: Path) -> None:
    bare = finding(real_nav2_run(NAV2, tmp_path / "bare"), "navigation")
    run = real_run_with_parameters(NAV2, tmp_path / "mixed", {
        "/controller_server": {"use_sim_time": True}, "/amcl": {"use_sim_time": True},
        "/bt_navigator": {"use_sim_time": False}})
    mixed = finding(run, "navigation")
    assert mixed.causes == bare.causes == ["navigation.transform_error"]
    assert mixed.text == (f"{bare.text} My nodes' parameters show the mix: use_sim_time was true on /amcl, "
                          "/controller_server but false on /bt_navigator.")
    told = [e.item for e in mixed.evidence if e.topic == "/parameter_events"]
    assert told[0] == "/bt_navigator: use_sim_time = false"  # the odd one out first
    assert len(told) == 3


def test_nodes_that_agree_leave_the_finding_and_say_where_to_look(tmp_path: Path) -> None:
    bare = finding(real_module_run(MOVEIT, tmp_path / "bare"), "manipulation")
    run = real_run_with_parameters(MOVEIT, tmp_path / "same", {
        "/move_group": {"use_sim_time": True}, "/hello_moveit": {"use_sim_time": True}})
    same = finding(run, "manipulation")
    assert same.text == bare.text and same.causes == bare.causes
    assert same.details[-1] == ("use_sim_time was true on all 2 of my nodes that announced it (/hello_moveit, "
                                "/move_group), so the clocks did not differ between them: look for a node that "
                                "announced no parameters, or another machine's clock.")


def test_the_moveit_node_without_sim_time_is_named(tmp_path: Path) -> None:
    run = real_run_with_parameters(MOVEIT, tmp_path / "mixed", {
        "/move_group": {"use_sim_time": True}, "/hello_moveit": {"use_sim_time": False},
        "/robot_state_publisher": {"use_sim_time": True}})
    told = finding(run, "manipulation")
    assert told.text.endswith("My nodes' parameters show the mix: use_sim_time was true on /move_group, "
                              "/robot_state_publisher but false on /hello_moveit.")


def test_a_finding_about_something_else_is_left_alone(tmp_path: Path) -> None:
    case = "tb4-591-jazzy-no-footprint"
    bare = finding(real_nav2_run(case, tmp_path / "bare"), "navigation")
    run = real_run_with_parameters(case, tmp_path / "mixed", {
        "/controller_server": {"use_sim_time": True}, "/bt_navigator": {"use_sim_time": False}})
    assert finding(run, "navigation") == bare
