"""`hexar eval --suite real-modules` (and `real-modules-heldout`): HEXAR on recordings made from real console
excerpts of the arm's modules (MoveIt 2, ros2_control, bring-up, the system), graded against the cause each public
thread diagnosed (evals/data/real_modules/README.md).

The corpus format is real_nav2's (evals/real_nav2.py reads the consoles) plus `module`: manipulation, control,
bringup or system. Half of the excerpts of each outcome get a task on /task_info whose one step is the module's
skill (`move_arm` for manipulation, `follow_joint_trajectory` for control, `bring_up_controllers` for bring-up
and the system: the robot's own record of what it was doing, never the diagnosis); the others get none, and their
tasks are derived from the logs (events/arm_goals.py) or there is no task to explain.

Grading, from the answer's text (hexar/claims.py), as in real-nav2: `named` (the diagnosed cause affirmed),
`honest` (no unsupported cause, and an honest "my logs do not show a cause I know"), `wrong` (an unsupported cause,
a failure told as fine, or nothing named). The cause ids HEXAR returned are graded the same way (`structured`).
"""

from __future__ import annotations

import re
import shutil
import tempfile
from collections.abc import Callable, Iterable, Sequence
from dataclasses import asdict, dataclass
from functools import cache
from importlib import resources
from pathlib import Path
from typing import Any

from hexar.causes import vocabulary
from hexar.claims import ALL_FINE, TASK_FAILED, read_claims
from hexar.errors import USER_ERRORS, HexarError
from hexar.evals.real_nav2 import (
    DISTROS,
    OUTCOMES,
    TaskMaker,
    parse_entries,
    read_text_file,
    task_plan,
    write_excerpt,
)
from hexar.evals.real_nav2_suite import Grade, hexar_asker  # one grade, one asker; only the allowed causes differ
from hexar.events.console import parse_console, stamped

