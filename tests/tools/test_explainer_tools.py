"""One list of explainer tools for both protocols: the agent's LangGraph tools and the MCP tools carry the same
names, explainers and descriptions, built-in and added explainers alike."""

from __future__ import annotations

from pathlib import Path

from hexar.tools.explainer_tools import explainer_of_tool, tool_specs, tools_for
from tests.explainers.test_registry_descriptions import _registry


def test_langgraph_tools_are_built_from_the_tool_specs(tmp_path: Path) -> None:
    registry = _registry(tmp_path)  # the five built-in explainers plus battery, quiet, diagnostics, undocumented
    specs = tool_specs(registry)
    agent = tools_for(registry)
    assert [(s.name, s.description) for s in specs] == [(t.name, t.description) for t in agent]
    assert [s.explainer for s in specs] == [explainer_of_tool(t.name) for t in agent]
    assert {s.explainer for s in specs} == set(registry.names)
    planning = next(s for s in specs if s.name == "explain_planning")
    # the whole docstring, without the source's indentation on any Python (3.13 strips it when compiling, 3.11 not)
    assert planning.description.startswith("Explain the robot's task plan")
    assert "place\nit does not have, doing something other" in planning.description
