"""`hexar eval --suite real-nav2|real-modules --cases FILE`: a user's own excerpts (an owner's held-out set) graded
exactly as the suite's data, and every way such a file can be wrong as one ERROR line."""

from __future__ import annotations

import json
import shutil
from importlib import resources
from pathlib import Path
from typing import Any

import pytest

from hexar.cli import main

DATA = resources.files("hexar.evals").joinpath("data")


def copy_of(folder: str, name: str, tmp_path: Path) -> Path:
    target = tmp_path / f"my-{name}"
    with resources.as_file(DATA.joinpath(folder, name)) as source:
        shutil.copyfile(source, target)
    return target


def answers(out: Path) -> dict[str, tuple[str, str]]:
    report: dict[str, Any] = json.loads((out / "report.json").read_text(encoding="utf-8"))
    return {e["id"]: (e["text"]["verdict"], e["answer"] or e["error"]) for e in report["excerpts"]}


@pytest.mark.parametrize("suite, folder, name, same", [
    ("real-nav2", "real_nav2", "blind12.yaml", "real-nav2-blind12"),
    ("real-modules", "real_modules", "heldout15.yaml", "real-modules-heldout15"),
])
def test_a_users_file_is_graded_as_the_same_excerpts_in_a_suite(suite: str, folder: str, name: str, same: str,
                                                                 tmp_path: Path) -> None:
    cases = copy_of(folder, name, tmp_path)
    assert main(["eval", "--suite", suite, "--cases", str(cases), "--out", str(tmp_path / "mine")]) == 0
    assert main(["eval", "--suite", same, "--out", str(tmp_path / "ours")]) == 0
    mine = answers(tmp_path / "mine")
    assert mine == answers(tmp_path / "ours") and len(mine) >= 2
    report = json.loads((tmp_path / "mine" / "report.json").read_text(encoding="utf-8"))
    assert report["data"] == str(cases) and report["cases"] is True and report["suite"] == suite
    # the table says where the excerpts came from: the user's file, not a data file of the suite
    assert f"({cases})" in (tmp_path / "mine" / "results.md").read_text(encoding="utf-8")


def test_a_users_nav_file_can_be_its_own_baseline(tmp_path: Path) -> None:
    cases = copy_of("real_nav2", "blind13.yaml", tmp_path)
    base = tmp_path / "base.json"
    args = ["eval", "--suite", "real-nav2", "--cases", str(cases)]
    assert main([*args, "--out", str(tmp_path / "a"), "--write-baseline", str(base)]) == 0
    assert main([*args, "--out", str(tmp_path / "b"), "--baseline", str(base)]) == 0


def _write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "cases.yaml"
    path.write_text(text, encoding="utf-8")
    return path


NAV_ENTRY = ("- {id: a, source: s, url: u, distro: humble, outcome: failed, cause: navigation.no_progress, "
             "cause_quote: q, logs_show_cause: false, lines: '[controller_server]: Failed to make progress'}\n")


@pytest.mark.parametrize("suite, make, message", [
    ("real-nav2", lambda p: p / "missing.yaml", "ERROR: cannot read --cases "),
    ("real-nav2", lambda p: p, "ERROR: --cases must be a YAML file, not a folder: "),
    ("real-nav2", lambda p: _write(p, "a: [b\n  c: d"), "is not valid YAML: while parsing a flow sequence"),
    ("real-nav2", lambda p: _write(p, ""), "must be a non-empty list of excerpts"),
    ("real-nav2", lambda p: _write(p, NAV_ENTRY * 2), "duplicate ids in "),
    ("real-nav2", lambda p: _write(p, NAV_ENTRY.replace("navigation.no_progress", "navigation.gremlins")),
     "unknown cause 'navigation.gremlins'"),
    # a Nav2 file given to the module harness: its entries lack the module each excerpt belongs to
    ("real-modules", lambda p: _write(p, NAV_ENTRY), "entry 'a' lacks module"),
    ("real-nav2-blind3", lambda p: _write(p, NAV_ENTRY), "--cases goes with --suite real-nav2 or --suite "
     "real-modules (the file's format), not --suite real-nav2-blind3"),
    ("real-modules-heldout2", lambda p: _write(p, NAV_ENTRY), "not --suite real-modules-heldout2"),
    ("paper", lambda p: _write(p, NAV_ENTRY), "--cases goes with --suite real-nav2 or --suite real-modules, not the "
     "paper's suite"),
])
def test_a_bad_cases_file_is_one_error_line(suite: str, make: Any, message: str, tmp_path: Path,
                                            capsys: pytest.CaptureFixture[str]) -> None:
    cases = make(tmp_path)
    assert main(["eval", "--suite", suite, "--cases", str(cases), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr()
    said = (err.out + err.err).strip().splitlines()
    assert len(said) == 1 and said[0].startswith("ERROR: ") and message in said[0]
    assert not (tmp_path / "o").exists()
