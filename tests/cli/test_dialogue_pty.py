"""Whole conversations with `hexar chat` through a pseudo-terminal, each answer checked against the recording:
a first question, two follow-ups, a content question and a task switch, over different scenarios."""

from __future__ import annotations

import os
import re
import sys
from pathlib import Path

import pexpect
import pytest

from hexar.events import read_recording
from hexar.events.log import EventLog

HEXAR = str(Path(sys.executable).with_name("hexar"))
ANSI = re.compile(r"\x1b\[[0-9;?]*[ -/]*[@-~]|\x1b[()][A-Z0-9]|\r")
ROOMS = ("kitchen", "dining room", "living room")
# Model notation a person should never be handed, at any depth: causal queries, LIME dumps, plan call syntax.
JARGON = ("do(", "P(", "P =", "_next ->", "person_std_rms", "LIME", "weights", "input=", "location=", "(ingredient",
          ", present, ", ", absent, ")
# Where an answer says I reached a place: the clause after it names rooms, up to the next clause.
REACHED = re.compile(r"\b(?:I went to|I got to|I reached|I'm in|I arrived (?:in|at))\b(.*)")
CLAUSE_END = re.compile(r"[.;:]| but | because |, and I | and I | for ")


def _spawn(run: Path, db: Path) -> pexpect.spawn:
    env = {**os.environ, "COLUMNS": "200", "TERM": "xterm", "PROMPT_TOOLKIT_NO_CPR": "1", "HOME": str(db.parent)}
    child = pexpect.spawn(HEXAR, ["chat", str(run), "--llm", "none", "--checkpoints", str(db)], env=env,
                          encoding="utf-8", timeout=90, dimensions=(60, 200))
    child.expect("you>")
    return child


def _turn(child: pexpect.spawn, line: str) -> str:
    """Send one line; the text of the answer panel (or of the line printed instead of a panel)."""
    child.sendline(line)
    child.expect(["╰", r"Switched to task[\s\S]*?Ask me about it\.", r"no task [^\n]*\n"])
    raw = ANSI.sub("", (child.before or "") + (child.after or ""))
    child.expect("you>")
    if "╭" in raw:
        body = raw[raw.index("╭"):raw.rindex("╰")]
        lines = [ln.strip().strip("│").strip() for ln in body.splitlines()[1:]]
        return " ".join(ln for ln in lines if ln)
    raw = raw[raw.index("Switched"):] if "Switched" in raw else raw
    return " ".join(ln.strip() for ln in raw.splitlines() if ln.strip() and "you>" not in ln)


def _goals(log: EventLog) -> tuple[set[str], set[str], dict[int, dict[int, str]], set[tuple[float, float]]]:
    """Rooms any plan meant to go to, rooms the robot reached (the step succeeded), each task's step -> room, and
    the coordinates of goals inside skills."""
    planned: set[str] = set()
    reached: set[str] = set()
    steps: dict[int, dict[int, str]] = {}
    for task in log.tasks:
        for run in task.skills:
            loc = run.params.get("location")
            if run.skill == "navigate_to_zone" and isinstance(loc, str):
                planned.add(loc.replace("_", " "))
                if run.state == "succeeded":
                    reached.add(loc.replace("_", " "))
                if run.history:
                    steps.setdefault(task.order, {})[run.index + 1] = loc.replace("_", " ")
    inner = {(float(m.group(1)), float(m.group(2))) for line in log.logs
             if (m := re.match(r"Navigating to the person at \((-?[\d.]+), (-?[\d.]+)\)", line.msg))}
    return planned, reached, steps, inner


def _check(answer: str, log: EventLog, task_order: int) -> None:
    assert answer, "no answer"
    for token in JARGON:
        assert token not in answer, (token, answer)
    planned, reached, steps, inner = _goals(log)
    own_words = re.sub(r'"[^"]*"', "", answer)  # quoted request or log lines are not places I name
    # "I did not go to the X" may name a room no plan had: it is the person's own question, denied
    named = re.sub(r"I did not go to the [a-z ]+", "", own_words)
    for room in ROOMS:
        if f"the {room}" in named and "plan goes to" not in named:
            assert room in planned, (room, answer)
    # A room I say I went to (or am in) must be one the recording shows me reaching.
    for sentence in re.split(r"(?<=[.!?])\s+", own_words):
        for m in REACHED.finditer(sentence):
            clause = CLAUSE_END.split(m.group(1))[0]
            for room in ROOMS:
                if f"the {room}" in clause:
                    assert room in reached, (f"says it reached the {room}", answer)
    for m in re.finditer(r"Step (\d+), going to the ([a-z ]+?):", answer):
        assert steps.get(task_order, {}).get(int(m.group(1))) == m.group(2), (m.group(0), answer)
    for m in re.finditer(r"the person at \((-?[\d.]+), (-?[\d.]+)\)", answer):
        assert (float(m.group(1)), float(m.group(2))) in inner, (m.group(0), answer)
    assert "the kitchen" not in answer.split("approach to")[-1][:40] if "approach to" in answer else True


def test_place_check_catches_a_room_never_reached(suite: Path) -> None:
    """The check itself: bagfile_5_1 never reached the kitchen or the living room, so saying so must fail it."""
    log = read_recording(suite / "bagfile_5_1")
    _check("I tried to go to the kitchen but didn't get there, and I never set off for the living room.", log, 1)
    for wrong in ("I went to the living room because step 3 of my plan was to go there.",
                  "I didn't go there; I went to the kitchen and the living room, because my plan was to go there."):
        with pytest.raises(AssertionError):
            _check(wrong, log, 1)


