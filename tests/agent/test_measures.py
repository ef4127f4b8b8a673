"""How far a place was, how fast I drove and where I set off from: figures read from the recording's positions and
plan times, checked here against the same recording read on its own."""

from __future__ import annotations

import itertools
import math
import re
from pathlib import Path

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.followups import content_kind
from hexar.agent.session import Session
from hexar.events import read_recording
from hexar.events.records import clock
from tests.agent.helpers import converse


def _leg(run: Path, step: int) -> tuple[list[tuple[float, float]], float]:
    """The positions recorded while a step of the first task ran, and its seconds."""
    log = read_recording(run)
    skill = log.tasks[0].skills[step]
    start, end = skill.time_of("running"), skill.last_change
    assert start is not None
    return [(p.x, p.y) for p in log.poses if start <= p.t <= end], (end - start) / 1e9


@pytest.mark.parametrize(("question", "kind"), [
    ("How far away was the kitchen?", "far"), ("how far is the living room", "far"), ("How far was it?", "far"),
    ("How fast were you going?", "fast"), ("what was your average speed?", "fast"),
    ("how quickly did you drive", "fast"), ("what's your top speed", "fast"),
    ("Where did you start?", "start"), ("where did you set off from?", "start"),
    ("where were you when I asked?", "start"),
    # asked before: still theirs
    ("how far did you drive?", "far"), ("when did you start?", "when"), ("where are you?", "where"),
    ("where did you go?", "went"),
    # the person's distance is the help skill's measurement, asked of its explainer
    ("How far away was the person?", None), ("how far was the man", None),
    # a limit is a published setting (agent/flags.py), not a speed driven; a trip under way is where I went
    ("what is your speed limit?", "limit"), ("where were you going?", "went"),
])
def test_distance_speed_and_start_questions_are_told_apart(question: str, kind: str | None) -> None:
    assert content_kind(question) == kind


def test_how_far_a_place_was_is_the_trip_there(suite: Path) -> None:
    """bagfile_8_1 got to the kitchen (step 1): the way driven there and how far it ended from where it set off."""
    points, seconds = _leg(suite / "bagfile_8_1", 0)
    kitchen, dining, errand = converse(suite / "bagfile_8_1", "How far away was the kitchen?",
                                       "how far is the dining room?", "how far was it?")
    driven = sum(math.dist(a, b) for a, b in itertools.pairwise(points))
    across = math.dist(points[0], points[-1])
    assert kitchen["answer"] == (f"I drove about {driven:.1f} m to get to the kitchen, in {round(seconds)} s; where "
                                 f"I got to was about {across:.1f} m in a straight line from where I set off.")
    assert kitchen["explainers"] == ["navigation"] and kitchen["error"] == ""
    # a room no step went to is not answered with the whole errand's figures
    assert dining["answer"] == ('No step of my plan for your request "Bring me a coffee from the kitchen" went to the '
                                "dining room, so my recording has no distance to it.")
    assert str(errand["answer"]).startswith('For your request "Bring me a coffee from the kitchen", I drove about ')


def test_how_far_a_place_was_on_a_trip_that_failed_or_never_set_off(suite: Path) -> None:
    (towards,) = converse(suite / "bagfile_5_1", "how far away was the kitchen?")
    assert re.fullmatch(r"I drove about \d+\.\d m towards the kitchen in \d+ s, and I did not get there; I was then "
                        r"about \d+\.\d m in a straight line from where I set off\.", str(towards["answer"]))
    (never,) = converse(suite / "bagfile_5_1", "how far was the living room?")
    assert str(never["answer"]).startswith("I never set off for the living room, so my recording has no distance to "
                                           "it: that was step 3 of your request")
    assert "step 1 (to go to the kitchen) failed first." in str(never["answer"])


def test_a_plan_rejected_before_it_started_drove_nowhere(suite: Path) -> None:
    """bagfile_1_1's plan was invalid: no step ran, so the answer is that it drove nowhere, not that the recording
    holds no position (it holds three)."""
    far, fast = converse(suite / "bagfile_1_1", "How far did you drive?", "How fast were you going?")
    for answer in (far, fast):
        assert answer["answer"] == ('I didn\'t drive anywhere for your request "Bring me a coffee from the kitchen": '
                                    "my plan was rejected before I started.")


