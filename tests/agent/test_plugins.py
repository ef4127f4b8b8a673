""""Which planner did you use?": the plugins named by the stacks' own start-up lines (real Nav2 and MoveIt strings),
or that the recording holds no such line; a bare "which controller?" stays a question about the failure."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.followups import content_kind
from hexar.evals import real_nav2
from hexar.evals.scenarios.arm import simulate_arm_suite
from tests.agent.helpers import converse


@pytest.mark.parametrize(("question", "kind"), [
    ("which planner did you use?", "plugins"), ("which controller plugin?", "plugins"),
    ("what plugins were loaded?", "plugins"), ("which behaviours did you load?", "plugins"),
    ("what planning algorithm did you use?", "plugins"),
    ("which controller?", None), ("which controller failed?", None), ("why did the planner fail?", None),
])
def test_which_plugin_is_its_own_question(question: str, kind: str | None) -> None:
    assert content_kind(question) == kind


def test_nav2_plugins_are_named_from_its_start_up_lines(tmp_path: Path) -> None:
    case = next(e for e in real_nav2.blind_set(26) if e.id == "kilted-nav2-dock-nominal")
    lines = case.lines if isinstance(case.lines, str) else "\n".join(case.lines)
    assert "Created controller : FollowPath of type nav2_regulated_pure_pursuit_controller" in lines
    run = real_nav2.write_recording(case, tmp_path / "run", task=False)
    planner, controller, everything = converse(run, "which planner did you use?", "which controller plugin?",
                                               "what plugins were loaded?")
    assert planner["answer"] == ("My log names what I loaded: my global planner GridBased "
                                 "(nav2_navfn_planner::NavfnPlanner).")
    assert controller["answer"] == ("My log names what I loaded: my controller FollowPath "
                                    "(nav2_regulated_pure_pursuit_controller::RegulatedPurePursuitController).")
    text = str(everything["answer"])
    assert "my recovery behaviours spin (nav2_behaviors::Spin), backup (nav2_behaviors::BackUp)" in text
    assert "my goal checker general_goal_checker (nav2_controller::SimpleGoalChecker)" in text
    cited = [e["item"] for e in everything["evidence"]]  # type: ignore[union-attr]
    assert any("Created global planner plugin GridBased" in item for item in cited)


def test_moveit_s_planner_and_a_recording_without_start_up_lines(tmp_path: Path, suite: Path) -> None:
    simulate_arm_suite(tmp_path, only=lambda s, v: v == 1 and s == "nominal")
    (arm,) = converse(tmp_path / "armfile_nominal_1", "which planner did you use?")
    assert arm["answer"] == ("My log names what I loaded: my arm's motion planner arm[RRTConnectkConfigDefault] "
                             "(geometric::RRTConnect).")
    (none,) = converse(suite / "bagfile_5_1", "which controller plugin?")
    assert str(none["answer"]).startswith("I can't tell: my log holds no line naming my controller for your request")
    assert none["enough_information"] is False


def test_the_plugin_a_named_server_loaded(tmp_path: Path) -> None:
    from tests.agent.helpers import converse, real_nav2_run

    run = real_nav2_run("kilted-nav2-mppi-heavy", tmp_path / "run")
    (loaded,) = converse(run, "Which controller plugin did controller_server load for this run?")
    assert loaded["answer"] == ("My log names what I loaded: my controller FollowPath "
                                "(nav2_mppi_controller::MPPIController).")
