"""The page's API answers strict JSON: a NaN or infinity recorded in /task_info or a pose reaches the page as null
with a warning, never as `NaN` (which the browser's JSON.parse rejects, leaving the page blank)."""

from __future__ import annotations

import urllib.request
from pathlib import Path
from typing import Any

from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from tests.events.helpers import T0, task_msg
from tests.fuzz.harness import _strict
from tests.web.browser import served


def _strict_get(url: str) -> Any:
    with urllib.request.urlopen(url, timeout=60) as r:
        return _strict(r.read().decode("utf-8"))


def test_non_finite_recorded_numbers_are_null_on_the_page(tmp_path: Path) -> None:
    b = BagBuilder()
    nav = ("navigate_to_zone", {"location": "kitchen", "speed": float("nan")})
    b.task_info(T0, task_msg("t1", "go to the kitchen", [(*nav, "Running", "")]))
    b.pose(T0 + sec_ns(1), float("nan"), 1.0, 0.0, float("inf"), 0.1, 0.1)
    b.task_info(T0 + sec_ns(9), task_msg("t1", "go to the kitchen", [(*nav, "failed", "Goal failed")]))
    b.write(tmp_path / "runs" / "nan_run")
    with served(tmp_path / "runs", tmp_path / "t.sqlite") as url:
        detail = _strict_get(url + "api/run?name=nan_run")
        _strict_get(url + "api/runs")
    assert any("non-finite number replaced by null" in w for w in detail["warnings"]), detail.get("warnings")
