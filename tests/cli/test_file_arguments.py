"""Every file or folder argument: one `ERROR:` line and exit 2 for a missing, folder, unreadable, binary or
wrongly encoded input, never a traceback; UTF-8 with or without a BOM and UTF-16 with a BOM are read."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from hexar.cli import main
from hexar.errors import InputFileError
from hexar.evals.scenarios.bag import BagBuilder
from hexar.explainers.errors import RegistryConfigError
from hexar.explainers.registry import read_config
from hexar.inputs import output_dir, read_text_arg
from tests.events.helpers import T0, two_skill_task

QUESTIONS = "What happened?\nWhy did it take so long?\n"


@pytest.fixture(scope="module")
def bag(tmp_path_factory: pytest.TempPathFactory) -> Path:
    b = BagBuilder()
    two_skill_task(b, T0, "t1", fail_second=True)
    return b.write(tmp_path_factory.mktemp("rec") / "bag")


def _one_line_error(args: list[str], capsys: pytest.CaptureFixture[str], *words: str) -> str:
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.startswith("ERROR: ") and err.count("\n") == 1 and "Traceback" not in err, err
    for word in words:
        assert word in err
    return err


def _bad_files(tmp: Path) -> dict[str, tuple[Path, str]]:
    binary = tmp / "q.pdf"
    binary.write_bytes(b"%PDF-1.7\n\x00\x01\x02\xff" * 10)
    latin1 = tmp / "q_latin1.txt"
    latin1.write_bytes("Warum hast du es nicht gebracht, Jürgen?".encode("latin-1"))
    folder = tmp / "a_folder"
    folder.mkdir()
    return {"missing": (tmp / "nope.txt", "no such file"), "folder": (folder, "is a folder"),
            "binary": (binary, "binary file"), "latin-1": (latin1, "not UTF-8 text (byte 0xfc at offset 34)")}


@pytest.mark.parametrize("case", ["missing", "folder", "binary", "latin-1"])
def test_questions_file_errors(bag: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str], case: str) -> None:
    path, words = _bad_files(tmp_path)[case]
    _one_line_error(["ask", str(bag), "--questions", str(path), "--llm", "none"], capsys, "--questions", words)


@pytest.mark.skipif(os.geteuid() == 0, reason="root reads any file")
def test_unreadable_questions_file(bag: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "q.txt"
    path.write_text(QUESTIONS)
    path.chmod(0)
    _one_line_error(["ask", str(bag), "--questions", str(path), "--llm", "none"], capsys, "permission denied")


@pytest.mark.parametrize("encoding", ["utf-8", "utf-8-sig", "utf-16"])
def test_questions_in_accepted_encodings(bag: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                         encoding: str) -> None:
    path = tmp_path / "q.txt"
    path.write_bytes(QUESTIONS.encode(encoding))  # utf-16 writes its BOM, as Notepad does
    assert main(["ask", str(bag), "--questions", str(path), "--llm", "none", "--json"]) == 0
    results = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert len(results) == 2 and all(r["answer"] and not r["error"] for r in results)


def test_text_reader_refuses_a_bom_that_lies(tmp_path: Path) -> None:
    path = tmp_path / "q.txt"
    path.write_bytes(b"\xff\xfeW\x00\x00\xd8")  # UTF-16 BOM, then a lone surrogate
    with pytest.raises(InputFileError, match="starts like UTF-16"):
        read_text_arg(path, "--questions")


def test_registry_config_errors(tmp_path: Path) -> None:
    bad = _bad_files(tmp_path)
    for path, words in bad.values():
        with pytest.raises(RegistryConfigError, match=words.split(" (")[0]):
            read_config(path)


@pytest.mark.parametrize("case", ["missing", "folder", "binary"])
def test_wav_argument_errors(bag: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str], case: str) -> None:
    path, words = _bad_files(tmp_path)[case]
    words = {"binary": "not a readable WAV file"}.get(case, words)
    _one_line_error(["listen", str(bag), "--wav", str(path), "--out", str(tmp_path / "out"), "--llm", "none"],
                    capsys, words)


def test_output_folder_that_is_a_file(bag: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    taken = tmp_path / "taken"
    taken.write_text("x")
    for args in (["simulate", "--out", str(taken), "--scenario", "19"],
                 ["eval", "--out", str(taken), "--runs", str(tmp_path), "--scenario", "19", "--no-figures"]):
        _one_line_error(args, capsys, "--out", "folder", str(taken))
    with pytest.raises(InputFileError, match="cannot create folder"):
        output_dir(taken / "sub", "--out")
    assert output_dir(tmp_path / "new" / "deeper", "--out").is_dir()