SUITE = "real-modules"
HELDOUT_SUITE = "real-modules-heldout"
HELDOUT2_SUITE = "real-modules-heldout2"  # collected in a later round, measured once before and once after tuning
HELDOUT3_SUITE = "real-modules-heldout3"  # the same, one round later
HELDOUT4_SUITE = "real-modules-heldout4"  # and again in round 5
HELDOUT5_SUITE = "real-modules-heldout5"  # and in round 6
HELDOUT6_SUITE = "real-modules-heldout6"  # and in round 7
HELDOUT7_SUITE = "real-modules-heldout7"  # and in round 8
HELDOUT8_SUITE = "real-modules-heldout8"  # and in round 9
HELDOUT9_SUITE = "real-modules-heldout9"  # and in round 10
HELDOUT10_SUITE = "real-modules-heldout10"  # and in round 18
HELDOUT11_SUITE = "real-modules-heldout11"  # and in round 20
HELDOUT12_SUITE = "real-modules-heldout12"  # and in round 21
HELDOUT13_SUITE = "real-modules-heldout13"  # and in round 21, from stored web pages
HELDOUT14_SUITE = "real-modules-heldout14"  # and a third in round 21
HELDOUT15_SUITE = "real-modules-heldout15"  # and in round 22
HELDOUT16_SUITE = "real-modules-heldout16"  # and in round 23, from git histories
HELDOUT17_SUITE = "real-modules-heldout17"  # and a second in round 23, from issue threads found by symptom
HELDOUT18_SUITE = "real-modules-heldout18"  # round 24, by a sweep of the sources' less common messages
HELDOUT19_SUITE = "real-modules-heldout19"  # round 25, from threads of the hardware drivers and simulators
HELDOUT20_SUITE = "real-modules-heldout20"  # and a second in round 25, from stored web pages
HELDOUT21_SUITE = "real-modules-heldout21"  # round 26, from arm and kit makers' threads
HELDOUT22_SUITE = "real-modules-heldout22"  # round 27: printed by the real ROS 2 stack here, one fault each
HELDOUT23_SUITE = "real-modules-heldout23"  # round 28: the same, runtime and launch faults
HELDOUT24_SUITE = "real-modules-heldout24"  # and a third, settings of the environment or code
HELDOUT25_SUITE = "real-modules-heldout25"  # round 29: a running graph's parameters, services, names and time
HELDOUT26_SUITE = "real-modules-heldout26"  # round 30: bring-ups run by the real ros2/launch and launch_ros
HELDOUT27_SUITE = "real-modules-heldout27"  # and rclpy actions' goals, feedback and results
HELDOUT28_SUITE = "real-modules-heldout28"  # and a machine or network short of something
HELDOUT29_SUITE = "real-modules-heldout29"  # and managed nodes, executors and timers
HELDOUT30_SUITE = "real-modules-heldout30"  # round 35: the real ros2_control run here, one fault each
HELDOUT31_SUITE = "real-modules-heldout31"  # and a second, its spawners chained
HELDOUT32_SUITE = "real-modules-heldout32"  # round 36: a mobile base on diff_drive_controller, and its teleop
HELDOUT33_SUITE = "real-modules-heldout33"  # and the arm's trajectories, loop and spawners
HELDOUT34_SUITE = "real-modules-heldout34"  # and a parallel gripper's
HELDOUT35_SUITE = "real-modules-heldout35"  # round 38: a pan-tilt head on forward_command_controller
HELDOUT36_SUITE = "real-modules-heldout36"  # and trajectories as a script sends them
FILES = {SUITE: "corpus.yaml", HELDOUT_SUITE: "heldout.yaml", HELDOUT2_SUITE: "heldout2.yaml",
         HELDOUT3_SUITE: "heldout3.yaml", HELDOUT4_SUITE: "heldout4.yaml",
         HELDOUT5_SUITE: "heldout5.yaml", HELDOUT6_SUITE: "heldout6.yaml",
         HELDOUT7_SUITE: "heldout7.yaml", HELDOUT8_SUITE: "heldout8.yaml",
         HELDOUT9_SUITE: "heldout9.yaml", HELDOUT10_SUITE: "heldout10.yaml",
         HELDOUT11_SUITE: "heldout11.yaml", HELDOUT12_SUITE: "heldout12.yaml",
         HELDOUT13_SUITE: "heldout13.yaml", HELDOUT14_SUITE: "heldout14.yaml",
         HELDOUT15_SUITE: "heldout15.yaml", HELDOUT16_SUITE: "heldout16.yaml",
         HELDOUT17_SUITE: "heldout17.yaml", HELDOUT18_SUITE: "heldout18.yaml",
         HELDOUT19_SUITE: "heldout19.yaml", HELDOUT20_SUITE: "heldout20.yaml",
         HELDOUT21_SUITE: "heldout21.yaml", HELDOUT22_SUITE: "heldout22.yaml",
         HELDOUT23_SUITE: "heldout23.yaml",
         HELDOUT24_SUITE: "heldout24.yaml", HELDOUT25_SUITE: "heldout25.yaml",
         HELDOUT26_SUITE: "heldout26.yaml", HELDOUT27_SUITE: "heldout27.yaml",
         HELDOUT28_SUITE: "heldout28.yaml", HELDOUT29_SUITE: "heldout29.yaml",
         HELDOUT30_SUITE: "heldout30.yaml", HELDOUT31_SUITE: "heldout31.yaml",
         HELDOUT32_SUITE: "heldout32.yaml", HELDOUT33_SUITE: "heldout33.yaml", HELDOUT34_SUITE: "heldout34.yaml",
         HELDOUT35_SUITE: "heldout35.yaml", HELDOUT36_SUITE: "heldout36.yaml"}
MODULES = ("manipulation", "control", "bringup", "system")
SKILL = {"manipulation": "move_arm", "control": "follow_joint_trajectory", "bringup": "bring_up_controllers",
         "system": "bring_up_controllers"}
PREFIXES = ("manipulation.", "control.", "bringup.", "system.")
HONEST_CAUSES = frozenset({"manipulation.unexplained_failure", "control.unexplained_failure"})
HONEST_WORDS = re.compile(r"logs do not show a cause I know|(not|n't) (have )?enough information|"
                          r"(can(no|')t|could ?n[o']t) tell (why|what)|do(es)? not show (why|what)", re.I)
QUESTIONS = {"failed": "Why didn't that work?", "succeeded": "How did it go?", "slow": "Why did it take so long?"}
_REQUIRED = ("id", "source", "url", "distro", "module", "outcome", "cause", "cause_quote", "logs_show_cause", "lines")


