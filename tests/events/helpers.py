from __future__ import annotations

from typing import Any

from hexar.evals.scenarios.bag import BagBuilder, sec_ns

T0 = sec_ns(1_750_000_000)


def task_msg(task_id: str, instruction: str, skills: list[tuple[str, dict[str, Any], str, str]],
             valid: bool = True, error: str = "") -> dict[str, Any]:
    return {
        "instruction": instruction, "task_id": task_id, "task_status": "valid" if valid else "invalid",
        "task_error_msg": error,
        "skill_sequence": [{"skill": s, "params": p, "status": st, "error_msg": em} for s, p, st, em in skills],
    }


def two_skill_task(b: BagBuilder, t0: int, task_id: str, fail_second: bool) -> None:
    """navigate_to_zone then say, published at start and at each skill start and end."""
    nav = ("navigate_to_zone", {"location": "kitchen"})
    say = ("say", {"input": "hello"})
    b.task_info(t0, task_msg(task_id, "go to the kitchen and say hello",
                             [(*nav, "waiting", ""), (*say, "waiting", "")]))
    b.task_info(t0 + sec_ns(1), task_msg(task_id, "go to the kitchen and say hello",
                                         [(*nav, "Running", ""), (*say, "waiting", "")]))
    b.task_info(t0 + sec_ns(10), task_msg(task_id, "go to the kitchen and say hello",
                                          [(*nav, "succeeded", ""), (*say, "waiting", "")]))
    b.task_info(t0 + sec_ns(11), task_msg(task_id, "go to the kitchen and say hello",
                                          [(*nav, "succeeded", ""), (*say, "Running", "")]))
    last = ("failed", "The skill has timed out") if fail_second else ("SUCCEEDED", "")
    b.task_info(t0 + sec_ns(15), task_msg(task_id, "go to the kitchen and say hello",
                                          [(*nav, "succeeded", ""), (*say, *last)]))
