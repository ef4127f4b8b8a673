"""The HEXAR agent as a LangGraph StateGraph."""

from __future__ import annotations

from typing import Any, Literal

from langgraph.graph import END, START, StateGraph
from langgraph.graph.state import CompiledStateGraph

from hexar.agent import nodes
from hexar.agent.context import RunContext
from hexar.agent.state import AgentState


def after_intake(state: AgentState) -> Literal["context", "followup", "__end__"]:
    intent = state.get("intent")
    if intent == "invalid":
        return "__end__"
    if intent in {"deeper", "helped"}:
        return "followup"
    return "context"


def after_context(state: AgentState) -> Literal["failure_check", "walk", "content"]:
    intent = state.get("intent")
    if intent == "else":
        return "walk"
    return "content" if intent == "content" else "failure_check"


def after_failure_check(state: AgentState) -> Literal["tools", "router"]:
    return "tools" if state.get("selected") else "router"


def after_router(state: AgentState) -> Literal["tools", "answer"]:
    return "tools" if state.get("selected") else "answer"


def build(checkpointer: Any = None) -> CompiledStateGraph[AgentState, RunContext, AgentState, AgentState]:
    g = StateGraph(AgentState, context_schema=RunContext)
    g.add_node("intake", nodes.intake)
    g.add_node("context", nodes.context)
    g.add_node("failure_check", nodes.failure_check)
    g.add_node("router", nodes.router)
    g.add_node("tools", nodes.tools)
    g.add_node("answer", nodes.answer)
    g.add_node("followup", nodes.followup)
    g.add_node("walk", nodes.walk)
    g.add_node("content", nodes.content)
    g.add_edge(START, "intake")
    g.add_conditional_edges("intake", after_intake)
    g.add_conditional_edges("context", after_context)
    g.add_conditional_edges("failure_check", after_failure_check)
    g.add_conditional_edges("router", after_router)
    g.add_edge("tools", "answer")
    g.add_edge("answer", END)
    g.add_edge("followup", END)
    g.add_edge("walk", END)
    g.add_edge("content", END)
    return g.compile(checkpointer=checkpointer)


def mermaid() -> str:
    return build().get_graph().draw_mermaid()