def test_how_fast_is_each_legs_average(suite: Path) -> None:
    points, seconds = _leg(suite / "bagfile_12_1", 0)
    metres = sum(math.dist(a, b) for a, b in itertools.pairwise(points))
    (fast,) = converse(suite / "bagfile_12_1", "How fast were you going?")
    assert fast["answer"] == (f'For your request "Bring me a coffee from the kitchen", I drove at about '
                              f"{metres / seconds:.2f} m/s to go to the kitchen ({metres:.1f} m in "
                              f"{round(seconds)} s), on average.")


def test_where_i_set_off_from_is_my_last_position_before_the_first_step(suite: Path) -> None:
    log = read_recording(suite / "bagfile_8_1")
    first = log.tasks[0].skills[0].time_of("running")
    assert first is not None
    before = [p for p in log.poses if p.t <= first][-1]
    (start,) = converse(suite / "bagfile_8_1", "Where did you start?")
    assert start["answer"] == (f"When I set off on step 1 (to go to the kitchen), I was at ({before.x:.2f}, "
                               f"{before.y:.2f}) on my map: my last position recorded before then, at "
                               f"{clock(before.t).split('.')[0]} UTC. I can't say which room that is: I know "
                               "rooms only as the places my plan's steps name.")
    # a plan that never started: where I was when asked
    (asked,) = converse(suite / "bagfile_1_1", "where were you when I asked?")
    assert str(asked["answer"]).startswith('When I got your request "Bring me a coffee from the kitchen", I was at ')


def test_without_positions_the_start_is_not_guessed(tmp_path: Path) -> None:
    from hexar.evals.real_nav2 import corpus, write_recording

    excerpt = next(e for e in corpus() if e.outcome == "failed")
    run = write_recording(excerpt, tmp_path / "run", task=False)
    start, fast = converse(run, "Where did you start?", "How fast were you going?")
    assert "I can't tell where I was when I set off" in str(start["answer"])
    assert "I can't tell how fast I drove" in str(fast["answer"])


def test_how_far_the_person_was_goes_to_the_help_skill(suite: Path) -> None:
    """bagfile_8_1 asked for help and got it, and drove slowly: the person's distance is the help skill's, not the
    slow drive's finding nor "no step went to the person"."""
    (person,) = converse(suite / "bagfile_8_1", "How far away was the person?")
    assert person["explainers"] == ["ask_human_for_help"]
    assert re.match(r"I measured the person at \d+\.\d\d m, within my limit for asking", str(person["answer"]))


def test_where_a_recovery_started_is_the_place_a_trip_had_taken_me(suite: Path) -> None:
    """bagfile_12_1 reached the kitchen, then asking for help failed: its recovery set off from there, and says so;
    bagfile_14_1 drove on towards the person after the kitchen, so its recovery names no room."""
    arrived = read_recording(suite / "bagfile_12_1").tasks[0].skills[0].last_change
    kitchen = Session(RunSettings(recording=suite / "bagfile_12_1", llm="none")).ask("Where did you start?", task="2")
    assert str(kitchen["answer"]).endswith('That is the kitchen, where step 1 (to go to the kitchen) of your request '
                                           f'"Bring me a coffee from the kitchen" had taken me at '
                                           f"{clock(arrived).split('.')[0]}.")
    away = Session(RunSettings(recording=suite / "bagfile_14_1", llm="none")).ask("Where did you start?", task="2")
    assert str(away["answer"]).endswith("I can't say which room that is: I know rooms only as the places my plan's "
                                        "steps name.")


def test_how_long_before_a_rejected_plan_was_told_is_the_recoverys_words(suite: Path) -> None:
    """A plan rejected at once took no time; what the person waited for is the apology the recovery said."""
    from tests.agent.helpers import converse

    (told,) = converse(suite / "bagfile_2_2", "How long did it take before you told me you couldn't do it?")
    assert told["answer"] == ('My plan for your request "Could you bring me the book from the dining room?" was '
                              "rejected at once, at 12:20:32 UTC, before I started anything. I told you at 12:20:34 "
                              'UTC, 2 s after that: "Sorry, I could not complete the task.".')
