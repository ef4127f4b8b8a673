"""`--checkpoints` (hexar chat, listen, web): a folder, a file that is not SQLite, a damaged database or a place
that cannot be written is one `ERROR: --checkpoints: ...` line and exit 2, before any recording is decoded."""

from __future__ import annotations

import os
import sqlite3
import subprocess
import sys
from pathlib import Path

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.cli import main
from hexar.evals.scenarios.bag import BagBuilder
from hexar.inputs import checkpoints_file
from tests.events.helpers import T0, two_skill_task

HEXAR = str(Path(sys.executable).with_name("hexar"))


@pytest.fixture(scope="module")
def bag(tmp_path_factory: pytest.TempPathFactory) -> Path:
    b = BagBuilder()
    two_skill_task(b, T0, "t1", fail_second=True)
    return b.write(tmp_path_factory.mktemp("rec") / "bag")


def _bad(tmp: Path, case: str) -> tuple[Path, str]:
    if case == "folder":
        (tmp / "convs").mkdir()
        return tmp / "convs", "is a folder"
    if case == "binary":
        (tmp / "t.sqlite").write_bytes(bytes(range(256)) * 8)
        return tmp / "t.sqlite", "is not a SQLite database"
    if case == "text":
        (tmp / "t.sqlite").write_text("threads: none yet\n")
        return tmp / "t.sqlite", "is not a SQLite database"
    if case == "damaged":  # a SQLite header over garbage: sqlite3 says only "file is not a database"
        (tmp / "t.sqlite").write_bytes(b"SQLite format 3\x00" + b"\xff" * 4080)
        return tmp / "t.sqlite", "is a damaged SQLite database"
    (tmp / "afile").write_text("x")  # "unwritable": a file where the folder should be (root can write anywhere)
    return tmp / "afile" / "sub" / "t.sqlite", "cannot create"


CASES = ["folder", "binary", "text", "damaged", "unwritable"]


def _one_line(code: int, err: str, *words: str) -> None:
    assert code == 2, err
    assert err.startswith("ERROR: --checkpoints: ") and err.count("\n") == 1 and "internal error" not in err, err
    for word in words:
        assert word in err, err


@pytest.mark.parametrize("case", CASES)
def test_chat_refuses_a_bad_checkpoints_file(bag: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                             case: str) -> None:
    path, words = _bad(tmp_path, case)
    code = main(["chat", str(bag), "--llm", "none", "--checkpoints", str(path)])
    captured = capsys.readouterr()
    _one_line(code, captured.err, words)
    assert "task" not in captured.out  # refused before the recording was decoded and the chat began


@pytest.mark.parametrize("case", CASES)
def test_listen_refuses_a_bad_checkpoints_file(bag: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                               case: str) -> None:
    path, words = _bad(tmp_path, case)
    wav = tmp_path / "q.wav"  # never reached: the conversation file is checked before any audio or model
    code = main(["listen", str(bag), "--wav", str(wav), "--out", str(tmp_path / "answers"),
                 "--checkpoints", str(path)])
    _one_line(code, capsys.readouterr().err, words)


@pytest.mark.parametrize("case", ["folder", "damaged"])
def test_web_refuses_a_bad_checkpoints_file_before_serving(bag: Path, tmp_path: Path, case: str) -> None:
    path, words = _bad(tmp_path, case)
    done = subprocess.run([HEXAR, "web", str(bag.parent), "--llm", "none", "--port", "0", "--checkpoints",
                           str(path)], capture_output=True, text=True, timeout=60,
                          env={**os.environ, "HOME": str(tmp_path)})
    _one_line(done.returncode, done.stderr, words)
    assert "HEXAR web:" not in done.stdout


def test_good_checkpoints_files_are_accepted(bag: Path, tmp_path: Path) -> None:
    used = tmp_path / "used.sqlite"
    session = Session(RunSettings(recording=bag, llm="none"), checkpoints=used)
    session.ask("What happened?", thread="a")
    session._conn.close()
    assert checkpoints_file(used) == used  # a file hexar chat wrote
    with sqlite3.connect(used) as conn:
        assert conn.execute("SELECT count(*) FROM checkpoints").fetchone()[0] > 0
    empty = tmp_path / "empty.sqlite"
    empty.touch()
    assert checkpoints_file(empty) == empty  # SQLite makes an empty file a new database
    fresh = tmp_path / "new" / "deeper" / "t.sqlite"
    assert checkpoints_file(fresh) == fresh and not fresh.exists()  # created later by the session


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes any file")
def test_a_read_only_checkpoints_file(bag: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "t.sqlite"
    path.touch()
    path.chmod(0o400)
    code = main(["chat", str(bag), "--llm", "none", "--checkpoints", str(path)])
    _one_line(code, capsys.readouterr().err, "permission denied")
