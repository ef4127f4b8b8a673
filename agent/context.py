"""Run settings and the resources a run shares across turns (kept apart from the checkpointed state)."""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path

from hexar.agent.backends import Backend
from hexar.agent.classifier import QuestionClassifier, default_classifier
from hexar.events import EventLog, read_recording
from hexar.events.tasks import WHOLE, Task, whole_recording
from hexar.explainers.registry import Registry


@dataclass(frozen=True)
class RunSettings:
    recording: Path
    llm: str = "auto"
    time_budget_s: float = 20.0
    recursion_limit: int = 16
    registry_config: Path | None = None
    # None: phrase with Ollama, not with the embedded model (on 2 CPU cores a 1.5B rewrite costs 5-15 s per
    # answer and the faithfulness guard rejects many of them; routing is where it earns its time).
    phrase: bool | None = None


@dataclass
class RunContext:
    """What every node may use: settings, the decoded recording, the explainers and the model."""

    settings: RunSettings
    backend: Backend
    registry: Registry
    probe: Registry  # the same explainers without a model: cheap grounded findings for routing
    classifier: QuestionClassifier
    _log: EventLog | None = field(default=None, repr=False)
    started: float = field(default_factory=time.monotonic)

    @classmethod
    def create(cls, settings: RunSettings, backend: Backend) -> RunContext:
        phrase = settings.phrase if settings.phrase is not None else backend.name.startswith("ollama")
        probe = Registry.load(None, settings.registry_config)
        phrasing = backend.model if phrase else None
        return cls(
            settings=settings,
            backend=backend,
            registry=Registry.load(phrasing, settings.registry_config) if phrasing is not None else probe,
            probe=probe,
            classifier=default_classifier(),
        )

    @property
    def log(self) -> EventLog:
        if self._log is None:
            self._log = read_recording(self.settings.recording)
        return self._log

    def task(self, ref: str | None = None) -> Task:
        """A task of the recording (EventLog.task); of one that holds none, the whole recording for WHOLE."""
        if ref == WHOLE and not self.log.tasks:
            return whole_recording(self.log.start, self.log.end)
        return self.log.task(ref)

    def budget_left(self) -> float:
        return self.settings.time_budget_s - (time.monotonic() - self.started)
