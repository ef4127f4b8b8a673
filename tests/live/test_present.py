"""Live answers as a person at home hears them (live/present.py): "what I heard", never "the recording"; a task
still going on told as going on; a question asked before any task answered aloud instead of dropped as an error."""

from __future__ import annotations

import ast
import re
import time
from dataclasses import replace
from pathlib import Path

from hexar.agent.topic import OFF_TOPIC
from hexar.events import contract as c
from hexar.events.tasks import build_tasks
from hexar.live.present import heard_words, no_task_yet, present
from tests.live.dds_helpers import NO_DDS, Listener, fresh_domain, live_node, other, replay_process

ROOT = Path(__file__).resolve().parents[2]
TTS_TOPIC = "/hexar_tts_text"
RECORDING = re.compile(r"\b(?:the|this|my) recording\b", re.IGNORECASE)


def _answer_phrases() -> list[str]:
    """Every text the explainers and the agent word about "the recording" (string constants, docstrings left out):
    the phrases a live answer can carry."""
    found = []
    for folder in ("explainers", "agent"):
        for path in sorted((ROOT / folder).rglob("*.py")):
            tree = ast.parse(path.read_text())
            docs = {id(n.body[0].value) for n in ast.walk(tree)
                    if isinstance(n, ast.Module | ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef)
                    and n.body and isinstance(n.body[0], ast.Expr)}
            found += [n.value for n in ast.walk(tree) if isinstance(n, ast.Constant) and isinstance(n.value, str)
                      and id(n) not in docs and RECORDING.search(n.value)]
    return found


def test_no_phrase_of_the_answers_says_the_recording_when_live() -> None:
    phrases = _answer_phrases()
    assert len(phrases) > 25  # the scan found the answers' wording, not nothing
    assert [p for p in phrases if RECORDING.search(heard_words(p))] == []


def test_heard_words_keep_sentences_and_quotes() -> None:
    assert heard_words("I don't have enough information to say. The recording does not show whether I reached "
                       "the goal.") == ("I don't have enough information to say. What I heard does not show "
                                        "whether I reached the goal.")
    assert heard_words("As far as my recording shows, my navigation went normally") == \
        "As far as I heard, my navigation went normally"
    assert heard_words("I set off for the kitchen, and the recording ends while I was still on my way.") == \
        "I set off for the kitchen, and I'm still on my way."
    assert heard_words("My last goal was the kitchen; the recording does not show whether I got there. My last") == \
        "I'm on my way to the kitchen; I have not heard that I got there yet. My last"
    assert heard_words("My last goal was (1.50, -2.00) on my map; the recording does not show whether I got there.") \
        == "I'm on my way to (1.50, -2.00) on my map; I have not heard that I got there yet."
    assert heard_words("Task 2, and the recording ends while it waited.") == "Task 2, and the last I heard, it waited."
    assert heard_words("Step 2 was still running when the recording ends.") == \
        "Step 2 was still running when I last heard of it."
    # a log line quoted in an answer is the robot's own words
    quoted = 'recorder said "the recording ends here" and “my recording stopped”; the recording shows it'
    assert heard_words(quoted) == ('recorder said "the recording ends here" and “my recording stopped”; '
                                   "what I heard shows it")


def test_a_task_going_on_is_told_where_it_is_and_one_that_ended_is_left_alone(suite: Path) -> None:
    from hexar.agent.context import RunSettings
    from hexar.agent.session import Session

    session = Session(RunSettings(recording=suite / "bagfile_5_1", llm="none"))
    task = next(t for t in session.context.log.tasks if t.outcome == "failed")
    updates = [u for u in session.context.log.task_updates if u.task_id == task.task_id]
    running = build_tasks(updates[:-1])  # its failing update has not come yet
    started = running[0].skills[0].time_of("running")
    assert started is not None
    unknown = {"task_id": task.task_id, "causes": [], "enough_information": False,
               "answer": "I don't have enough information to say. The recording does not show whether I reached "
                         "the goal."}
    present(unknown, running, started + 12 * 10**9)
    assert unknown["answer"] == ('I\'m still working on your request "Bring me a coffee from the kitchen": I\'m at '
                                 "step 1 of 4 (to go to the kitchen), for 12 s so far. Nothing I heard so far says "
                                 "anything went wrong.")
    assert unknown["running"] is True
    said = {"task_id": task.task_id, "causes": [], "enough_information": True, "answer": "I saw a person."}
    present(said, running, started)
    assert said["answer"].endswith("(to go to the kitchen), for 0 s so far. I saw a person.")
    # an answer that already tells what the robot is doing (where it is going) is left as it is
    going = {"task_id": task.task_id, "causes": ["planner.plan_ok"], "enough_information": True, "answer": "On it."}
    present(going, running, started)
    assert going == {"task_id": task.task_id, "causes": ["planner.plan_ok"], "enough_information": True,
                     "answer": "On it.", "running": True}
    for result in ({"task_id": task.task_id, "causes": ["navigation.blocked"], "answer": "A cause."},
                   {"task_id": task.task_id, "causes": [], "contact": [{}], "answer": "A hole."}):
        kept = dict(result)
        present(result, running, started)  # a cause, or contact's note, already says what happened
        assert result == kept
    derived = {"task_id": task.task_id, "causes": [], "enough_information": False, "answer": "?"}
    present(derived, [replace(running[0], derived=True)], started)  # a Nav2 goal's: nobody's request
    assert derived["answer"].startswith("I'm still working on it: I'm at step 1 of 4 (to go to the kitchen)")
    ended = dict(unknown, answer="Told.")
    present(ended, session.context.log.tasks, started)
    assert ended["answer"] == "Told."


