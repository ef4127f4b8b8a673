"""Fleet triage, one recording at a time: every task's outcome and, with no LLM, the explanation of what went wrong.

This is the unit of work of `hexar triage`: the local process pool and Ray both call `triage_recording` and get
plain rows (dicts of str/int/float/list) back, so results travel between processes without pickling events.
"""

from __future__ import annotations

import glob
import os
import re
from collections.abc import Iterable, Iterator
from datetime import UTC, datetime
from functools import cache
from pathlib import Path
from typing import Any

from hexar.errors import HexarError
from hexar.events import EventLog, EventsError, Task, read_recording
from hexar.explainers.base import Context, Explanation
from hexar.explainers.errors import ExplainerError
from hexar.explainers.registry import Registry
from hexar.workspace import find_recordings, is_recording

QUESTION = "What happened?"
# What an explainer reports when nothing went wrong: not worth a look in a fleet report.
BENIGN = {"planner.plan_ok", "navigation.nominal", "ask_human.succeeded", "tts.completed"}


class TriageError(HexarError):
    """Bad triage input: nothing to triage, a bad option, an unreadable results folder."""


@cache
def registry() -> Registry:
    """No model: explainers phrase their own template answers (the `--llm none` path)."""
    return Registry.load(None)


def notable_finding(log: EventLog, task: Task, reg: Registry) -> Explanation | None:
    """For a task that did not fail: the first explainer, in plan order, that found something worth a look
    (slow, erratic or awkward behaviour), as the agent routes an open question."""
    seen: list[str] = []
    for run in task.skills:
        for name in reg.for_module(run.skill):
            if name in seen:
                continue
            seen.append(name)
            exp = reg.get(name).explain(QUESTION, Context.for_task(log, task, reg))
            if exp.enough_information and exp.causes and not set(exp.causes) <= BENIGN:
                return exp
    return None


def _iso(t: int) -> str:
    return datetime.fromtimestamp(t / 1e9, tz=UTC).isoformat(timespec="seconds")


# A folder named by a date, with an optional time (2025-03-10, 2025-03-10_14-30, 2025-03-10T14:30:00Z): never a robot.
_DATE = re.compile(r"\d{4}-\d{2}-\d{2}(?:[T_ -]?\d{2}[-:_.]?\d{2}(?:[-:_.]?\d{2}(?:\.\d+)?)?(?:Z|[+-]\d{2}:?\d{2})?)?")
# A sentence ends at . ! or ? (and any closing quote or bracket) before a space and a capital, or at the end;
# "0.5 m" has no space after its point, and these abbreviations end no sentence.
_SENTENCE_END = re.compile(r"[.!?][\"')\]]*(?=\s+[\"'(\[]?[A-Z]|\s*$)")
_ABBREVIATIONS = ("e.g.", "i.e.", "vs.", "approx.", "cf.", "etc.", "No.", "Dr.", "St.", "Mr.", "Ms.")


def is_date(name: str) -> bool:
    return _DATE.fullmatch(name) is not None


def robot_of(rel: str) -> str:
    """Fleets keep recordings as [FLEET/]ROBOT/[DATE/...]RECORDING: the first folder of the recording's label that
    is not a date (`expand` makes every label start at or above its robot)."""
    return next((part for part in rel.split("/")[:-1] if not is_date(part)), "")


def first_sentence(text: str) -> str:
    """The one-sentence explanation of a report row: up to the first sentence end of the first line."""
    line = text.strip().split("\n")[0].strip()
    for m in _SENTENCE_END.finditer(line):
        if not line[: m.start() + 1].endswith(_ABBREVIATIONS):
            return line[: m.end()]
    return line


