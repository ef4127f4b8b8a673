"""Whole-task answers (issue 24): a fix asked for as a first question, "did everything go ok?" and "what happened"
about every step, the robot's recovery task explained by the failure before it, and a recording of only
/rosout answered with what it does not hold."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.overview import presumes_goal_not_done, presumes_not_done, with_lead
from hexar.agent.session import Session
from hexar.cli import main
from hexar.evals.real_nav2 import Excerpt, corpus, write_recording


def _ask(run: Path, *questions: str, task: str | None = None) -> list[dict[str, object]]:
    session = Session(RunSettings(recording=run, llm="none"))
    thread = session.new_thread()
    if task is not None:
        session.switch(thread, task)
    return [session.ask(q, thread=thread) for q in questions]


@pytest.mark.parametrize("question", ["how can I fix this", "what would have helped?",
                                      "What would you recommend I do?", "what should I check?",
                                      "what do I need to look at?", "which parameter should I change?",
                                      "what settings should I tune?"])
def test_a_fix_question_is_answered_with_the_fix(suite: Path, question: str,
                                                 capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["ask", str(suite / "bagfile_5_1"), question, "--llm", "none"]) == 0
    out = " ".join(capsys.readouterr().out.replace("│", " ").split())
    assert "something blocked my path" in out and "Clear the way to the kitchen and ask me again." in out
    # a counterfactual the cause already says is not said twice
    assert main(["ask", str(suite / "bagfile_14_1"), question, "--llm", "none"]) == 0
    out = " ".join(capsys.readouterr().out.replace("│", " ").split())
    assert out.count("If my navigation to the person had succeeded") == 1
    assert "Clear the way to the person and ask me again." in out


def test_did_everything_go_ok_is_about_every_step(suite: Path) -> None:
    ok, happened, slow = _ask(suite / "bagfile_10_1", "did everything go ok?", "what happened",
                              "why did it take so long?")
    for answer in (ok, happened):
        text = str(answer["answer"])
        assert text.startswith("I did all 4 steps of my plan: go to the kitchen, ask someone for help")
        assert 'go to the living room and then say "Here is your coffee."' in text
        assert answer["route"] == "findings"  # no guess at one module for a question about the whole task
    assert "4 steps" not in str(slow["answer"])  # a question about one thing is answered about that thing


def test_what_happened_on_a_failed_task_names_every_step(suite: Path) -> None:
    (happened,) = _ask(suite / "bagfile_14_1", "what happened")
    text = str(happened["answer"])
    # the cause first (speech keeps only the first sentences), then every step
    assert text.startswith("I could not get help: my navigation to the person failed.")
    assert text.endswith("I did 1 of the 4 steps of my plan: step 2 (to ask someone for help) failed; steps 3 "
                         "and 4 never started.")


def test_why_did_you_say_sorry_is_the_failure_before_it(suite: Path) -> None:
    sorry, fix = _ask(suite / "bagfile_5_1", "why did you say sorry", "what would have helped?", task="2")
    text = str(sorry["answer"])
    assert text.startswith('I did my own recovery task (say "Sorry, I could not complete the task.") because my '
                           'task before it, "Bring me a coffee from the kitchen", failed: I couldn\'t reach the '
                           'kitchen')
    assert sorry["route"] == "recovery" and sorry["causes"] == ["navigation.blocked_path"]
    assert "second" not in text  # no speech timing
    assert str(fix["answer"]) == "Clear the way to the kitchen and ask me again."


@pytest.fixture(scope="module")
def plain_nav2(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """An ordinary Nav2 recording of only /rosout (a real log excerpt): no /task_info, no poses."""
    excerpt = next(e for e in corpus() if e.id == "tb4-679-humble-trajectory-hits-obstacle")
    return write_recording(excerpt, tmp_path_factory.mktemp("plain") / "bag", task=False)  # type: ignore[no-any-return]


def test_plain_nav2_follow_ups_say_what_is_not_recorded(plain_nav2: Path) -> None:
    first, deeper, deepest, where = _ask(plain_nav2, "what happened", "why?", "why?", "where are you now?")
    said = " ".join(str(t["answer"]) for t in (first, deeper, deepest, where))
    assert "I tried 0" not in said and "where I started" not in said
    assert "My log records no recovery manoeuvre" in str(deepest["answer"])
    assert "My position is not recorded: this recording has no /amcl_pose messages." in str(where["answer"])


def test_the_evidence_of_a_why_is_told_in_time_order(suite: Path) -> None:
    import re

    _, why = _ask(suite / "bagfile_14_1", "what happened", "why?")
    times = re.findall(r"at (\d\d:\d\d:\d\d\.\d{3})", str(why["answer"]))
    assert len(times) == 3 and times == sorted(times)
    assert "navigation_failure = True" in str(why["answer"])  # the explainer's own strongest items are kept


@pytest.mark.parametrize("question", ["Why didn't you suggest a Hawaiian?", "why did not you recommend pepperoni",
                                      "Why didn't you pick another pizza?", "Why didn't you choose the Diavola?"])
def test_why_not_another_option_takes_the_choice_as_made(question: str) -> None:
    assert not presumes_not_done(question) and not presumes_goal_not_done(question)


@pytest.mark.parametrize(("question", "about_the_goal"), [
    ("Why didn't you bring me the apple?", True),
    ("why didn't you finish?", True),
    ("Why did you fail?", True),
    ("why didn't it work", True),
    ("Why didn't you finish telling me the recipe?", False),  # the speech's own answer says how far it got
    ("Why didn't you take the shorter way?", False),  # the drive's figures answer it
    ("Why didn't you ask me for help?", False),
])
def test_which_questions_take_the_tasks_goal_for_not_reached(question: str, about_the_goal: bool) -> None:
    # of a task done with nothing wrong, only these are answered with every step done alone
    assert presumes_goal_not_done(question) is about_the_goal
    assert presumes_not_done(question)


def test_why_not_on_a_goal_the_logs_show_reached_says_it_was_reached(tmp_path: Path) -> None:
    # CIT-Autonomous-Robot-Lab/daifuku_autonomous (blind10, spent): Nav2's lines only, ending in "Goal succeeded";
    # "why didn't you get there?" once got an empty answer (no plan recorded, so no steps to say instead)
    excerpt = Excerpt(id="t", source="test", url="", distro="humble", outcome="succeeded", cause="navigation.nominal",
                      cause_quote="", logs_show_cause=True, lines="\n".join([
                          "[bt_navigator]: Begin navigating from current location (0.00, 0.00) to (44.08, -5.12)",
                          "[controller_server]: Received a goal, begin computing control effort.",
                          "[controller_server]: Reached the goal!", "[bt_navigator]: Goal succeeded"]) + "\n")
    [said] = _ask(write_recording(excerpt, tmp_path / "bag", task=False), "Why didn't you get there?")
    assert str(said["answer"]).startswith("I reached the goal at (44.08, -5.12)")


@pytest.mark.parametrize(("run", "question", "lead"), [
    ("bagfile_5_1", "Did you reach the goal?", "No. I couldn't reach the kitchen"),
    ("bagfile_5_1", "so did you make it", "No. I couldn't reach the kitchen"),
    ("bagfile_5_1", "Did you fail?", "Yes. I couldn't reach the kitchen"),
    ("bagfile_5_1", "were you successful?", "No. "),
    ("bagfile_2_1", "Did you finish?", "No. I didn't start because my plan was faulty"),
    ("bagfile_10_1", "Did you make it?", "Yes. I did all 4 steps of my plan"),
    ("bagfile_10_1", "did you get stuck?", "No. "),
    ("bagfile_10_1", "did anything go wrong?", "No. I did all 4 steps of my plan"),
    ("bagfile_12_1", "has something gone wrong", "Yes. I could not get help: the person was farther away"),
])
def test_a_yes_or_no_question_on_the_outcome_is_answered_yes_or_no(suite: Path, run: str, question: str,
                                                                   lead: str) -> None:
    (answer,) = _ask(suite / run, question)
    assert str(answer["answer"]).startswith(lead)


@pytest.mark.parametrize("question", ["did you bring me the coffee?", "why didn't you reach the goal?",
                                      "what happened", "did you see the person?"])
def test_no_yes_or_no_where_the_question_is_not_about_the_outcome(suite: Path, question: str) -> None:
    (answer,) = _ask(suite / "bagfile_5_1", question)
    assert not str(answer["answer"]).startswith(("Yes.", "No."))


def test_a_goal_found_in_real_nav2_logs_is_answered_yes_or_no(tmp_path: Path) -> None:
    by_outcome = {}
    for excerpt in corpus():  # the first goal that ends in the lines ("Goal succeeded" / "Goal failed")
        if "Goal succeeded" in excerpt.lines or "Goal failed" in excerpt.lines:
            by_outcome.setdefault(excerpt.outcome, excerpt)
    for outcome, lead in (("succeeded", "Yes."), ("failed", "No.")):
        run = write_recording(by_outcome[outcome], tmp_path / outcome, task=False)  # the goal from the logs alone
        (answer,) = _ask(run, "did you reach the goal?")
        assert str(answer["answer"]).startswith(lead), answer["answer"]


@pytest.mark.parametrize(("text", "lead", "said"), [
    ("I couldn't reach the kitchen.", "No.", "No. I couldn't reach the kitchen."),
    ("No, I couldn't reach the kitchen.", "No.", "No, I couldn't reach the kitchen."),  # a model's own, agreeing
    ("Yes, i reached it.", "No.", "No. I reached it."),  # a model's own, against the recorded outcome
    ("No pizza recommendation was recorded.", "Yes.", "Yes. No pizza recommendation was recorded."),
])
def test_the_lead_is_the_recorded_outcome_whatever_a_model_said(text: str, lead: str, said: str) -> None:
    assert with_lead(text, lead) == said


def test_what_went_well_is_about_every_step(suite: Path) -> None:
    (well,) = _ask(suite / "bagfile_9_1", "what went well?")
    assert str(well["answer"]).startswith("I did all 4 steps of my plan: go to the kitchen, ask someone for help")
    assert "people or things kept moving into my way" in str(well["answer"])  # and what did not go as well


@pytest.mark.parametrize("question", ["who did you ask for help?", "did anyone help you?"])
def test_a_module_named_by_what_it_does_answers_though_another_found_more(suite: Path, question: str) -> None:
    """The trip to the kitchen was slow, the asking went well: the question is about the asking."""
    (answer,) = _ask(suite / "bagfile_9_1", question)
    assert answer["route"] == "named" and answer["explainers"] == ["ask_human_for_help"]
    assert str(answer["answer"]).startswith("Asking for help went as planned: I found a person")


def test_a_setting_to_change_asked_after_the_cause_is_the_fix(suite: Path) -> None:
    cause, setting = _ask(suite / "bagfile_5_1", "what happened?", "which parameter should I change?")
    assert "something blocked my path" in str(cause["answer"])
    assert str(setting["answer"]) == "Clear the way to the kitchen and ask me again."
