"""Human-readable and JSON renderings of a recording for `hexar inspect` and `hexar runs`."""

from __future__ import annotations

from typing import Any

from rich.console import Console
from rich.padding import Padding
from rich.table import Table

from hexar.events.log import NO_TASK_SOURCES, EventLog, last_error
from hexar.events.records import clock
from hexar.events.tasks import Task
from hexar.safe_text import clip, json_dumps, safe, visible

__all__ = ["clock", "json_dumps", "log_dict", "print_inspection", "safe", "task_dict", "visible"]


def task_dict(task: Task) -> dict[str, Any]:
    start, end = task.window()
    return {
        "task_id": task.task_id,
        "order": task.order,
        "instruction": task.instruction,
        "recovery": task.is_recovery,
        "derived_from_nav2": task.derived,
        "valid": task.valid,
        "error_msg": task.error_msg,
        "outcome": task.outcome,
        "created_ns": task.created,
        "last_update_ns": task.last_update,
        "window_ns": [start, end],
        "skills": [
            {
                "index": run.index,
                "skill": run.skill,
                "params": run.params,
                "status": run.state,
                "error_msg": run.error_msg,
                "history": [{"t_ns": ch.t, "status": ch.status, "error_msg": ch.error_msg} for ch in run.history],
            }
            for run in task.skills
        ],
    }


def log_dict(log: EventLog) -> dict[str, Any]:
    return {
        "path": str(log.path),
        "storage": log.storage,
        "start_ns": log.start,
        "end_ns": log.end,
        "duration_s": round((log.end - log.start) / 1e9, 3),
        "topics": [{"topic": i.topic, "type": i.type, "count": i.count} for i in log.topics.values()],
        "tasks": [task_dict(t) for t in log.tasks],
        "parameters": [{"t_ns": p.t, "node": p.node, "name": p.name, "value": p.said, "change": p.change}
                       for p in log.parameters],
        "warnings": list(log.warnings),
    }


def print_inspection(console: Console, log: EventLog) -> None:
    console.print(f"[bold]{safe(log.path.name)}[/bold]  {log.storage}, {(log.end - log.start) / 1e9:.1f} s, "
                  f"{clock(log.start)} to {clock(log.end)} UTC")
    topics = Table(title="Topics", title_justify="left")
    topics.add_column("topic", overflow="fold")
    topics.add_column("type", overflow="fold")  # wrapped, never cut: the type is what a user looks up
    topics.add_column("messages", justify="right", no_wrap=True)
    for info in log.topics.values():
        topics.add_row(safe(info.topic), safe(info.type), str(info.count))
    console.print(topics)
    if log.parameters:
        held = log.settings(log.end)
        changed = sum(p.change == "changed" for p in held.values())
        console.print(f"Parameters: {len(held)} of {len({node for node, _ in held})} nodes, as they announced them on "
                      f"/parameter_events ({changed} changed while running); --json lists them.")
    for task in log.tasks:
        label = "recovery task" if task.is_recovery else f"\"{safe(clip(task.instruction))}\""
        if task.derived and task.instruction.endswith(" (derived from Nav2)"):
            goal = safe(clip(task.instruction.removesuffix(" (derived from Nav2)")))
            label = f"Nav2 goal: {goal} [dim](derived from Nav2: no /task_info)[/dim]"
        elif task.derived:  # an arm goal or the robot's start (events/arm_goals.py): its instruction says from what
            label = f"{safe(clip(task.instruction))} [dim](no /task_info)[/dim]"
        colour = {"succeeded": "green", "failed": "red", "invalid": "red"}.get(task.outcome, "yellow")
        console.print(f"\n[bold]Task {task.order}[/bold] {safe(task.task_id)}: {label}  "
                      f"[{colour}]{safe(task.outcome)}[/{colour}]")
        if not task.valid:
            console.print(f"  invalid plan: {safe(clip(task.error_msg))}")
        console.print(_steps(log, task))
        start, end = task.window()
        console.print(f"  window: {clock(start)} to {clock(end)}")
    if not log.tasks:
        console.print(f"[yellow]No task to explain: this recording has no /task_info, {NO_TASK_SOURCES}"
                      f"{safe(last_error(log.logs))}.[/yellow]")
    for warning in log.warnings:
        console.print(f"[yellow]warning:[/yellow] {safe(warning)}")


def _steps(log: EventLog, task: Task) -> Table:
    """One row per step: its number, then its name, status and times on one line (a skill name is never cut),
    with parameters, error and the step's own recorded facts wrapped below."""
    from hexar.explainers.recorded import step_facts

    grid = Table.grid(padding=(0, 1))
    grid.add_column(justify="right", no_wrap=True)
    grid.add_column(overflow="fold")
    for run in task.skills:
        started = run.time_of("running")
        ended = run.time_of(run.state) if run.state in {"succeeded", "failed"} else None
        when = f"{clock(started)} to {clock(ended)}" if started and ended else clock(started) if started else ""
        colour = {"succeeded": "green", "failed": "red"}.get(run.state, "yellow")
        grid.add_row(f"  {run.index + 1}.", f"[bold]{safe(run.skill)}[/bold]  [{colour}]{safe(run.state)}[/{colour}]"
                     f"  {when}")
        for key, value in run.params.items():
            grid.add_row("", Padding(f"{safe(str(key))}: {safe(repr(value))}", (0, 0, 0, 2)))
        if run.error_msg:
            grid.add_row("", Padding(f"[red]error:[/red] {safe(clip(run.error_msg))}", (0, 0, 0, 2)))
        for fact in step_facts(log, task, run):
            grid.add_row("", Padding(f"[dim]{safe(fact)}[/dim]", (0, 0, 0, 2)))
    return grid