def test_no_task_yet_quotes_the_last_error_heard(suite: Path) -> None:
    from hexar.events.reader import read_recording

    log = read_recording(suite / "bagfile_5_1")
    assert no_task_yet([]) == ("I haven't had a task since I started listening, so there is nothing I did that I "
                               "can explain yet.")
    last = max((ln for ln in log.logs if ln.level >= 40), key=lambda ln: ln.t)
    said = no_task_yet(log.logs)
    assert said.startswith("I haven't had a task since I started listening")
    assert f" The last error I heard came from {last.speaker} at " in said and said.endswith('".')


@NO_DDS  # reads the TTS topic through the listener's cyclonedds endpoint
def test_questions_before_and_during_a_task_get_spoken_answers(suite: Path, transport: str) -> None:
    """Asked before the robot had any task, the node answers aloud that there is nothing to explain yet (the
    developer's reason kept in "error"); asked while the robot drives to the kitchen, it says it is still at
    that step rather than "I don't have enough information", and no live answer says "the recording"."""
    from hexar.live.speech import TopicSpeaker
    from hexar.live.topics import TTS_QOS

    domain = fresh_domain()
    listener = Listener(domain)
    said = listener.endpoint.reader(TTS_TOPIC, c.STRING_TYPE, TTS_QOS)
    proc = None
    try:
        with live_node(domain, transport=transport, tts_topic=TTS_TOPIC) as node:
            node.speakers.append(TopicSpeaker(node.transport, TTS_TOPIC))
            # what the node says before its TTS writer has matched this reader is lost (volatile, as a robot's TTS
            # topic is); across vendors the writer's side can match a moment after the reader's
            deadline = time.monotonic() + 30
            while not said.get_matched_publications() and time.monotonic() < deadline:
                time.sleep(0.02)
            time.sleep(0.5)
            listener.ask("Why did you stop?")
            before = listener.wait_answers(1, "question", timeout=15.0)[0]
            proc = replay_process(suite / "bagfile_5_1", domain, 1.0, transport=other(transport))
            deadline = time.monotonic() + 60
            while not node.log.stats()["tasks"] and time.monotonic() < deadline:
                time.sleep(0.05)
            time.sleep(1.5)
            listener.ask("Why did you stop?")
            during = listener.wait_answers(2, "question", timeout=15.0)[1]
            listener.ask("tell me a joke")
            joke = listener.wait_answers(3, "question", timeout=15.0)[2]
            listener.ask("thank you")
            thanks = listener.wait_answers(4, "question", timeout=15.0)[3]
            time.sleep(0.3)
            spoken = [str(s.data) for s in said.take(20) if s.sample_info.valid_data]
    finally:
        if proc is not None:
            proc.kill()
            proc.communicate()
        listener.close()
    assert before["answer"].startswith("I haven't had a task since I started listening")
    assert before["error"].startswith("no task to explain") and before["no_task"] is True
    assert during["answer"].startswith('I\'m still working on your request "Bring me a coffee from the kitchen": '
                                       "I'm at step 1 of 4 (to go to the kitchen), for ")
    assert during["causes"] == [] and during["running"] is True
    assert not RECORDING.search(during["answer"]) and not RECORDING.search(before["answer"])
    assert any(s.startswith("I haven't had a task") for s in spoken)
    assert any(s.startswith("I'm still working on your request") for s in spoken)
    # a question about nothing the robot did: refused, and the person hears why rather than silence
    assert joke["intent"] == "offtopic" and "is not about anything I did" in joke["error"]
    assert OFF_TOPIC.split(". ")[0] in " ".join(spoken), spoken
    # thanks: no question, and the person hears a reply, not silence
    assert thanks["intent"] == "smalltalk" and "You're welcome." in spoken, spoken
