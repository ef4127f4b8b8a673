"""The three methods of the paper's evaluation, each answering one case of one recording.

- `hexar`: the agent (`Session.ask`), selector and one component explainer.
- `end-to-end`: one LLM reads all the information HEXAR has (task info, the task's logs, recorded values) and
  the question; no explainers, no selector.
- `all-components`: every registered explainer runs on the task; an LLM, prompted only to select the relevant
  information, aggregates their outputs.

Runtime is the wall time of answering, without decoding the recording (done once per recording and method,
before the clock starts), so that the three methods are timed on the same work.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Protocol

from hexar.agent.backends import Backend
from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.evals.cases import Case
from hexar.evals.evidence import run_facts
from hexar.events import EventLog, read_recording
from hexar.explainers.base import Context, TextModel
from hexar.explainers.errors import ExplainerError
from hexar.explainers.registry import Registry
from hexar.prompts import load

HEXAR = "hexar"
END_TO_END = "end-to-end"
ALL_COMPONENTS = "all-components"
METHODS: tuple[str, ...] = (HEXAR, END_TO_END, ALL_COMPONENTS)
ANSWER_TOKENS = 200
# The packaged model has a 2048-token context: its prompt must leave room for the answer.
SMALL_CONTEXT_CHARS = 3_500
LARGE_CONTEXT_CHARS = 12_000


@dataclass(frozen=True)
class Answer:
    """One method's answer to one case. `causes`/`explainers` are None for methods that have none."""

    text: str
    runtime_s: float
    causes: list[str] | None = None
    explainers: list[str] | None = None
    error: str = ""
    extra: dict[str, object] = field(default_factory=dict)


class Method(Protocol):
    name: str

    def answer(self, case: Case, recording: Path) -> Answer: ...


class HexarMethod:
    """The agent; one session per recording, a new conversation per question."""

    name = HEXAR

    def __init__(self, backend: Backend) -> None:
        self.backend = backend
        self._sessions: dict[Path, Session] = {}

    def answer(self, case: Case, recording: Path) -> Answer:
        session = self._sessions.get(recording)
        if session is None:
            session = Session(RunSettings(recording=recording, llm=self.backend.name), backend=self.backend)
            self._sessions = {recording: session}  # one recording at a time: cases come grouped by recording
        started = time.perf_counter()
        result = session.ask(case.question)
        runtime = time.perf_counter() - started
        return Answer(
            text=str(result["answer"]), runtime_s=runtime, causes=list(result["causes"]),
            explainers=list(result["explainers"]), error=str(result.get("error", "")),
            extra={"route": result["route"], "fallback": result["fallback"], "timings_ms": result["timings_ms"]},
        )


class _Recordings:
    """The decoded recording of the current group of cases."""

    def __init__(self) -> None:
        self._path: Path | None = None
        self._log: EventLog | None = None

    def get(self, path: Path) -> EventLog:
        if self._path != path or self._log is None:
            self._log, self._path = read_recording(path), path
        return self._log


def _chat(model: TextModel, system: str, user: str) -> tuple[str, str]:
    """The model's reply and an error message (empty when it answered)."""
    try:
        return model.chat([{"role": "system", "content": system}, {"role": "user", "content": user}],
                          max_tokens=ANSWER_TOKENS).strip(), ""
    except ExplainerError as err:  # ModelError: unreachable server, context overflow
        return "", str(err)


def context_chars(backend: Backend) -> int:
    return SMALL_CONTEXT_CHARS if backend.name.startswith("embedded") else LARGE_CONTEXT_CHARS


class EndToEndMethod:
    name = END_TO_END

    def __init__(self, model: TextModel, budget_chars: int = LARGE_CONTEXT_CHARS) -> None:
        self.model = model
        self.budget_chars = budget_chars
        self._recordings = _Recordings()
        self._prompt = load("baseline_end_to_end")

    def answer(self, case: Case, recording: Path) -> Answer:
        log = self._recordings.get(recording)
        started = time.perf_counter()
        facts = run_facts(log, log.task(), self.budget_chars)
        text, error = _chat(self.model, self._prompt, f"{facts}\n\n## Question\n{case.question}")
        return Answer(text=text, runtime_s=time.perf_counter() - started, error=error)


class AllComponentsMethod:
    name = ALL_COMPONENTS

    def __init__(self, model: TextModel, registry_config: Path | None = None) -> None:
        self.model = model
        self.registry = Registry.load(model, registry_config)
        self._recordings = _Recordings()
        self._prompt = load("baseline_all_components")

    def answer(self, case: Case, recording: Path) -> Answer:
        log = self._recordings.get(recording)
        started = time.perf_counter()
        task = log.task()
        outputs: list[str] = []
        for name in self.registry.names:
            applies = getattr(self.registry.get(name), "applies", None)
            if applies is not None and not applies(log):
                continue  # a module this robot's recording never shows (an arm on the paper's TIAGo runs)
            try:
                exp = self.registry.get(name).explain(case.question, Context.for_task(log, task, self.registry))
                outputs.append(f"- {name}: {exp.text}")
            except ExplainerError as err:
                outputs.append(f"- {name}: (failed: {err})")
        user = "## Component explanations\n" + "\n".join(outputs) + f"\n\n## Question\n{case.question}"
        text, error = _chat(self.model, self._prompt, user)
        return Answer(text=text, runtime_s=time.perf_counter() - started, error=error,
                      extra={"components": outputs})


def build_methods(names: list[str], backend: Backend) -> tuple[list[Method], dict[str, str]]:
    """The methods that can run with this backend, and why the others cannot."""
    methods: list[Method] = []
    skipped: dict[str, str] = {}
    for name in names:
        if name == HEXAR:
            methods.append(HexarMethod(backend))
        elif backend.model is None:
            skipped[name] = "the LLM baselines need a model (--llm none)"
        elif name == END_TO_END:
            methods.append(EndToEndMethod(backend.model, context_chars(backend)))
        elif name == ALL_COMPONENTS:
            methods.append(AllComponentsMethod(backend.model))
    return methods, skipped