@dataclass(frozen=True)
class Excerpt:
    id: str
    source: str
    url: str
    distro: str
    module: str
    outcome: str
    cause: str
    cause_quote: str
    logs_show_cause: bool
    lines: str
    notes: str = ""


def _excerpt(entry: Any, n: int) -> Excerpt:
    if not isinstance(entry, dict):
        raise HexarError(f"real-modules entry {n} is not a mapping")
    missing = [k for k in _REQUIRED if k not in entry]
    if missing:
        raise HexarError(f"real-modules entry {entry.get('id', n)!r} lacks {', '.join(missing)}")
    ex = Excerpt(**{k: entry[k] for k in (*_REQUIRED, "notes") if k in entry})
    if ex.distro not in DISTROS or ex.outcome not in OUTCOMES or ex.module not in MODULES:
        raise HexarError(f"real-modules entry {ex.id!r}: distro, outcome or module is not one of the known values")
    if ex.cause not in vocabulary() or not ex.cause.startswith(PREFIXES):
        raise HexarError(f"real-modules entry {ex.id!r}: unknown cause {ex.cause!r}")
    if not isinstance(ex.logs_show_cause, bool) or not parse_console(ex.lines):
        raise HexarError(f"real-modules entry {ex.id!r}: logs_show_cause must be true/false, lines not empty")
    return ex


def parse_corpus(text: str) -> tuple[Excerpt, ...]:
    return parse_entries(text, _excerpt, "real-modules corpus", "real-modules ids")


@cache
def load_excerpts(suite: str) -> tuple[Excerpt, ...]:
    if suite not in FILES:
        raise HexarError(f"unknown suite {suite!r}")
    folder = resources.files("hexar.evals").joinpath("data/real_modules")
    try:
        text = folder.joinpath(FILES[suite]).read_text(encoding="utf-8")
    except OSError as err:
        raise HexarError(f"cannot read evals/data/real_modules/{FILES[suite]}: {err}") from err
    return parse_corpus(text)


def read_cases(path: Path) -> tuple[Excerpt, ...]:
    """A user's own excerpts (`hexar eval --suite real-modules --cases FILE`), checked as the corpus is."""
    return parse_entries(read_text_file(path, "--cases"), _excerpt, f"--cases file {path}", f"ids in {path}")


def _task(task_id: str, skill: str, status: str, error: str) -> dict[str, Any]:
    return {"instruction": "move the arm" if skill != "bring_up_controllers" else "start the robot's drivers",
            "task_id": task_id, "task_status": "valid", "task_error_msg": "",
            "skill_sequence": [{"skill": skill, "params": {}, "status": status, "error_msg": error}]}


def write_recording(excerpt: Excerpt, out: Path, task: bool, storage: str = "sqlite3") -> Path:
    """`excerpt` as a rosbag2 recording at `out`: /rosout, and /task_info when `task` (the skill's own outcome,
    "The skill has been aborted" on failure, never the diagnosis)."""
    skill = SKILL[excerpt.module]
    maker: TaskMaker = lambda task_id, status, error: _task(task_id, skill, status, error)  # noqa: E731
    records = stamped(parse_console(excerpt.lines))
    return Path(write_excerpt(records, excerpt.id, excerpt.outcome == "failed", out, maker if task else None,
                              "The skill has been aborted", storage))


def unsupported(excerpt: Excerpt, claims: Iterable[str]) -> list[str]:
    known = vocabulary().get(excerpt.cause)
    # as in the real-nav2 grader (evals/real_nav2_suite.py): a cause that implies the label is the same cause told
    # in more detail (a controller whose type was never defined is a controller set up wrongly)
    finer = {c for c, k in vocabulary().items() if excerpt.cause in k.implies}
    allowed = {excerpt.cause, *(known.implies if known else ()), *finer, *HONEST_CAUSES}
    out = []
    for c in claims:
        if c == ALL_FINE:
            wrong = excerpt.outcome == "failed"
        elif c == TASK_FAILED:
            wrong = excerpt.outcome != "failed"
        else:
            wrong = c in vocabulary() and c not in allowed
        if wrong:
            out.append(c)
    return sorted(out)


