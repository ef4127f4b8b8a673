"""The event log: recordings read into typed records, tasks, and per-explainer views."""

from __future__ import annotations

from hexar.events.errors import EventsError
from hexar.events.log import EventLog, TopicInfo, View
from hexar.events.reader import read_recording, read_tasks
from hexar.events.tasks import SkillRun, Task

__all__ = ["EventLog", "EventsError", "SkillRun", "Task", "TopicInfo", "View", "read_recording", "read_tasks"]
