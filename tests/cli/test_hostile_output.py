"""Recorded text is shown, never obeyed: escape sequences, control characters and rich markup from a recording
reach no terminal raw in any command; JSON stays exact and strict."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from rich.console import Console

from hexar.cli import main
from hexar.cli_guard import out
from hexar.evals import audit
from hexar.evals.cases import scenario
from hexar.evals.scenarios.bag import TYPESTORE, BagBuilder
from hexar.evals.scenarios.suite import record
from hexar.events import contract as c
from hexar.safe_text import json_dumps, safe, visible
from tests.events.helpers import T0, task_msg
from tests.fuzz.harness import _bad_char, _strict

CLIPBOARD = "\x1b]52;c;ZWNobyBwd25lZA==\x07"  # OSC 52: writes the user's clipboard
TITLE = "\x1b]0;pwned\x07"
RED = "\x1b[31m"
HOSTILE = f"{RED}{TITLE}{CLIPBOARD}[/] [bold]\u202e"
_T = TYPESTORE.types


@pytest.fixture(scope="module")
def hostile(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Scenario 5 (a blocked path) with escape sequences and markup in its log lines, instruction and skills."""
    b = record(scenario(5), 1)
    for i, (t, topic, typ, m) in enumerate(b.messages):
        if typ == c.LOG_TYPE:
            m = _T[c.LOG_TYPE](stamp=m.stamp, level=m.level, name=m.name, msg=m.msg + HOSTILE, file=m.file,
                               function=m.function, line=m.line)
        elif topic == c.TASK_INFO:
            obj = json.loads(m.data)
            if obj["instruction"]:  # an empty one marks the robot's own recovery task
                obj["instruction"] += HOSTILE
            for step in obj["skill_sequence"]:
                if step.get("error_msg"):
                    step["error_msg"] += HOSTILE
            m = _T[c.STRING_TYPE](data=json.dumps(obj))
        b.messages[i] = (t, topic, typ, m)
    folder = tmp_path_factory.mktemp("hostile")
    b.write(folder / "bagfile_hostile")
    return folder


