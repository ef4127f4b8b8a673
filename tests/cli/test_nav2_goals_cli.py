"""`hexar inspect`, `hexar runs` and `hexar ask` on an ordinary Nav2 recording without /task_info: the goals
are derived from Nav2 and marked as such, and "Why didn't you get there?" is answered from them."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from hexar.cli import main
from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events.records import ERROR, INFO, WARN

T0 = 1_700_000_000_000_000_000


def _ordinary_nav2_recording(out: Path) -> Path:
    """bt_navigator and NavFn lines as Humble prints them (shared reference nav2_log_messages.md:
    navigate_to_pose.cpp:213, navfn_planner.cpp:253, planner_server.cpp:348, bt_action_server_impl.hpp:269)."""
    b = BagBuilder()
    b.log(T0, "bt_navigator", INFO, "Begin navigating from current location (0.00, 0.00) to (25.00, 1.00)")
    b.log(T0 + sec_ns(1), "planner_server", WARN,
          "The goal sent to the planner is off the global costmap. Planning will always fail to this goal.")
    b.log(T0 + sec_ns(1.1), "planner_server", WARN,
          "Planning algorithm GridBased failed to generate a valid path to (25.00, 1.00)")
    b.log(T0 + sec_ns(5), "bt_navigator", ERROR, "Goal failed")
    return b.write(out)


def test_inspect_and_runs_show_goals_derived_from_nav2(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    bag = _ordinary_nav2_recording(tmp_path / "runs" / "nav2_only")
    assert main(["inspect", str(bag)]) == 0
    out = capsys.readouterr().out
    assert "Navigate to (25.00, 1.00)" in out and "derived from Nav2" in out and "failed" in out
    assert "No task to explain" not in out
    assert main(["inspect", str(bag), "--json"]) == 0
    task = json.loads(capsys.readouterr().out)["tasks"][0]
    assert task["derived_from_nav2"] is True and task["skills"][0]["params"]["x"] == 25.0
    assert main(["runs", str(tmp_path / "runs"), "--json"]) == 0
    (row,) = json.loads(capsys.readouterr().out)
    assert row["outcome"] == "failed" and row["derived_from_nav2"] is True and row["tasks"] == 1


def test_why_didnt_you_get_there_on_an_ordinary_nav2_recording(tmp_path: Path,
                                                              capsys: pytest.CaptureFixture[str]) -> None:
    bag = _ordinary_nav2_recording(tmp_path / "nav2_only")
    assert main(["ask", str(bag), "Why didn't you get there?", "--llm", "none", "--json"]) == 0
    answer = json.loads(capsys.readouterr().out)
    text = json.dumps(answer)
    assert "navigation.goal_unreachable" in text and "navigation.blocked_path" not in text
    assert "pick a reachable goal" in text
