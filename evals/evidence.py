"""What the end-to-end baseline reads: the same information HEXAR has (task info, the task's /rosout lines and
the recorded values), as raw records rather than any explainer's findings (paper section V-B).

The only processing is what the original applies before any explainer: known noise lines and immediate repeats
are dropped (the navigation filter's noise list), and the text is cut to a character budget so that it fits the
model's context, keeping the start of the task and as much of its end (where failures are) as fits.
"""

from __future__ import annotations

import json

from hexar.events import EventLog, Task
from hexar.events import contract as c
from hexar.events.records import LogLine, StatusRecord
from hexar.explainers.navigation.filter import is_noise

POSE_SAMPLES = 8


def _rel(t: int, t0: int) -> str:
    return f"+{(t - t0) / 1e9:.1f}s"


def task_lines(task: Task) -> list[str]:
    out = [f"Instruction: {task.instruction or '(robot recovery task)'}",
           f"Task status: {'invalid' if not task.valid else 'valid'}"]
    if task.error_msg:
        out.append(f"Task error: {task.error_msg}")
    for run in task.skills:
        params = json.dumps(run.params, ensure_ascii=False)
        err = f" error_msg={run.error_msg!r}" if run.error_msg else ""
        out.append(f"Step {run.index + 1}: {run.skill} {params} status={run.state}{err}")
    if not task.skills:
        out.append("Plan: (empty)")
    return out


def log_lines(lines: list[LogLine], t0: int) -> list[str]:
    out: list[str] = []
    previous: dict[str, str] = {}
    for line in lines:
        if is_noise(line.msg) or previous.get(line.name) == line.msg:
            continue
        previous[line.name] = line.msg
        out.append(f"{_rel(line.t, t0)} [{line.name}] {line.level_name} {line.msg}")
    return out


def _status(r: StatusRecord, t0: int) -> str:
    values = ", ".join(f"{k}={v}" for k, v in r.data_items())
    return f"{_rel(r.t, t0)} {r.name}: {r.message}" + (f" ({values})" if values else "")


def value_lines(log: EventLog, window: tuple[int, int]) -> list[str]:
    t0, t1 = window
    out: list[str] = []
    for topic in (c.EPISODIC_MEMORY, c.SAY_EVENTS, c.PIZZA_EVENTS):
        out += [_status(r, t0) for r in log.statuses.get(topic, []) if t0 <= r.t <= t1]
    # Node settings repeat at 1 Hz: each distinct value once.
    seen: set[str] = set()
    for r in log.statuses.get(c.DIAGNOSTICS, []):
        key = f"{r.name}: {r.message} " + ", ".join(f"{k}={v}" for k, v in r.data_items())
        if t0 <= r.t <= t1 and key not in seen:
            seen.add(key)
            out.append(f"parameter {key}")
    for topic in (c.JOY_PRIORITY, c.IS_CHARGING):
        samples = log.flags.get(topic, [])
        before = [s for s in samples if s.t <= t0]
        during = [s for s in samples if t0 < s.t <= t1]
        values = ([before[-1]] if before else []) + during
        shown: list[str] = []
        for s in values:
            if not shown or shown[-1].split("=")[-1] != str(s.value):
                shown.append(f"{_rel(max(s.t, t0), t0)} {topic}={s.value}")
        out += shown
    return out


def pose_lines(log: EventLog, window: tuple[int, int]) -> list[str]:
    """A few evenly spaced localisation samples with their covariance, not all of them (10 Hz)."""
    t0, t1 = window
    poses = [p for p in log.poses if t0 <= p.t <= t1]
    step = max(1, len(poses) // POSE_SAMPLES)
    return [f"{_rel(p.t, t0)} {c.AMCL_POSE} x={p.x:.2f} y={p.y:.2f} yaw={p.yaw:.2f} "
            f"cov_x={p.cov_x:.3f} cov_y={p.cov_y:.3f} cov_yaw={p.cov_yaw:.3f}" for p in poses[::step]]


def _fit(lines: list[str], budget: int) -> list[str]:
    """Keep the first few lines and then the latest ones that fit: failures are logged at the end."""
    if _size(lines) <= budget:
        return lines
    head = lines[:5]
    used = _size(head) + 40
    tail: list[str] = []
    for line in reversed(lines[5:]):
        if used + len(line) + 1 > budget:
            break
        tail.append(line)
        used += len(line) + 1
    return [*head, f"... ({len(lines) - len(head) - len(tail)} lines left out) ...", *reversed(tail)]


def run_facts(log: EventLog, task: Task, budget_chars: int = 12_000) -> str:
    """The prompt body within `budget_chars`: task info and recorded values first (capped at half the budget),
    localisation samples if they fit, then as many log lines as the rest allows."""
    window = (task.created, task.last_update)
    task_part = ["## Task (/task_info)", *task_lines(task)]
    values = _fit(value_lines(log, window), max(200, budget_chars // 2 - _size(task_part)))
    head = [*task_part, "## Recorded values", *values]
    poses = pose_lines(log, window)
    if _size(head) + _size(poses) > budget_chars * 2 // 3:
        poses = []
    logs = log_lines([ln for ln in log.logs if window[0] <= ln.t <= window[1]], window[0])
    room = max(0, budget_chars - _size(head) - _size(poses) - 60)
    return "\n".join([*head, *poses, "## Log (/rosout, times from the task's start)", *_fit(logs, room)])


def _size(lines: list[str]) -> int:
    return sum(len(s) + 1 for s in lines)
