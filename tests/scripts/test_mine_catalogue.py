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


MIDDLEWARE = """
min_literal: 10
repos:
  - name: someone/dds
    layer: fastdds
    branches: {main: [rolling]}
    packages: [src/cpp]
    exclude: [src/cpp/vendored.c]
    wrappers: {EPROSIMA_LOG_ERROR: ERROR, GVERROR: ERROR}
  - name: someone/rclpy
    layer: rclpy
    branches: {main: [rolling]}
    packages: []
rules:
  - {text: "Calculated port number is too high", role: cause, cause: stack.network}
"""


def test_mines_a_dds_libraries_stream_and_printf_helpers_and_python_exception_classes(tmp_path: Path) -> None:
    # Fast DDS's EPROSIMA_LOG_ERROR(CATEGORY, "text" << value) and Cyclone's `GVERROR ("fmt", ...)` (a space before
    # the parenthesis), with a vendored file left out; rclpy's exception classes word their text in __init__
    dds = new_repo(tmp_path / "someone+dds" / "repo", "main")
    (dds / "src" / "cpp").mkdir(parents=True)
    (dds / "src" / "cpp" / "net.cpp").write_text(
        'EPROSIMA_LOG_ERROR(RTPS, "Calculated port number is too high. Probably the domainId is over 232 or "\n'
        '    << "portBase is too high.");\n'
        'EPROSIMA_LOG_ERROR(XMLPARSER, "Error opening \'" << filename << "\'");\n'
        'GVERROR ("%s: does not match an available interface.\\n", name);\n')
    (dds / "src" / "cpp" / "vendored.c").write_text('EPROSIMA_LOG_ERROR(X, "a vendored file is never read");\n')
    git(dds, "add", ".")
    git(dds, "commit", "-q", "-m", "main")
    py = new_repo(tmp_path / "someone+rclpy" / "repo", "main")
    (py / "rclpy").mkdir()
    (py / "rclpy" / "exceptions.py").write_text(
        "class InvalidParameterTypeException(ParameterException):\n"
        "    def __init__(self, p, expected):\n"
        "        ParameterException.__init__(\n"
        "            self,\n"
        "            f\"Trying to set parameter '{p._name}' to '{p._value}'\"\n"
        "            f\", expecting type '{expected}'\",\n"
        "            p.name)\n")
    git(py, "add", ".")
    git(py, "commit", "-q", "-m", "main")
    (tmp_path / "sources.yaml").write_text(MIDDLEWARE)
    out = tmp_path / "out.json"
    assert load_script("mine_catalogue").main(["--mirrors", str(tmp_path), "--config", str(tmp_path / "sources.yaml"),
                                               "--out", str(out)]) == 0
    by_text = {e["text"]: e for e in json.loads(out.read_text())["entries"]}
    assert set(by_text) == {
        "Calculated port number is too high. Probably the domainId is over 232 or portBase is too high.",
        "Error opening '…'", "…: does not match an available interface.",
        "Trying to set parameter '…' to '…', expecting type '…'"}
    port = by_text["Calculated port number is too high. Probably the domainId is over 232 or portBase is too high."]
    assert (port["cause"], port["source"]) == ("stack.network", "src/cpp/net.cpp:1@main")
    assert by_text["Trying to set parameter '…' to '…', expecting type '…'"]["form"] == "throw"
