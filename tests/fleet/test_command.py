"""`hexar triage` over a simulated fleet: two robots (sqlite3 and mcap, different seeds), a ROS 1 bag, and broken
recordings mixed in. Ground truth comes from evals/data/scenarios.yaml, read here only."""

from __future__ import annotations

import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path
from typing import Any

import pandas as pd
import pytest
from rich.console import Console

from hexar.cli import main
from hexar.evals.cases import scenario
from hexar.fleet.command import RESULTS, TriageOptions, triage_command
from hexar.fleet.compare import compare
from hexar.fleet.work import first_sentence

HEXAR = str(Path(sys.executable).with_name("hexar"))
BROKEN = {"robot-c/truncated", "robot-c/garbage", "robot-c/empty_meta"}
# A nominal run has nothing to look at: its ground-truth "cause" is an explanation of normal speed, not a problem.
NOTHING_WRONG = {"navigation.nominal_speed"}


def _ros1_invalid_plan(path: Path) -> None:
    from rosbags.rosbag1 import Writer as Writer1
    from rosbags.typesys import Stores, get_typestore

    ts = get_typestore(Stores.ROS1_NOETIC)
    data = json.dumps({"task_id": "ros1task", "instruction": "Open the window in the living room",
                       "task_status": "invalid", "task_error_msg": "Skill open_window is not a valid skill.",
                       "skill_sequence": [{"skill": "open_window", "params": {"window": "living_room"},
                                           "status": "waiting", "error_msg": ""}]})
    with Writer1(path) as w:
        info = w.add_connection("/task_info", "std_msgs/msg/String", typestore=ts)
        w.write(info, 1_741_600_800 * 10**9, ts.serialize_ros1(ts.types["std_msgs/msg/String"](data=data),
                                                                "std_msgs/msg/String"))


def make_fleet(root: Path, seeds: dict[str, tuple[int, str]]) -> Path:
    from hexar.evals.scenarios.suite import simulate_suite

    for robot, (seed, storage) in seeds.items():
        simulate_suite(root / robot / f"seed-{seed}", storage, seed)  # type: ignore[arg-type]
    first = next(iter(seeds))  # its copies become the broken recordings: it must be sqlite3
    some = next((root / first).glob("*/bagfile_5_1"))
    broken = root / "robot-c"
    shutil.copytree(some, broken / "truncated")
    db = next((broken / "truncated").glob("*.db3"))
    db.write_bytes(db.read_bytes()[:4096])
    shutil.copytree(some, broken / "garbage")
    next((broken / "garbage").glob("*.db3")).write_bytes(b"not a database at all" * 100)
    (broken / "empty_meta").mkdir()
    (broken / "empty_meta" / "metadata.yaml").write_text("not: [yaml")
    _ros1_invalid_plan(broken / "old_robot.bag")
    return root


def ground_truth(fleet: Path) -> Counter[str]:
    truth: Counter[str] = Counter()
    for rec in fleet.rglob("bagfile_*_*"):
        if rec.is_dir():
            cause = scenario(int(rec.name.split("_")[1])).cause
            truth[cause if cause not in NOTHING_WRONG else ""] += 1
    truth["planner.request_beyond_capabilities"] += 1  # the ROS 1 bag written above
    return truth


def user_causes(df: pd.DataFrame) -> Counter[str]:
    return Counter(df.loc[~df["recovery"], "cause"])


def rows_of(out: Path) -> list[str]:
    return sorted((out / "tasks.jsonl").read_text(encoding="utf-8").splitlines())


