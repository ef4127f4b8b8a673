"""The page's API on an arm recording: the run list shows the manipulation cause, the run shows its finding."""

from __future__ import annotations

from pathlib import Path

from hexar.evals.scenarios.arm import arm_recording_name, simulate_arm_suite
from tests.web.browser import served
from tests.web.test_server import get


def test_the_page_shows_the_manipulation_finding(tmp_path: Path) -> None:
    root = tmp_path / "runs"
    simulate_arm_suite(root, only=lambda s, v: (s, v) == ("stale_state", 1))
    name = arm_recording_name("stale_state", 1)
    with served(root, tmp_path / "t.sqlite") as url:
        import time

        deadline = time.monotonic() + 120
        while True:
            _, runs = get(url + "api/runs")
            if runs["pending"] == 0 or time.monotonic() > deadline:
                break
            time.sleep(0.5)
        _, run = get(url + f"api/run?name={name}")
    row = {r["recording"]: r for r in runs["runs"]}[name]
    # the failed pick's cause leads; the trip before it, which succeeded, may be listed as the normal run it was
    assert row["causes"][0] == "manipulation.stale_robot_state" and "manipulation" in row["modules"]
    assert set(row["causes"][1:]) <= {"navigation.nominal"}
    assert run["findings"][0]["causes"] == ["manipulation.stale_robot_state"]