# (recording, first question, what the first answer must say, content question, what it must say)
CONVERSATIONS = [
    ("bagfile_5_1", "Why didn't you bring me the coffee?", r"blocked", "Why did you go to the living room?",
     r"^I did not go to the living room: step 3 of my plan"),
    ("bagfile_6_1", "What happened?", r"joystick", "Where are you now?", r"kitchen, but I didn't get there"),
    ("bagfile_7_2", "Why didn't you move?", r"charg", "What did you say?", r"Sorry, I could not complete"),
    ("bagfile_11_1", "What happened when you asked for help?", r"did not detect", "Where are you now?",
     r"living room"),
    ("bagfile_14_1", "What happened?", r"couldn't reach the person", "Why did you go to the kitchen?",
     r"step 1 of my plan for your request"),
    ("bagfile_17_1", "Why did you stop so awkwardly when you went to get the coffee?", r"approach",
     "Where are you now?", r"in the living room"),
    ("bagfile_19_2", "What happened?", r"20-second limit", "Did you read me the right recipe?",
     r"No\. What I said did not match your request.*lasagne"),
    ("bagfile_10_3", "What happened?", r"reached|took me longer|kept moving", "What did you say?",
     r"Maria, dinner is at eight\.\", which is what you asked for"),
    ("bagfile_3_1", "Why did you do something different from what I asked?", r"plan did not match",
     "Why did you go to the dining room?", r"dining room because step 1"),
    ("bagfile_20_1", "Why did you recommend that pizza?", r"Margherita", "What did you say?",
     r"I recommend a Margherita"),
    ("bagfile_1_1", "What happened?", r"navigate_to_room", "Where are you now?", r"didn't drive anywhere|living room"),
]


# Conversations that ask "why?" a second time in a row, and what that depth-2 answer says in plain words.
DEPTH_TWO = {
    "bagfile_20_1": r"What weighed most for a Margherita: that you have basil \(strongly\)",
    "bagfile_3_1": r"My plan was to go to the dining room",
    "bagfile_14_1": r"the smallest one that makes success most likely",
}
# After the task switch: what to ask about the other task, and what its depth-2 answer says.
SWITCH_ASKS = {"bagfile_5_1": ("What was your plan?",
                              r"^Step 1, to say \"Sorry, I could not complete the task\.\": done\.")}


@pytest.mark.parametrize(("name", "first", "first_says", "content", "content_says"), CONVERSATIONS,
                         ids=[c[0] for c in CONVERSATIONS])
def test_conversation(suite: Path, tmp_path: Path, name: str, first: str, first_says: str, content: str,
                      content_says: str) -> None:
    run = suite / name
    log = read_recording(run)
    latest = log.task().order
    child = _spawn(run, tmp_path / "threads.sqlite")

    answer = _turn(child, first)
    _check(answer, log, latest)
    assert re.search(first_says, answer, re.I), answer

    deeper = _turn(child, "why?")
    _check(deeper, log, latest)
    assert deeper != answer
    if name in DEPTH_TWO:
        deepest = _turn(child, "why?")
        _check(deepest, log, latest)
        assert re.search(DEPTH_TWO[name], deepest), deepest

    walked: list[str] = []
    while len(walked) < 8 and not (walked and walked[-1].startswith("Nothing else happened")):
        walked.append(_turn(child, "what else happened?"))
        _check(walked[-1], log, latest)
    assert len(set(walked)) >= 2 or walked[0].startswith("Nothing else happened")
    assert any(w.startswith("Nothing else happened") for w in walked), walked  # the walk ends, and says so

    said = _turn(child, content)
    _check(said, log, latest)
    assert re.search(content_says, said), said

    helped = _turn(child, "what would have helped?")
    _check(helped, log, latest)

    others = [t for t in log.tasks if t.order != latest]
    if others:
        other = others[-1]
        switched = _turn(child, f"/task {other.order}")
        assert switched.startswith(f"Switched to task {other.order}:"), switched
        assert "recovery" in switched if other.is_recovery else other.instruction in switched
        question, depth_two = SWITCH_ASKS.get(name, ("What happened?", None))
        after = _turn(child, question)
        _check(after, log, other.order)
        assert 'plan for ""' not in after
        if depth_two is not None:
            _check(_turn(child, "why?"), log, other.order)
            deepest = _turn(child, "why?")
            _check(deepest, log, other.order)
            assert re.search(depth_two, deepest), deepest
    child.sendeof()
    child.expect(pexpect.EOF)


def test_piped_questions_read_cleanly(suite: Path, tmp_path: Path) -> None:
    """Questions piped into chat: one prompt per question, no terminal warning, every answer printed."""
    import subprocess

    questions = "What happened?\nwhat else happened?\n/task 2\nWhat happened?\n"
    env = {**os.environ, "COLUMNS": "120", "HOME": str(tmp_path)}
    done = subprocess.run([HEXAR, "chat", str(suite / "bagfile_14_1"), "--llm", "none", "--checkpoints",
                           str(tmp_path / "t.sqlite")], input=questions, capture_output=True, text=True, env=env,
                          timeout=120, check=False)
    assert done.returncode == 0, done.stderr
    out = done.stdout
    assert out.count("you> ") == 4
    assert "not a terminal" not in out + done.stderr
    assert "Switched to task 2: my own recovery task after task 1 failed" in out
    assert "Step 1, going to the kitchen" in out
