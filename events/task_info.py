"""`/task_info` updates: the original HEXAR system's JSON task messages (std_msgs/String) as TaskUpdate records."""

from __future__ import annotations

from hexar.events.records import SkillStep, TaskUpdate


def parse_task_info(t: int, data: str) -> TaskUpdate | None:
    """A `/task_info` JSON update, or None when the text is no task update (or too large or too deep to read)."""
    from hexar.bounded_json import loads
    from hexar.errors import BadJsonError

    try:
        obj = loads(data)
    except BadJsonError:
        return None
    if not isinstance(obj, dict) or "task_id" not in obj:
        return None
    skills = []
    for step in obj.get("skill_sequence") or []:
        if not isinstance(step, dict):
            continue
        params = step.get("params") or {}
        skills.append(
            SkillStep(
                skill=str(step.get("skill", "")),
                params=dict(params) if isinstance(params, dict) else {"value": params},
                status=str(step.get("status", "")),
                error_msg=str(step.get("error_msg") or ""),
            )
        )
    return TaskUpdate(
        t=t,
        task_id=str(obj["task_id"]),
        instruction=str(obj.get("instruction") or ""),
        task_status=str(obj.get("task_status") or "valid"),
        task_error_msg=str(obj.get("task_error_msg") or ""),
        skills=tuple(skills),
        raw=data,
    )