@pytest.fixture(scope="module")
def fleet(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return make_fleet(tmp_path_factory.mktemp("fleet"), {"robot-a": (1, "sqlite3"), "robot-b": (2, "mcap")})


@pytest.fixture(scope="module")
def full(fleet: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("triage")
    code = triage_command(TriageOptions((str(fleet),), out, workers=2, progress=False), Console(quiet=True))
    assert code == 0
    return out


def test_counts_per_cause_equal_the_ground_truth(fleet: Path, full: Path) -> None:
    df = pd.read_parquet(full / "tasks.parquet")
    assert user_causes(df) == ground_truth(fleet)
    failed = df[df["kind"] == "failure"]
    assert (failed["evidence"] > 0).all() and (failed["explanation"].str.len() > 0).all()
    explained = [e for e in df["explanation"] if e]  # one sentence each, though explainers often say two or three
    assert explained and all(first_sentence(e) == e for e in explained)
    assert all(e[-1] in ".!?\"')" for e in failed["explanation"])
    assert set(df["robot"]) == {"robot-a", "robot-b", "robot-c"}
    assert set(df["storage"]) == {"sqlite3", "mcap", "rosbag1"}
    nav = df[(df["cause"] == "navigation.blocked_path") & ~df["recovery"]].iloc[0]
    assert nav["failed_skill"] == "navigate_to_zone" and nav["explainer"] == "navigation"
    assert nav["outcome"] == "failed" and nav["day"] == "2025-03-10"
    results = [json.loads(line) for line in (full / RESULTS).read_text().splitlines()]
    bad = {r["recording"]: r["error"] for r in results if r["error"]}
    assert set(bad) == BROKEN and all("\n" not in e and e for e in bad.values())
    assert pd.read_json(full / "tasks.jsonl", lines=True).shape == df.shape


def test_report_and_figures(full: Path) -> None:
    report = (full / "report.md").read_text()
    assert "124 recordings (3 unreadable" in report
    for section in ("## Most frequent causes", "### By cause", "### By module", "### By robot", "### By day",
                    "## Recordings to look at first", "## Unreadable recordings"):
        assert section in report
    assert "| navigation.blocked_path | 6 |" in report
    causes = report.split("## Most frequent causes")[1].split("## Counts")[0]
    counted = re.findall(r"\*\*: (\d+) (tasks?)\. .*\((\d+) (evidence items?)\)$", causes, re.M)
    assert counted and all((n == "1") == (word in {"task", "evidence item"})
                           for n, word in [(c[0], c[1]) for c in counted] + [(c[2], c[3]) for c in counted])
    assert "robot-c/truncated" in report and "cannot read" in report
    first = report.split("## Recordings to look at first")[1].splitlines()[4].split("|")
    assert first[4].strip() == "1"  # failures come before findings
    for png in ("causes_over_time.png", "causes_per_robot.png"):
        assert (full / png).stat().st_size > 10_000


def _wait_for_lines(path: Path, n: int, proc: subprocess.Popen[bytes], limit: float = 120) -> None:
    deadline = time.monotonic() + limit
    while time.monotonic() < deadline:
        if path.is_file() and len(path.read_text().splitlines()) >= n:
            return
        assert proc.poll() is None, "triage ended before it could be interrupted"
        time.sleep(0.05)
    raise AssertionError("no results appeared")


def test_ctrl_c_keeps_what_is_done_and_a_rerun_finishes_with_the_same_result(fleet: Path, full: Path,
                                                                             tmp_path: Path) -> None:
    out = tmp_path / "out"
    proc = subprocess.Popen([HEXAR, "triage", str(fleet), "--out", str(out), "--workers", "2", "--no-figures"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True,
                            # a test run started in the background ignores SIGINT, and a child would inherit that
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    _wait_for_lines(out / RESULTS, 10, proc)
    os.killpg(proc.pid, signal.SIGINT)  # as Ctrl-C does: the whole process group
    stdout, stderr = proc.communicate(timeout=120)
    assert proc.returncode == 130, stderr.decode()
    assert b"Traceback" not in stderr and b"interrupted" in stdout
    kept = len((out / RESULTS).read_text().splitlines())
    assert 10 <= kept < 124
    with (out / RESULTS).open("a") as f:
        f.write('{"recording": "robot-a/seed-1/bagf')  # a crash in the middle of a line: that one runs again
    console = Console(record=True, width=200)
    assert triage_command(TriageOptions((str(fleet),), out, workers=2, progress=False), console) == 0
    assert f"{kept} done before, {124 - kept} to triage" in console.export_text()
    assert rows_of(out) == rows_of(full)


def test_compare_two_runs_and_two_days(fleet: Path, full: Path, tmp_path: Path) -> None:
    later = tmp_path / "later"
    shutil.copytree(fleet / "robot-a", later / "robot-a")
    for rec in later.rglob("bagfile_5_*"):
        shutil.rmtree(rec)  # the blocked corridor was cleared
    out = tmp_path / "later-out"
    assert triage_command(TriageOptions((str(later),), out, workers=1, progress=False), Console(quiet=True)) == 0
    diff = compare(str(full), str(out), None)
    rows: dict[str, Any] = {r["cause"]: r for r in diff["causes"]}
    assert rows["navigation.blocked_path"]["a"] == 6 and rows["navigation.blocked_path"]["b"] == 0
    assert "navigation.blocked_path" in diff["gone"] and diff["new"] == []
    assert rows["tts.timeout"]["a"] == 6 and rows["tts.timeout"]["b"] == 3
    days = compare("2025-03-10", "2025-03-11", full)
    assert days["tasks_a"] + days["tasks_b"] == len(pd.read_parquet(full / "tasks.parquet"))


@pytest.mark.parametrize(("args", "message"), [
    (["triage"], "give folders or globs"),
    (["triage", "/nonexistent/fleet"], "no such folder"),
    (["triage", "/nonexistent/*/x"], "no recordings match"),
    (["triage", "--compare", "nothing-here", "2025-03-10"], "cannot compare 'nothing-here'"),
])
def test_bad_input_is_one_line(args: list[str], message: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.startswith("ERROR:") and message in err and err.count("\n") == 1


def test_bad_workers_and_empty_folder_are_one_line(tmp_path: Path, fleet: Path,
                                                   capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["triage", str(fleet / "robot-c"), "--workers", "0", "--out", str(tmp_path / "o")]) == 2
    assert "--workers must be 1 or more" in capsys.readouterr().err
    (tmp_path / "empty").mkdir()
    assert main(["triage", str(tmp_path / "empty"), "--out", str(tmp_path / "o")]) == 2
    assert "no recordings under" in capsys.readouterr().err


def test_globs_and_nested_folders(fleet: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "o"
    pattern = str(fleet / "robot-*" / "seed-*" / "bagfile_1[12]_1")
    assert main(["triage", pattern, "--out", str(out), "--workers", "1", "--no-figures"]) == 0
    # the summary line counts as report.md does: the failed tasks are not "0 with a finding"
    said = " ".join(capsys.readouterr().out.split())
    assert "4 recordings, 8 tasks: 4 failed or wrongly planned, 0 succeeded with a finding worth a look; " \
        "0 unreadable" in said, said
    df = pd.read_parquet(out / "tasks.parquet")
    # named under the matches' common folder: the same run on two robots is two recordings
    assert sorted(set(df["recording"])) == [f"robot-{r}/seed-{s}/bagfile_{n}_1" for r, s in (("a", 1), ("b", 2))
                                            for n in (11, 12)]
    assert set(df["robot"]) == {"robot-a", "robot-b"}
    assert len(df[~df["recovery"]]) == 4  # two robots, two scenarios
    from hexar.fleet.inputs import expand

    named = {rel for _, rel in expand([str(fleet / "robot-[ab]")])}
    assert "robot-a/seed-1/bagfile_5_1" in named and "robot-b/seed-2/bagfile_5_1" in named


def test_ray_local_equals_the_local_pool(fleet: Path, full: Path, tmp_path: Path) -> None:
    pytest.importorskip("ray")
    out = tmp_path / "ray"
    assert triage_command(TriageOptions((str(fleet),), out, workers=2, ray="", progress=False),
                          Console(quiet=True)) == 0
    assert rows_of(out) == rows_of(full)


@pytest.mark.slow
def test_several_hundred_recordings(tmp_path: Path) -> None:
    """Five seeds on five robots: 300 recordings plus the broken ones, counts per cause against the truth."""
    seeds = {f"robot-{chr(ord('a') + i)}": (10 + i, "mcap" if i % 2 else "sqlite3") for i in range(5)}
    seeds["robot-c"] = (20, "sqlite3")  # robot-c also holds the broken recordings
    fleet = make_fleet(tmp_path / "fleet", seeds)
    out = tmp_path / "out"
    assert triage_command(TriageOptions((str(fleet),), out, progress=False), Console(quiet=True)) == 0
    assert user_causes(pd.read_parquet(out / "tasks.parquet")) == ground_truth(fleet)


def test_report_shows_recorded_control_characters_visibly(tmp_path: Path) -> None:
    from hexar.evals.scenarios.bag import BagBuilder
    from tests.events.helpers import T0, two_skill_task

    robot = tmp_path / "fleet" / "robot-\x1b[31mred"  # a folder name and a task id carrying terminal escapes
    b = BagBuilder()
    two_skill_task(b, T0, "t1\x1b]52;c;ZWNobyBwd25lZA==\x07", fail_second=True)
    b.write(robot / "run1")
    out = tmp_path / "o"
    assert main(["triage", str(tmp_path / "fleet"), "--out", str(out), "--workers", "1", "--no-figures"]) == 0
    report = (out / "report.md").read_text()
    assert "\x1b" not in report and "\x07" not in report
    assert "robot-\\x1b[31mred" in report
    assert "| (failed, no cause found) | 1 |" in report  # a failure no explainer explains is still listed
