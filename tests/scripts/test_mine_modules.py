"""scripts/mine_modules.py on a small git repository made here: log macros (printf, stream, throttle), throws and
Python spawner logs become anchored regexes, branches merge into one entry with file:line@branch each, rules
give causes, and a rule that matches nothing stops the miner."""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import pytest
import yaml

from tests.scripts.helpers import commit_files, git, load_script, new_repo

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "mine_modules.py"
CPP_A = """
void f() {
  RCLCPP_ERROR(get_logger(), "Loader for controller '%s' not found.", name.c_str());
  RCLCPP_WARN_STREAM_THROTTLE(logger_, *clock, 1000, "Controller '" << name_ << "' failed with error " << code);
  throw std::runtime_error("Joint '" + joint + "' not found in URDF");
  RCLCPP_INFO(get_logger(), "Loading controller '%s'", name.c_str());
}
"""
CPP_B = """
void f() {
  RCLCPP_ERROR(get_logger(), "Loader for controller '%s' (type '%s') not found.", name.c_str(), t.c_str());
  RCLCPP_WARN_STREAM_THROTTLE(logger_, *clock, 1000, "Controller '" << name_ << "' failed with error " << code);
}
"""
PY = 'def main():\n    logger.error(bcolors.FAIL + f"Failed loading controller {name}" + bcolors.ENDC)\n'


@pytest.fixture
def mirror(tmp_path: Path) -> Path:
    repo = new_repo(tmp_path / "me+ctl" / "repo", "humble")
    (repo / "cm" / "src").mkdir(parents=True)
    (repo / "cm" / "src" / "cm.cpp").write_text(CPP_A)
    (repo / "cm" / "spawner.py").write_text(PY)
    (repo / "cm" / "test").mkdir()
    (repo / "cm" / "test" / "test_cm.cpp").write_text('RCLCPP_ERROR(l, "only in a test %d", 1);')
    git(repo, "add", ".")
    git(repo, "commit", "-qm", "a")
    git(repo, "checkout", "-qb", "jazzy")
    (repo / "cm" / "src" / "cm.cpp").write_text("\n" + CPP_B)
    git(repo, "commit", "-qam", "b")
    return tmp_path


def _config(rules: list[dict[str, Any]]) -> dict[str, Any]:
    return {"distro_of_branch": {"humble": "humble", "jazzy": "jazzy"},
            "modules": {"control": {"out": "x.json", "about": "t", "roles": {}, "rules": rules, "repos": [
                {"name": "ctl", "mirror": "me+ctl", "branches": ["humble", "jazzy"],
                 "skip_paths": "(^|/)test(/|$)", "info_files": r"cm\.cpp"}]}}}


def test_messages_become_anchored_patterns_with_their_sources(mirror: Path) -> None:
    mod = load_script("mine_modules")
    rules = [{"match": "^Loader for controller", "kind": "cause", "cause": "control.controller_load_failed",
              "meaning": "m"}]
    rows = {r["text"]: r for r in mod.classify(mod.collect(_config(rules), mirror, "control"), _config(rules),
                                                "control")}
    assert "only in a test" not in " ".join(rows)
    old, new = rows["Loader for controller '…' not found."], rows["Loader for controller '…' (type '…') not found."]
    assert old["cause"] == new["cause"] == "control.controller_load_failed"
    assert old["distros"] == ["humble"] and new["distros"] == ["jazzy"]
    assert re.search(new["pattern"], "Loader for controller 'jsb' (type 'jsb/JSB') not found.")
    assert not re.search(new["pattern"], "my node says: Loader for controller 'a' (type 'b') not found.")
    both = rows["Controller '…' failed with error"]
    assert both["distros"] == ["humble", "jazzy"] and both["level"] == "WARN"
    assert both["source"] == "ctl/cm/src/cm.cpp:4@humble (5@jazzy)"
    assert "Joint '…' not found in URDF" in rows and rows["Joint '…' not found in URDF"]["level"] == "THROW"
    spawner = rows["Failed loading controller"]
    assert spawner["level"] == "ERROR" and "\\x1b" not in spawner["pattern"]
    assert rows["Loading controller '…'"]["level"] == "INFO"  # INFO only from the configured files


def test_a_rule_that_matches_nothing_stops_the_miner(mirror: Path) -> None:
    mod = load_script("mine_modules")
    cfg = _config([{"match": "^No such line$", "kind": "cause", "cause": "control.nominal", "meaning": "m"}])
    with pytest.raises(SystemExit, match="rules that match no mined line"):
        mod.classify(mod.collect(cfg, mirror, "control"), cfg, "control")


def test_the_committed_catalogues_cite_a_file_line_and_branch_for_every_message() -> None:
    root = SCRIPT.parents[1]
    for path in ("explainers/manipulation/moveit_catalogue.json", "explainers/control/ros2_control_catalogue.json"):
        doc = json.loads((root / path).read_text(encoding="utf-8"))
        assert doc["messages"]
        assert all(re.match(r"[\w/.+-]+:\d+@[\w.]+", m["source"]) for m in doc["messages"])
        assert all(re.compile(m["pattern"]) for m in doc["messages"])


