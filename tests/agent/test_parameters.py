"""A developer asks for a setting by its name: the values the nodes announced on /parameter_events, node by node
as they stood at the task's end; a setting that differs between nodes is said as such. Without the topic, or for
a name no node declared, the answer says so, never a value it does not have. Recordings: a real Nav2 excerpt
written with rosbags, with the parameter events its nodes publish."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.errors import BadQuestionError
from hexar.agent.questions import check_question
from tests.agent.helpers import converse, real_nav2_run, real_run_with_parameters

CASE = "nav2-3746-sim-time-extrapolation"  # Extrapolation into the future: a clock mix-up on a real robot
DECLARED = {
    "/controller_server": {"use_sim_time": True, "failure_tolerance": 0.3, "FollowPath.max_vel_x": 0.26,
                           "controller_frequency": 20.0},
    "/amcl": {"use_sim_time": True, "transform_tolerance": 1.0},
    "/bt_navigator": {"use_sim_time": False},
    "/local_costmap/local_costmap": {"use_sim_time": True, "transform_tolerance": 0.3},
}


@pytest.fixture(scope="module")
def run(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return real_run_with_parameters(CASE, tmp_path_factory.mktemp("params") / "run", DECLARED,
                                     [(0.5, "/controller_server", "failure_tolerance", 0.5)])


def test_a_setting_that_differs_between_nodes_is_said_node_by_node(run: Path) -> None:
    for question in ("is use_sim_time set?", "which nodes use sim time?", "use_sim_time?"):
        (answer,) = converse(run, question)
        assert str(answer["answer"]).endswith(
            "use_sim_time differs between my nodes: true on 3 nodes (/amcl, /controller_server, "
            "/local_costmap/local_costmap) but false on 1 node (/bt_navigator)."), question
        assert "/parameter_events" in {e["topic"] for e in answer["evidence"]}  # type: ignore[union-attr]


def test_a_value_changed_while_running_is_the_one_at_the_end_with_what_it_was(run: Path) -> None:
    (answer,) = converse(run, "what's failure_tolerance set to?")
    assert str(answer["answer"]).endswith(
        "/controller_server has failure_tolerance = 0.5. Changed while running: /controller_server set "
        "failure_tolerance to 0.5 at 16:12:53 (declared as 0.3).")
    (changed,) = converse(run, "which parameters changed?")
    assert changed["answer"] == ("1 parameter was changed while running: /controller_server set failure_tolerance "
                                 "to 0.5 at 16:12:53 (declared as 0.3).")


@pytest.mark.parametrize(("question", "said"), [
    ("what's max_vel_x?", "/controller_server has FollowPath.max_vel_x = 0.26."),
    ("what is FollowPath.max_vel_x?", "/controller_server has FollowPath.max_vel_x = 0.26."),
    ("what's the controller frequency?", "/controller_server has controller_frequency = 20.0."),
    ("what is the transform tolerance?", "transform_tolerance differs between my nodes: 1.0 on 1 node (/amcl) but "
                                         "0.3 on 1 node (/local_costmap/local_costmap)."),
])
def test_a_parameter_is_found_by_its_name_its_last_part_or_its_words(run: Path, question: str, said: str) -> None:
    (answer,) = converse(run, question)
    assert str(answer["answer"]).endswith(said)


def test_a_nodes_parameters_are_listed(run: Path) -> None:
    (answer,) = converse(run, "what parameters did amcl have?")
    assert answer["answer"] == "/amcl announced 2 parameters on /parameter_events: transform_tolerance = 1.0, " \
                               "use_sim_time = true."


def test_a_name_no_node_declared_gets_no_value(run: Path) -> None:
    (answer,) = converse(run, "what is inflation_radius?")
    text = str(answer["answer"])
    assert "none of the 9 parameters my nodes announced on /parameter_events is inflation_radius" in text
    assert "= " not in text


def test_a_question_about_the_failure_keeps_its_way_beside_recorded_parameters(run: Path) -> None:
    (answer,) = converse(run, "which controller?")
    assert "/parameter_events" not in str(answer["answer"])
    assert "Extrapolation Error" in str(answer["answer"])


def test_without_parameter_events_the_answer_says_the_recording_holds_no_values(tmp_path: Path) -> None:
    (answer,) = converse(real_nav2_run(CASE, tmp_path / "bare"), "what's failure_tolerance set to?")
    text = str(answer["answer"])
    assert text.startswith("I can't tell: no line of my log (/rosout) up to the end of the navigation goal")
    assert "my recording holds no parameter values (no /parameter_events; record it from before the bring-up" in text
    assert "failure_tolerance =" not in text


def test_a_parameter_name_is_a_word_but_a_made_up_one_alone_is_not() -> None:
    assert check_question("what's max_vel_x?") == "what's max_vel_x?"
    assert check_question("use_sim_time?") == "use_sim_time?"
    with pytest.raises(BadQuestionError, match="I don't understand 'asdf_qwer\\?'"):
        check_question("asdf_qwer?")


@pytest.fixture(scope="module")
def arm(tmp_path_factory: pytest.TempPathFactory) -> Path:
    from hexar.evals.scenarios.arm import simulate_arm_suite

    out = tmp_path_factory.mktemp("arm")
    simulate_arm_suite(out, only=lambda s, v: v == 1 and s in {"tolerance", "nominal"})
    return out


def test_a_word_a_parameter_ends_in_is_no_question_about_it(arm: Path) -> None:
    # constraints.arm_1_joint.trajectory ends in "trajectory"; update_rate spaced is "update rate"
    (far,) = converse(arm / "armfile_tolerance_1", "how far into the trajectory did arm_controller abort?")
    assert "/parameter_events" not in str(far["answer"])
    (warned,) = converse(arm / "armfile_nominal_1",
                         "anything in the warnings I should worry about, e.g. the costmap missing its update rate?")
    assert "/parameter_events" not in str(warned["answer"])


def test_a_node_named_in_words_lists_its_parameters(arm: Path) -> None:
    (listed,) = converse(arm / "armfile_nominal_1", "what parameters did the arm controller announce?")
    assert str(listed["answer"]).startswith("/arm_controller announced 18 parameters on /parameter_events: "
                                            "constraints.arm_1_joint.goal = 0.05, ")
    (joint,) = converse(arm / "armfile_tolerance_1", "what path tolerance is configured for arm_6_joint?")
    assert str(joint["answer"]).endswith("/arm_controller has constraints.arm_6_joint.goal = 0.05; /arm_controller "
                                         "has constraints.arm_6_joint.trajectory = 0.1.")