@pytest.fixture(autouse=True)
def _wide(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("COLUMNS", "1000")  # rich wraps table cells at the terminal width
    # the CLI's console read COLUMNS once, when it was made: pytest-xdist's workers had set it to 80 by then
    monkeypatch.setattr(out, "width", 1000)


def _run(args: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    code = main(args)
    cap = capsys.readouterr()
    assert _bad_char(cap.out + cap.err) is None, "a raw control character reached the terminal"
    return code, cap.out, cap.err


def test_safe_shows_controls_and_escapes_markup() -> None:
    assert visible(HOSTILE) == "\\x1b[31m\\x1b]0;pwned\\x07\\x1b]52;c;ZWNobyBwd25lZA==\\x07[/] [bold]\\u202e"
    assert visible("two\nlines") == "two\\nlines" and visible("two\nlines", keep_newlines=True) == "two\nlines"
    console = Console(record=True, width=200)
    console.print(safe(HOSTILE))
    assert console.export_text().strip() == visible(HOSTILE)  # markup printed literally, nothing styled
    assert visible("\ud800\U000e0041") == "\\ud800\\U000e0041"


def test_json_dumps_is_strict_and_says_what_it_replaced() -> None:
    out = _strict(json_dumps({"a": [1.0, float("nan")], "b": {"c": float("-inf")}, "warnings": ["w"]}))
    assert out["a"] == [1.0, None] and out["b"]["c"] is None
    assert out["warnings"][0] == "w" and any("a[1] was nan" in w for w in out["warnings"])
    assert _strict(json_dumps([{"x": float("inf")}]))[0]["warnings"]


def test_inspect_table_shows_escapes_visibly(hostile: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = _run(["inspect", str(hostile / "bagfile_hostile")], capsys)
    assert code == 0
    assert "\\x1b]52;c;" in out.replace("\n", "") and "[/]" in out


def test_inspect_json_is_strict_and_exact(hostile: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = _run(["inspect", str(hostile / "bagfile_hostile"), "--json"], capsys)
    assert code == 0 and _strict(out)["tasks"][0]["instruction"].endswith(HOSTILE)  # JSON keeps the exact text


def test_nan_and_infinity_from_task_info_become_null(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    b = BagBuilder()
    skills = [("navigate_to_zone", {"location": "kitchen", "speed": float("nan"), "limit": float("inf")},
               "Running", "")]
    b.task_info(T0, task_msg("t1", "go to the kitchen", skills))
    code, out, _ = _run(["inspect", str(b.write(tmp_path / "bag")), "--json"], capsys)
    data = _strict(out)
    assert code == 0 and data["tasks"][0]["skills"][0]["params"] == {"location": "kitchen", "speed": None,
                                                                      "limit": None}
    assert any("non-finite number replaced by null" in w and "speed" in w for w in data["warnings"])


def test_runs_lists_a_recording_with_markup(hostile: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = _run(["runs", str(hostile)], capsys)
    assert code == 0 and not err and "bagfile_hostile" in out and "[/]" in out
    code, out, _ = _run(["runs", str(hostile), "--json"], capsys)
    assert code == 0 and _strict(out)[0]["instruction"].endswith(HOSTILE)


def test_ask_verbose_evidence_is_shown_not_obeyed(hostile: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = _run(["ask", str(hostile / "bagfile_hostile"), "What happened?", "--llm", "none", "-v"], capsys)
    assert code == 0 and "blocked" in out
    assert "\\x1b]52;c;" in out.replace("\n", "")


def test_ask_json_keeps_the_recorded_bytes(hostile: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = _run(["ask", str(hostile / "bagfile_hostile"), "What happened?", "--llm", "none", "--json"],
                        capsys)
    result = _strict(out)
    assert code == 0 and result["causes"]
    assert any(ev["item"].endswith(HOSTILE) for ev in result["evidence"] if ev["topic"] == c.ROSOUT)


def test_ask_batch_prints_visible_text(hostile: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    questions = tmp_path / "q.txt"
    questions.write_text(f"What happened?\nwhy {CLIPBOARD}?\n", encoding="utf-8")
    code, out, err = _run(["ask", str(hostile / "bagfile_hostile"), "--questions", str(questions), "--llm", "none"],
                          capsys)
    assert code == 2 and "blocked" in out  # the second line is no question: exit 2, refused on stderr
    assert err.startswith("ERROR: bagfile_hostile line 2:")
    code, out, _ = _run(["ask", str(hostile / "bagfile_hostile"), "--questions", str(questions), "--llm", "none",
                         "--json"], capsys)
    assert [bool(_strict(line)["error"]) for line in out.splitlines()] == [False, True]


def test_error_lines_quote_recorded_text_visibly(hostile: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = _run(["ask", str(hostile / "bagfile_hostile"), "What happened?", "--llm", "none",
                         "--task", f"nope{RED}"], capsys)
    assert code == 2 and err.startswith("ERROR: ") and err.count("\n") == 1 and "\\x1b[31m" in err


def test_eval_audit_shows_answers_visibly() -> None:
    res = {"answer": f"I stopped. {HOSTILE}", "error": "", "explainers": ["navigation"],
           "grades": {"root_cause": True, "incorrect_facts": False, "accuracy": True, "selection": True,
                      "claims": ["navigation.blocked"], "false_claims": []}}
    report = {"methods": ["hexar"], "cases": [{"id": "s5v1q1", "question": f"why{RED}?",
                                                "truth": {"root_cause": "blocked", "cause": "navigation.blocked"},
                                                "results": {"hexar": res}}]}
    console = Console(record=True, width=300, force_terminal=False)
    audit.show(report, 1, console)
    text = console.export_text()
    assert _bad_char(text) is None and "\\x1b]52" in text.replace("\n", "").replace(" ", "")
    md = audit.markdown(report, 1)
    assert _bad_char(md) is None and "\\x1b]52;c;" in md
