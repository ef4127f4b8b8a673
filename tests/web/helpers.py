"""A recording whose recorded text is hostile: markup, script and mathtext in the task, the log and the error."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events import contract as c

HOSTILE_LOG = "<img src=x onerror=\"document.title='pwned'\"> Failed to make progress $\\frac{"
HOSTILE_ERROR = "<script>document.title='pwned'</script> Navigation failed $x^{"
HOSTILE_INSTRUCTION = "Bring me <b>the</b> $coffee"


def _task(t: int, status: str, error: str = "") -> tuple[int, dict[str, Any]]:
    return t, {"instruction": HOSTILE_INSTRUCTION, "task_id": "hostile01", "task_status": "valid",
               "task_error_msg": "", "skill_sequence": [
                   {"skill": "navigate_to_zone", "params": {"zone": "kitchen"}, "status": status, "error_msg": error}]}


def hostile_recording(out: Path) -> Path:
    b = BagBuilder()
    t0 = sec_ns(1_741_600_000)
    for t, payload in (_task(t0, "waiting"), _task(t0 + sec_ns(1), "Running"),
                       _task(t0 + sec_ns(12), "failed", HOSTILE_ERROR)):
        b.task_info(t, payload)
    for i in range(60):
        b.pose(t0 + i * 200_000_000, 0.1 * i, 0.05 * i, 0.0, 0.02, 0.02, 0.01)
    b.log(t0 + sec_ns(2), "bt_navigator", 20, "Begin navigating from current location (0.00, 0.00) to (4.20, 2.10)")
    b.log(t0 + sec_ns(8), "controller_server", 40, HOSTILE_LOG)
    b.log(t0 + sec_ns(11), "bt_navigator", 40, "Goal failed")
    b.flag(t0, c.JOY_PRIORITY, False)
    b.flag(t0, c.IS_CHARGING, False)
    return b.write(out)
