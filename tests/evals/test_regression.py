"""The regression gate: a run against a committed baseline of the same backend."""

from __future__ import annotations

import copy
from pathlib import Path
from typing import Any

import pytest

from hexar.errors import HexarError
from hexar.evals import regression as reg


def report(outcomes: dict[str, bool], backend: str = "none", prompts: dict[str, str] | None = None) -> dict[str, Any]:
    cases = []
    for cid, ok in outcomes.items():
        grades = {"root_cause": ok, "incorrect_facts": False, "accuracy": ok, "selection": True}
        cases.append({"id": cid, "results": {"hexar": {"answer": f"answer {cid} {ok}", "grades": grades}}})
    return {"backend": backend, "methods": ["hexar"], "prompts": prompts or {"router.md": "abc"},
            "selection": {}, "cases": cases}


GOOD = {f"{s}.1.generic": True for s in range(1, 21)}


def test_same_run_passes(tmp_path: Path) -> None:
    path = tmp_path / "none.json"
    reg.write_baseline(report(GOOD), path)
    result = reg.compare(report(GOOD), reg.read_baseline(path))
    assert not result.failed and result.compared == {"hexar": 20} and result.answers_changed == 0
    assert reg.differences(report(GOOD), reg.read_baseline(path)) == []


def test_a_case_turning_wrong_fails_even_within_tolerance() -> None:
    worse = {**GOOD, "7.1.generic": False}
    result = reg.compare(report(worse), reg.baseline_of(report(GOOD)), tolerance=0.10)
    assert result.failed and not result.drops
    assert {(f.case, f.metric) for f in result.flips} == {("7.1.generic", "root_cause"), ("7.1.generic", "accuracy")}


def test_a_metric_drop_beyond_tolerance_fails() -> None:
    worse = {**GOOD, "7.1.generic": False, "8.1.generic": False}
    result = reg.compare(report(worse), reg.baseline_of(report(GOOD)), tolerance=0.05)
    assert {(d.metric, d.baseline, d.now) for d in result.drops} == {("root_cause", 1.0, 0.9), ("accuracy", 1.0, 0.9)}


def test_more_incorrect_facts_is_worse() -> None:
    worse = report(GOOD)
    worse["cases"][0]["results"]["hexar"]["grades"]["incorrect_facts"] = True
    result = reg.compare(worse, reg.baseline_of(report(GOOD)))
    assert [f.metric for f in result.flips] == ["incorrect_facts"]


def test_improvements_pass_but_are_differences() -> None:
    base = {**GOOD, "7.1.generic": False}
    result = reg.compare(report(GOOD), reg.baseline_of(report(base)))
    assert not result.failed
    assert reg.differences(report(GOOD), reg.baseline_of(report(base))) == [
        "hexar 7.1.generic root_cause: False -> True", "hexar 7.1.generic accuracy: False -> True"]


def test_subset_runs_compare_on_their_cases() -> None:
    subset = {k: v for k, v in GOOD.items() if k.startswith("7.")}
    result = reg.compare(report(subset), reg.baseline_of(report(GOOD)))
    assert result.compared == {"hexar": 1} and not result.failed


def test_prompt_changes_are_listed() -> None:
    result = reg.compare(report(GOOD, prompts={"router.md": "new"}), reg.baseline_of(report(GOOD)))
    assert result.prompts_changed == ["router.md"]


def test_other_backend_or_file_is_a_user_error(tmp_path: Path) -> None:
    with pytest.raises(HexarError, match="backend"):
        reg.compare(report(GOOD, backend="ollama:phi4"), reg.baseline_of(report(GOOD)))
    bad = tmp_path / "bad.json"
    bad.write_text("{}")
    with pytest.raises(HexarError, match="not a hexar eval baseline"):
        reg.read_baseline(bad)
    with pytest.raises(HexarError, match="no such file"):
        reg.read_baseline(tmp_path / "missing.json")


def test_baseline_keeps_no_more_than_it_gates() -> None:
    full = report(GOOD)
    full["cases"][0]["results"]["hexar"]["grades"]["claims"] = ["navigation.charging"]
    kept = reg.baseline_of(copy.deepcopy(full))["methods"]["hexar"]["1.1.generic"]
    assert set(kept) == {*reg.GATED, "answer"}
