"""The arm's fetch recordings (evals/scenarios/arm.py) through the interfaces a person uses: `hexar ask` (the
agent's graph), piped `hexar chat`, and `hexar triage`; each shows the manipulation finding."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest
from rich.console import Console

from hexar.cli import main
from hexar.evals.scenarios.arm import arm_recording_name, simulate_arm_suite
from hexar.fleet.command import TriageOptions, triage_command

HEXAR = str(Path(sys.executable).with_name("hexar"))
PICKED = {("controllers_not_found", 1), ("tolerance", 1), ("out_of_reach", 2), ("nominal", 1)}


@pytest.fixture(scope="module")
def arm_runs(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("arm")
    simulate_arm_suite(out, only=lambda s, v: (s, v) in PICKED)
    return out


def _ask(run: Path, question: str, capsys: pytest.CaptureFixture[str]) -> dict[str, object]:
    assert main(["ask", str(run), question, "--llm", "none", "--json"]) == 0
    return json.loads(capsys.readouterr().out)  # type: ignore[no-any-return]


def test_ask_names_the_arm_cause_through_the_failure_check(arm_runs: Path, capsys: pytest.CaptureFixture[str]) -> None:
    r = _ask(arm_runs / arm_recording_name("controllers_not_found", 1), "Why didn't you bring me the cup?", capsys)
    assert r["causes"] == ["manipulation.controllers_not_found"] and r["explainers"] == ["manipulation"]
    assert r["route"] == "failure_check"
    assert "found no controllers for my arm's joints" in str(r["answer"])


def test_a_failed_pick_after_a_bad_trip_asks_navigation(arm_runs: Path, capsys: pytest.CaptureFixture[str]) -> None:
    r = _ask(arm_runs / arm_recording_name("out_of_reach", 2), "What happened?", capsys)
    assert r["causes"] == ["manipulation.planning_failed", "navigation.poor_localisation"]
    assert "not sure where I was on my map" in str(r["answer"])


@pytest.mark.parametrize(("question", "explainer", "route", "says"), [
    # the arm named in the question's words ("arm", "drop", "pick ... up") decides before the classifier's guess
    ("Why did the arm stop?", "manipulation", "named", "I moved my arm as asked without any problem"),
    ("Was the arm slow?", "manipulation", "named", "I moved my arm as asked without any problem"),
    ("Did you drop anything?", "manipulation", "named", "picking up the cup and putting it down"),
    ("What did the controllers do?", "control", "classifier",
     "My controllers followed the joint trajectory without any problem"),
    ("Why were you so slow?", "navigation", "classifier", "m/s"),
])
def test_without_a_model_the_arms_words_route_to_the_arm(arm_runs: Path, question: str, explainer: str, route: str,
                                                         says: str, capsys: pytest.CaptureFixture[str]) -> None:
    # nothing failed: the no-LLM router reads the question (before, the arm's words went to navigation or the plan)
    r = _ask(arm_runs / arm_recording_name("nominal", 1), question, capsys)
    assert r["route"] == route and r["explainers"] == [explainer]
    assert says in str(r["answer"])


def test_a_fetch_that_was_done_says_so_when_asked_why_it_was_not(arm_runs: Path,
                                                                 capsys: pytest.CaptureFixture[str]) -> None:
    done = arm_runs / arm_recording_name("nominal", 1)
    r = _ask(done, "Why didn't you bring me the cup?", capsys)
    assert str(r["answer"]).startswith("I did all 5 steps of my plan: go to the kitchen, pick up the cup, go to the "
                                       "dining room, ")
    # about the task's goal, all done and nothing wrong: that is the whole answer (a clean drive's speed was added)
    r = _ask(done, "Why didn't you bring me the apple?", capsys)
    assert r["answer"] == ('I did all 5 steps of my plan: go to the kitchen, pick up the cup, go to the dining room, '
                           'put down the cup and then say "Here is your cup."')
    r = _ask(done, "Did you finish?", capsys)  # the task, not the sentence said at its end; a yes-or-no question
    assert str(r["answer"]).startswith("Yes. I did all 5 steps of my plan")
    # about something else than the goal, the finding that answers it stays
    r = _ask(done, "Why didn't you take the shorter way?", capsys)
    assert str(r["answer"]).startswith("I did all 5 steps of my plan") and "m/s" in str(r["answer"])
    # a failed fetch opens with its cause, as before
    r = _ask(arm_runs / arm_recording_name("tolerance", 1), "Why didn't you bring me the cup?", capsys)
    assert "I did all" not in str(r["answer"]) and "tolerance" in str(r["answer"])


def test_piped_chat_answers_and_goes_deeper(arm_runs: Path, tmp_path: Path) -> None:
    env = {**os.environ, "HEXAR_LLM": "none"}
    done = subprocess.run([HEXAR, "chat", str(arm_runs / arm_recording_name("tolerance", 1)), "--llm", "none",
                           "--checkpoints", str(tmp_path / "t.sqlite")], input="Why didn't you bring it?\nwhy?\n",
                          capture_output=True, text=True, env=env, timeout=300, check=False)
    assert done.returncode == 0, done.stderr
    assert "beyond the controller's tolerance" in done.stdout
    deeper = done.stdout.split("you> why?", 1)[1]
    assert "State tolerances failed for joint" in deeper  # "why?" goes to the controller's own recorded lines


def test_triage_counts_the_arm_causes(arm_runs: Path, tmp_path: Path) -> None:
    out = tmp_path / "triage"
    assert triage_command(TriageOptions((str(arm_runs),), out, workers=1, figures=False, progress=False),
                          Console(quiet=True)) == 0
    df = pd.read_parquet(out / "tasks.parquet")
    user = df[~df["recovery"]]
    causes = set(user["cause"])
    assert {"manipulation.controllers_not_found", "control.tolerance_violated",
            "manipulation.planning_failed"} <= causes
    row = user[user["cause"] == "manipulation.controllers_not_found"].iloc[0]
    assert row["failed_skill"] == "pick" and row["explainer"] == "manipulation"
    # the fetch that went fine is a success with nothing worth a look, as a drive that went fine is
    fine = user[user["recording"].str.endswith(arm_recording_name("nominal", 1))]
    assert len(fine) == 1 and fine.iloc[0]["outcome"] == "succeeded" and fine.iloc[0]["kind"] == ""
    report = (out / "report.md").read_text()
    assert "0 succeeded with a finding worth a look" in report
    assert "- **manipulation.controllers_not_found**: 1 task. Example, " in report  # not "1 tasks"
