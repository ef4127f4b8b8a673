"""The embedded model end to end (slow, opt-in: `pytest -m slow`): one case per scenario."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.backends import embedded_available, resolve
from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.causes import stated_causes
from hexar.evals.cases import cases

pytestmark = pytest.mark.slow


@pytest.mark.skipif(not embedded_available(), reason="embedded model not installed (scripts/setup.sh --full)")
def test_embedded_selects_and_guard_holds(suite: Path) -> None:
    backend = resolve("embedded")
    picked = [c for c in cases() if c.variant == 1 and c.kind == "task"]
    assert len(picked) == 20
    right = 0
    for case in picked:
        settings = RunSettings(recording=suite / case.recording, llm="embedded", phrase=True, time_budget_s=120)
        result = Session(settings, backend=backend).ask(case.question)
        right += result["explainers"][:1] == [case.scenario.explainer]
        allowed = set(result["causes"]) | {case.scenario.cause, *case.scenario.also}
        own_modules = {c.split(".")[0] for c in result["causes"]}
        foreign = {c for c in stated_causes(result["answer"]) - allowed if c.split(".")[0] not in own_modules}
        assert not foreign, (case.id, result["answer"], result["fallback"])
    assert right >= 19
