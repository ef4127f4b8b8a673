"""A question about one goal of several ("the goal to (4, 5.5)", "the second goal", "the first two waypoints") is
answered about that goal, on a real Nav2 waypoint run whose goals HEXAR reads from the logs; and the time questions
people ask of a slow or a quick failure."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.followups import content_kind
from hexar.agent.questions import check_question, normalise
from tests.agent.helpers import converse, real_nav2_run

WAYPOINTS = "kilted-nav2-waypoints-doorway-blocked"  # goals to (4, 2.5) and (4, 5.5) reached, (9, 4) failed


@pytest.fixture(scope="module")
def waypoints(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return real_nav2_run(WAYPOINTS, tmp_path_factory.mktemp("waypoints") / "run")


def test_a_goal_named_by_its_coordinates_is_the_one_answered(waypoints: Path) -> None:
    (second,) = converse(waypoints, "Why did the goal to (4, 5.5) succeed?")
    assert second["task_id"] == "nav2-goal-2"
    assert str(second["answer"]).startswith("I reached the goal at (4.00, 5.50) without any problem.")
    (latest,) = converse(waypoints, "Why did the goal fail?")
    assert latest["task_id"] == "nav2-goal-3"


def test_a_goal_named_by_its_order_is_the_one_answered(waypoints: Path) -> None:
    (took,) = converse(waypoints, "how long did the second goal take?")
    assert str(took["answer"]).startswith("The navigation goal to (4.00, 5.50) took 7 s, from 07:26:46 to 07:26:53 UTC")
    (first,) = converse(waypoints, "Did the first waypoint succeed?")
    assert first["task_id"] == "nav2-goal-1"


def test_several_goals_asked_together_are_each_timed(waypoints: Path) -> None:
    (each,) = converse(waypoints, "How long did the first two waypoints take each?")
    text = str(each["answer"])
    assert text.startswith("The navigation goal to (4.00, 2.50) took 7 s, from 07:26:38 to 07:26:45 UTC; I finished "
                           "it.")
    assert "The navigation goal to (4.00, 5.50) took 7 s" in text and "(9.00, 4.00)" not in text


def test_where_the_planner_failed_comes_from_its_own_line(waypoints: Path) -> None:
    (where,) = converse(waypoints, "Where was the robot when planning to (9, 4) failed?")
    assert "I was at (5.03, 4.13) on my map then, as step 1 (to drive to (9.00, 4.00)) failed." in str(where["answer"])


def test_which_waypoint_failed_is_the_failure_not_a_list_of_lines(waypoints: Path) -> None:
    (which,) = converse(waypoints, "Which waypoint failed, and why?")
    assert str(which["answer"]).startswith("I couldn't reach the goal at (9.00, 4.00)")
    assert "lifecycle node launched" not in str(which["answer"])


def test_a_goal_rejected_at_once_is_timed_in_milliseconds(tmp_path: Path) -> None:
    run = real_nav2_run("kilted-nav2-theta-goal-in-wall", tmp_path / "run")
    (took,) = converse(run, "How quickly did the goal fail after it was sent?")
    assert str(took["answer"]).startswith("The navigation goal to (6.10, 2.00) took 20 ms, at 04:34:02 UTC;")
    assert "less than a second" not in str(took["answer"])


@pytest.mark.parametrize("question", [
    "Why were you in the dining room for almost a minute before you said here is your book?",
    "Why did you stand around in the living room for so long before coming back?",
    "How quickly did the goal fail after it was sent?",
])
def test_where_the_time_went_is_asked_in_many_ways(question: str) -> None:
    assert content_kind(question) == "long"


def test_the_time_spent_waiting_for_help_is_named(suite: Path) -> None:
    (dining,) = converse(suite / "bagfile_3_2",
                         "Why were you in the dining room for almost a minute before you said here is your book?")
    assert "step 2 (to ask someone for help) took 52 s" in str(dining["answer"])
    assert str(dining["answer"]).endswith("Most of that time went to step 2 (to ask someone for help).")


def test_coordinates_and_values_in_parentheses_stay_in_the_question() -> None:
    assert check_question("Why did the goal to (4, 5.5) succeed?") == "Why did the goal to (4, 5.5) succeed?"
    assert normalise("why (controller_server) failed") == "why (controller_server) failed"
    # a transcript's markers of sound are still dropped
    assert normalise("[Music] why did you stop (laughs)") == "why did you stop"
    assert normalise("(static noise)") == ""


def test_which_part_took_longest_names_the_wait_for_help(suite: Path) -> None:
    (longest,) = converse(suite / "bagfile_17_1", "Which part of the trip took the longest?")
    assert str(longest["answer"]).endswith("Most of that time went to step 2 (to ask someone for help).")


def test_how_far_without_positions_uses_the_positions_nav2_logged(tmp_path: Path) -> None:
    run = real_nav2_run("kilted-nav2-through-doorway-blocked", tmp_path / "run")
    (far,) = converse(run, "How far did the robot get before the planner gave up?")
    text = str(far["answer"])
    assert text.startswith("I can't tell how far I drove for the navigation goal to (9.00, 4.00): this recording holds "
                           "no position of mine")
    assert "My log states where I was, though: at 07:43:46 at (5.06, 4.49) (planner_server), and at 07:44:03 at " \
           "(4.90, 4.22) (bt_navigator:" in text and "0.3 m apart in a straight line" in text


def test_which_leg_took_longest_compares_the_goals(tmp_path: Path) -> None:
    run = real_nav2_run("kilted-nav2-waypoints-nominal", tmp_path / "run")
    (leg,) = converse(run, "which leg took the longest?")
    text = str(leg["answer"])
    assert text.startswith("The navigation goal to (4.00, 2.50) took 7 s")
    assert text.endswith("The longest was the navigation goal to (9.00, 4.00).")
