"""The agent's state: plain data only, so the SQLite checkpointer can keep a conversation."""

from __future__ import annotations

from typing import Any, Literal, TypedDict

Intent = Literal["new", "deeper", "helped", "else", "switch", "content", "invalid", "smalltalk", "about",
                 "offtopic"]
# Refusals (the result's error is set) whose answer a conversation says as its reply: small talk gets one, and a
# question off the robot's topic hears why, not "not understood".
SAID_REFUSALS = frozenset({"smalltalk", "offtopic"})
Route = Literal["failure_check", "recovery", "llm", "named", "classifier", "findings", "followup", "none"]


class Turn(TypedDict):
    question: str
    answer: str
    explainers: list[str]


class AgentState(TypedDict, total=False):
    # the turn being answered
    question: str
    intent: Intent
    task_ref: str | None
    asked: str  # the module a question names that its task never ran ("" for none)
    object: str  # the object of the task's pick and place steps a question asks about ("" for none)
    # context vector C (the recording stays on disk; the run context caches its decoded log)
    task_id: str
    task_outcome: str
    candidates: list[str]
    # selection
    route: Route
    selected: list[str]
    # results
    explanations: list[dict[str, Any]]
    answer: str
    error: str
    fallback: list[str]
    depth: int
    used: list[str]
    told: list[str]  # causes the person has heard in this conversation about this task
    timings_ms: dict[str, float]
    history: list[Turn]
