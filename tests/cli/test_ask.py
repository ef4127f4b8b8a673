"""`hexar ask` in batches: a file of questions and many recordings in one process; a bad line fails only itself."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from hexar.cli import main


def test_a_bad_line_fails_only_itself(suite: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    questions = tmp_path / "q.txt"
    questions.write_text("you didnt bring the coffee why\nasdf qwer zxcv\ncant you drive any faster\n\nhello\n")
    code = main(["ask", str(suite / "bagfile_5_1"), "--questions", str(questions), "--llm", "none", "--json"])
    rows = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert code == 2  # some line was refused
    assert [r["line"] for r in rows] == [1, 2, 3, 5]  # the file's own line numbers: line 4 is blank
    assert [bool(r["error"]) for r in rows] == [False, True, False, True]
    assert rows[1]["question"] == "asdf qwer zxcv" and "ask me" in rows[1]["error"]
    assert all("navigation.blocked_path" in r["causes"] for r in (rows[0], rows[2]))


def test_a_batch_in_text_prints_answers_and_refusals_apart(suite: Path, tmp_path: Path,
                                                           capsys: pytest.CaptureFixture[str]) -> None:
    questions = tmp_path / "q.txt"
    questions.write_text("why did you stop talking\nblorp zzzk\n")
    assert main(["ask", str(suite / "bagfile_19_1"), "--questions", str(questions), "--llm", "none"]) == 2
    captured = capsys.readouterr()
    assert captured.out.splitlines()[0] == "Q: why did you stop talking"
    assert len(captured.out.splitlines()) == 2 and "blorp" not in captured.out
    assert captured.err.startswith("ERROR: bagfile_19_1 line 2:")


def test_all_good_lines_exit_0(suite: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    questions = tmp_path / "q.txt"
    questions.write_text("what happened\nyou didnt move why\n")
    assert main(["ask", str(suite / "bagfile_6_1"), "--questions", str(questions), "--llm", "none", "--json"]) == 0
    assert len(capsys.readouterr().out.splitlines()) == 2


def test_many_recordings_in_one_process(suite: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    runs = tmp_path / "runs"
    runs.mkdir()
    for name in ("bagfile_1_1", "bagfile_6_1", "bagfile_19_1"):
        shutil.copytree(suite / name, runs / name)
    (runs / "bagfile_broken").mkdir()
    (runs / "bagfile_broken" / "metadata.yaml").write_text("not: [a rosbag2")
    code = main(["ask", "--runs", str(runs), "what went wrong", "--llm", "none", "--json"])
    rows = {Path(r["recording"]).name: r for r in map(json.loads, capsys.readouterr().out.splitlines())}
    assert code == 2  # the broken recording
    assert rows["bagfile_broken"]["error"]
    assert rows["bagfile_1_1"]["explainers"] == ["planner"]
    assert rows["bagfile_6_1"]["explainers"] == ["navigation"]
    assert rows["bagfile_19_1"]["explainers"] == ["text_to_speech"]
    # the same, naming the recordings (as a shell expands DIR/*)
    named = [str(suite / "bagfile_1_1"), str(suite / "bagfile_6_1")]
    assert main(["ask", *named, "what went wrong", "--llm", "none"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert [line.split(":")[0] for line in out] == ["bagfile_1_1", "bagfile_6_1"]


def test_no_question_and_no_recording_are_one_line_errors(suite: Path, tmp_path: Path,
                                                          capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["ask", str(suite / "bagfile_5_1")]) == 2
    assert "give a recording, then a question" in capsys.readouterr().err
    assert main(["ask", "--runs", str(tmp_path), "what happened", "--llm", "none"]) == 2
    assert "no recordings in" in capsys.readouterr().err
    assert main(["ask", str(suite / "bagfile_5_1"), "--questions", str(tmp_path / "nope.txt"), "--llm", "none"]) == 2
    assert "--questions: no such file" in capsys.readouterr().err
