"""The real-Nav2 corpus (evals/data/real_nav2/corpus.yaml): console excerpts people pasted in public threads, each
with the cause the thread diagnosed, and the converter that turns an excerpt into a rosbag2 recording (the console
formats it reads are listed in `hexar.events.console`).
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import cache
from importlib import resources
from pathlib import Path
from typing import Any, Protocol, TypeVar

import yaml

from hexar.errors import HexarError
from hexar.events.console import NS, ConsoleLine, parse_console, stamped

DISTROS = ("foxy", "galactic", "humble", "iron", "jazzy", "kilted", "rolling", "unknown")
OUTCOMES = ("failed", "succeeded", "slow")


@dataclass(frozen=True)
class Excerpt:
    """One corpus entry (see evals/data/real_nav2/README.md for the fields)."""

    id: str
    source: str
    url: str
    distro: str
    outcome: str
    cause: str
    cause_quote: str
    logs_show_cause: bool
    lines: str
    notes: str = ""


_REQUIRED = ("id", "source", "url", "distro", "outcome", "cause", "cause_quote", "logs_show_cause", "lines")


def _excerpt(entry: Any, n: int, causes: frozenset[str]) -> Excerpt:
    if not isinstance(entry, dict):
        raise HexarError(f"corpus entry {n} is not a mapping")
    missing = [k for k in _REQUIRED if k not in entry]
    if missing:
        raise HexarError(f"corpus entry {entry.get('id', n)!r} lacks {', '.join(missing)}")
    ex = Excerpt(**{k: entry[k] for k in (*_REQUIRED, "notes") if k in entry})
    if ex.distro not in DISTROS:
        raise HexarError(f"corpus entry {ex.id!r}: distro {ex.distro!r} is not one of {', '.join(DISTROS)}")
    if ex.outcome not in OUTCOMES:
        raise HexarError(f"corpus entry {ex.id!r}: outcome {ex.outcome!r} is not one of {', '.join(OUTCOMES)}")
    if ex.cause not in causes:
        raise HexarError(f"corpus entry {ex.id!r}: unknown cause {ex.cause!r}")
    if not isinstance(ex.logs_show_cause, bool) or not parse_console(ex.lines):
        raise HexarError(f"corpus entry {ex.id!r}: logs_show_cause must be true/false and lines must not be empty")
    return ex


# The cause ids of NAV_CAUSES (issue 9); the corpus may name them before hexar/causes.yaml phrases them all.
NAV_CAUSES = frozenset({
    "navigation.blocked_path", "navigation.joystick", "navigation.charging", "navigation.poor_localisation",
    "navigation.moving_obstacles", "navigation.nominal_speed", "navigation.nominal", "navigation.unexplained_failure",
    "navigation.goal_unreachable", "navigation.off_costmap", "navigation.transform_error",
    "navigation.commands_not_reaching_base", "navigation.configuration_error", "navigation.collision_ahead",
    "navigation.controller_failure", "navigation.docking_failure", "navigation.no_progress",
    # issue 20: a start pose on occupied/unknown cells, and a node of the stack that never came up
    "navigation.start_in_obstacle", "navigation.bringup_failure",
})


class _HasId(Protocol):
    @property
    def id(self) -> str: ...


E = TypeVar("E", bound=_HasId)


def parse_entries(text: str, make: Callable[[Any, int], E], corpus: str, ids_of: str) -> tuple[E, ...]:
    """A corpus file's excerpts, each made and checked by `make`; bad YAML, an empty file or a repeated id is one
    HexarError naming the `corpus` ("the real-Nav2 corpus") or its ids ("corpus ids")."""
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError as err:
        raise HexarError(f"the {corpus} is not valid YAML: {' '.join(str(err).split())}") from err
    if not isinstance(data, list) or not data:
        raise HexarError(f"the {corpus} must be a non-empty list of excerpts")
    out = tuple(make(e, i) for i, e in enumerate(data))
    ids = [e.id for e in out]
    if dupes := sorted({i for i in ids if ids.count(i) > 1}):
        raise HexarError(f"duplicate {ids_of}: {', '.join(dupes)}")
    return out


def parse_corpus(text: str) -> tuple[Excerpt, ...]:
    return parse_entries(text, lambda e, i: _excerpt(e, i, NAV_CAUSES), "real-Nav2 corpus", "corpus ids")


# The tuning corpus and the held-out set (threads the catalogue was never tuned on), both in the data package.
CORPUS_FILE = "corpus.yaml"
HELDOUT_FILE = "heldout.yaml"
# Issue 20's blind sets, in the order collected, each by other hands from sources in no file before it and measured
# once before that round's tuning and once after (README.md in the data folder says who, when and how): the first
# with the catalogue frozen before it was read, then one per round from round 4 on.
BLIND_FILES = ("blind.yaml", "blind2.yaml", "blind3.yaml", "blind4.yaml", "blind5.yaml", "blind6.yaml", "blind7.yaml",
               "blind8.yaml", "blind9.yaml", "blind10.yaml", "blind11.yaml", "blind12.yaml",
               "blind13.yaml", "blind14.yaml", "blind15.yaml", "blind16.yaml", "blind17.yaml", "blind18.yaml",
               "blind19.yaml", "blind20.yaml", "blind21.yaml", "blind22.yaml", "blind23.yaml", "blind24.yaml",
               "blind25.yaml", "blind26.yaml", "blind27.yaml", "blind28.yaml", "blind29.yaml")


@cache
def load_excerpts(name: str) -> tuple[Excerpt, ...]:
    text = resources.files("hexar.evals").joinpath(f"data/real_nav2/{name}").read_text(encoding="utf-8")
    return parse_corpus(text)


def read_text_file(path: Path, what: str) -> str:
    """A data file the user named, or one HexarError that says which and why."""
    if path.is_dir():
        raise HexarError(f"{what} must be a YAML file, not a folder: {path}")
    try:
        return path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as err:
        raise HexarError(f"cannot read {what} {path}: {err}") from err


def read_cases(path: Path) -> tuple[Excerpt, ...]:
    """A user's own excerpts (`hexar eval --suite real-nav2 --cases FILE`), checked as the corpus is."""
    return parse_entries(read_text_file(path, "--cases"), lambda e, i: _excerpt(e, i, NAV_CAUSES),
                         f"--cases file {path}", f"ids in {path}")


