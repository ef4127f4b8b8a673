"""A folder of recordings served read-only to an outside client (`hexar mcp`): paths confined to the folder,
answers bounded in size and paged, every bad input a one-line error.

Nothing here imports the MCP SDK: the server module maps these calls onto tools and resources.
"""

from __future__ import annotations

import os
import re
from collections import OrderedDict
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from hexar.confined import leaving
from hexar.errors import HexarError
from hexar.events import EventLog, EventsError, Task, read_recording, read_tasks
from hexar.events import contract as c
from hexar.events.recover import STORAGE, holds_storage, loose_storage
from hexar.render import clock, task_dict

PAGE = 50
"""The most log lines, timeline entries, evidence items or recordings one call returns; the rest is paged."""
CACHED = 8  # decoded recordings and agent sessions kept in memory


class WorkspaceError(HexarError):
    """A request the workspace refuses: a bad or outside path, a bad page, an unknown task or explainer."""


class OutsideFolderError(WorkspaceError):
    """The path leaves the served folder (`..`, an absolute path elsewhere, or a symlink pointing out)."""


def is_recording(path: Path) -> bool:
    """A rosbag2 folder (with its metadata.yaml, or storage files whose recorder never wrote it), a ROS 1 bag, or
    a storage file that is a recording of its own (MCAP files side by side that no metadata.yaml joins)."""
    if path.is_dir():
        return (path / "metadata.yaml").is_file() or holds_storage(path)
    return path.is_file() and (path.suffix == ".bag" or (path.suffix in STORAGE and path in loose_storage(path.parent)))


NEVER_RECORDINGS = frozenset({".git", ".hg", ".svn", "__pycache__", "node_modules", ".mypy_cache", ".ruff_cache",
                              ".pytest_cache", ".tox", ".nox"})


def find_recordings(root: Path, follow_links: bool = False, linked: bool = False) -> Iterator[Path]:
    """Every rosbag2 folder, ROS 1 bag and storage file of its own under `root`, nested at any depth, in name
    order. Symlinked folders are
    followed only with `follow_links` (a fleet folder of links to recordings), each real folder once, so a link
    cannot lead the walk round in circles; without it, a link cannot lead the walk out of `root`, and a link that
    is itself a recording is yielded only with `linked` (for a caller that refuses what links out, by name). A
    folder the walk cannot open is yielded too, so the caller reports it instead of skipping it."""
    seen: set[str] = set()
    unreadable: list[Path] = []

    def failed(err: OSError) -> None:
        if err.filename:
            unreadable.append(Path(err.filename))

    for dirpath, dirnames, filenames in os.walk(root, onerror=failed, followlinks=follow_links):
        here = Path(dirpath)
        real = os.path.realpath(here)
        if real in seen:
            dirnames[:] = []
            continue
        seen.add(real)
        yield from unreadable
        unreadable.clear()
        if is_recording(here):
            dirnames[:] = []
            yield here
            continue
        # a virtualenv, a repository's history and caches hold thousands of folders and never a recording
        dirnames[:] = sorted(d for d in dirnames
                             if d not in NEVER_RECORDINGS and not (here / d / "pyvenv.cfg").is_file())
        if linked and not follow_links:
            yield from (here / name for name in dirnames if (here / name).is_symlink() and is_recording(here / name))
        for name in sorted(filenames):
            if name.endswith(".bag"):
                yield here / name
        yield from loose_storage(here)
    yield from unreadable


def recordings_under(folder: Path) -> list[Path]:
    """What a person means by the recordings in a folder (`hexar runs`, `hexar web`, `ask --runs`): the folder
    itself when it is one, else every recording under it at any depth (a `robot/date/run` layout as triage reads
    it) and each link in it to a recording, in natural order of their paths under it (bagfile_2_1 before
    bagfile_10_1). A folder the walk cannot open is among them, for the caller to report."""
    if is_recording(folder):
        return [folder]

    def natural(path: Path) -> list[int | str]:
        return [int(p) if p.isdigit() else p.lower() for p in re.split(r"(\d+)", recording_name(folder, path))]

    return sorted(find_recordings(folder, linked=True), key=natural)


def recording_name(folder: Path, path: Path) -> str:
    """A recording's name among `recordings_under(folder)`: its path under the folder, or its own name when the
    folder is the recording."""
    return path.name if path == folder else path.relative_to(folder).as_posix()


def _page(items: list[Any], offset: int, limit: int, key: str) -> dict[str, Any]:
    if offset < 0:
        raise WorkspaceError(f"offset must be 0 or more, not {offset}")
    if not 1 <= limit <= PAGE:
        raise WorkspaceError(f"limit must be between 1 and {PAGE}, not {limit}")
    chunk = items[offset:offset + limit]
    nxt = offset + len(chunk)
    return {key: chunk, "total": len(items), "offset": offset, "next_offset": nxt if nxt < len(items) else None}


