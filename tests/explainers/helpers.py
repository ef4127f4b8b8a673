"""Recordings of real log lines for the log explainers' tests: (seconds, logger, level, text) rows on /rosout,
written with rosbags, then one explainer asked about the recording's task."""

from __future__ import annotations

from pathlib import Path

from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events import read_recording
from hexar.events.log import EventLog
from hexar.events.tasks import Task
from hexar.explainers.base import Context, Explanation
from hexar.explainers.registry import Registry

T0 = 1_700_000_000_000_000_000
Line = tuple[float, str, int, str]


def write_lines(tmp_path: Path, lines: list[Line], b: BagBuilder | None = None) -> EventLog:
    """The lines, `s` seconds after T0 each, added to `b` (a new recording without one) and read back."""
    b = b or BagBuilder()
    for s, name, level, msg in lines:
        b.log(T0 + sec_ns(s), name, level, msg)
    return read_recording(b.write(tmp_path / "run"))


def explain(log: EventLog, explainer: str, question: str) -> tuple[Task, Explanation]:
    """The recording's task and what `explainer` answers about it."""
    registry = Registry.load()
    task = log.task()
    return task, registry.get(explainer).explain(question, Context.for_task(log, task, registry))


def derived_start(tmp_path: Path, lines: list[Line]) -> Explanation:
    """The lines alone (no /task_info, no goal): the robot's start is derived from them and failed; what `control`
    answers about it."""
    log = write_lines(tmp_path, lines)
    assert [t.skills[0].skill for t in log.tasks] == ["bring_up_controllers"]
    task, found = explain(log, "control", "Why didn't that work?")
    assert task.outcome == "failed"
    return found


def claimed(found: Explanation) -> set[str]:
    """The causes the answer's text affirms (the claims reader's ids, less the generic claim.* ones)."""
    from hexar.claims import read_claims

    return {c for c in read_claims(found.text).affirmed if not c.startswith("claim.")}


def console_lines(console: str) -> list[Line]:
    """A pasted console's records (events/console.py), timed from its first stamp plus half a second; a record
    without a stamp at that first time."""
    from hexar.events.console import parse_console, stamped

    records = stamped(parse_console(console))
    first = min(r.stamp_ns or 0 for r in records)
    return [(((r.stamp_ns or first) - first) / 1e9 + 0.5, r.name or r.process, r.level, r.msg) for r in records]


def printed(suite: str, ident: str) -> str:
    """What the real stack printed for one excerpt of a real_modules suite (its `lines`), as the set froze it."""
    from hexar.evals.real_modules import load_excerpts

    return next(e.lines for e in load_excerpts(suite) if e.id == ident)


def one_step_task(tmp_path: Path, lines: list[Line], explainer: str, skill: str) -> Explanation:
    """The lines under a /task_info task of one `skill` step that runs from before them and fails after the last:
    what `explainer` answers about it."""
    def update(status: str) -> dict[str, object]:
        return {"instruction": "move the arm", "task_id": "0000000000000031", "task_status": "valid",
                "task_error_msg": "", "skill_sequence": [{"skill": skill, "params": {}, "status": status,
                                                          "error_msg": "The skill has been aborted"
                                                          if status == "failed" else ""}]}

    b = BagBuilder()
    b.task_info(T0 - 1_000_000_000, update("waiting"))
    b.task_info(T0 - 500_000_000, update("Running"))
    b.task_info(T0 + sec_ns(max(s for s, *_ in lines) + 0.5), update("failed"))
    return explain(write_lines(tmp_path, lines, b), explainer, "Why didn't that work?")[1]


def ask_run(tmp_path: Path, suite: str, ident: str, task: bool) -> Explanation:
    """A real_modules run of `suite` (its id without the kilted-control- prefix), written as a recording with or
    without a /task_info task; what `control` answers to the suite's question about it."""
    from hexar.evals.real_modules import QUESTIONS, load_excerpts, write_recording

    excerpt = next(e for e in load_excerpts(suite) if e.id == f"kilted-control-{ident}")
    log = read_recording(write_recording(excerpt, tmp_path / f"run{int(task)}", task=task))
    return explain(log, "control", QUESTIONS["succeeded" if excerpt.outcome == "succeeded" else "failed"])[1]
