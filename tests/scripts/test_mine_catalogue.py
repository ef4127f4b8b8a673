"""scripts/mine_catalogue.py on a small git repository made here: distro branches merged into one entry, rules
giving roles, tests skipped, and bad input a one-line ERROR."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.scripts.helpers import git, load_script, new_repo

CONFIG = """
min_literal: 10
repos:
  - name: someone/robot_nav
    layer: nav2
    branches: {humble: [humble], jazzy: [jazzy], lyrical: [rolling]}
    packages: []
rules:
  - {text: "Failed to make progress", role: symptom}
  - {text: "Transform data too old", role: cause, cause: stack.transform_error}
"""


def _repo(root: Path) -> None:
    repo = new_repo(root / "someone+robot_nav" / "repo", "humble")
    (repo / "pkg" / "src").mkdir(parents=True)
    (repo / "pkg" / "test").mkdir()
    (repo / "pkg" / "src" / "a.cpp").write_text(
        'RCLCPP_ERROR(logger_, "Transform data too old when converting from %s to %s", a, b);\n'
        'RCLCPP_WARN(logger_, "Failed to make progress");\nRCLCPP_ERROR(logger_, "short");\n')
    (repo / "pkg" / "test" / "t.cpp").write_text('RCLCPP_ERROR(logger_, "a test-only message here");\n')
    git(repo, "add", ".")
    git(repo, "commit", "-q", "-m", "humble")
    git(repo, "branch", "jazzy")


def test_mines_branches_into_entries_with_roles(tmp_path: Path) -> None:
    _repo(tmp_path)
    (tmp_path / "sources.yaml").write_text(CONFIG)
    out = tmp_path / "out.json"
    rc = load_script("mine_catalogue").main(["--mirrors", str(tmp_path), "--config", str(tmp_path / "sources.yaml"),
                                             "--out", str(out)])
    assert rc == 0
    data = json.loads(out.read_text())
    assert data["mined"] == ["someone/robot_nav"]
    by_text = {e["text"]: e for e in data["entries"]}
    assert set(by_text) == {"Transform data too old when converting from … to …", "Failed to make progress"}
    tf = by_text["Transform data too old when converting from … to …"]
    assert (tf["role"], tf["cause"], tf["level"], tf["distros"]) == ("cause", "stack.transform_error", "ERROR",
                                                                      ["humble", "jazzy"])
    assert tf["source"] == "pkg/src/a.cpp:1@jazzy" and tf["package"] == "pkg"
    assert by_text["Failed to make progress"]["role"] == "symptom"


def test_no_mirror_is_a_one_line_error(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "sources.yaml").write_text(CONFIG)
    rc = load_script("mine_catalogue").main(["--mirrors", str(tmp_path), "--config", str(tmp_path / "sources.yaml"),
                                             "--out", str(tmp_path / "o.json")])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 1 and err[-1].startswith("ERROR: no repository") and not (tmp_path / "o.json").exists()


def test_a_config_without_repos_is_a_one_line_error(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "sources.yaml").write_text("rules: []\n")
    rc = load_script("mine_catalogue").main(["--mirrors", str(tmp_path), "--config", str(tmp_path / "sources.yaml")])
    assert rc == 1 and capsys.readouterr().err.startswith("ERROR: sources.yaml: a mapping with a `repos` list")
