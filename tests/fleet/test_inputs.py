"""`hexar triage` on a fleet kept as ROBOT/DATE/RUN: which robot a recording belongs to, labels unique across
robots, a bare `--ray`, a plain install without pyarrow, and the one-sentence explanation."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from hexar.cli import main
from hexar.evals.scenarios.bag import BagBuilder
from hexar.fleet.work import first_sentence
from tests.events.helpers import T0, two_skill_task

DAYS = ("2025-03-10", "2025-03-11_08-30-00")


@pytest.fixture(scope="module")
def dated_fleet(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Two robots, two days each, and the same run name every day: the task id says where each run really is."""
    root = tmp_path_factory.mktemp("dated") / "fleet"
    for robot in ("robot-a", "robot-b"):
        for day in DAYS:
            b = BagBuilder()
            two_skill_task(b, T0, f"{robot}@{day}", fail_second=True)
            b.write(root / robot / day / "run1")
    return root


def triage_rows(args: list[str], out: Path) -> list[dict[str, Any]]:
    assert main(["triage", *args, "--out", str(out), "--workers", "1", "--no-figures"]) == 0
    return [json.loads(line) for line in (out / "tasks.jsonl").read_text(encoding="utf-8").splitlines()]


@pytest.mark.parametrize(("given", "robots"), [
    (["{fleet}"], {"robot-a", "robot-b"}),  # a fleet root with robot folders
    (["{fleet}/robot-a"], {"robot-a"}),  # a robot folder given directly
    (["{fleet}/robot-*/2025-03-1?*"], {"robot-a", "robot-b"}),  # a glob over robots and dates (the README's)
    (["{fleet}/robot-b/2025-03-1?*"], {"robot-b"}),  # a glob over one robot's dates
    (["{fleet}/robot-a", "{fleet}/robot-b/2025-03-10"], {"robot-a", "robot-b"}),
    (["{fleet}/robot-b/2025-03-10/run1"], {"robot-b"}),  # one recording
])
def test_the_robot_is_the_folder_that_names_it_never_a_date(dated_fleet: Path, tmp_path: Path, given: list[str],
                                                              robots: set[str]) -> None:
    rows = triage_rows([g.format(fleet=dated_fleet) for g in given], tmp_path / "o")
    assert {row["robot"] for row in rows} == robots
    for row in rows:
        robot, day = row["task_id"].split("@")
        assert row["robot"] == robot
        assert row["recording"].endswith(f"{robot}/{day}/run1")  # the label names the robot and the day
    assert len({row["recording"] for row in rows}) == len(rows)


def test_two_robots_with_the_same_day_and_run_are_two_recordings_to_look_at(dated_fleet: Path,
                                                                           tmp_path: Path) -> None:
    rows = triage_rows([str(dated_fleet / "robot-*" / "2025-03-10")], tmp_path / "o")
    assert sorted(row["recording"] for row in rows) == ["robot-a/2025-03-10/run1", "robot-b/2025-03-10/run1"]
    report = (tmp_path / "o" / "report.md").read_text()
    look = report.split("## Recordings to look at first")[1].split("\n\n")[1].splitlines()[2:]
    assert [line.split("|")[1:3] for line in look] == [[" robot-a/2025-03-10/run1 ", " robot-a "],
                                                         [" robot-b/2025-03-10/run1 ", " robot-b "]]
    assert "### By robot" in report and "| robot-a | 1 |" in report and "| robot-b | 1 |" in report


def test_a_bare_ray_flag_means_a_local_instance_and_an_address_may_follow(dated_fleet: Path, tmp_path: Path,
                                                                         capsys: pytest.CaptureFixture[str]) -> None:
    """Everything is done by a local run first, so no Ray instance starts: what is parsed shows in the plan line."""
    out = tmp_path / "o"
    one = str(dated_fleet / "robot-a" / DAYS[0])
    triage_rows([one], out)
    capsys.readouterr()
    for args, where in ((["--ray"], "Ray (a local instance)"), (["--ray", "local"], "Ray (a local instance)"),
                        (["--ray", "auto"], "Ray (auto)"), (["--ray", "ray://head:10001"], "Ray (ray://head:10001)"),
                        (["--ray-address", "10.0.0.5:6379"], "Ray (10.0.0.5:6379)")):
        for argv in ([one, *args], [*args, one]):  # the flag before or after the folder
            assert main(["triage", *argv, "--out", str(out), "--no-figures"]) == 0, argv
            assert f"1 recordings: 1 done before, 0 to triage on {where}" in capsys.readouterr().out, argv


def test_two_ray_addresses_and_ray_without_input_are_one_line_errors(tmp_path: Path,
                                                                    capsys: pytest.CaptureFixture[str]) -> None:
    for args, message in ((["--ray"], "give folders or globs"),
                          (["auto", "10.0.0.5:6379", "--ray"], "two Ray addresses")):
        assert main(["triage", *args, "--out", str(tmp_path / "o")]) == 2
        err = capsys.readouterr().err
        assert err.startswith("ERROR:") and message in err and err.count("\n") == 1


def test_without_pyarrow_the_tables_are_json_lines_and_the_run_says_so(dated_fleet: Path, tmp_path: Path) -> None:
    """A plain install (no `fleet` extra): pyarrow cannot be imported from the start, so pandas works without it
    too; a fresh interpreter is the only place to have that."""
    out = tmp_path / "o"
    out.mkdir()
    (out / "tasks.parquet").write_bytes(b"an earlier run's table")
    script = ("import sys; sys.modules['pyarrow'] = None\n"  # every `import pyarrow` raises ImportError
              "from hexar.cli import main; sys.exit(main(sys.argv[1:]))")
    proc = subprocess.run([sys.executable, "-c", script, "triage", str(dated_fleet), "--out", str(out),
                           "--workers", "1", "--no-figures"], capture_output=True, text=True, timeout=300,
                          env={**os.environ, "COLUMNS": "200"})
    assert proc.returncode == 0, proc.stderr
    assert len((out / "tasks.jsonl").read_text().splitlines()) == 4 and (out / "report.md").is_file()
    assert not (out / "tasks.parquet").exists()  # a stale table would be read by --compare as this run's
    said = proc.stdout
    assert said.index("pyarrow is not installed") < said.index("4 recordings: 0 done before")
    assert "pip install 'hexar[fleet]'" in said and "(no tasks.parquet: pyarrow is not installed)" in said


@pytest.mark.parametrize(("text", "sentence"), [
    ("The robot stopped 0.5 m short of the goal. The costmap showed an obstacle. Nav2 aborted.",
     "The robot stopped 0.5 m short of the goal."),
    ("Planning failed: open_window is not a valid skill! Valid skills are navigate_to_zone, speak.",
     "Planning failed: open_window is not a valid skill!"),
    ("Speed was low, e.g. 0.12 m/s vs. 0.5 m/s. Controller ok.", "Speed was low, e.g. 0.12 m/s vs. 0.5 m/s."),
    ('The TTS said "Please move." Nobody moved.', 'The TTS said "Please move."'),
    ("Why did it stop? The path was blocked.", "Why did it stop?"),
    ("One sentence with no end", "One sentence with no end"),
    ("First line. Second sentence.\nEvidence: 3 items", "First line."),
    ("Stopped at x=1.5. then resumed", "Stopped at x=1.5. then resumed"),  # no capital after: not an end
])
def test_the_explanation_column_is_the_first_sentence(text: str, sentence: str) -> None:
    assert first_sentence(text) == sentence

