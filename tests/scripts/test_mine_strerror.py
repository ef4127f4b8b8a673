"""scripts/mine_strerror.py on a small git repository made here in glibc's layout: the texts of
sysdeps/gnu/errlist.h become the committed catalogue's entries with file:line@commit, and a missing errno stops the
miner with a one-line error."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.scripts.helpers import git, load_script

COMMITTED = Path(__file__).resolve().parents[2] / "explainers" / "stack" / "strerror.json"


def _glibc(tmp_path: Path, errnos: list[dict[str, str]]) -> Path:
    """A repository whose errlist.h holds the committed texts, each in glibc's `_S(E…, N_("…"))` form."""
    repo = tmp_path / "glibc"
    (repo / "sysdeps" / "gnu").mkdir(parents=True)
    body = ["_S(0, N_(\"Success\"))"]
    for e in errnos:
        body += [f"#ifdef {e['errno']}", f"_S({e['errno']}, N_(\"{e['text']}\"))", "#endif"]
    (repo / "sysdeps" / "gnu" / "errlist.h").write_text("\n".join(body) + "\n", encoding="utf-8")
    for args in (["init", "-q"], ["add", "."], ["-c", "user.email=t@t", "-c", "user.name=t", "commit", "-qm", "x"]):
        git(repo, *args)
    return repo


def test_the_mined_texts_and_lines_come_from_errlist(tmp_path: Path) -> None:
    committed = json.loads(COMMITTED.read_text(encoding="utf-8"))["errnos"]
    mined = load_script("mine_strerror").mine(_glibc(tmp_path, committed))
    assert [(e["errno"], e["text"], e["cause"]) for e in mined["errnos"]] == \
           [(e["errno"], e["text"], e["cause"]) for e in committed]
    first = mined["errnos"][0]
    assert first["source"] == f"glibc/sysdeps/gnu/errlist.h:3@{mined['commit'][:12]}"  # line 3 of the file above
    # the number a driver may print alone: Linux's (asm-generic errno-base.h), EACCES first
    assert (first["errno"], first["number"]) == ("EACCES", 13)
    assert [e["number"] for e in mined["errnos"]] == [e["number"] for e in committed]


def test_an_errno_missing_from_errlist_stops_the_miner(tmp_path: Path) -> None:
    committed = json.loads(COMMITTED.read_text(encoding="utf-8"))["errnos"]
    repo = _glibc(tmp_path, [e for e in committed if e["errno"] != "EACCES"])
    with pytest.raises(SystemExit, match=r"ERROR: .* has no text for EACCES"):
        load_script("mine_strerror").mine(repo)