def _mined(tmp_path: Path, name: str, files: dict[str, str], **repo: str) -> dict[str, dict[str, Any]]:
    """The control catalogue's rows, by text, mined from one repository of `files` on branch main."""
    commit_files(new_repo(tmp_path / f"me+{name}" / "repo", "main"), files)
    mod = load_script("mine_modules")
    cfg = {"distro_of_branch": {"main": "rolling"}, "modules": {"control": {"rules": [], "repos": [
        {"name": name, "mirror": f"me+{name}", "branches": ["main"], "skip_paths": "^$", **repo}]}}}
    return {r["text"]: r for r in mod.classify(mod.collect(cfg, tmp_path, "control"), cfg, "control")}


def test_driver_macros_returned_texts_full_stops_and_long_first_sentences(tmp_path: Path) -> None:
    rows = _mined(tmp_path, "drv", {
        "src/driver.cpp":
        'void f() {\n  URCL_LOG_ERROR("Failed to connect to the RTDE server, retrying in %i seconds", t);\n'
        '  RCLCPP_ERROR(l, "The calibration parameters of the connected robot don\'t match the ones from the given "\n'
        '               "kinematics config file. Please be aware that this can lead to critical inaccuracies.");\n'
        '  RCLCPP_ERROR(l, "Loader for controller \'%s\' not found.", n);\n}\n',
        "src/result.cpp": 'std::string r() {\n  return "No motion plan found. No execution attempted.";\n}\n'},
        return_files=r"result\.cpp")
    assert re.search(rows["Failed to connect to the RTDE server, retrying in … seconds"]["pattern"],
                     "Failed to connect to the RTDE server, retrying in 10 seconds")
    calibration = next(r for t, r in rows.items() if t.startswith("The calibration parameters"))
    assert re.search(calibration["pattern"], "The calibration parameters of the connected robot don't match the ones "
                                             "from the given kinematics config file.")
    assert re.search(rows["Loader for controller '…' not found."]["pattern"], "Loader for controller 'cart' not found")
    assert rows["No motion plan found. No execution attempted."]["level"] == "INFO"


def test_a_drivers_lines_carry_the_callbacks_that_log_them_and_their_role(tmp_path: Path) -> None:
    # shaped as ros2_robotiq_gripper's robotiq_driver/src/hardware_interface.cpp@main (on_init checks the joint's
    # interfaces, on_configure opens the serial port) and a plain node of the same repository
    commit_files(new_repo(tmp_path / "me+grip" / "repo", "main"), {
        "src/hw.hpp": "class RobotiqGripperHardwareInterface : public hardware_interface::SystemInterface {};\n",
        "src/hw.cpp":
        "CallbackReturn RobotiqGripperHardwareInterface::on_init(const HardwareInfo& info) {\n"
        '  RCLCPP_FATAL(kLogger, "Joint \'%s\' has %zu command interfaces found. 1 expected.", n, s);\n}\n'
        "CallbackReturn RobotiqGripperHardwareInterface::on_configure(const State& s) {\n"
        '  RCLCPP_ERROR(kLogger, "Cannot connect to the Robotiq gripper");\n}\n'
        'void Node::spin() {\n  RCLCPP_ERROR(l, "Cannot spin the gripper node");\n}\n'})
    mod = load_script("mine_modules")
    roles = yaml.safe_load((SCRIPT.parent / "modules_mining.yaml").read_text(encoding="utf-8"))
    cfg = {"distro_of_branch": {"main": "rolling"}, "modules": {"control": {
        "rules": [], "hardware_roles": roles["modules"]["control"]["hardware_roles"], "repos": [
            {"name": "grip", "mirror": "me+grip", "branches": ["main"], "skip_paths": "^$"}]}}}
    rows = {r["text"]: r for r in mod.classify(mod.collect(cfg, tmp_path, "control"), cfg, "control")}
    joint = rows["Joint '…' has … command interfaces found. 1 expected."]
    assert joint["functions"] == ["on_init"] and joint["hw_role"] == "configuration"
    connect = rows["Cannot connect to the Robotiq gripper"]
    assert connect["functions"] == ["on_configure"] and connect["hw_role"] == "setup"
    assert "functions" not in rows["Cannot spin the gripper node"]


def test_an_unknown_module_is_a_one_line_error(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    mod = load_script("mine_modules")
    assert mod.main(["--mirror", str(tmp_path), "--module", "navigation"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("ERROR: no module navigation in modules_mining.yaml; use manipulation, control")
    assert "\n" not in err


def test_fmt_format_messages_logged_through_a_percent_s_are_mined_at_that_calls_level(tmp_path: Path) -> None:
    # ros2_control 5.x (controller_manager.cpp@kilted) builds a message with fmt::format(FMT_COMPILE(...)) and logs
    # it with RCLCPP_WARN(get_logger(), "%s", message.c_str()): the "%s" alone holds nothing to recognise a line by
    rows = _mined(tmp_path, "cm", {
        "src/cm.cpp":
        'void f() {\n  message = fmt::format(\n    FMT_COMPILE(\n'
        '      "Unable to activate controller \'{}\' since the "\n'
        '      "command interface \'{}\' is not available."),\n    name, itf);\n'
        '  RCLCPP_WARN(get_logger(), "%s", message.c_str());\n'
        '  auto unused = fmt::format("Never logged {} here", x);\n}\n'})
    row = rows["Unable to activate controller '…' since the command interface '…' is not available."]
    assert row["level"] == "WARN"
    assert re.search(row["pattern"], "Unable to activate controller 'arm_controller' since the command interface "
                                     "'wrist_joint/position' is not available.")
    assert not any(t.startswith("Never logged") for t in rows)
