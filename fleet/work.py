"""Fleet triage, one recording at a time: every task's outcome and, with no LLM, the explanation of what went wrong.

This is the unit of work of `hexar triage`: the local process pool and Ray both call `work` and get plain rows
(dicts of str/int/float/list) back, so results travel between processes without pickling events.
"""

from __future__ import annotations

import re
from datetime import UTC, datetime
from functools import cache
from pathlib import Path
from typing import Any

from hexar.events import EventLog, EventsError, Task, read_recording
from hexar.explainers.base import Context, Explanation
from hexar.explainers.errors import ExplainerError
from hexar.explainers.registry import Registry
from hexar.fleet.inputs import robot_of

QUESTION = "What happened?"
# What an explainer reports when nothing went wrong: not worth a look in a fleet report.
BENIGN = {"planner.plan_ok", "navigation.nominal", "ask_human.succeeded", "tts.completed"}


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


def triage_recording(path: Path, rel: str) -> dict[str, Any]:
    """One recording's rows, or its one-line error; never raises for a bad recording."""
    try:
        log = read_recording(path)
        reg = registry()
        # A recording without tasks is readable, just not explainable: it is counted, not listed as bad.
        return {"recording": rel, "rows": [task_row(log, task, rel, reg) for task in log.tasks], "error": "",
                "recovered": [w for w in log.warnings if w.startswith("recovered:")]}
    except (EventsError, ExplainerError) as err:
        return {"recording": rel, "rows": [], "error": str(err).splitlines()[0] if str(err) else type(err).__name__}
    except Exception as err:  # an explainer bug on odd data must not stop a fleet run: report it as that run's
        return {"recording": rel, "rows": [], "error": f"{type(err).__name__}: {err}".splitlines()[0]}


def work(path: str, rel: str) -> dict[str, Any]:
    """`triage_recording` keyed by the recording's resolved path, as the results file keeps it."""
    result = triage_recording(Path(path), rel)
    result["key"] = path
    return result


def warm() -> None:
    """Load the explainers and their models before forking (the help-seeking causal model; the pizza tree, with
    scikit-learn and LIME, a second and more to import): forked workers share them instead of each loading its own."""
    import lime.lime_tabular  # noqa: F401 - what a pizza explanation imports

    from hexar.explainers.ask_human.explainer import shipped_model
    from hexar.explainers.pizza.recommender import default_recommender

    registry()
    shipped_model()
    default_recommender()
