"""Questions as people type and say them are taken and routed right; only what carries no question is refused."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import yaml

from hexar.agent.errors import BadQuestionError
from hexar.agent.questions import check_question, normalise
from hexar.cli import main
from hexar.evals.cases import cases

DATA = yaml.safe_load((Path(__file__).parent / "data" / "question_phrasings.yaml").read_text(encoding="utf-8"))
ACCEPTED: list[list[str]] = DATA["accepted"]
REFUSED: list[str] = DATA["refused"]


def test_the_data_is_new_and_large_enough() -> None:
    eval_questions = {c.question.lower().rstrip("?") for c in cases()}
    assert len(ACCEPTED) >= 40 and len(REFUSED) >= 20
    assert not {q.lower().rstrip("?") for q, _, _ in ACCEPTED} & eval_questions


@pytest.mark.parametrize(("question", "recording", "explainer"), ACCEPTED, ids=[a[0] for a in ACCEPTED])
def test_phrasing_is_accepted_and_routed_right(suite: Path, capsys: pytest.CaptureFixture[str], question: str,
                                               recording: str, explainer: str) -> None:
    code = main(["ask", str(suite / f"bagfile_{recording}"), question, "--llm", "none", "--json"])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    result = json.loads(captured.out)
    assert result["error"] == "" and result["explainers"] == [explainer], (question, result["route"])
    assert result["answer"] and "enough information" not in result["answer"]


@pytest.mark.parametrize("text", REFUSED)
def test_non_question_is_refused_with_a_line_saying_what_works(suite: Path, capsys: pytest.CaptureFixture[str],
                                                               text: str) -> None:
    code = main(["ask", str(suite / "bagfile_5_1"), text, "--llm", "none"])
    captured = capsys.readouterr()
    assert code == 2 and captured.out == ""
    err = captured.err.strip()
    assert err.startswith("ERROR:") and "\n" not in err
    assert "ask me" in err and "e.g. \"Why didn't you bring me the coffee?\"" in err


def test_the_eval_questions_pass_unchanged() -> None:
    for q in {c.question for c in cases()}:
        assert check_question(q) == q


@pytest.mark.parametrize(("heard", "meant"), [
    ("you didnt do anything why", "you didn't do anything why"),
    ("um, why did u stop", "why did you stop"),
    ("uh y cant you go faster", "why can't you go faster"),
    ("[BLANK_AUDIO] whats wrong", "what's wrong"),
    ("what could of helped", "what could have helped"),
    ("Why didn't you bring me the coffee?", "Why didn't you bring me the coffee?"),
])
def test_normalise_spells_out_slips_and_drops_fillers(heard: str, meant: str) -> None:
    assert normalise(heard) == meant


def test_a_typo_is_not_gibberish() -> None:
    assert check_question("why didnt you bring the cofee") == "why didn't you bring the cofee"
    with pytest.raises(BadQuestionError, match="I don't understand"):
        check_question("qzx vbnm why")
