"""Fleet triage, one recording at a time: every task's outcome and, with no LLM, the explanation of what went wrong.

This is the unit of work of `hexar triage`: the local pool calls `work_chunk` and Ray calls `work`; both get the
results file's JSON lines back, so results travel between processes as text, without pickling events.
"""

from __future__ import annotations

import json
import re
import sys
from datetime import UTC, datetime
from functools import cache
from pathlib import Path
from typing import Any

from hexar.causes import BENIGN
from hexar.events import EventLog, EventsError, Task, read_recording
from hexar.explainers.base import Context, Explanation
from hexar.explainers.errors import ExplainerError
from hexar.explainers.pizza.explainer import PizzaRecommenderExplainer
from hexar.explainers.registry import Registry
from hexar.fleet.inputs import robot_of

QUESTION = "What happened?"
# Explainers whose answer needs scikit-learn and LIME (a second and more to import).
NEEDS_SCIKIT_LEARN = frozenset({PizzaRecommenderExplainer.name})


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


# A sentence ends at . ! or ? (and any closing quote or bracket) before a space and a capital, or at the end;
# "0.5 m" has no space after its point, and these abbreviations end no sentence.
_SENTENCE_END = re.compile(r"[.!?][\"')\]]*(?=\s+[\"'(\[]?[A-Z]|\s*$)")
_ABBREVIATIONS = ("e.g.", "i.e.", "vs.", "approx.", "cf.", "etc.", "No.", "Dr.", "St.", "Mr.", "Ms.")


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


def needs_scikit_learn(log: EventLog, reg: Registry) -> bool:
    """Whether explaining this recording may call an explainer that imports scikit-learn and LIME (the pizza
    recommender): a pool keeps that one-second import to one worker. Erring either way only moves work, never
    changes a row: a worker that meets such an explainer anyway imports the libraries itself."""
    for task in log.tasks:
        if reg.failure_explainer(task) in NEEDS_SCIKIT_LEARN:
            return True
        if not task.is_recovery and any(NEEDS_SCIKIT_LEARN.intersection(reg.for_module(run.skill))
                                         for run in task.skills):
            return True
    return False


class _LeftForScikitLearn(Exception):
    """A light worker's recording that needs scikit-learn: handed back, not triaged."""


def triage_recording(path: Path, rel: str, light: bool = False) -> dict[str, Any]:
    """One recording's rows, or its one-line error; never raises for a bad recording. `light`: raises
    _LeftForScikitLearn instead when the recording needs scikit-learn and this process has not imported it."""
    try:
        log = read_recording(path)
        reg = registry()
        if light and "sklearn" not in sys.modules and needs_scikit_learn(log, reg):
            raise _LeftForScikitLearn(rel)
        # A recording without tasks is readable, just not explainable: it is counted, not listed as bad.
        return {"recording": rel, "rows": [task_row(log, task, rel, reg) for task in log.tasks], "error": "",
                "recovered": [w for w in log.warnings if w.startswith("recovered:")]}
    except _LeftForScikitLearn:
        raise
    except (EventsError, ExplainerError) as err:
        return {"recording": rel, "rows": [], "error": str(err).splitlines()[0] if str(err) else type(err).__name__}
    except Exception as err:  # an explainer bug on odd data must not stop a fleet run: report it as that run's
        return {"recording": rel, "rows": [], "error": f"{type(err).__name__}: {err}".splitlines()[0]}


def work(path: str, rel: str) -> str:
    """One line of the results file: `triage_recording` keyed by the recording's resolved path. Workers send this
    text rather than the rows, so the parent writes it as it comes without encoding it again."""
    lines, _ = work_chunk([(path, rel)], light=False)
    return lines[0]


def work_chunk(chunk: list[tuple[str, str]], light: bool) -> tuple[list[str], list[tuple[str, str]]]:
    """A pool worker's unit: the lines of a few recordings, and those left for a worker with scikit-learn."""
    lines: list[str] = []
    left: list[tuple[str, str]] = []
    for path, rel in chunk:
        try:
            result = triage_recording(Path(path), rel, light)
        except _LeftForScikitLearn:
            left.append((path, rel))
            continue
        result["key"] = path
        lines.append(json.dumps(result, ensure_ascii=False))
    return lines, left


def warm() -> None:
    """Load what every recording needs before forking (the explainers, the help-seeking causal model), so that
    forked workers share it instead of each building its own."""
    from hexar.explainers.ask_human.explainer import shipped_model

    registry()
    shipped_model()