def _task_row(t: Task) -> dict[str, Any]:
    return {"task_id": t.task_id, "order": t.order, "instruction": t.instruction, "outcome": t.outcome,
            "failed_skill": t.failed_skill.skill if t.failed_skill else None}


class Workspace:
    """The recordings under one folder, as a client may see them."""

    def __init__(self, root: Path, llm: str = "none", explainers: Path | None = None) -> None:
        if not root.is_dir():
            raise WorkspaceError(f"not a folder: {root}")
        self.root = root.resolve()
        self.llm = llm
        self.explainers = explainers  # a modules.toml adding explainers, as for the agent
        self._logs: OrderedDict[tuple[Path, int], EventLog] = OrderedDict()
        self._sessions: OrderedDict[Path, Any] = OrderedDict()
        self._registry: Any = None

    # paths -------------------------------------------------------------------------------------------------
    def resolve(self, recording: str) -> Path:
        """The recording's real path, which must lie inside the folder (symlinks resolved first)."""
        if not recording or not recording.strip():
            raise WorkspaceError("give a recording: a path relative to the served folder (see list_recordings)")
        if "\x00" in recording:
            raise WorkspaceError("a recording path cannot contain a NUL character")
        raw = Path(recording)
        path = (raw if raw.is_absolute() else self.root / raw).resolve()
        if path != self.root and not path.is_relative_to(self.root):
            raise OutsideFolderError(f"{recording!r} is outside the served folder")
        if not path.exists():
            raise WorkspaceError(f"no recording {recording!r} in the served folder")
        if path.is_file() and path.suffix in STORAGE and not is_recording(path):
            path = path.parent  # a file of a recording: the recording is its folder
        if not is_recording(path):
            raise WorkspaceError(f"{recording!r} is not a recording (a rosbag2 folder or a ROS 1 .bag)")
        out = leaving(self.root, path)  # the folder is inside; its metadata.yaml or .db3 may still link out
        if out is not None:
            raise OutsideFolderError(f"{recording!r} holds {out.name!r}, a link to a file outside the served folder")
        return path

    def name(self, path: Path) -> str:
        return path.relative_to(self.root).as_posix() if path != self.root else "."

    def log(self, recording: str) -> EventLog:
        path = self.resolve(recording)
        key = (path, max(p.stat().st_mtime_ns for p in ([path, *path.iterdir()] if path.is_dir() else [path])))
        if key not in self._logs:
            self._logs[key] = read_recording(path)
            if len(self._logs) > CACHED:
                self._logs.popitem(last=False)
        self._logs.move_to_end(key)
        return self._logs[key]

    def task(self, recording: str, task: str | None) -> tuple[EventLog, Task]:
        log = self.log(recording)
        return log, log.task(task or None)

    # tools -------------------------------------------------------------------------------------------------
    def list_recordings(self, offset: int = 0, limit: int = PAGE) -> dict[str, Any]:
        """Recordings with their tasks (id, instruction, outcome); an unreadable one carries its error."""
        paths = list(find_recordings(self.root))
        page = _page(paths, offset, limit, "recordings")
        rows: list[dict[str, Any]] = []
        for path in page["recordings"]:
            row: dict[str, Any] = {"recording": self.name(path)}
            out = leaving(self.root, path)
            if out is not None:
                row["error"] = f"{out.name!r} is a link to a file outside the served folder: not read"
                rows.append(row)
                continue
            try:
                log = read_tasks(path)  # one task per Nav2 goal without /task_info, as `hexar runs` sees it
                tasks = _page(log.tasks, 0, PAGE, "tasks")  # the rest through list_tasks
                row.update({"tasks": [_task_row(t) for t in tasks["tasks"]], "tasks_total": tasks["total"],
                            "tasks_next_offset": tasks["next_offset"]})
            except EventsError as err:
                row["error"] = str(err).replace(str(self.root) + os.sep, "")
            rows.append(row)
        page["recordings"] = rows
        return page

    def list_tasks(self, recording: str, offset: int = 0, limit: int = PAGE) -> dict[str, Any]:
        """One page of a recording's tasks (id, order, instruction, outcome, failed skill)."""
        log = self.log(recording)
        page = _page(log.tasks, offset, limit, "tasks")
        page["tasks"] = [_task_row(t) for t in page["tasks"]]
        page["recording"] = self.name(log.path)
        return page

    def inspect_task(self, recording: str, task: str | None = None, tasks_offset: int = 0) -> dict[str, Any]:
        """The task's plan with each step's status history and times, and the window HEXAR explains; the ids
        of the recording's other tasks one page at a time."""
        log, found = self.task(recording, task)
        out = task_dict(found)
        out["recording"] = self.name(log.path)
        others = _page([t.task_id for t in log.tasks], tasks_offset, PAGE, "ids")
        out.update({"tasks_in_recording": others["ids"], "tasks_total": others["total"],
                    "tasks_next_offset": others["next_offset"]})
        out["created"] = clock(found.created)
        return out

    def registry(self) -> Any:
        if self._registry is None:
            from hexar.explainers.registry import Registry

            self._registry = Registry.load(config=self.explainers)
        return self._registry

    def explain(self, explainer: str, recording: str, question: str, task: str | None = None,
                evidence_offset: int = 0) -> dict[str, Any]:
        """One explainer's structured Explanation of one task, its evidence paged."""
        from hexar.agent.questions import check_question
        from hexar.explainers.base import Context

        q = check_question(question)
        log, found = self.task(recording, task)
        registry = self.registry()
        exp = registry.get(explainer).explain(q, Context.for_task(log, found, registry))
        out: dict[str, Any] = exp.model_dump()
        evidence = _page(out.pop("evidence"), evidence_offset, PAGE, "evidence")
        out.update({"evidence": evidence["evidence"], "evidence_total": evidence["total"],
                    "evidence_next_offset": evidence["next_offset"], "task_id": found.task_id,
                    "recording": self.name(log.path)})
        return out

    def ask(self, recording: str, question: str, task: str | None = None, thread: str | None = None,
            evidence_offset: int = 0) -> dict[str, Any]:
        """The whole agent (failure check, routing, guard, threads) on one question; the thread id comes back."""
        from hexar.agent.context import RunSettings
        from hexar.agent.errors import BadQuestionError
        from hexar.agent.session import Session

        path = self.resolve(recording)
        session = self._sessions.get(path)
        if session is None:
            session = Session(RunSettings(recording=path, llm=self.llm, registry_config=self.explainers))
            self._sessions[path] = session
            if len(self._sessions) > CACHED:
                self._sessions.popitem(last=False)
        self._sessions.move_to_end(path)
        result: dict[str, Any] = session.ask(question, thread=thread or None, task=task or None)
        if result["error"]:
            raise BadQuestionError(result["error"])
        evidence = _page(result["evidence"], evidence_offset, PAGE, "evidence")
        result.update({"evidence": evidence["evidence"], "evidence_total": evidence["total"],
                       "evidence_next_offset": evidence["next_offset"], "recording": self.name(path)})
        return result

    def timeline(self, recording: str, offset: int = 0, limit: int = PAGE) -> dict[str, Any]:
        """Task and skill status changes, log lines and flag changes in time order, one page at a time."""
        log = self.log(recording)
        entries: list[tuple[int, str, str]] = []
        for t in log.tasks:
            entries.append((t.created, c.TASK_INFO, f"task {t.task_id} created: {t.instruction or '(recovery)'}"))
            if not t.valid:
                entries.append((t.last_update, c.TASK_INFO, f"task {t.task_id} invalid: {t.error_msg}"))
            for run in t.skills:
                for ch in run.history:
                    err = f" ({ch.error_msg})" if ch.error_msg else ""
                    entries.append((ch.t, c.TASK_INFO, f"step {run.index + 1} {run.skill}: {ch.status}{err}"))
        entries += [(line.t, line.origin, line.render()) for line in log.logs]
        for topic, samples in log.flags.items():
            previous: bool | None = None
            for s in samples:
                if s.value != previous:
                    entries.append((s.t, topic, f"{topic} = {s.value}"))
                    previous = s.value
        entries.sort(key=lambda e: e[0])
        rows = [{"t": t, "clock": clock(t), "topic": topic, "item": item} for t, topic, item in entries]
        page = _page(rows, offset, limit, "entries")
        page["recording"] = self.name(log.path)
        return page

    def contract(self, recording: str) -> dict[str, Any]:
        """Which topics of the HEXAR topic contract the recording has, with the right type, and how many."""
        log = self.log(recording)
        rows = []
        for spec in c.CONTRACT:
            info = log.topics.get(spec.topic)
            if info is None:
                status = "missing"
            elif info.type not in c.ACCEPTED_TYPES[spec.topic]:
                status = "wrong type"
            else:
                status = "ok"
            rows.append({"topic": spec.topic, "expected_type": spec.type, "recorded_type": info.type if info else None,
                         "messages": info.count if info else 0, "status": status})
        others = [{"topic": i.topic, "type": i.type, "messages": i.count}
                  for i in log.topics.values() if i.topic not in c.ALL_TOPICS]
        return {"recording": self.name(log.path), "storage": log.storage, "contract": rows,
                "other_topics": others[:PAGE], "other_topics_total": len(others),
                "explainable": bool(log.tasks), "warnings": log.warnings[:PAGE]}
