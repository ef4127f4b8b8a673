"""Questions of round 53's blind set 14 that the answers got wrong, asked again of real consoles written as
recordings: an either-or question answered with no bare yes or no."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.overview import confirmed, yes_or_no
from hexar.causes import BENIGN
from tests.agent.helpers import converse, real_module_run, real_nav2_run


def test_an_either_or_question_gets_no_bare_yes_or_no(tmp_path: Path) -> None:
    run = real_nav2_run("jzt-custom-docking-plugin-goal-succeeded-mux-timeouts", tmp_path / "run")
    either, whether = converse(run, "Are the mux timeouts after the goal succeeded harmless or do I need to fix "
                                    "something?", "Did you reach the goal or not?")
    assert str(either["answer"]).startswith("I reached my goal without any problem.")
    assert str(whether["answer"]).startswith("Yes. I reached my goal")  # "or not" still asks one thing
    assert confirmed("were you charging or was the joystick on?", {"navigation.charging"}, BENIGN) == ""
    assert confirmed("were you charging?", {"navigation.charging"}, BENIGN) == "Yes."
    assert yes_or_no("did you finish or did you give up?", "succeeded") == ""


def test_the_launch_failing_is_its_error_not_its_start(tmp_path: Path) -> None:
    run = real_nav2_run("tb4robot-20-humble-rplidar-executable-missing", tmp_path / "run")
    (gap,) = converse(run, 'How long after "bringup turtlebot4" started did the launch fail?')
    assert str(gap["answer"]).startswith("5.0 s passed from a node's \"Started \"bringup turtlebot4\".\" at 11:09:32 "
                                         "to launch's \"Caught exception in launch")


def test_a_trajectory_goal_kilted_aborts_on_its_goal_time_ends_failed(tmp_path: Path) -> None:
    run = real_module_run("kilted-control-hardware-state-offset", tmp_path / "run")
    (why,) = converse(run, "Is the hardware reporting a state offset that keeps the JTC from reaching the goal?")
    assert str(why["answer"]).startswith("My controllers could not go on because my arm strayed from its planned "
                                         "trajectory beyond the controller's tolerance")
    assert "The recording ends before" not in str(why["answer"])


def test_a_copied_log_line_is_no_word_the_question_must_know(tmp_path: Path) -> None:
    from hexar.agent.errors import BadQuestionError
    from hexar.agent.questions import check_question

    asked = 'Does the "cannot access /etc/ros/humble/turtlebot4.d/*.xacro" warning matter?'
    assert check_question(asked) == asked
    with pytest.raises(BadQuestionError):
        check_question('"asdf qwer"?')  # a quote alone is judged by its own words
    run = real_nav2_run("tb4robot-20-humble-rplidar-executable-missing", tmp_path / "run")
    (matters,) = converse(run, asked)
    assert "cannot access" in str(matters["answer"]) and "I don't understand" not in str(matters["answer"])


def test_a_question_naming_the_stack_is_not_off_topic(tmp_path: Path) -> None:
    from hexar.agent.topic import off_topic

    assert not off_topic("Could this be a Twist vs TwistStamped mismatch on cmd_vel in Jazzy?")
    assert off_topic("what is the capital of France?")
    run = real_nav2_run("leo-blog-jazzy-tb3-twist-vs-twiststamped-no-motion", tmp_path / "run")
    (asked,) = converse(run, "Could this be a Twist vs TwistStamped mismatch on cmd_vel in Jazzy?")
    assert "not about it" not in str(asked["answer"])
