"""`hexar simulate`, `hexar runs` and `hexar inspect` as a user runs them."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from hexar.cli import main


def test_simulate_one_scenario_in_mcap_and_inspect_it(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["simulate", "--out", str(tmp_path), "--storage", "mcap", "--scenario", "19"]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bagfile_19_1", "bagfile_19_2", "bagfile_19_3"]
    assert any(p.suffix == ".mcap" for p in (tmp_path / "bagfile_19_1").iterdir())
    capsys.readouterr()
    assert main(["inspect", str(tmp_path / "bagfile_19_1"), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["storage"] == "mcap"
    first = data["tasks"][0]
    assert first["outcome"] == "failed" and first["instruction"].startswith("Go to the kitchen and tell Maria")
    say = first["skills"][-1]
    assert say["skill"] == "say" and say["status"] == "failed" and say["error_msg"] == "The skill has timed out"
    assert [h["status"].lower() for h in say["history"]] == ["waiting", "running", "failed"]
    assert data["tasks"][1]["recovery"] is True
    topics = {t["topic"]: t["count"] for t in data["topics"]}
    assert topics["/skills/say/events"] >= 2 and topics["/task_info"] >= 5


def test_inspect_renders_a_timeline(suite: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["inspect", str(suite / "bagfile_1_1")]) == 0
    out = capsys.readouterr().out
    assert "invalid plan: Skill navigate_to_room is not a valid skill." in out
    assert "Bring me a coffee from the kitchen" in out and "/rosout" in out


def test_runs_lists_outcomes(suite: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["runs", str(suite), "--json"]) == 0
    rows = {r["recording"]: r for r in json.loads(capsys.readouterr().out)}
    assert len(rows) == 60
    assert rows["bagfile_5_1"]["outcome"] == "failed"
    assert rows["bagfile_2_1"]["outcome"] == "invalid"
    assert rows["bagfile_10_1"]["outcome"] == "succeeded"


@pytest.mark.parametrize("name", ["rosbag2_talker_sqlite3", "rosbag2_talker_mcap", "gps_vehicle_run"])
def test_real_bags_inspect_cleanly_and_say_there_is_no_task(real_bags: Path, name: str,
                                                          capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["inspect", str(real_bags / name)]) == 0
    out = capsys.readouterr().out
    assert "No task to explain" in out and "/rosout" in out


def test_a_real_bags_parameters_are_counted_and_listed(real_bags: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["inspect", str(real_bags / "gps_vehicle_run")]) == 0
    assert "Parameters: 13 of 5 nodes" in " ".join(capsys.readouterr().out.split())
    assert main(["inspect", "--json", str(real_bags / "gps_vehicle_run")]) == 0
    listed = json.loads(capsys.readouterr().out)["parameters"]
    assert {"node": "/motion_spec_provider", "name": "look_ahead_dist", "value": "3.0", "change": "new"}.items() <= \
        next(p for p in listed if p["name"] == "look_ahead_dist").items()


@pytest.mark.parametrize(("args", "message"), [
    (["inspect", "/definitely/not/here"], "recording not found"),
    (["runs", "/definitely/not/here"], "not a folder"),
    (["simulate", "--out", "x", "--storage", "zip"], "unknown storage"),
    (["simulate", "--out", "x", "--scenario", "21"], "--scenario 21 is none of the paper's scenarios"),  # wrote 0
])
def test_bad_input_is_one_line_and_exit_2(args: list[str], message: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.startswith("ERROR:") and message in err and err.count("\n") == 1


def test_inspect_corrupt_bag(tmp_path: Path, suite: Path, capsys: pytest.CaptureFixture[str]) -> None:
    import shutil

    bag = tmp_path / "bag"
    shutil.copytree(suite / "bagfile_5_1", bag)
    db = next(bag.glob("*.db3"))
    db.write_bytes(db.read_bytes()[:4096])
    assert main(["inspect", str(bag)]) == 2
    assert "ERROR: cannot read" in capsys.readouterr().err


def test_simulation_is_deterministic_per_seed(tmp_path: Path) -> None:
    from hexar.evals.cases import scenario
    from hexar.evals.scenarios.suite import record

    a, b, c = record(scenario(9), 2, seed=0), record(scenario(9), 2, seed=0), record(scenario(9), 2, seed=1)
    assert [(t, topic) for t, topic, _, _ in a.messages] == [(t, topic) for t, topic, _, _ in b.messages]
    assert [t for t, *_ in a.messages] != [t for t, *_ in c.messages]


def test_verbose_answer_shows_cited_lines_verbatim(suite: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # recorded text is data, not rich markup: a logger name in brackets must survive
    assert main(["ask", str(suite / "bagfile_5_2"), "What happened?", "--llm", "none", "--verbose"]) == 0
    out = capsys.readouterr().out
    assert "[controller_server] ERROR Failed to make progress" in out
    assert "route=failure_check" in out and "backend=none" in out


def _hexar_at_80(*args: str) -> str:
    import os
    import subprocess
    import sys

    hexar = str(Path(sys.executable).with_name("hexar"))
    done = subprocess.run([hexar, *args], capture_output=True, text=True, check=False, timeout=120,
                          env={**os.environ, "COLUMNS": "80", "TERM": "dumb"})
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_inspect_at_80_columns_shows_whole_skill_names_and_their_facts(suite: Path) -> None:
    out = _hexar_at_80("inspect", str(suite / "bagfile_20_1"))
    assert all(len(line) <= 80 for line in out.splitlines())
    assert "recommend_pizza  succeeded" in out and "say  succeeded" in out
    assert "recommended: Margherita" in out and "ingredients available:" in out
    assert 'said: "I recommend a Margherita." (said in full' in out
    asked = _hexar_at_80("inspect", str(suite / "bagfile_14_1"))
    assert "ask_human_for_help  failed" in asked and "approached the person at (" in asked
    assert "question: 'Could you please put the coffee on my tray?'" in " ".join(asked.split())
    cut = _hexar_at_80("inspect", str(suite / "bagfile_19_2"))
    assert "cut off at the speech time limit" in cut and "got through 49 of 109 words" in cut


def test_runs_in_natural_order_and_an_empty_folder(suite: Path, tmp_path: Path,
                                                   capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["runs", str(suite), "--json"]) == 0
    names = [r["recording"] for r in json.loads(capsys.readouterr().out)]
    assert names[:4] == ["bagfile_1_1", "bagfile_1_2", "bagfile_1_3", "bagfile_2_1"]
    assert names.index("bagfile_9_3") < names.index("bagfile_10_1")
    assert main(["runs", str(tmp_path)]) == 0
    assert "No recordings in" in capsys.readouterr().out


def test_ask_questions_file_echoes_each_question(suite: Path, tmp_path: Path,
                                                 capsys: pytest.CaptureFixture[str]) -> None:
    questions = tmp_path / "q.txt"
    questions.write_text("What happened?\n\nWhy didn't you move?\n", encoding="utf-8")
    assert main(["ask", str(suite / "bagfile_7_1"), "--questions", str(questions), "--llm", "none"]) == 0
    out = capsys.readouterr().out
    assert out.count("Q: ") == 2
    first, second = out.split("Q: ")[1:]
    assert first.startswith("What happened?\n") and "charger" in first
    assert second.startswith("Why didn't you move?\n") and "charger" in second


def test_inspect_labels_a_derived_start_as_such_and_a_quiet_recording_says_what_it_looked_for(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from hexar.events.records import ERROR, INFO
    from tests.explainers.helpers import write_lines

    # sllidar_ros2 src/sllidar_node.cpp:287@main: a lidar driver's error, the robot's start that failed
    started = write_lines(tmp_path / "lidar", [(0.0, "sllidar_node", ERROR,
                                                "Error, cannot bind to the specified serial port /dev/ttyUSB0.")])
    assert main(["inspect", str(started.path)]) == 0
    out = capsys.readouterr().out
    assert "Start the robot (derived from its start lines)" in out and "Nav2 goal" not in out
    # demo_nodes_cpp's talker (talker.cpp: "Publishing: '%s'"): nothing started, nothing asked
    quiet = write_lines(tmp_path / "talker", [(0.0, "talker", INFO, "Publishing: 'Hello World: 1'")])
    assert main(["inspect", str(quiet.path)]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "No task to explain" in out and "no MoveIt or arm controller goal" in out
    assert "no start of the robot's drivers or controllers" in out and "last error" not in out
    # moveit_task_constructor's executor (no goal, no start): the one error is quoted, not explained
    lone = write_lines(tmp_path / "mtc", [(0.0, "moveit_task_constructor_executor", ERROR,
                                          "Failed to connect to the 'execute_task_solution' action server")])
    assert main(["inspect", str(lone.path)]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "No task to explain" in out
    assert "last error it logged came from moveit_task_constructor_executor" in out
    assert "\"Failed to connect to the 'execute_task_solution' action server\"" in out
