"""Follow-ups keep the thread: deeper 'why?', 'what would have helped?', 'what else?', and task switching;
a conversation resumes from its SQLite checkpoint in a new process-like session."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.session import Session


def _session(suite: Path, rec: str, db: Path) -> Session:
    return Session(RunSettings(recording=suite / rec, llm="none"), checkpoints=db)


@pytest.mark.parametrize(("rec", "cause", "evidence_word"), [
    ("bagfile_5_1", "navigation.blocked_path", "Failed to make progress"),
    ("bagfile_7_2", "navigation.charging", "my charger was on (/power/is_charging)"),
    ("bagfile_12_1", "ask_human.person_too_far", "person_distance"),
    ("bagfile_19_1", "tts.timeout", "timed_out"),
])
def test_three_turns_resumed_from_checkpoint(suite: Path, tmp_path: Path, rec: str, cause: str,
                                             evidence_word: str) -> None:
    db = tmp_path / "threads.sqlite"
    first = _session(suite, rec, db)
    r1 = first.ask("What happened?")
    assert cause in r1["causes"]
    thread = r1["thread"]
    # a new session (as after restarting `hexar chat`) continues the same thread from SQLite
    second = _session(suite, rec, db)
    r2 = second.ask("and why was that?", thread=thread)
    assert r2["intent"] == "deeper" and evidence_word in r2["answer"]
    r3 = second.ask("What would have helped?", thread=thread)
    assert r3["intent"] == "helped"
    assert r3["answer"] and "don't have enough information" not in r3["answer"]
    history = second.history(thread)
    assert [t["question"] for t in history] == ["What happened?", "and why was that?", "What would have helped?"]


def test_why_goes_one_level_deeper_each_time(suite: Path, tmp_path: Path) -> None:
    s = _session(suite, "bagfile_14_1", tmp_path / "t.sqlite")
    thread = s.ask("Why didn't you bring me the coffee?")["thread"]
    evidence = s.ask("why?", thread=thread)["answer"]
    chain = s.ask("why?", thread=thread)["answer"]
    bottom = s.ask("why?", thread=thread)["answer"]
    assert evidence.startswith("Here is what I recorded")
    assert chain != evidence and chain
    assert "don't have enough information" in bottom


def test_what_else_tries_the_next_explainer(suite: Path, tmp_path: Path) -> None:
    s = _session(suite, "bagfile_9_1", tmp_path / "t.sqlite")
    r1 = s.ask("What happened?")
    r2 = s.ask("What else happened?", thread=r1["thread"])
    assert r1["explainers"] == ["navigation"]
    assert r2["explainers"] and r2["explainers"] != r1["explainers"]


def test_switching_to_the_first_task(suite: Path, tmp_path: Path) -> None:
    # bagfile_5_1 holds the failed request and then the robot's recovery task
    s = _session(suite, "bagfile_5_1", tmp_path / "t.sqlite")
    r1 = s.ask("What happened?")
    r2 = s.ask("What about the first task?", thread=r1["thread"])
    assert r2["intent"] == "switch"
    assert r2["task_id"] == r1["task_id"]  # the failed request is the first task
    assert "navigation.blocked_path" in r2["causes"]


def test_followup_without_history_is_a_new_question(suite: Path, tmp_path: Path) -> None:
    r = _session(suite, "bagfile_19_2", tmp_path / "t.sqlite").ask("why?")
    assert r["intent"] == "new" and "tts.timeout" in r["causes"]


def test_second_why_on_a_pizza_is_plain_and_keeps_the_numbers(suite: Path, tmp_path: Path) -> None:
    """Depth 2 says LIME's weights in words; the weights themselves travel as figures (shown with the evidence)."""
    session = _session(suite, "bagfile_20_1", tmp_path / "threads.sqlite")
    first = session.ask("Why did you recommend that pizza?")
    thread = first["thread"]
    session.ask("why?", thread=thread)
    second = session.ask("why?", thread=thread)
    assert second["intent"] == "deeper"
    assert "What weighed most for a Margherita: that you have basil (strongly)" in second["answer"]
    assert "LIME" not in second["answer"] and "+0." not in second["answer"]
    assert second["figures"][0].startswith("LIME weights toward Margherita")
    assert any(f.strip().startswith("basil, present, +") for f in second["figures"])


@pytest.mark.parametrize("rec", ["bagfile_19_1", "bagfile_5_1", "bagfile_12_1"])
def test_the_second_why_is_told_in_whole_sentences(suite: Path, tmp_path: Path, rec: str) -> None:
    import re

    s = _session(suite, rec, tmp_path / "t.sqlite")
    thread = s.ask("What happened?")["thread"]
    s.ask("why?", thread=thread)
    deeper = s.ask("why?", thread=thread)["answer"]
    assert deeper.endswith((".", "!", "?", '."', ".'"))
    # no note runs into the next: a sentence never ends in a quote followed by a lower-case word
    assert not re.search(r"['\"] [a-z]", deeper), deeper


@pytest.mark.parametrize("followup", ["why not?", "how come"])
def test_why_not_after_a_no_goes_deeper(suite: Path, tmp_path: Path, followup: str) -> None:
    s = _session(suite, "bagfile_5_1", tmp_path / "threads.sqlite")
    first = s.ask("did you make it?")
    assert str(first["answer"]).startswith("No. I couldn't reach the kitchen")
    deeper = s.ask(followup, thread=first["thread"])
    # the evidence behind the "no", not the same sentence again
    assert deeper["intent"] == "deeper" and "Failed to make progress" in str(deeper["answer"])
    assert not str(deeper["answer"]).startswith("I couldn't reach the kitchen")


def test_a_fix_asked_after_walking_past_the_failure_is_the_failures(suite: Path, tmp_path: Path) -> None:
    """"What else happened?" moves on to a step that went well, the steps that never ran, then "nothing else";
    "how do I fix it?" there still means the task's failure, not "nothing went wrong"."""
    s = _session(suite, "bagfile_14_1", tmp_path / "t.sqlite")
    thread = s.ask("What happened?")["thread"]
    fix = s.ask("how can I fix it?", thread=thread)["answer"]
    assert "Clear the way to the person" in fix
    walked = s.ask("what else happened?", thread=thread)["answer"]
    assert walked.startswith("Step 1, going to the kitchen: I reached the kitchen")
    after_good_step = s.ask("what could you have done differently?", thread=thread)["answer"]
    assert after_good_step.startswith("Nothing went wrong there. As for what failed: ")
    assert after_good_step.endswith(fix)
    rest = [s.ask("what else happened?", thread=thread)["answer"] for _ in range(3)]
    assert rest[-1].startswith("Nothing else happened")
    assert s.ask("how do I fix it?", thread=thread)["answer"] == fix
    ok = _session(suite, "bagfile_10_1", tmp_path / "t.sqlite")  # a task that went well has no failure to fix
    thread = ok.ask("What happened?")["thread"]
    assert ok.ask("how can I fix it?", thread=thread)["answer"].startswith("Nothing went wrong there, so I have")
