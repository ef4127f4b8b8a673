""""Where is the kitchen?": where the robot was when a trip there got there, read from the recording, or why it
cannot tell; never a room's position the recording does not hold."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.followups import content_kind
from hexar.agent.session import Session
from hexar.events import read_recording
from hexar.events.records import clock


def _ask(run: Path, question: str) -> str:
    return str(Session(RunSettings(recording=run, llm="none")).ask(question)["answer"])


@pytest.mark.parametrize(("question", "kind"), [
    ("Where is the kitchen?", "place"), ("where's the living room", "place"), ("where is my bedroom?", "place"),
    # the robot, a trip, an object: their own questions
    ("where are you?", "where"), ("where did you go?", "went"), ("where is the coffee?", None),
    ("why did you go to the kitchen?", "went"), ("what was your position?", "where"),
    ("where were you when it failed?", "failed_at"), ("what was the robot's position when it stopped?", "failed_at"),
])
def test_a_room_asked_for_is_a_place_question(question: str, kind: str | None) -> None:
    assert content_kind(question) == kind


def test_a_room_reached_is_where_i_stopped_for_it(suite: Path) -> None:
    run = suite / "bagfile_8_1"
    log = read_recording(run)
    trip = log.tasks[0].skills[0]
    pose = [p for p in log.poses if p.t <= trip.last_change][-1]
    assert _ask(run, "Where is the kitchen?") == (
        f"When I got to the kitchen at {clock(trip.last_change).split('.')[0]} UTC, for step 1 (to go to the kitchen) "
        f'of your request "Bring me a coffee from the kitchen", I was at ({pose.x:.2f}, {pose.y:.2f}) on my map. I '
        "know the kitchen only as a place my plan names, so that is where I stopped for it, not the room's outline.")


def test_a_room_never_reached_or_never_in_a_plan_is_not_placed(suite: Path) -> None:
    assert _ask(suite / "bagfile_5_1", "where is the kitchen?") == (
        "I can't tell: I never got to the kitchen in my recording, so I have no position for it. Step 1 (to go to the "
        'kitchen) of your request "Bring me a coffee from the kitchen" failed.')
    assert _ask(suite / "bagfile_5_1", "where's the living room?").endswith("Step 3 (to go to the living room) of "
                                                                             'your request "Bring me a coffee from the '
                                                                             'kitchen" never started.')
    assert _ask(suite / "bagfile_5_1", "where is the bathroom?") == (
        "I can't tell: no step of any plan in my recording went to the bathroom, and I know rooms only as the places "
        "my plans name.")


def test_the_position_when_it_failed_is_the_last_one_before_the_failure(suite: Path) -> None:
    run = suite / "bagfile_5_1"
    log = read_recording(run)
    failed = log.tasks[0].failed_skill
    assert failed is not None
    before = [p for p in log.poses if p.t <= failed.last_change][-1]
    assert log.poses[-1].t > failed.last_change  # the robot's pose went on being recorded after the failure
    said = _ask(run, "where were you when it failed?")
    assert said == (f"When step 1 (to go to the kitchen) failed, at {clock(failed.last_change).split('.')[0]} UTC, my "
                    f"last recorded position was ({before.x:.2f}, {before.y:.2f}) on my map, at "
                    f"{clock(before.t).split('.')[0]}.")
    fine = _ask(suite / "bagfile_10_1", "where were you when it failed?")
    assert fine.startswith('Nothing failed in your request "Bring me a coffee from the kitchen". I\'m in the living '
                           "room")


def test_the_position_when_it_failed_falls_back_to_odometry_and_says_so(tmp_path: Path) -> None:
    """A robot that records /odom but no /amcl_pose: its odometry is the position, named as such (not "my map")."""
    from hexar.evals.scenarios.bag import BagBuilder, sec_ns
    from tests.agent.helpers import one_step_task
    from tests.events.test_motion import _odom

    t0 = sec_ns(1_741_600_000)
    b = BagBuilder()
    one_step_task(b, t0, 3, "Go to the kitchen", "navigate_to_zone", {"location": "kitchen"}, "failed",
                  "Navigation to kitchen failed")
    for s, x in ((1, 0.0), (3, 0.5), (5, 1.25), (8, 9.0)):  # the last after the failure, at 7 s
        b.raw(t0 + sec_ns(s), "/odom", "nav_msgs/msg/Odometry", _odom(t0 + sec_ns(s), x, 0.5))
    said = _ask(b.write(tmp_path / "run"), "where were you when it failed?")
    assert said == (f"When step 1 (to go to the kitchen) failed, at {clock(t0 + sec_ns(7)).split('.')[0]} UTC, my last "
                    f"recorded position was (1.25, 0.50) by my odometry (/odom), at "
                    f"{clock(t0 + sec_ns(5)).split('.')[0]}.")


@pytest.mark.parametrize(("question", "kind"), [
    ("what was your goal?", "goal"), ("where was the goal?", "goal"), ("what were the goal coordinates?", "goal"),
    ("what was the goal pose?", "goal"), ("why did you go to the kitchen?", "went"),
])
def test_the_goal_is_its_own_question(question: str, kind: str) -> None:
    assert content_kind(question) == kind


def test_the_goal_is_each_trip_s_place_or_position_or_what_the_recording_lacks(suite: Path, tmp_path: Path) -> None:
    from hexar.evals import real_nav2

    assert _ask(suite / "bagfile_5_1", "what was your goal?") == (
        'For your request "Bring me a coffee from the kitchen", my goals were the kitchen (I didn\'t get there) and '
        "the living room (I never set off).")
    cases = {e.id: e for e in real_nav2.corpus()}
    # a real Nav2 log with its goal line: the position it gives
    posed = real_nav2.write_recording(cases["nav2-1367-reached-goal-but-navigation-failed"], tmp_path / "a", False)
    assert _ask(posed, "where was the goal?") == (
        "My goal was (0.58, -0.55) on my map (I didn't get there).")
    # one without: it says where it knows of the goal from, never a position
    unposed = real_nav2.write_recording(cases["nav2-451-goaldist-unreachable-area"], tmp_path / "b", False)
    assert _ask(unposed, "what was your goal?") == ("My recording does not give my goal: I know of it only from the "
                                                    "Nav2 log (no goal line). I didn't get there.")


@pytest.mark.parametrize(("question", "kind"), [
    ("did you reach the kitchen?", "reached"), ("did you get to the living room?", "reached"),
    ("did you get there?", "reached"), ("did you make it to the garage?", "reached"),
    ("did you make it?", None), ("why didn't you reach the kitchen?", None), ("did you reach the goal?", None),
])
def test_did_you_reach_is_its_own_question(question: str, kind: str | None) -> None:
    assert content_kind(question) == kind


def test_did_you_reach_a_place_is_yes_or_no_from_the_trip(suite: Path) -> None:
    failed = _ask(suite / "bagfile_5_1", "did you reach the kitchen?")
    assert failed.startswith("No. I never got to the kitchen: I set off at ")
    never = _ask(suite / "bagfile_5_1", "did you get to the living room?")
    assert never.startswith("No. I never set off for the living room: that was step 3")
    done = _ask(suite / "bagfile_9_1", "did you reach the kitchen?")
    assert done.startswith("Yes. I got to the kitchen at ")
    nowhere = _ask(suite / "bagfile_9_1", "did you make it to the garage?")
    assert nowhere == ('No: no step of your request "Bring me a coffee from the kitchen" went to the garage. I went to '
                       "the kitchen and the living room.")
