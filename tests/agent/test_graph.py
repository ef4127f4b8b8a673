from __future__ import annotations

from pathlib import Path

from hexar.agent.graph import after_failure_check, after_intake, mermaid

ROOT = Path(__file__).resolve().parents[2]


def test_mermaid_drawing_matches_the_committed_one() -> None:
    committed = (ROOT / "docs" / "agent_graph.mmd").read_text()
    assert mermaid() == committed, "graph changed: regenerate docs/agent_graph.mmd and the README drawing"
    readme = (ROOT / "README.md").read_text()
    body = committed.split("graph TD;", 1)[1].strip()
    assert body.splitlines()[0].strip() in readme


def test_routing_functions() -> None:
    assert after_intake({"intent": "invalid"}) == "__end__"
    assert after_intake({"intent": "deeper"}) == "followup"
    assert after_intake({"intent": "new"}) == "context"
    assert after_failure_check({"selected": ["planner"]}) == "tools"
    assert after_failure_check({"selected": []}) == "router"
