"""The one-shot path (no LangGraph) walks the same nodes as the graph and gives identical answers."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import Any

from hexar.agent.backends import Backend
from hexar.agent.context import RunSettings
from hexar.agent.oneshot import OneShot
from hexar.agent.session import Session
from hexar.evals.cases import cases

_PER_CALL = {"thread", "timings_ms"}


def _same(result: dict[str, Any]) -> dict[str, Any]:
    return {k: v for k, v in result.items() if k not in _PER_CALL}


def test_identical_answers_on_all_180_cases(suite: Path) -> None:
    backend = Backend("none", None)
    pairs: dict[str, tuple[Session, OneShot]] = {}
    for case in cases():
        if case.recording not in pairs:
            settings = RunSettings(recording=suite / case.recording, llm="none")
            pairs[case.recording] = (Session(settings, backend), OneShot(settings, backend))
        graph, oneshot = pairs[case.recording]
        expected = graph.ask(case.question)
        got = oneshot.ask(case.question)
        assert _same(got) == _same(expected), case.id
        # the same nodes ran, in the same order
        assert list(got["timings_ms"]) == list(expected["timings_ms"]), case.id
    assert len(cases()) == 180


def test_refusals_and_task_choice_match_too(suite: Path) -> None:
    settings = RunSettings(recording=suite / "bagfile_5_1", llm="none")
    graph, oneshot = Session(settings), OneShot(settings)
    for question, task in [("blorp zzzk", None), ("you didnt bring it why", "first"), ("what happened", "latest")]:
        assert _same(oneshot.ask(question, task=task)) == _same(graph.ask(question, task=task))


def test_a_cold_ask_imports_no_langgraph_and_no_scikit_learn(suite: Path) -> None:
    """What makes `hexar ask --llm none` start in under a second: checked in a fresh interpreter."""
    code = (
        "import sys\nfrom hexar.cli import main\n"
        f"code = main(['ask', {str(suite / 'bagfile_5_1')!r}, \"Why didn't you bring me the coffee?\", "
        "'--llm', 'none', '--json'])\n"
        "heavy = sorted({m.split('.')[0] for m in sys.modules} & {'sklearn', 'scipy', 'langgraph', 'langchain_core', "
        "'pandas', 'pgmpy', 'lime', 'llama_cpp'})\n"
        "print('HEAVY', heavy, code)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=True).stdout
    assert "navigation.blocked_path" in out
    assert out.strip().splitlines()[-1] == "HEAVY [] 0"
