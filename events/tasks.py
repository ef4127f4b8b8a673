"""Tasks: `/task_info` updates grouped by task_id, with per-skill status histories and time windows."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from hexar.events.records import SkillStep, TaskUpdate

Outcome = Literal["invalid", "failed", "succeeded", "canceled", "running", "waiting"]


@dataclass(frozen=True, slots=True)
class StatusChange:
    t: int
    status: str
    error_msg: str


@dataclass(frozen=True, slots=True)
class SkillRun:
    """One step of a plan and the history of its status."""

    index: int
    skill: str
    params: dict[str, object]
    history: tuple[StatusChange, ...]

    @property
    def state(self) -> str:
        return self.history[-1].status.strip().lower() if self.history else "waiting"

    @property
    def error_msg(self) -> str:
        return self.history[-1].error_msg if self.history else ""

    @property
    def last_change(self) -> int:
        return self.history[-1].t

    def time_of(self, state: str) -> int | None:
        for change in self.history:
            if change.status.strip().lower() == state:
                return change.t
        return None

    def label(self) -> str:
        return SkillStep(self.skill, self.params, self.state).label()


@dataclass(frozen=True, slots=True)
class Task:
    """One task of the recording (the paper's task in the context vector C)."""

    task_id: str
    instruction: str
    updates: tuple[TaskUpdate, ...]
    skills: tuple[SkillRun, ...]
    order: int
    derived: bool = False  # built from Nav2 goals (events/nav_goals.py), not from /task_info

    @property
    def created(self) -> int:
        return self.updates[0].t

    @property
    def last_update(self) -> int:
        return self.updates[-1].t

    @property
    def valid(self) -> bool:
        return self.updates[-1].valid

    @property
    def error_msg(self) -> str:
        return self.updates[-1].task_error_msg

    @property
    def is_recovery(self) -> bool:
        """The robot's own follow-up after a failure: it publishes such tasks with an empty instruction."""
        return self.instruction.strip() == ""

    @property
    def failed_skill(self) -> SkillRun | None:
        for run in self.skills:
            if run.state == "failed":
                return run
        return None

    @property
    def outcome(self) -> Outcome:
        if not self.valid:
            return "invalid"
        if self.failed_skill is not None:
            return "failed"
        states = [run.state for run in self.skills]
        if states and all(s == "succeeded" for s in states):
            return "succeeded"
        if "canceled" in states:
            return "canceled"
        if any(s in {"running", "succeeded"} for s in states):
            return "running"
        return "waiting"

    def window(self) -> tuple[int, int]:
        """Where to look: a failed skill runs from the previous skill's last update (or the task's creation)
        to its failure; otherwise the whole task."""
        failed = self.failed_skill
        if failed is None:
            return self.created, self.last_update
        start = self.created if failed.index == 0 else self.skills[failed.index - 1].last_change
        end = failed.time_of("failed") or failed.last_change
        return start, end

    def skill_window(self, run: SkillRun) -> tuple[int, int]:
        """From the skill's start (or the previous skill's end) to its last update."""
        prev = self.created if run.index == 0 else self.skills[run.index - 1].last_change
        return run.time_of("running") or prev, run.last_change


def build_tasks(updates: list[TaskUpdate]) -> list[Task]:
    """Tasks in the order they were created."""
    grouped: dict[str, list[TaskUpdate]] = {}
    for update in sorted(updates, key=lambda u: u.t):
        grouped.setdefault(update.task_id, []).append(update)
    tasks = []
    for order, (task_id, ups) in enumerate(grouped.items(), start=1):
        plan = ups[-1].skills
        runs = []
        for index, step in enumerate(plan):
            history: list[StatusChange] = []
            for up in ups:
                if index >= len(up.skills) or up.skills[index].skill != step.skill:
                    continue
                s = up.skills[index]
                if not history or history[-1].status.lower() != s.status.lower():
                    history.append(StatusChange(up.t, s.status, s.error_msg))
            runs.append(SkillRun(index, step.skill, dict(step.params), tuple(history)))
        instruction = next((u.instruction for u in ups if u.instruction), "")
        tasks.append(Task(task_id, instruction, tuple(ups), tuple(runs), order))
    return tasks


# A recording that holds no task (no /task_info, no goal, no start of the robot read from its logs) is still a
# recording of what the robot logged and published: a question about that (its lines of a moment, a node, a topic,
# a parameter) is answered over the whole of it, as this one task of no steps.
WHOLE = "recording"


def whole_recording(start: int, end: int) -> Task:
    """The recording from its first message to its last, as a task with no steps that nobody asked for."""
    updates = tuple(TaskUpdate(t, WHOLE, "", "valid", "", (), raw="") for t in dict.fromkeys((start, end)))
    return Task(WHOLE, "", updates, (), 1, derived=True)
