"""`hexar mcp` on hostile recordings: strict JSON when /task_info or a pose carries NaN, and a recording with more
Nav2 goals (tasks) than a page answered one page at a time."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from mcp import ClientSession

from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events.records import INFO
from hexar.tools.mcp_server import resource_uri
from hexar.workspace import PAGE
from tests.events.helpers import T0, task_msg
from tests.fuzz.harness import _strict
from tests.tools.test_mcp_server import call, error_of, run, stdio_session

GOALS = PAGE + 17


@pytest.fixture(scope="module")
def served(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("served")
    b = BagBuilder()  # no /task_info: every Nav2 goal becomes a task
    for i in range(GOALS):
        t = T0 + sec_ns(10 * i)
        b.log(t, "bt_navigator", INFO, "Begin navigating from current location (0.00, 0.00) to (1.00, 2.00)")
        b.log(t + sec_ns(5), "bt_navigator", INFO, "Goal succeeded")
    b.write(root / "goals")
    b = BagBuilder()
    nav = ("navigate_to_zone", {"location": "kitchen", "speed": float("nan"), "limit": float("inf")})
    b.task_info(T0, task_msg("t1", "go to the kitchen", [(*nav, "Running", "")]))
    b.pose(T0 + sec_ns(1), float("nan"), 1.0, 0.0, float("inf"), 0.1, 0.1)
    b.task_info(T0 + sec_ns(9), task_msg("t1", "go to the kitchen", [(*nav, "failed", "Goal failed")]))
    b.write(root / "nan")
    return root


async def _text(s: ClientSession, tool: str, **args: Any) -> Any:
    result = await s.call_tool(tool, args)
    assert not result.isError, result.content
    return _strict(result.content[0].text)  # type: ignore[union-attr]


def test_non_finite_numbers_reach_the_client_as_null_with_a_warning(served: Path) -> None:
    async def go() -> None:
        async with stdio_session(served) as s:
            task = await _text(s, "inspect_task", recording="nan")
            assert task["skills"][0]["params"] == {"location": "kitchen", "speed": None, "limit": None}
            assert any("non-finite number replaced by null" in w and "speed" in w for w in task["warnings"])
            structured = await call(s, "inspect_task", recording="nan")
            assert structured["skills"][0]["params"]["limit"] is None
            await _text(s, "list_recordings")
            await _text(s, "ask", recording="nan", question="Why did you fail?")
            await _text(s, "explain_navigation", recording="nan", question="Why didn't you get there?")
            for kind in ("timeline", "contract"):
                res = await s.read_resource(resource_uri("nan", kind))
                _strict(res.contents[0].text)  # type: ignore[union-attr]

    run(go)


def test_tasks_of_a_recording_are_paged(served: Path) -> None:
    async def go() -> None:
        async with stdio_session(served) as s:
            listing = await call(s, "list_recordings")
            row = {r["recording"]: r for r in listing["recordings"]}["goals"]
            assert len(row["tasks"]) == PAGE and row["tasks_total"] == GOALS and row["tasks_next_offset"] == PAGE
            assert all(t["outcome"] == "succeeded" for t in row["tasks"])
            seen = list(row["tasks"])
            offset = row["tasks_next_offset"]
            while offset is not None:
                page = await call(s, "list_tasks", recording="goals", offset=offset, limit=20)
                assert len(page["tasks"]) <= 20 and page["total"] == GOALS
                seen += page["tasks"]
                offset = page["next_offset"]
            assert [t["order"] for t in seen] == list(range(1, GOALS + 1))

            task = await call(s, "inspect_task", recording="goals", task="first")
            assert len(task["tasks_in_recording"]) == PAGE and task["tasks_total"] == GOALS
            rest = await call(s, "inspect_task", recording="goals", task="first",
                              tasks_offset=task["tasks_next_offset"])
            assert task["tasks_in_recording"] + rest["tasks_in_recording"] == [t["task_id"] for t in seen]
            assert rest["tasks_next_offset"] is None
            assert "offset must be" in await error_of(s, "list_tasks", recording="goals", offset=-1)
            assert "limit must be" in await error_of(s, "list_tasks", recording="goals", limit=PAGE + 1)

    run(go)