def corpus() -> tuple[Excerpt, ...]:
    return load_excerpts(CORPUS_FILE)


def heldout() -> tuple[Excerpt, ...]:
    return load_excerpts(HELDOUT_FILE)


def blind_set(n: int) -> tuple[Excerpt, ...]:
    """The n-th blind set (1: issue 20's first, blind.yaml)."""
    return load_excerpts(BLIND_FILES[n - 1])


def blind() -> tuple[Excerpt, ...]:
    return blind_set(1)


# ---------------------------------------------------------------------------------------------------------------
# Recordings

INSTRUCTION = "go to the goal"
# What the navigate_to_pose skill reports when its goal fails: the action's outcome, never the thread's diagnosis
# (explainers must find the cause in the logs).
SKILL_ERROR = "The navigation goal was aborted"
_GOAL = re.compile(r"to \((-?\d+(?:\.\d+)?), (-?\d+(?:\.\d+)?)\)")


def with_task(index: int) -> bool:
    """Half of the excerpts, alternating in corpus order, get a navigation task on /task_info."""
    return index % 2 == 0


def task_plan(excerpts: Sequence[Excerpt]) -> list[bool]:
    """Which excerpts get a /task_info task: every other one in corpus order *within each outcome*, so failures,
    successes and slow runs are each split between recordings with a task and recordings without one."""
    seen: dict[str, int] = {}
    plan = []
    for ex in excerpts:
        plan.append(with_task(seen.get(ex.outcome, 0)))
        seen[ex.outcome] = seen.get(ex.outcome, 0) + 1
    return plan


def _goal(records: Sequence[ConsoleLine]) -> dict[str, float]:
    for r in records:
        if r.msg.startswith("Begin navigating") and (m := _GOAL.search(r.msg)):
            return {"x": float(m[1]), "y": float(m[2])}
    return {}


def _task(task_id: str, goal: dict[str, float], status: str, error: str) -> dict[str, Any]:
    return {"instruction": INSTRUCTION, "task_id": task_id, "task_status": "valid", "task_error_msg": "",
            "skill_sequence": [{"skill": "navigate_to_pose", "params": goal, "status": status, "error_msg": error}]}


TaskMaker = Callable[[str, str, str], dict[str, Any]]  # (task id, status, error) -> /task_info JSON


def write_excerpt(records: Sequence[ConsoleLine], excerpt_id: str, failed: bool, out: Any, task: TaskMaker | None,
                  error: str, storage: str = "sqlite3") -> Any:
    """`records` (the excerpt's stamped lines) as a rosbag2 recording at `out`: /rosout, and with `task` a one-skill
    /task_info that waits 1 s before the first line, runs from 0.5 s before it and ends 0.5 s after the last with
    its outcome (`error` when `failed`, never the diagnosis); returns the path."""
    from hexar.evals.scenarios.bag import BagBuilder

    b = BagBuilder()
    for r in records:
        assert r.stamp_ns is not None
        # a line without a logger (stderr) keeps the process launch printed it under, as launch.log is read
        b.log(r.stamp_ns, r.name or r.process, r.level, r.msg, r.file, r.function, r.line)
    if task is not None:
        first = min(r.stamp_ns or 0 for r in records)
        last = max(r.stamp_ns or 0 for r in records)
        task_id = re.sub(r"[^A-Za-z0-9]", "", excerpt_id)[-16:].rjust(16, "0")
        ok = not failed
        b.task_info(first - NS, task(task_id, "waiting", ""))
        b.task_info(first - NS // 2, task(task_id, "Running", ""))
        b.task_info(last + NS // 2, task(task_id, "succeeded" if ok else "failed", "" if ok else error))
    return b.write(out, "mcap" if storage == "mcap" else "sqlite3")


def write_recording(excerpt: Excerpt, out: Any, task: bool, storage: str = "sqlite3") -> Any:
    """Writes `excerpt` as a rosbag2 recording at `out` (/rosout, and /task_info when `task`); returns the path."""
    records = stamped(parse_console(excerpt.lines))
    goal = _goal(records)
    maker: TaskMaker = lambda task_id, status, error: _task(task_id, goal, status, error)  # noqa: E731
    return write_excerpt(records, excerpt.id, excerpt.outcome == "failed", out, maker if task else None,
                         SKILL_ERROR, storage)
