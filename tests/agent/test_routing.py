"""Issue acceptance: on the 180 cases the failure check routes every failure without an LLM call, and the
remaining cases reach the right explainer; answers state the ground-truth cause."""

from __future__ import annotations

from pathlib import Path

from hexar.agent.backends import Backend
from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.causes import vocabulary
from hexar.evals.cases import cases
from hexar.events import read_recording
from tests.agent.helpers import CountingModel


def test_all_cases_route_right_and_failures_never_call_the_llm(suite: Path) -> None:
    sessions: dict[str, tuple[Session, CountingModel]] = {}
    wrong = []
    for case in cases():
        if case.recording not in sessions:
            model = CountingModel()
            settings = RunSettings(recording=suite / case.recording, llm="none", phrase=False)
            sessions[case.recording] = (Session(settings, backend=Backend("counting", model)), model)
        session, model = sessions[case.recording]
        before = len(model.calls)
        result = session.ask(case.question)
        task = read_recording(suite / case.recording).task()
        failed = task.outcome in {"failed", "invalid"}
        if failed:
            assert result["route"] == "failure_check", case.id
            assert len(model.calls) == before, f"{case.id}: the failure check must not ask the LLM"
        if result["explainers"][:1] != [case.scenario.explainer]:
            wrong.append(case.id)
        assert case.scenario.cause in result["causes"], (case.id, result["causes"])
        assert vocabulary()[case.scenario.cause].stated_in(result["answer"]), (case.id, result["answer"])
    assert wrong == []


def test_invalid_plan_and_unfulfilled_plan_go_to_the_planner(suite: Path) -> None:
    for rec in ("bagfile_2_3", "bagfile_3_1"):
        result = Session(RunSettings(recording=suite / rec, llm="none")).ask("Why didn't you do it?")
        assert result["route"] == "failure_check"
        assert result["explainers"] == ["planner"]
