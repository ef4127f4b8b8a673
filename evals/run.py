"""Runs the evaluation: picks the cases, makes sure their recordings exist, asks every method, grades."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from itertools import groupby
from pathlib import Path
from typing import Any

from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

from hexar.agent.backends import Backend
from hexar.errors import USER_ERRORS, HexarError
from hexar.evals.cases import KINDS, Case, cases, scenarios
from hexar.evals.graders import Graded, Grader, Grades, Truth
from hexar.evals.judge import Judge, Verdict
from hexar.evals.methods import METHODS, Answer, Method, build_methods


def modules() -> list[str]:
    return list(dict.fromkeys(s.module for s in scenarios()))


def module_of(name: str) -> str:
    """A module by its id or the paper's words: "ask human for help", "pizza", "tts"."""
    key = name.strip().lower().replace(" ", "_").replace("-", "_")
    aliases = {"tts": "text_to_speech", "pizza": "pizza_recommender", "planner": "planning",
               "ask_human": "ask_human_for_help"}
    key = aliases.get(key, key)
    if key not in modules():
        raise HexarError(f"unknown module {name!r}: use one of {', '.join(modules())}")
    return key


@dataclass(frozen=True)
class Selection:
    """Which of the 180 cases to run; empty filters select everything."""

    scenarios: frozenset[int] = frozenset()
    modules: frozenset[str] = frozenset()
    kinds: frozenset[str] = frozenset()
    first: int | None = None  # the first N cases of each scenario, in case order

    def __post_init__(self) -> None:
        known = {s.id for s in scenarios()}
        if bad := sorted(self.scenarios - known):
            raise HexarError(f"unknown scenario {bad[0]}: use 1-{max(known)}")
        if bad_kinds := sorted(self.kinds - set(KINDS)):
            raise HexarError(f"unknown question kind {bad_kinds[0]!r}: use {', '.join(KINDS)}")
        for m in self.modules:
            module_of(m)
        if self.first is not None and self.first < 1:
            raise HexarError("--first must be at least 1")

    def pick(self, pool: Sequence[Case]) -> list[Case]:
        wanted_modules = {module_of(m) for m in self.modules}
        chosen = [c for c in pool
                  if (not self.scenarios or c.scenario.id in self.scenarios)
                  and (not wanted_modules or c.scenario.module in wanted_modules)
                  and (not self.kinds or c.kind in self.kinds)]
        if self.first is not None:
            chosen = [c for _, group in groupby(chosen, key=lambda c: c.scenario.id) for c in list(group)[:self.first]]
        if not chosen:
            raise HexarError("no case matches the selection")
        return chosen

    def as_dict(self) -> dict[str, Any]:
        return {"scenarios": sorted(self.scenarios), "modules": sorted(self.modules), "kinds": sorted(self.kinds),
                "first": self.first}


def default_runs(seed: int = 0) -> Path:
    return Path.home() / ".cache" / "hexar" / "eval-runs" / f"seed-{seed}"


def ensure_recordings(runs: Path, chosen: Sequence[Case], seed: int, fresh: bool = False) -> list[Path]:
    """Simulate the recordings the cases need that `runs` lacks (all of them when `fresh`); the paths written."""
    from hexar.evals.scenarios.suite import simulate_suite

    if runs.exists() and not runs.is_dir():
        raise HexarError(f"--runs must be a folder: {runs}")
    missing = {(c.scenario.id, c.variant) for c in chosen if fresh or not (runs / c.recording).exists()}
    if not missing:
        return []
    return simulate_suite(runs, "sqlite3", seed, only=lambda s, v: (s, v) in missing)


@dataclass
class MethodResult:
    answer: Answer
    grades: Grades
    verdict: Verdict | None = None


@dataclass
class CaseResult:
    case: Case
    results: dict[str, MethodResult] = field(default_factory=dict)


@dataclass
class RunOutput:
    backend: str
    methods: list[str]
    skipped: dict[str, str]
    results: list[CaseResult]
    simulated: int
    judge: str | None


def _ask(method: Method, case: Case, recording: Path) -> Answer:
    try:
        return method.answer(case, recording)
    except USER_ERRORS as err:  # a broken recording or backend fails that answer, not the run
        return Answer(text="", runtime_s=0.0, error=f"{type(err).__name__}: {err}")


Step = Callable[[str], None]


def evaluate(chosen: Sequence[Case], runs: Path, methods: Sequence[Method], judge: Judge | None = None,
             step: Step | None = None) -> list[CaseResult]:
    grader = Grader()
    out: list[CaseResult] = []
    for case in chosen:
        row = CaseResult(case)
        truth = Truth.of(case)
        for method in methods:
            ans = _ask(method, case, runs / case.recording)
            grades = grader.grade(truth, Graded(ans.text, ans.causes, ans.explainers))
            verdict = judge.grade(case, ans.text) if judge is not None else None
            row.results[method.name] = MethodResult(ans, grades, verdict)
            if step is not None:
                step(f"{method.name} {case.id}")
        out.append(row)
    return out


def run(runs: Path, backend: Backend, selection: Selection, method_names: Sequence[str] = METHODS,
        judge: Judge | None = None, seed: int = 0, console: Console | None = None, fresh: bool = False) -> RunOutput:
    """Everything `hexar eval` measures; `console` shows a progress bar."""
    if bad := [m for m in method_names if m not in METHODS]:
        raise HexarError(f"unknown method {bad[0]!r}: use {', '.join(METHODS)}")
    chosen = selection.pick(cases())
    simulated = ensure_recordings(runs, chosen, seed, fresh)
    methods, skipped = build_methods(list(dict.fromkeys(method_names)), backend)
    total = len(chosen) * len(methods)
    if console is None:
        results = evaluate(chosen, runs, methods, judge)
    else:
        columns = (TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn())
        with Progress(*columns, console=console, transient=True) as bar:
            task = bar.add_task("eval", total=total)

            def step(label: str) -> None:
                bar.update(task, advance=1, description=f"eval {label}")

            results = evaluate(chosen, runs, methods, judge, step)
    return RunOutput(backend.name, [m.name for m in methods], skipped, results, len(simulated),
                     judge.name if judge is not None else None)
