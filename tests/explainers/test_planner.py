"""The planner explainer on a plan that checks out: the plan in plain words at every depth, never call notation."""

from __future__ import annotations

from pathlib import Path

from hexar.events import read_recording
from hexar.explainers.base import Context
from hexar.explainers.evidence_check import exists
from hexar.explainers.planner import PlannerExplainer


def test_recovery_plan_in_plain_words(suite: Path) -> None:
    log = read_recording(suite / "bagfile_5_1")
    recovery = log.tasks[-1]
    assert recovery.is_recovery
    exp = PlannerExplainer().explain("What was your plan?", Context.for_task(log, recovery))
    assert exp.causes == ["planner.plan_ok"]
    assert exp.text == ("My own recovery plan, which I made after the task before it failed, looks right to me: "
                        'say "Sorry, I could not complete the task."')
    assert exp.details == ['Step 1, to say "Sorry, I could not complete the task.": done.', "The task succeeded."]
    # the empty instruction of a recovery task is no evidence: its step's own recorded words are
    assert [e.item for e in exp.evidence] == ["Sorry, I could not complete the task."]
    assert all(exists(log, e) for e in exp.evidence)


def test_plan_steps_said_as_sentences(suite: Path) -> None:
    log = read_recording(suite / "bagfile_5_1")
    task = log.tasks[0]
    exp = PlannerExplainer().explain("What was your plan?", Context.for_task(log, task))
    assert exp.text.startswith('My plan for "Bring me a coffee from the kitchen" looks right to me: go to the kitchen, '
                               'ask someone for help')
    assert exp.details[0] == "Step 1, to go to the kitchen: failed."
    assert exp.details[2] == "Step 3, to go to the living room: never started."
    for said in (exp.text, *exp.details):
        assert "(input=" not in said and "navigate_to_zone" not in said and "location=" not in said
    assert all(exists(log, e) for e in exp.evidence)


def test_a_navigate_to_pose_goal_may_carry_its_pose_but_nothing_else() -> None:
    from hexar.explainers.plan_check import check_plan

    assert check_plan("go to the goal", [("navigate_to_pose", {"x": 1.46, "y": 0.05})]) == []
    [bad] = check_plan("go to the goal", [("navigate_to_pose", {"x": 1.0, "y": 2.0, "speed": 3})])
    assert bad.cause == "planner.invalid_parameter" and "'speed'" in bad.message


def test_a_request_that_named_my_place_needs_no_change(suite: Path) -> None:
    """"Bring me a coffee from the kitchen", planned to 'kitchen_counter': the fix says the request was fine."""
    from tests.agent.helpers import converse

    (asked,) = converse(suite / "bagfile_2_1", "What should I say differently so you'll actually fetch coffee next "
                                               "time?")
    assert "Your request was fine: it named the kitchen, one of my places, and my task planner put another name " \
           "in my plan. Ask me again the same way" in str(asked["answer"])
