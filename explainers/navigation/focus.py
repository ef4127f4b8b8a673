"""Which navigation step of the task a window is about, where its goal was, and what /task_info recorded of it."""

from __future__ import annotations

import re

from hexar.events import contract as c
from hexar.events.nav_servers import DOCK_SKILL, NO_GOAL_LINE
from hexar.events.records import LogLine
from hexar.events.tasks import SkillRun
from hexar.explainers.base import Context, Evidence
from hexar.explainers.recorded import NAV_SKILLS


def focus(context: Context) -> SkillRun | None:
    """The plan's navigation step this window is about: the failed one, else the last one inside the window."""
    failed = context.task.failed_skill
    if failed is not None and failed.skill in NAV_SKILLS:
        return failed
    lo, hi = context.window
    # Strict overlap: a step that merely ends where the window starts (the trip before an approach to a
    # person) is not the trip this window is about.
    inside = [r for r in context.task.skills if r.skill in NAV_SKILLS and r.history
              and context.task.skill_window(r)[0] < hi and context.task.skill_window(r)[1] > lo]
    return inside[-1] if inside else None


_NAVIGATING_TO = re.compile(r"^Navigating to (.+?) at \(")


def place_of(context: Context, lines: list[LogLine]) -> str:
    run = focus(context)
    location = run.params.get("location") if run is not None else None
    if isinstance(location, str) and location:
        return f"the {location.replace('_', ' ')}"
    if run is not None and run.skill == DOCK_SKILL:  # the trip a docking sent: to the dock's staging pose
        return f"the staging pose of {run.params.get('dock') or 'my dock'}"
    if run is not None and run.params.get("source") == "nav2" and "x" in run.params and "y" in run.params:
        return f"the goal at ({run.params['x']:.2f}, {run.params['y']:.2f})"  # a goal derived from Nav2
    # A navigation that is no plan step (e.g. approaching a person) names its goal in the skill's own log.
    for line in lines:
        m = _NAVIGATING_TO.match(line.msg)
        if m:
            return m.group(1)
    return "my goal"


def inferred(context: Context) -> bool:
    """A goal that no goal line, action status or /task_info shows: inferred from Nav2's activity (events.nav_goals),
    failed only because some node logged an error, or still running as far as the recording shows."""
    return any(r.skill in NAV_SKILLS and r.params.get("derived_from") == NO_GOAL_LINE for r in context.task.skills)


def skill_state(context: Context) -> str | None:
    run = focus(context)
    return run.state if run is not None else None


def status_evidence(context: Context, cause: str) -> list[Evidence]:
    """The /task_info update where the navigation skill failed: the record of a failure no log line explains."""
    run = focus(context)
    change = next((h for h in reversed(run.history) if h.status.strip().lower() == "failed"), None) if run else None
    if change is None:
        return []
    return [Evidence(cause=cause, topic=c.TASK_INFO, t=change.t, item=change.error_msg or change.status)]
