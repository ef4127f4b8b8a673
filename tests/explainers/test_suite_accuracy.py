"""Issue acceptance: every scenario's module explainer finds the ground truth, only it, with real evidence."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.evals.cases import recording_name, scenarios
from hexar.events import read_recording
from hexar.explainers.base import Context, Evidence
from hexar.explainers.evidence_check import exists
from hexar.explainers.registry import Registry


@pytest.mark.parametrize("sid", [s.id for s in scenarios()])
def test_module_explainer_finds_ground_truth_on_every_variant(suite: Path, sid: int) -> None:
    registry = Registry.load()
    scenario = next(s for s in scenarios() if s.id == sid)
    for variant in (1, 2, 3):
        log = read_recording(suite / recording_name(sid, variant))
        questions = [q.format(object=scenario.variants[variant - 1].object) for q in scenario.questions]
        for question in questions:
            exp = registry.get(scenario.explainer).explain(question, Context.for_task(log, log.task(), registry))
            assert scenario.cause in exp.causes, (variant, question, exp.causes, exp.text)
            assert set(exp.causes) <= {scenario.cause, *scenario.also}, (variant, exp.causes)
            assert exp.evidence, "a finding without evidence is a claim"
            missing = [ev for ev in exp.evidence if not exists(log, ev)]
            assert not missing, missing


def test_evidence_check_rejects_items_not_in_the_recording(suite: Path) -> None:
    log = read_recording(suite / recording_name(5, 1))
    registry = Registry.load()
    exp = registry.get("navigation").explain("What happened?", Context.for_task(log, log.task(), registry))
    real = exp.evidence[0]
    assert exists(log, real)
    assert not exists(log, real.model_copy(update={"t": real.t + 1}))
    assert not exists(log, real.model_copy(update={"item": real.item.replace("ERROR", "WARN")}))
    assert not exists(log, Evidence(cause="x", topic="/joy_priority", t=real.t, item="data=True"))


def test_another_seed_changes_values_not_scenarios(tmp_path: Path) -> None:
    from hexar.evals.scenarios.suite import simulate_suite

    simulate_suite(tmp_path, seed=7, only=lambda s, v: v == 1)
    registry = Registry.load()
    for scenario in scenarios():
        log = read_recording(tmp_path / recording_name(scenario.id, 1))
        question = scenario.questions[2].format(object=scenario.variants[0].object)
        exp = registry.get(scenario.explainer).explain(question, Context.for_task(log, log.task(), registry))
        assert scenario.cause in exp.causes, (scenario.id, exp.causes)
