""""What is my footprint?", "which dock?", "is use_sim_time set?": the log lines that name what a developer asks for,
with their node and time, or that none does (and why the recording holds no value for it), then the finding;
never the finding alone, as if it answered."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.followups import content_kind
from hexar.agent.mentions import asked_terms
from hexar.evals.scenarios.arm import simulate_arm_suite
from tests.agent.helpers import converse, real_module_run, real_nav2_run


@pytest.mark.parametrize(("question", "kind"), [
    ("what is my footprint?", "mentions"), ("which dock?", "mentions"), ("is use_sim_time set?", "mentions"),
    ("what's the transform tolerance?", "mentions"), ("which behavior tree did you load?", "mentions"),
    ("what baud rate did it use?", "mentions"), ("is my tf tree ok?", "mentions"),
    ("where is the bt file?", "mentions"),
    # a specific of the failure keeps the finding and its lines (agent/cited.py); errors and plugins their own
    ("which controller?", None), ("which trajectory failed?", None), ("what errors were there?", "logs"),
    ("which planner did you use?", "plugins"), ("what happened?", None), ("why did you fail?", None),
    ("what did the controllers do?", None), ("what did the joint do?", None),
])
def test_a_named_thing_of_the_stack_is_its_own_question(question: str, kind: str | None) -> None:
    assert content_kind(question) == kind


def test_the_longest_name_is_asked_for() -> None:
    assert asked_terms("what is the progress checker threshold?") == ["progress checker", "threshold"]
    assert asked_terms("what baud rate did it use?") == ["baud rate"]



def test_the_lines_that_name_it_are_quoted_with_their_node(tmp_path: Path) -> None:
    (footprint,) = converse(real_nav2_run("tb4-591-jazzy-no-footprint", tmp_path / "fp"), "what is my footprint?")
    assert footprint["answer"] == (
        'My log names footprint in 1 line up to the end of the navigation goal: at 13:06:22, controller_server '
        '(ERROR) "Original error: Considering footprint in collision checking but no robot footprint provided in '
        'the costmap.". My recording holds no parameter values (no /parameter_events), only what my nodes logged.')
    assert any("no robot footprint provided" in e["item"] for e in footprint["evidence"])  # type: ignore[union-attr]
    (dock,) = converse(real_nav2_run("mowgli-486-dock-charge-timeout", tmp_path / "dock"), "which dock?")
    assert str(dock["answer"]).startswith("My log names dock in 4 lines at warning or error level (4 more at info "
                                          "level) up to the end of the navigation goal: at 10:33:12, a node (ERROR) "
                                          '"Docking failed, will retry: Timed out waiting for charge to start" (2 '
                                          "times);")


def test_what_no_line_names_is_said_beside_what_one_does(tmp_path: Path) -> None:
    run = real_nav2_run("nav2-3746-sim-time-extrapolation", tmp_path / "tf")
    (tolerance,) = converse(run, "what's the transform tolerance?")
    text = str(tolerance["answer"])
    assert text.startswith("My log names transform in 2 lines")
    assert "No line names tolerance." in text
    # "which critic?" is a specific of the failure: the finding (with the critics DWB's summary names), then the lines
    # it rests on (agent/cited.py)
    (critic,) = converse(real_nav2_run("nav2-3807-dwb-no-valid-trajectories", tmp_path / "dwb"),
                         "which critic rejected the trajectories?")
    assert critic["answer"] == (
        "I couldn't reach my goal because my controller failed to compute velocity commands to follow the path. "
        "DWB's critics rejected the trajectories it sampled, by share: BaseObstacle 100% (\"Trajectory Hits "
        'Obstacle"). Here is what I recorded: at 01:36:58.760 my log recorded "[controller_server] WARN No valid '
        'trajectories out of 419!".')


def test_a_parameter_a_module_s_log_never_names(tmp_path: Path) -> None:
    # the simulated arm's nodes announce their parameters: the values answer, and "why?" goes on to the failure
    simulate_arm_suite(tmp_path, only=lambda s, v: v == 1 and s == "stale_state")
    asked, why = converse(tmp_path / "armfile_stale_state_1", "is use_sim_time set?", "why?")
    assert str(asked["answer"]).endswith("use_sim_time differs between my nodes: true on 3 nodes (/arm_controller, "
                                         "/controller_manager, /robot_state_publisher) but false on 1 node "
                                         "(/move_group).")
    assert "Didn't receive robot state" in str(why["answer"])
    # a real excerpt records no parameters: no line names it, and the recording holds no value
    (baud,) = converse(real_module_run("dynamixel-hw-14-wrong-baud-rate", tmp_path / "dxl"),
                       "what baud rate did it use?")
    assert str(baud["answer"]).startswith("I can't tell: no line of my log (/rosout) up to the end of")
    assert "names baud rate" in str(baud["answer"])
