"""The HEXAR agent as a LangGraph StateGraph, built from the nodes and edges in agent/routing.py."""

from __future__ import annotations

from typing import Any

from langgraph.graph import END, START, StateGraph
from langgraph.graph.state import CompiledStateGraph

from hexar.agent.context import RunContext
from hexar.agent.routing import END as ROUTING_END
from hexar.agent.routing import (
    FIRST,
    NEXT,
    NODES,
    after_context,
    after_failure_check,
    after_intake,
    after_router,
)
from hexar.agent.state import AgentState

__all__ = ["after_context", "after_failure_check", "after_intake", "after_router", "build", "mermaid"]


def build(checkpointer: Any = None) -> CompiledStateGraph[AgentState, RunContext, AgentState, AgentState]:
    g = StateGraph(AgentState, context_schema=RunContext)
    for name, fn in NODES.items():
        g.add_node(name, fn)
    g.add_edge(START, FIRST)
    for name, nxt in NEXT.items():
        if callable(nxt):
            g.add_conditional_edges(name, nxt)
        else:
            g.add_edge(name, END if nxt == ROUTING_END else nxt)
    return g.compile(checkpointer=checkpointer)


def mermaid() -> str:
    return build().get_graph().draw_mermaid()