def grade(excerpt: Excerpt, claims: Iterable[str], text: str = "") -> Grade:
    claims = set(claims)
    bad = tuple(unsupported(excerpt, claims))
    named = excerpt.cause in claims
    honest = not bad and (bool(claims & HONEST_CAUSES) or bool(HONEST_WORDS.search(text)))
    verdict = "wrong" if bad else "named" if named else "honest" if honest else "wrong"
    return Grade(named, honest, bad, verdict)


@dataclass(frozen=True)
class Result:
    id: str
    module: str
    distro: str
    cause: str
    outcome: str
    logs_show_cause: bool
    with_task: bool
    question: str
    answer: str
    error: str
    causes: tuple[str, ...]
    claims: tuple[str, ...]
    text: Grade
    structured: Grade


Ask = Callable[[Path, str], dict[str, Any]]


def evaluate(excerpts: Sequence[Excerpt], runs: Path, ask: Ask) -> list[Result]:
    out: list[Result] = []
    for ex, task in zip(excerpts, task_plan(excerpts), strict=True):  # type: ignore[arg-type]
        path = runs / ex.id
        if path.exists():
            shutil.rmtree(path)
        write_recording(ex, path, task)
        question = QUESTIONS[ex.outcome]
        try:
            r = ask(path, question)
            answer, error, causes = str(r.get("answer", "")), str(r.get("error", "")), tuple(r.get("causes", ()))
        except USER_ERRORS as err:  # e.g. no task to explain
            # the recording's temporary folder is no part of the result: name the excerpt instead
            answer, error, causes = "", f"{type(err).__name__}: {err}".replace(str(path), ex.id), ()
        claims = tuple(sorted(read_claims(answer).affirmed))
        out.append(Result(ex.id, ex.module, ex.distro, ex.cause, ex.outcome, ex.logs_show_cause, task, question,
                          answer, error, causes, claims, grade(ex, claims, answer), grade(ex, causes)))
    return out


def summarise(results: Sequence[Result], key: Callable[[Result], str] | None = None) -> dict[str, dict[str, Any]]:
    groups: dict[str, list[Result]] = {}
    for r in results:
        groups.setdefault(key(r) if key else "all", []).append(r)
    out: dict[str, dict[str, Any]] = {}
    for name, rs in groups.items():
        shown = [r for r in rs if r.logs_show_cause]
        row: dict[str, Any] = {"n": len(rs), "n_shown": len(shown)}
        for kind in ("text", "structured"):
            g = [getattr(r, kind) for r in rs]
            named = sum(getattr(r, kind).named for r in shown)
            row[kind] = {"named": named, "named_all": sum(x.named for x in g),
                         "named_rate": named / len(shown) if shown else None,
                         "no_unsupported": sum(not x.unsupported for x in g),
                         "honest": sum(x.verdict == "honest" for x in g),
                         "wrong": sum(x.verdict == "wrong" for x in g)}
        out[name] = row
    return out


def build_report(results: Sequence[Result], backend: str, suite: str, cases: Path | None = None) -> dict[str, Any]:
    data = {"data": str(cases), "cases": True} if cases is not None else {"data": FILES[suite]}
    return {"suite": suite, **data, "backend": backend, "n": len(results),
            "summary": summarise(results)["all"],
            "by_module": dict(sorted(summarise(results, key=lambda r: r.module).items())),
            "by_cause": dict(sorted(summarise(results, key=lambda r: r.cause).items())),
            "excerpts": [asdict(r) for r in results]}


def run_suite(backend: Any, suite: str = SUITE, runs: Path | None = None, ask: Ask | None = None,
              excerpts: Sequence[Excerpt] | None = None, cases: Path | None = None) -> dict[str, Any]:
    """`cases`: a file of the user's own excerpts in the corpus's format, run instead of the suite's data."""
    if excerpts is None:
        excerpts = read_cases(cases) if cases is not None else load_excerpts(suite)
    ask = ask or hexar_asker(backend)
    if runs is None:
        with tempfile.TemporaryDirectory(prefix="hexar-real-modules-") as tmp:
            return build_report(evaluate(excerpts, Path(tmp), ask), backend.name, suite, cases)
    runs.mkdir(parents=True, exist_ok=True)
    return build_report(evaluate(excerpts, runs, ask), backend.name, suite, cases)
