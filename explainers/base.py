"""The component-explainer interface: e = <f_e, V_e> (paper section III)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, ClassVar, Protocol, runtime_checkable

from pydantic import BaseModel, Field

from hexar.events.log import EventLog, View
from hexar.events.records import LogLine
from hexar.events.tasks import Task

if TYPE_CHECKING:
    from hexar.explainers.registry import Registry


class Evidence(BaseModel):
    """One recorded item that supports a cause: where and when it was recorded, and what it said."""

    cause: str
    topic: str
    t: int = Field(description="message time in integer nanoseconds")
    item: str = Field(description="the log line or the value, as recorded")

    @classmethod
    def of_log(cls, cause: str, line: LogLine) -> Evidence:
        return cls(cause=cause, topic=line.origin, t=line.t, item=line.render())


class Explanation(BaseModel):
    """What a component explainer found. The person hears `text`; grading and follow-ups use the rest."""

    explainer: str
    text: str = Field(description="1-2 first-person sentences for a non-expert")
    causes: list[str] = Field(default_factory=list, description="stable cause identifiers, e.g. navigation.charging")
    evidence: list[Evidence] = Field(default_factory=list)
    counterfactual: str | None = None
    fix: str | None = None
    details: list[str] = Field(default_factory=list, description="the causal chain, deepest last, for 'why?'")
    figures: list[str] = Field(default_factory=list, description="a model's own numbers (e.g. LIME weights): shown "
                               "with the evidence, never spoken")
    confidence: float = 1.0
    enough_information: bool = True
    phrased_by: str = "template"

    @classmethod
    def not_enough(cls, explainer: str, reason: str) -> Explanation:
        return cls(
            explainer=explainer,
            text=f"I don't have enough information to say. {reason}".strip(),
            confidence=0.0,
            enough_information=False,
        )


@dataclass(frozen=True)
class Context:
    """The paper's context vector C: the task being explained, its plan and statuses, and the time window."""

    log: EventLog
    task: Task
    window: tuple[int, int]
    registry: Registry | None = field(default=None, compare=False)

    @classmethod
    def for_task(cls, log: EventLog, task: Task, registry: Registry | None = None) -> Context:
        return cls(log=log, task=task, window=task.window(), registry=registry)

    def view(self, topics: frozenset[str], window: tuple[int, int] | None = None) -> View:
        return self.log.view(topics, window or self.window)

    def with_window(self, window: tuple[int, int]) -> Context:
        return Context(self.log, self.task, window, self.registry)


@runtime_checkable
class TextModel(Protocol):
    """A chat model: messages in, text out; with `schema`, the text is JSON that fits it."""

    name: str

    def chat(
        self,
        messages: Sequence[Mapping[str, str]],
        *,
        schema: Mapping[str, Any] | None = None,
        max_tokens: int = 160,
    ) -> str: ...


class Explainer(Protocol):
    """f_e(q, C) -> Explanation over the events of `topics` (V_e)."""

    name: ClassVar[str]
    topics: ClassVar[frozenset[str]]
    description: ClassVar[str]

    def explain(self, question: str, context: Context) -> Explanation: ...
