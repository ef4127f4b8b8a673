"""What the page shows, as JSON: the runs under a folder, one run's task, and its explainers' findings.

Everything recorded is passed through as data; the page puts it into the DOM as text, never as markup.
"""

from __future__ import annotations

import re
import threading
from bisect import bisect_left, bisect_right
from pathlib import Path
from typing import Any

from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.events.records import PoseSample
from hexar.events.tasks import Task
from hexar.web.errors import WebError
from hexar.web.explain import GENERIC_QUESTION
from hexar.web.runview import POOR_COV, SIGMAS, spans, track

MAX_POINTS = 1500  # the page's path: an hour of 5 Hz poses thinned to what a 700-pixel drawing can show
MAX_ELLIPSES = 60
MAX_LINES = 5000  # "all filtered lines" of an hour-long task: the page lists this many and says how many more
LIME_LINE = re.compile(r"^\s+(\S+), (present|absent), ([+-]\d+\.\d+)$")


def recordings(root: Path) -> list[Path]:
    """The recordings the page lists: the folder itself when it is one, else every recording under it at any depth
    (rosbag2 folders, a crashed one without metadata.yaml too, and ROS 1 bags; each link in it to a recording, which
    the page refuses by name when it leads out), in natural order of their paths; a folder that holds no recording
    (a virtualenv) is not one."""
    from hexar.workspace import is_recording, recordings_under

    if not root.is_dir() and not is_recording(root):
        raise WebError(f"not a folder: {root}")
    return recordings_under(root)


def explainers_for(registry: Any, task: Task) -> list[str]:
    """Every explainer with something to say about the task: the one the agent's failure check picks first (a
    wrong plan goes to the planner even when every step succeeded), then every started module's, and the planner
    whenever it faults the plan, so what `hexar ask` and triage find is on the page too."""
    from hexar.explainers.planner import task_findings

    first = registry.failure_explainer(task)
    names: list[str] = [first] if first else []
    if task.valid:
        for skill in [r.skill for r in task.skills if r.state != "waiting"]:
            names.extend(n for n in registry.for_module(skill) if n not in names)
    if "planner" not in names and (not names or task_findings(task)):
        names.append("planner")
    return names


def cause_words(cause: str) -> str:
    """A cause id in words for the page ("the plan used a skill the robot does not have"): its meaning in the
    cause vocabulary, else the id's own words ("plan ok")."""
    from hexar.causes import vocabulary

    known = vocabulary().get(cause)
    return known.means if known is not None else cause.split(".", 1)[-1].replace("_", " ")


def verdict(task: Task) -> str:
    """The outcome a person should see: a task that ran to its end on a plan that did not match the request
    (or asked the impossible) succeeded only as the robot counts it, so it is shown as "wrong plan"."""
    from hexar.explainers.planner import task_findings

    if task.outcome == "succeeded" and task.valid and task_findings(task):
        return "wrong plan"
    return task.outcome


class Findings:
    """The explainers' Explanation objects per (recording, task), computed once; explainers are not
    thread-safe (pgmpy inference, LIME's RandomState), so one lock serialises them. A cache that lives only
    as long as one live snapshot shares its lock and registry with the page's (`shared`)."""

    def __init__(self, shared: Findings | None = None) -> None:
        self._lock: threading.Lock = shared._lock if shared is not None else threading.Lock()
        self._shared = shared
        self._cache: dict[tuple[str, str], list[dict[str, Any]]] = {}
        self._registry: Any = None

    def registry(self) -> Any:
        from hexar.explainers.registry import Registry

        if self._shared is not None:
            return self._shared.registry()
        if self._registry is None:
            self._registry = Registry.load()
        return self._registry

    def modules(self, task: Task) -> list[str]:
        """The robot modules (explainers) the task's plan used, for the runs list's module filter."""
        reg = self.registry()
        return sorted({name for run in task.skills for name in reg.for_module(run.skill)})

    def cached(self, key: tuple[str, str]) -> list[dict[str, Any]] | None:
        return self._cache.get(key)

    def get(self, name: str, log: EventLog, task: Task) -> list[dict[str, Any]]:
        key = (name, task.task_id)
        if key in self._cache:
            return self._cache[key]
        from hexar.explainers.base import Context

        with self._lock:
            if key in self._cache:
                return self._cache[key]
            registry = self.registry()
            context = Context.for_task(log, task, registry)
            found = [registry.get(n).explain(GENERIC_QUESTION, context).model_dump()
                     for n in explainers_for(registry, task)]
            self._cache[key] = found
            return found


def _records(log: EventLog, topic: str, window: tuple[int, int]) -> list[dict[str, Any]]:
    records = log.statuses.get(topic, [])
    times = log.times(f"status:{topic}", records)
    lo, hi = bisect_left(times, window[0]), bisect_right(times, window[1])
    return [{"t_ns": r.t, "message": r.message, "values": [list(kv) for kv in r.data_items()]}
            for r in records[lo:hi]]