def task_row(log: EventLog, task: Task, rel: str, reg: Registry) -> dict[str, Any]:
    name = reg.failure_explainer(task)
    kind = "failure" if name else ""
    exp: Explanation | None = None
    if name is not None:
        exp = reg.get(name).explain(QUESTION, Context.for_task(log, task, reg))
    elif not task.is_recovery:
        exp = notable_finding(log, task, reg)
        kind = "finding" if exp else ""
    failed = task.failed_skill
    causes = list(exp.causes) if exp else []
    return {
        "recording": rel,
        "robot": robot_of(rel),
        "storage": log.storage,
        "task_id": task.task_id,
        "order": task.order,
        "instruction": task.instruction,
        "recovery": task.is_recovery,
        "outcome": task.outcome,
        "failed_skill": failed.skill if failed else "",
        "kind": kind,
        "explainer": exp.explainer if exp else "",
        "cause": causes[0] if causes else "",
        "causes": causes,
        "explanation": first_sentence(exp.text) if exp else "",
        "evidence": len(exp.evidence) if exp else 0,
        "time": _iso(task.created),
        "day": _iso(task.created)[:10],
        "t_ns": task.created,
        "duration_s": round((task.last_update - task.created) / 1e9, 3),
    }


def triage_recording(path: Path, rel: str) -> dict[str, Any]:
    """One recording's rows, or its one-line error; never raises for a bad recording."""
    try:
        log = read_recording(path)
        reg = registry()
        # A recording without tasks is readable, just not explainable: it is counted, not listed as bad.
        return {"recording": rel, "rows": [task_row(log, task, rel, reg) for task in log.tasks], "error": ""}
    except (EventsError, ExplainerError) as err:
        return {"recording": rel, "rows": [], "error": str(err).splitlines()[0] if str(err) else type(err).__name__}
    except Exception as err:  # an explainer bug on odd data must not stop a fleet run: report it as that run's
        return {"recording": rel, "rows": [], "error": f"{type(err).__name__}: {err}".splitlines()[0]}


def _matches(inputs: Iterable[str]) -> Iterator[tuple[Path, Path]]:
    """Every recording under the inputs with the folder it was found from: a plain folder itself; for a glob,
    the matched folder's parent (`fleet/robot-*` names robots); for a recording, its own folder."""
    for raw in inputs:
        matches = sorted(glob.glob(raw, recursive=True)) if glob.has_magic(raw) else [raw]
        if not matches:
            raise TriageError(f"no recordings match {raw!r}")
        for match in matches:
            path = Path(os.path.abspath(match))
            if not Path(match).exists():
                raise TriageError(f"no such folder or recording: {raw}")
            if is_recording(path):
                yield path, path.parent
            else:
                base = path.parent if glob.has_magic(raw) else path
                for rec in find_recordings(path):
                    yield rec, base


def _robot_folder(folder: Path) -> Path:
    """The nearest folder at or above `folder` that is not a date: the robot of a robot folder given directly,
    or of a glob over robots and dates."""
    while is_date(folder.name) and folder.parent != folder:
        folder = folder.parent
    return folder


def expand(inputs: Iterable[str]) -> list[tuple[Path, str]]:
    """Recordings under folders or globs, nested at any depth, each with a label unique in this run: its path under
    the inputs' common folder, starting at or above its robot (see `robot_of`)."""
    found: list[tuple[Path, Path]] = []
    seen: set[Path] = set()
    for rec, base in _matches(inputs):
        real = rec.resolve()
        if real not in seen:
            seen.add(real)
            found.append((rec, base))
    if not found:
        return []
    root = Path(os.path.commonpath([str(base) for _, base in found]))
    above = _robot_folder(root).parent  # where a label starts that has no robot folder under the common one
    labels: set[str] = set()
    named: list[tuple[Path, str]] = []
    for rec, _ in found:
        rel = rec.relative_to(root).as_posix()
        if not robot_of(rel):
            rel = rec.relative_to(above).as_posix()
        if rel in labels:  # only a folder repeating its parent's name can get here; the full path is unique
            rel = rec.as_posix().lstrip("/")
        labels.add(rel)
        named.append((rec, rel))
    return named
