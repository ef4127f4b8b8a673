"""The agent's nodes and edges, defined once: LangGraph builds the graph from them (agent/graph.py), and a
one-shot question walks the same nodes in the same order without importing LangGraph (agent/oneshot.py)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Literal

from hexar.agent import followup_node, nodes
from hexar.agent.state import AgentState

END = "__end__"
# Intents answered at intake, by no explainer: refused, small talk, off the robot's topic, or about HEXAR itself.
NO_EXPLAINER = frozenset({"invalid", "smalltalk", "about", "offtopic"})


def after_intake(state: AgentState) -> Literal["context", "followup", "__end__"]:
    intent = state.get("intent")
    if intent in NO_EXPLAINER:
        return "__end__"
    if intent in {"deeper", "helped"}:
        return "followup"
    return "context"


def after_context(state: AgentState) -> Literal["failure_check", "walk", "content"]:
    intent = state.get("intent")
    if intent == "else":
        return "walk"
    return "content" if intent == "content" else "failure_check"


def after_failure_check(state: AgentState) -> Literal["tools", "router", "answer"]:
    if state.get("route") == "recovery":  # the recovery task's answer is the failure before it, already found
        return "answer"
    return "tools" if state.get("selected") else "router"


def after_router(state: AgentState) -> Literal["tools", "answer"]:
    return "tools" if state.get("selected") else "answer"


FIRST = "intake"
NODES: dict[str, Callable[..., dict[str, Any]]] = {
    "intake": nodes.intake,
    "context": nodes.context,
    "failure_check": nodes.failure_check,
    "router": nodes.router,
    "tools": nodes.tools,
    "answer": nodes.answer,
    "followup": followup_node.followup,
    "walk": nodes.walk,
    "content": nodes.content,
}
# Where each node goes next: a fixed node, or a function of the state (a conditional edge).
NEXT: dict[str, str | Callable[[AgentState], str]] = {
    "intake": after_intake,
    "context": after_context,
    "failure_check": after_failure_check,
    "router": after_router,
    "tools": "answer",
    "answer": END,
    "followup": END,
    "walk": END,
    "content": END,
}
