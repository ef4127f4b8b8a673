"""Each component explainer as a tool: one list (`tool_specs`: name, explainer, description) from which both the
agent's LangGraph tools (`tools_for`) and the MCP server's tools (tools/mcp_server.py) are built. A built-in
explainer's description is the docstring of its function below, which is what the LLM router reads; a further
explainer's is the description the registry gives.

The tools run inside the agent's tool node, which sets the scope (the explainers and the context vector C of
the task being explained) for the duration of the call; the tools themselves take only the question.
LangChain is imported only when the tool objects are built (`tools_for`, `TOOLS`): a question answered without
an LLM runs the same explainers through `run_explainer` and never pays that import.
"""

from __future__ import annotations

import inspect
from collections.abc import Callable, Iterator
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


def described(fn: Callable[..., Any]) -> str:
    """A tool function's docstring as its description, the same on every Python: 3.13 strips the source's
    indentation from docstrings when it compiles them, and 3.11 and 3.12 keep it on every line but the first."""
    return inspect.cleandoc(fn.__doc__ or "")


@cache
def builtin_tools() -> tuple[BaseTool, ...]:
    """The five functions above as LangChain tools (name and argument schema taken from each, the description from
    its docstring by `described`)."""
    from langchain_core.tools import StructuredTool

    return tuple(StructuredTool.from_function(fn, description=described(fn)) for fn in _FUNCTIONS)


def __getattr__(name: str) -> Any:
    # `TOOLS` stays importable as before, built on first use rather than at import.
    if name == "TOOLS":
        return list(builtin_tools())
    raise AttributeError(name)


@dataclass(frozen=True)
class ToolSpec:
    name: str
    explainer: str
    description: str
    function: Callable[[str], dict[str, Any]] | None = None  # a built-in tool's function; None: run by name


def tool_specs(registry: Registry) -> list[ToolSpec]:
    """The five tools above plus one for every further explainer registered by entry point or config. A built-in
    description is its docstring (`described`), so both protocols say the same."""
    out = [ToolSpec(fn.__name__, TOOL_EXPLAINER[fn.__name__], described(fn), fn)
           for fn in _FUNCTIONS]
    known = set(TOOL_EXPLAINER.values())
    out += [ToolSpec(f"explain_{name}", name, description) for name, description in registry.descriptions().items()
            if name not in known]
    return out


def tools_for(registry: Registry) -> list[BaseTool]:
    """`tool_specs` as LangChain tools for the agent's router and tool node."""
    from langchain_core.tools import StructuredTool

    builtin = {t.name: t for t in builtin_tools()}
    out: list[BaseTool] = []
    for spec in tool_specs(registry):
        if spec.function is not None:
            out.append(builtin[spec.name])
            continue

        def _run(question: str, _name: str = spec.explainer) -> dict[str, Any]:
            return run_explainer(_name, question)

        out.append(StructuredTool.from_function(_run, name=spec.name, description=spec.description))
    return out


def explainer_of_tool(tool_name: str) -> str:
    return TOOL_EXPLAINER.get(tool_name, tool_name.removeprefix("explain_"))
