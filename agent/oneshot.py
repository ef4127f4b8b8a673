"""One question, one answer, no conversation: the agent's nodes walked in graph order without LangGraph.

`hexar ask` (one question, a file of questions, or many recordings) answers every question as a new
conversation, so it needs neither checkpoints nor LangGraph's machinery, whose import costs more than a second
on a cold start. It runs the same node functions along the same edges (agent/routing.py) and merges each
node's update into the state the way LangGraph does for keys without reducers: the update replaces the value.
tests/agent/test_oneshot.py checks that both give identical answers on all 180 eval cases.
"""

from __future__ import annotations

import time
import uuid
from dataclasses import dataclass
from typing import Any, cast

from hexar.agent.backends import Backend, resolve
from hexar.agent.context import RunContext, RunSettings
from hexar.agent.errors import AgentError
from hexar.agent.questions import bounded
from hexar.agent.routing import END, FIRST, NEXT, NO_EXPLAINER, NODES
from hexar.agent.state import AgentState
from hexar.explainers.base import Explanation


@dataclass(frozen=True)
class _Runtime:
    """What a node reads from LangGraph's Runtime: only the run context."""

    context: RunContext


def walk(update: dict[str, Any], context: RunContext, recursion_limit: int) -> dict[str, Any]:
    """Run the nodes from the first along the edges until the end; the state each node saw, merged."""
    state: dict[str, Any] = dict(update)
    runtime = _Runtime(context)
    node, steps = FIRST, 0
    while node != END:
        steps += 1
        if steps > recursion_limit:
            raise AgentError(f"the agent took more than {recursion_limit} steps without answering")
        state.update(NODES[node](state, runtime))
        nxt = NEXT[node]
        node = nxt if isinstance(nxt, str) else nxt(cast(AgentState, state))
    return state


def result_of(state: dict[str, Any], backend: str, recording: str, thread: str, started: float) -> dict[str, Any]:
    """The answer as `hexar ask --json` prints it (shared with the conversational Session)."""
    # a turn answered without an explainer keeps the conversation's explanations, but reports none of them
    told = state.get("intent") not in NO_EXPLAINER
    exps = [Explanation.model_validate(e) for e in state.get("explanations", [])] if told else []
    timings = dict(state.get("timings_ms", {}))
    timings["total"] = round((time.perf_counter() - started) * 1000, 2)
    followup = state.get("route") == "followup" and state.get("intent") in {"deeper", "helped"}
    return {
        "answer": state.get("answer", ""),
        "error": state.get("error", ""),
        "explainers": [e.explainer for e in exps],
        "route": state.get("route", "none"),
        "intent": state.get("intent", "new"),
        "backend": backend,
        "phrased_by": [e.phrased_by for e in exps] if not followup else [],
        "causes": [c for e in exps for c in e.causes],
        "enough_information": all(e.enough_information for e in exps),
        "evidence": [ev.model_dump() for e in exps for ev in e.evidence],
        "figures": [f for e in exps for f in e.figures],
        "counterfactual": next((e.counterfactual for e in exps if e.counterfactual), None),
        "fix": next((e.fix for e in exps if e.fix), None),
        "fallback": state.get("fallback", []),
        "task_id": state.get("task_id", ""),
        "thread": thread,
        "recording": recording,
        "timings_ms": timings,
    }


class OneShot:
    """Answers questions about one recording, each as a new conversation (what `Session.ask` does with a fresh
    thread), with the same result dictionary."""

    def __init__(self, settings: RunSettings, backend: Backend | None = None) -> None:
        self.settings = settings
        self.backend = backend or resolve(settings.llm)
        self.context = RunContext.create(settings, self.backend)
        self.context.log  # noqa: B018 -- decode once, so a bad recording fails before the first question

    def ask(self, question: str, task: str | None = None) -> dict[str, Any]:
        thread = uuid.uuid4().hex[:12]
        started = time.perf_counter()
        self.context.started = time.monotonic()
        update: dict[str, Any] = {"question": bounded(question)}
        if task is not None:
            update["task_ref"] = task
        state = walk(update, self.context, self.settings.recursion_limit)
        return result_of(state, self.backend.name, str(self.settings.recording), thread, started)
