"""The blind real-Nav2 excerpts of issue 20 (evals/data/real_nav2/blind.yaml): they load, share no source with the
corpus or the held-out set, every one becomes a rosbag2 recording read back line for line, `hexar eval --suite
real-nav2-blind` reports on them and its committed baselines (before and after tuning) are this suite's. Their
accuracy is measured, never pinned here."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from hexar.cli import main
from hexar.evals.real_nav2 import (
    BLIND_FILES,
    NAV_CAUSES,
    Excerpt,
    blind,
    blind_set,
    corpus,
    heldout,
    write_recording,
)
from hexar.evals.real_nav2_cli import read_baseline
from hexar.events import contract as c
from hexar.events import read_recording
from hexar.events.console import parse_console, stamped

BASELINES = Path(__file__).resolve().parents[2] / "evals" / "baselines"


# each blind set in the order collected (blind_set(1), blind_set(2), ...), its least size, and whether a fifth of it
# are successes or slow runs (the third, sixth, eighth, eleventh and thirteenth sets' collectors found too few to ask
# it of; the twenty-sixth has 2 of 12)
BLIND_SETS = [(40, True), (30, True), (14, False), (12, True), (25, True), (9, False), (19, True), (4, False),
              (6, True), (15, True), (6, False), (4, True),
              (4, False), (3, True), (1, False), (8, False), (1, False), (1, False), (2, False), (18, True), (11, True),
              (14, True), (10, True), (10, True), (10, True), (12, False), (10, True), (12, True),
              (8, True)]


def test_every_blind_file_has_its_expectations() -> None:
    assert len(BLIND_SETS) == len(BLIND_FILES)


@pytest.mark.parametrize("index", range(len(BLIND_SETS)), ids=lambda i: f"blind{i + 1}")
def test_each_blind_set_loads_and_shares_no_excerpt_or_thread_with_the_sets_before_it(index: int) -> None:
    least, successes = BLIND_SETS[index]
    excerpts = blind_set(index + 1)
    assert len(excerpts) >= least and {e.cause for e in excerpts} <= NAV_CAUSES
    if successes:
        assert sum(e.outcome != "failed" for e in excerpts) * 5 >= len(excerpts)
    others = corpus() + heldout() + tuple(e for n in range(1, index + 1) for e in blind_set(n))
    assert not {e.id for e in excerpts} & {e.id for e in others}
    assert not {e.url for e in excerpts} & {e.url for e in others}


def test_a_grep_line_number_before_a_launch_prefix_is_not_part_of_the_message() -> None:
    # a log file pasted as `grep -n` prints it (blind5's forklift excerpts)
    [line] = parse_console("115:[controller_server-2] [INFO] [1785836573.244524676] [local_costmap.local_costmap]: "
                           "Received request to clear entirely the local_costmap")
    assert line.name == "local_costmap.local_costmap" and line.msg.startswith("Received request")


@pytest.mark.parametrize("excerpt", [e for n in range(1, len(BLIND_FILES) + 1) for e in blind_set(n)],
                         ids=lambda e: e.id)
def test_every_blind_excerpt_becomes_a_readable_recording(excerpt: Excerpt, tmp_path: Path) -> None:
    # a paste from several terminals is not in time order; the recording is, as a robot's /rosout would be
    expected = sorted(stamped(parse_console(excerpt.lines)), key=lambda r: r.stamp_ns or 0)
    log = read_recording(write_recording(excerpt, tmp_path / "bag", task=False))
    assert [line.msg for line in log.view(frozenset({c.ROSOUT})).logs()] == [r.msg for r in expected]


def test_the_blind_suite_reports_every_excerpt_without_machine_paths(tmp_path: Path) -> None:
    out = tmp_path / "out"
    runs = tmp_path / "runs"
    assert main(["eval", "--suite", "real-nav2-blind", "--llm", "none", "--out", str(out), "--runs", str(runs)]) == 0
    text = (out / "report.json").read_text(encoding="utf-8")
    report = json.loads(text)
    assert report["suite"] == "real-nav2-blind" and report["data"] == "blind.yaml"
    assert [e["id"] for e in report["excerpts"]] == [e.id for e in blind()]
    assert str(runs) not in text  # an unanswered excerpt's error names the excerpt, not the recording's folder


@pytest.mark.parametrize("name", sorted(p.name for p in BASELINES.glob("real_nav2_blind*_none*.json")))
def test_the_committed_blind_baselines_are_this_suites(name: str) -> None:
    # real_nav2_blind<n>_none.json after tuning, ..._none_before.json before it: one of each per set
    n = int(name.split("_")[2].removeprefix("blind") or 1)
    baseline = read_baseline(BASELINES / name, "real-nav2-blind" + (str(n) if n > 1 else ""))
    assert set(baseline["excerpts"]) == {e.id for e in blind_set(n)}


def test_every_blind_set_has_its_baseline_from_before_tuning() -> None:
    assert {p.name for p in BASELINES.glob("real_nav2_blind*_none_before.json")} == {
        f"real_nav2_blind{n if n > 1 else ''}_none_before.json" for n in range(1, len(BLIND_FILES) + 1)}


def test_a_process_line_behind_launchs_prefix_continues_only_its_own_processs_message() -> None:
    # innate-os (blind.yaml): the controller server's crash text is its own output, not the end of a logger's line;
    # forcedimension_ros2#10 (heldout8.yaml): launch names processes with spaces in them
    lines = parse_console("[controller_server]: [follow_path] [ActionServer] Aborting handle.\n"
                          "[controller_server-6] double free or corruption (!prev)\n"
                          "[controller_manager fd_controller-4] No executable found\n"
                          "[controller_manager joint_state_broadcaster-5] No executable found\n"
                          "[ERROR] [controller_manager fd_controller-4]: process has died [pid 399580, exit code 1]")
    assert [(r.process, r.msg) for r in lines[1:4]] == [
        ("controller_server-6", "double free or corruption (!prev)"),
        ("controller_manager fd_controller-4", "No executable found"),
        ("controller_manager joint_state_broadcaster-5", "No executable found")]
    assert lines[4].name == "controller_manager fd_controller-4" and lines[4].msg.startswith("process has died")
    # a message's own next line behind the same prefix still continues it (a C++ exception's what())
    [thrown] = parse_console("[move_group-1] terminate called after throwing an instance of 'std::invalid_argument'\n"
                             "[move_group-1]   what():  invalid argument passed")
    assert thrown.msg.endswith("\nwhat():  invalid argument passed")
