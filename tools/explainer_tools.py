"""Each component explainer as a LangGraph tool. The docstring is what the LLM router reads.

The tools run inside the agent's tool node, which sets the scope (the explainers and the context vector C of
the task being explained) for the duration of the call; the tools themselves take only the question.
LangChain is imported only when the tool objects are built (`tools_for`, `TOOLS`): a question answered without
an LLM runs the same explainers through `run_explainer` and never pays that import.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass
from functools import cache
from typing import TYPE_CHECKING, Any

from hexar.explainers.base import Context
from hexar.explainers.registry import Registry

if TYPE_CHECKING:
    from langchain_core.tools import BaseTool


@dataclass(frozen=True)
class ToolScope:
    registry: Registry
    context: Context


_SCOPE: ContextVar[ToolScope | None] = ContextVar("hexar_tool_scope", default=None)


@contextmanager
def scope(registry: Registry, context: Context) -> Iterator[None]:
    token = _SCOPE.set(ToolScope(registry, context))
    try:
        yield
    finally:
        _SCOPE.reset(token)


def run_explainer(name: str, question: str) -> dict[str, Any]:
    current = _SCOPE.get()
    if current is None:
        raise RuntimeError("explainer tools run only inside the agent's tool node")
    return current.registry.get(name).explain(question, current.context).model_dump()


def explain_planning(question: str) -> dict[str, Any]:
    """Explain the robot's task plan: how it turned the request into steps, a plan it rejected, a step or place
    it does not have, doing something other than what was asked, or a request it cannot do at all."""
    return run_explainer("planner", question)


def explain_navigation(question: str) -> dict[str, Any]:
    """Explain how the robot drove between rooms: why it did not get somewhere, stopped, turned around, took
    long, changed direction, moved slowly or strangely, or its speed."""
    return run_explainer("navigation", question)


def explain_asking_for_help(question: str) -> dict[str, Any]:
    """Explain how the robot looked for a person and asked them for help: nobody found, the person too far or
    not clearly seen, could not reach them, they refused or did not confirm, or an awkward approach."""
    return run_explainer("ask_human_for_help", question)


def explain_speech(question: str) -> dict[str, Any]:
    """Explain what the robot said aloud: why it stopped talking, cut a message off or did not finish it."""
    return run_explainer("text_to_speech", question)


def explain_pizza_choice(question: str) -> dict[str, Any]:
    """Explain the robot's pizza recommendation: why that pizza, and which available ingredients led to it."""
    return run_explainer("pizza_recommender", question)


_FUNCTIONS = (explain_planning, explain_navigation, explain_asking_for_help, explain_speech, explain_pizza_choice)
TOOL_EXPLAINER: dict[str, str] = {
    "explain_planning": "planner",
    "explain_navigation": "navigation",
    "explain_asking_for_help": "ask_human_for_help",
    "explain_speech": "text_to_speech",
    "explain_pizza_choice": "pizza_recommender",
}


@cache
def builtin_tools() -> tuple[BaseTool, ...]:
    """The five functions above as LangChain tools (name, docstring and argument schema taken from each)."""
    from langchain_core.tools import tool

    return tuple(tool(fn) for fn in _FUNCTIONS)


def __getattr__(name: str) -> Any:
    # `TOOLS` stays importable as before, built on first use rather than at import.
    if name == "TOOLS":
        return list(builtin_tools())
    raise AttributeError(name)


def tools_for(registry: Registry) -> list[BaseTool]:
    """The five tools above plus one for every further explainer registered by entry point or config."""
    from langchain_core.tools import StructuredTool

    out = list(builtin_tools())
    known = set(TOOL_EXPLAINER.values())
    for name, description in registry.descriptions().items():
        if name in known:
            continue

        def _run(question: str, _name: str = name) -> dict[str, Any]:
            return run_explainer(_name, question)

        out.append(StructuredTool.from_function(_run, name=f"explain_{name}", description=description))
    return out


def explainer_of_tool(tool_name: str) -> str:
    return TOOL_EXPLAINER.get(tool_name, tool_name.removeprefix("explain_"))
