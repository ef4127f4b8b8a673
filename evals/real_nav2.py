"""The real-Nav2 corpus (evals/data/real_nav2/corpus.yaml): console excerpts people pasted in public threads, each
with the cause the thread diagnosed, and the converter that turns an excerpt into a rosbag2 recording.

Console formats read (a `NN: ` ctest prefix, a `name | ` docker-compose prefix and a `> ` quote prefix are removed):
- `[process-N] [LEVEL] [stamp] [logger]: msg`          ros2 launch, Foxy onwards
- `[LEVEL] [stamp] [logger]: msg`                       a node run on its own (`ros2 run`)
- `[process-N] [LEVEL] [logger]: msg`, `[LEVEL] [logger]: msg`   without stamps (Dashing/Eloquent-era output)
- `[process-N] [logger]: msg`, `logger: msg`            no level (hand-trimmed pastes)
- anything else is a bare message; a line that starts lower-case or indented, a launch prefix with nothing after
  it, or a line after one that ended in whitespace, continues the message before it (console-wrapped text).
What the console did not print is synthesised and marked so: levels from the message's wording, increasing stamps
between (or around) the printed ones, and an empty logger name when none was printed (rcl's own value for lines
logged before a node exists, e.g. `[ERROR] [stamp] []: Caught exception ...`).
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import cache
from importlib import resources
from typing import Any, Protocol, TypeVar

import yaml

from hexar.errors import HexarError

DISTROS = ("foxy", "galactic", "humble", "iron", "jazzy", "kilted", "rolling", "unknown")
OUTCOMES = ("failed", "succeeded", "slow")
LEVELS = {"DEBUG": 10, "INFO": 20, "WARN": 30, "WARNING": 30, "ERROR": 40, "FATAL": 50}
NS = 1_000_000_000
# A corpus line with no stamp at all gets stamps from here (2023-11-14), 100 ms apart.
BASE_NS = 1_700_000_000 * NS
STEP_NS = NS // 10

# a line's outer prefix: a numbered paste ("12: "), `grep -n` output ("115:[controller_server-2] …"), docker
# compose's "service | ", a quote
_OUTER = re.compile(r"^(?:\d+: |\d+:(?=\[)|[\w.-]+\s+\| |> )")
# launch's process name is the command's basename, or the `name` a launch file gives it, spaces allowed
# ("[controller_manager fd_controller-4]"): words joined by single spaces, then launch's "-N"
_PROC_NAME = r"[\w./-]+(?: [\w./-]+)*-\d+"
_PROC = rf"(?:\[(?P<proc>{_PROC_NAME})\]\s*)?"
_LEVEL = r"\[\s*(?P<level>DEBUG|INFO|WARN|WARNING|ERROR|FATAL)\]\s*"
_STAMP = r"(?:\[(?P<stamp>\d+(?:\.\d+)?|)\]\s*)?"
_LOGGER = rf"\[(?P<logger>[^\]\s]*|{_PROC_NAME})\]:\s?"
LEVELED = re.compile(rf"^{_PROC}{_LEVEL}{_STAMP}(?:{_LOGGER})?(?P<msg>.*)$")
# RCUTILS_CONSOLE_OUTPUT_FORMAT "[{severity} {time}] [{name}]: {message}": level and stamp in one bracket
LEVEL_STAMP = re.compile(rf"^{_PROC}\[\s*(?P<level>DEBUG|INFO|WARN|WARNING|ERROR|FATAL)\s+(?P<stamp>\d+(?:\.\d+)?)\]\s*"
                         rf"(?:{_LOGGER})?(?P<msg>.*)$")
NAMED = re.compile(rf"^{_PROC}{_LOGGER}(?P<msg>.*)$")
PLAIN_NAMED = re.compile(r"^(?P<logger>[A-Za-z_][\w.]*):\s+(?P<msg>\S.*)$")
PROC_ONLY = re.compile(rf"^\[(?P<proc>{_PROC_NAME})\](?P<rest>.*)$")
# Wall-clock consoles: "10:33:12  msg" (a summary pasted with times) and RCUTILS_CONSOLE_OUTPUT_FORMAT variants
# such as "[ WARN][6:31:18.730 PM -03][controller_server]: msg". Their times become stamps on BASE_NS's day.
_CLOCK = r"(?P<clock>\d{1,2}:\d{2}:\d{2}(?:\.\d+)?)(?:\s*(?P<ampm>AM|PM))?(?:\s*[+-]\d{2}(?::?\d{2})?)?"
CLOCK_LEVELED = re.compile(rf"^{_PROC}{_LEVEL}\[{_CLOCK}\]\s*(?:{_LOGGER})?(?P<msg>.*)$")
CLOCK_PREFIX = re.compile(rf"^{_CLOCK}\s+(?P<rest>\S.*)$")
# launch's screen format with timestamps ("{created:.7f} {line}"): the wall time it printed the line, in epoch seconds
EPOCH_PREFIX = re.compile(r"^(?P<epoch>\d{9,10}\.\d+)\s+(?P<rest>\[.*)$")
# Wording that decides a synthesised level; Nav2's own lines of these kinds are WARN/ERROR.
ERROR_WORDS = re.compile(r"\b(error|exception|failed|fail|fatal|abort(ed|ing)?|died|illegal instruction|"
                         r"segmentation fault|core dumped|SIG(ILL|SEGV|ABRT))\b", re.I)
WARN_WORDS = re.compile(r"\b(warn\w*|timed out|time out|dropping|cannot|could not|couldn't|unable|exceeded|"
                        r"not available|does not exist|out of (map )?bounds)\b", re.I)


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


@dataclass
class ConsoleLine:
    """One log record as read from a console excerpt; `synthesised` names the fields the console did not print."""

    stamp_ns: int | None
    level: int
    name: str
    msg: str
    process: str = ""
    synthesised: set[str] = field(default_factory=set)


def _stamp_ns(text: str) -> int:
    sec, _, frac = text.partition(".")
    return int(sec) * NS + int((frac + "000000000")[:9])


def infer_level(msg: str) -> int:
    if ERROR_WORDS.search(msg):
        return LEVELS["ERROR"]
    if WARN_WORDS.search(msg):
        return LEVELS["WARN"]
    return LEVELS["INFO"]


def _clock_ns(clock: str, ampm: str | None) -> int:
    h, m, sec = clock.split(":")
    hours = int(h) % 12 + (12 if ampm == "PM" else 0) if ampm else int(h)
    whole, _, frac = sec.partition(".")
    day = BASE_NS - BASE_NS % (86_400 * NS)
    return day + (hours * 3600 + int(m) * 60 + int(whole)) * NS + int((frac + "000000000")[:9])


def _record(level: str | None, stamp: str | None, logger: str | None, msg: str, proc: str | None,
            stamp_ns: int | None = None) -> ConsoleLine:
    made: set[str] = set()
    if level is None:
        made.add("level")
    if not stamp and stamp_ns is None:
        made.add("stamp")
    if logger is None:
        made.add("name")
    return ConsoleLine(
        stamp_ns=_stamp_ns(stamp) if stamp else stamp_ns,
        level=LEVELS[level] if level is not None else infer_level(msg),
        name=logger or "",
        msg=msg,
        process=proc or "",
        synthesised=made,
    )


def _is_continuation(raw: str, previous_raw: str, records: Sequence[ConsoleLine]) -> bool:
    if not records:
        return False
    if raw[:1].isspace() or raw[:1].islower():
        return True
    return previous_raw[-1:].isspace()


def _behind_prefix(rest: str, stamp_ns: int, records: list[ConsoleLine], keep_own: bool) -> None:
    """The records of a line printed behind a time prefix, stamped with that time (unless `keep_own` and the line
    prints its own stamp)."""
    inner: list[ConsoleLine] = []
    _parse_line(rest, "", inner)
    for r in inner:
        if not (keep_own and r.stamp_ns is not None):
            r.stamp_ns = stamp_ns
            r.synthesised.discard("stamp")
    records.extend(inner)


def _parse_line(line: str, previous: str, records: list[ConsoleLine]) -> None:
    c = CLOCK_LEVELED.match(line)
    if c:
        records.append(_record(c["level"].upper(), None, c["logger"], c["msg"], c["proc"],
                               _clock_ns(c["clock"], c["ampm"])))
        return
    t = CLOCK_PREFIX.match(line)
    if t:
        _behind_prefix(t["rest"], _clock_ns(t["clock"], t["ampm"]), records, keep_own=False)
        return
    e = EPOCH_PREFIX.match(line)
    if e:  # the node's own stamp, where printed, is the record's
        _behind_prefix(e["rest"], _stamp_ns(e["epoch"]), records, keep_own=True)
        return
    m = LEVELED.match(line) or LEVEL_STAMP.match(line)
    if m:
        msg = m["msg"] if m["logger"] is not None else re.sub(r"^:\s*", "", m["msg"])  # "[ERROR] : msg"
        records.append(_record(m["level"].upper(), m["stamp"], m["logger"], msg, m["proc"]))
        return
    n = NAMED.match(line)
    if n:
        records.append(_record(None, None, n["logger"], n["msg"], n["proc"]))
        return
    p = PROC_ONLY.match(line)
    proc, rest = (p["proc"], p["rest"]) if p else (None, line)
    if p and (not rest.strip() or rest[1:2].isspace()):
        if records and rest.strip():  # launch prints each line of a multi-line message behind its prefix
            records[-1].msg += "\n" + rest.strip()
        elif rest.strip():  # the excerpt begins inside such a message (an exception's what()): kept, not dropped
            records.append(_record(None, None, None, rest.strip(), proc))
        return
    q = PLAIN_NAMED.match(rest.strip())
    if q:
        records.append(_record(None, None, q["logger"], q["msg"], proc))
    elif _is_continuation(rest if p else line, previous, records) and (not p or records[-1].process == proc):
        # (behind launch's prefix, a line continues only its own process's message, never another's)
        records[-1].msg += "\n" + rest.strip()
    else:
        records.append(_record(None, None, None, rest.strip(), proc))


def parse_console(text: str) -> list[ConsoleLine]:
    """The log records of a pasted console excerpt, in the order printed (stamps may be missing: see `stamped`)."""
    records: list[ConsoleLine] = []
    previous = ""
    for raw in text.splitlines():
        line = _OUTER.sub("", raw, count=1)
        if line.strip():
            _parse_line(line, previous, records)
        previous = line
    for r in records:
        r.msg = r.msg.rstrip()
        if "level" in r.synthesised:
            r.level = infer_level(r.msg)
    return records


def stamped(records: Sequence[ConsoleLine]) -> list[ConsoleLine]:
    """`records` with every stamp set: printed stamps kept, missing ones spread between their printed neighbours
    (or 100 ms apart before the first / after the last printed one, or from BASE_NS when none is printed)."""
    known = [i for i, r in enumerate(records) if r.stamp_ns is not None]
    out = [ConsoleLine(r.stamp_ns, r.level, r.name, r.msg, r.process, set(r.synthesised)) for r in records]
    if not known:
        for i, r in enumerate(out):
            r.stamp_ns = BASE_NS + i * STEP_NS
        return out
    for i, r in enumerate(out):
        if r.stamp_ns is not None:
            continue
        before = max((k for k in known if k < i), default=None)
        after = min((k for k in known if k > i), default=None)
        if before is not None and after is not None:
            lo, hi = records[before].stamp_ns, records[after].stamp_ns
            assert lo is not None and hi is not None
            span = max(hi - lo, 0)
            r.stamp_ns = lo + span * (i - before) // (after - before) if span else lo + (i - before)
        elif before is not None:
            lo = records[before].stamp_ns
            assert lo is not None
            r.stamp_ns = lo + (i - before) * STEP_NS
        else:
            assert after is not None
            hi = records[after].stamp_ns
            assert hi is not None
            r.stamp_ns = hi - (after - i) * STEP_NS
    return out


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
        raise HexarError(f"the {corpus} is not valid YAML: {err}") from err
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
               "blind8.yaml", "blind9.yaml", "blind10.yaml", "blind11.yaml")


@cache
def load_excerpts(name: str) -> tuple[Excerpt, ...]:
    text = resources.files("hexar.evals").joinpath(f"data/real_nav2/{name}").read_text(encoding="utf-8")
    return parse_corpus(text)


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
        b.log(r.stamp_ns, r.name, r.level, r.msg)
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