def _flags(log: EventLog, window: tuple[int, int]) -> list[dict[str, Any]]:
    out = []
    for topic in (c.JOY_PRIORITY, c.IS_CHARGING):
        samples = log.flags.get(topic, [])
        if not samples:
            continue
        times = log.times(f"flag:{topic}", samples)
        i = bisect_right(times, window[0])
        at_start = samples[i - 1].value if i else None
        changes = [{"t_ns": s.t, "value": s.value} for s in samples[i:bisect_right(times, window[1])]
                   if s.value != at_start]
        out.append({"topic": topic, "at_start": at_start, "changes": changes[:50]})
    return out


def _pizza(findings: list[dict[str, Any]], log: EventLog, window: tuple[int, int]) -> dict[str, Any] | None:
    pizza = next((f for f in findings if f["explainer"] == "pizza_recommender"), None)
    if pizza is None:
        return None
    weights = [{"ingredient": m[1], "present": m[2] == "present", "weight": float(m[3])}
               for line in pizza.get("figures", []) if (m := LIME_LINE.match(line))]
    recommended = next((v for r in _records(log, c.PIZZA_EVENTS, window) for k, v in r["values"]
                        if k == "recommended_pizza"), None)
    return {"recommended": recommended, "weights": weights, "text": pizza["text"]}


def _events(findings: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """The evidence of every finding as timeline rows, one row per recorded item, with every cause citing it."""
    rows: dict[str, dict[str, Any]] = {}
    for f in findings:
        for ev in f["evidence"]:
            key = f"{ev['topic']}|{ev['t']}"
            row = rows.setdefault(key, {"key": key, "t_ns": ev["t"], "topic": ev["topic"], "item": ev["item"],
                                        "causes": []})
            if ev["cause"] not in row["causes"]:
                row["causes"].append(ev["cause"])
    return sorted(rows.values(), key=lambda r: (r["t_ns"], r["key"]))


def _path(task: Task, poses: list[PoseSample]) -> dict[str, Any]:
    """Path points as [seconds from the task's start, x, y] and 2-sigma ellipses as [x, y, rx, ry, poor]."""
    step = max(1, -(-len(poses) // MAX_POINTS))
    thinned = poses[::step] + ([poses[-1]] if poses and (len(poses) - 1) % step else [])
    every = max(1, len(poses) // MAX_ELLIPSES)
    return {
        "points": [[round((p.t - task.created) / 1e9, 3), p.x, p.y] for p in thinned],
        "ellipses": [[p.x, p.y, SIGMAS * max(p.cov_x, 0.0) ** 0.5, SIGMAS * max(p.cov_y, 0.0) ** 0.5,
                      max(p.cov_xy, p.cov_yaw) > POOR_COV] for p in poses[::every]],
    }


def _pose(p: PoseSample | None) -> dict[str, Any] | None:
    return None if p is None else {"t_ns": p.t, "x": p.x, "y": p.y, "cov_xy": p.cov_xy}


def task_summary(task: Task) -> dict[str, Any]:
    """`outcome` as the robot reported it; `verdict` what the page shows (see `verdict`)."""
    return {"task_id": task.task_id, "order": task.order, "instruction": task.instruction,
            "outcome": task.outcome, "verdict": verdict(task), "recovery": task.is_recovery, "valid": task.valid,
            "error_msg": task.error_msg}


def run_detail(name: str, log: EventLog, task: Task, findings: list[dict[str, Any]]) -> dict[str, Any]:
    window = (task.created, task.last_update)
    tr = track(log, task)
    return {
        "recording": name,
        "storage": log.storage,
        "start_ns": log.start,
        "duration_s": round((log.end - log.start) / 1e9, 3),
        "warnings": list(log.warnings),
        "tasks": [task_summary(t) for t in log.tasks],
        "task": {**task_summary(task), "created_ns": task.created, "last_update_ns": task.last_update,
                 "window_ns": list(task.window())},
        "spans": [s.as_dict() for s in spans(task)],
        "findings": findings,
        "cause_words": {cid: cause_words(cid) for f in findings for cid in f["causes"]},
        "events": _events(findings),
        "flags": _flags(log, window),
        "ask_human": _records(log, c.EPISODIC_MEMORY, window),
        "tts": _records(log, c.SAY_EVENTS, window),
        "pizza": _pizza(findings, log, window),
        "path": {**_path(task, tr.poses), "poses": len(tr.poses), "stop": _pose(tr.stop), "stop_label": tr.stop_label,
                 "trips": [{"index": t.index, "skill": t.skill, "status": t.status, "begin": _pose(t.begin),
                            "end": _pose(t.end)} for t in tr.trips]},
    }


def filtered_lines(log: EventLog, task: Task) -> dict[str, Any]:
    """The task's log lines (/rosout, and launch.log's where the recording has one) through the navigation
    explainer's filter (its loggers, no noise, no repeats)."""
    from hexar.explainers.navigation.filter import filter_logs

    times = log.times("logs", log.logs)
    window = log.logs[bisect_left(times, task.created):bisect_right(times, task.last_update)]
    kept = filter_logs(window)
    return {"total": len(window), "kept": len(kept), "shown": min(len(kept), MAX_LINES),
            "lines": [{"key": f"{ln.origin}|{ln.t}", "t_ns": ln.t, "topic": ln.origin, "item": ln.render(),
                       "level": ln.level_name} for ln in kept[:MAX_LINES]]}
