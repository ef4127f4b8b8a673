""""And then?", "what tasks did you have?", "when did this happen?", "why did you go back?": the order of the
recording's tasks and trips and their day, told from /task_info, not the failure nobody asked about."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.followups import content_kind
from hexar.evals.scenarios.bag import BagBuilder
from hexar.events import read_recording
from hexar.events.records import clock
from tests.agent.helpers import converse


@pytest.mark.parametrize(("question", "kind"), [
    ("and then?", "after"), ("what did you do after that?", "after"), ("what happened next?", "after"),
    ("then what", "after"), ("how many tasks did you have?", "tasks"), ("what was your first task?", "tasks"),
    ("when did this happen?", "when"), ("what day was it?", "when"), ("when was this recorded?", "when"),
    ("why did you go back?", "went"), ("what happens next?", "next"), ("what will you do next?", "next"),
    ("how long did you wait?", "long"), ("how long did you talk?", "long"),
])
def test_kinds(question: str, kind: str) -> None:
    assert content_kind(question) == kind


def test_and_then_tells_the_recovery_and_why_goes_on_to_the_failure_it_recovers_from(suite: Path) -> None:
    first, then, why, why2 = converse(suite / "bagfile_5_1", "what happened?", "and then?", "why?", "why?")
    assert "blocked my path" in str(first["answer"])
    assert then["answer"] == ('Right after that, I started on my own recovery task after task 1 failed. My plan was '
                              'to say "Sorry, I could not complete the task.", and I did it.'), then["answer"]
    assert "Failed to make progress" in str(why["answer"]) and 'task 2: "' not in str(why["answer"])
    assert str(why2["answer"]).startswith("I did my own recovery task") and "blocked my path" in str(why2["answer"])
    assert '."."' not in str(why2["answer"]) and '.".' not in str(why2["answer"]), why2["answer"]


def test_and_then_after_the_last_task_says_nothing_more(suite: Path) -> None:
    log = read_recording(suite / "bagfile_10_1")
    (then,) = converse(suite / "bagfile_10_1", "and then?")
    end = clock(max(log.task().last_update, log.end)).split(".")[0]
    assert then["answer"] == ('Nothing more: your request "Bring me a coffee from the kitchen" was the last task in my '
                              f"recording, which ends at {end} UTC.")


def test_the_tasks_are_listed_in_order_with_how_each_ended(suite: Path) -> None:
    (listed,) = converse(suite / "bagfile_1_1", "how many tasks did you have?")
    assert listed["answer"] == ('I had 2 tasks in this recording: 1. your request "Bring me a coffee from the '
                                'kitchen", rejected before it started; 2. my own recovery task after task 1 had an '
                                'invalid plan, done. Ask me about one with "what about task 2?".')
    (one,) = converse(suite / "bagfile_10_1", "what was your first task?")
    assert one["answer"] == 'I had one task in this recording: your request "Bring me a coffee from the kitchen", done.'


def test_when_it_happened_gives_the_day(suite: Path) -> None:
    from datetime import UTC, datetime

    task = read_recording(suite / "bagfile_5_1").task()
    day = datetime.fromtimestamp(task.created / 1e9, tz=UTC)
    dated, started = converse(suite / "bagfile_5_1", "when did this happen?", "when did you start?")
    assert str(dated["answer"]).startswith(f"On {day:%A} {day.day} {day:%B %Y}. I started on your request")
    assert str(started["answer"]).startswith("I started on your request")  # a time of day, asked as one


def test_a_simulators_clock_gives_no_day(tmp_path: Path) -> None:
    b = BagBuilder()
    for t, status in ((120_000_000_000, "Running"), (150_000_000_000, "succeeded")):
        b.task_info(t, {"instruction": "Go to the kitchen", "task_id": "T1", "task_status": "valid",
                        "task_error_msg": "", "skill_sequence": [{"skill": "navigate_to_zone",
                                                                  "params": {"location": "kitchen"},
                                                                  "status": status, "error_msg": ""}]})
    (answer,) = converse(b.write(tmp_path / "gazebo"), "what day was it?")
    assert str(answer["answer"]).startswith("My clock was a simulator's, which starts at zero, so my recording gives "
                                            "no calendar day. I started on"), answer["answer"]
    assert "1970" not in str(answer["answer"])


def test_why_did_you_go_back(suite: Path) -> None:
    (recovered,) = converse(suite / "bagfile_14_1", "why did you go back?")
    assert str(recovered["answer"]).startswith("I went to the living room because step 1 of my plan for my own "
                                               "recovery task after task 1 failed"), recovered["answer"]
    (delivered,) = converse(suite / "bagfile_10_1", "why did you go back?")
    assert str(delivered["answer"]).startswith("I went to the living room because step 3 of my plan")
    (never,) = converse(suite / "bagfile_5_1", "why did you go back?")
    assert str(never["answer"]).startswith('I didn\'t go back for your request "Bring me a coffee from the kitchen": '
                                           "I tried to go to the kitchen but didn't get there")


@pytest.mark.parametrize("question", ["what were you doing when it failed?", "what step did you fail at?",
                                      "what were you doing at the time", "at which step did it fail?"])
def test_what_were_you_doing_is_the_step_under_way(suite: Path, question: str) -> None:
    log = read_recording(suite / "bagfile_5_1")
    failed = log.task().failed_skill
    assert failed is not None
    at = clock(failed.time_of("failed") or failed.last_change).split(".")[0]
    (answer,) = converse(suite / "bagfile_5_1", question)
    assert answer["answer"] == f"When it failed at {at} UTC, I was at step 1 (to go to the kitchen), 36 s into it."


def test_what_were_you_doing_of_a_clean_run_and_of_one_still_going(suite: Path, tmp_path: Path) -> None:
    (clean,) = converse(suite / "bagfile_10_1", "what were you doing when it failed?")
    assert str(clean["answer"]).startswith("Nothing failed. I did all 4 steps of my plan")
    b = BagBuilder()
    for t, status in ((1_741_600_000_000_000_000, "Running"), (1_741_600_050_000_000_000, "Running")):
        b.task_info(t, {"instruction": "Go to the kitchen", "task_id": "T1", "task_status": "valid",
                        "task_error_msg": "", "skill_sequence": [{"skill": "navigate_to_zone",
                                                                  "params": {"location": "kitchen"},
                                                                  "status": status, "error_msg": ""}]})
    (going,) = converse(b.write(tmp_path / "going"), "what were you doing?")
    assert str(going["answer"]).startswith("At ") and str(going["answer"]).endswith(
        " UTC, when my recording ends, I was at step 1 (to go to the kitchen), 50 s into it."), going["answer"]
    # said live, while the robot is still at it: no recording in the words
    from hexar.live.present import heard_words

    assert "when I last heard of it, I was at step 1" in heard_words(str(going["answer"]))


def test_what_else_could_you_have_picked_is_the_alternative_not_the_next_finding(suite: Path) -> None:
    _, other, more = converse(suite / "bagfile_20_2", "what happened?", "what else could you have picked?",
                              "what else happened?")
    assert other["intent"] == "helped" and "I would have recommended a" in str(other["answer"]), other["answer"]
    assert more["intent"] == "else" and "speech limit" in str(more["answer"])


@pytest.mark.parametrize("question", ["What was your plan?", "what's the plan", "what were you supposed to do?",
                                      "tell me your plan"])
def test_the_plan_is_its_steps_then_what_became_of_them(suite: Path, question: str) -> None:
    assert content_kind(question) == "plan"
    (failed,) = converse(suite / "bagfile_5_1", question)
    assert failed["answer"] == ('My plan for your request "Bring me a coffee from the kitchen" was to go to the '
                                'kitchen, ask someone for help ("Could you please put the coffee on my tray?"), go to '
                                'the living room and then say "Here is your coffee." I did none of the 4 steps of my '
                                "plan: step 1 (to go to the kitchen) failed; steps 2, 3 and 4 never started.")


def test_a_plan_for_later_is_no_question_about_the_recorded_one() -> None:
    assert content_kind("what is the plan for tomorrow?") is None and content_kind("what's the plan now?") is None


def test_a_rejected_plan_and_a_goal_from_the_logs_say_what_they_were(suite: Path, tmp_path: Path) -> None:
    (rejected,) = converse(suite / "bagfile_1_1", "What was your plan?")
    assert str(rejected["answer"]).endswith("My planner rejected it: Skill navigate_to_room is not a valid skill.")
    (done,) = converse(suite / "bagfile_20_1", "what was the plan?")
    assert str(done["answer"]).endswith("and then say the pizza I recommend. I did every step.")
    from hexar.evals.real_nav2 import corpus, write_recording

    excerpt = next(e for e in corpus() if e.id == "nav2-3807-dwb-no-valid-trajectories")
    (goal,) = converse(write_recording(excerpt, tmp_path / "run", task=False), "what was your plan?")
    assert goal["answer"] == ("I had no plan of my own for the navigation goal: it is a goal I read from my logs, to "
                              "drive to my goal, and it failed.")


@pytest.mark.parametrize(("question", "kind"), [
    ("what did I ask you?", "request"), ("what was my request?", "request"), ("who gave you the task?", "request"),
    ("when did I ask you?", "request"), ("what did you want me to do?", None),
    ("how many steps did the plan have?", "plan"), ("which step took the longest?", "long"),
    ("what happens now?", "next"), ("which room are you in?", "where"),
])
def test_request_and_plan_questions_are_told_apart(question: str, kind: str | None) -> None:
    assert content_kind(question) == kind


def test_the_request_as_received_and_who_asked_never_recorded(suite: Path, tmp_path: Path) -> None:
    from hexar.evals import real_nav2

    run = suite / "bagfile_5_1"
    created = clock(read_recording(run).tasks[0].created).split(".")[0]
    asked, who, steps = converse(run, "what did I ask you?", "who gave you the task?",
                                 "how many steps did the plan have?")
    assert asked["answer"] == (f'You asked me "Bring me a coffee from the kitchen" at {created} UTC. It failed at '
                               "step 1 (to go to the kitchen).")
    assert str(who["answer"]).startswith("My recording does not say who asked: it holds the request")
    assert str(steps["answer"]).startswith('My plan for your request "Bring me a coffee from the kitchen" had 4 steps: '
                                           "go to the kitchen, ask someone for help")
    case = next(e for e in real_nav2.corpus() if e.id == "nav2-1367-reached-goal-but-navigation-failed")
    (derived,) = converse(real_nav2.write_recording(case, tmp_path / "run", task=False), "what was my request?")
    assert str(derived["answer"]).startswith("No one asked me in words that my recording holds: the navigation goal")
