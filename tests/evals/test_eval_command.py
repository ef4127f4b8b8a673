"""`hexar eval` end to end on a few cases, with a fake LLM behind both baselines and the judge."""

from __future__ import annotations

import io
import json
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import pytest
from rich.console import Console

from hexar.agent.backends import Backend
from hexar.errors import HexarError
from hexar.evals.cli import EvalOptions, eval_command
from hexar.evals.methods import ALL_COMPONENTS, END_TO_END, HEXAR


class FakeLLM:
    """End-to-end: names the charger when the recording shows it; all-components: repeats every component."""

    name = "fake:llm"

    def __init__(self, good: bool = True) -> None:
        self.good = good

    def chat(self, messages: Sequence[Mapping[str, str]], *, schema: Mapping[str, Any] | None = None,
             max_tokens: int = 160) -> str:
        user = messages[-1]["content"]
        if schema is not None:
            props = schema.get("properties", {})
            if "root_cause" in props:
                return json.dumps({"root_cause": 1, "incorrect_facts": 0, "reason": "fake"})
            return json.dumps({"explainer": "none"})
        if "## Component explanations" in user:
            return " ".join(line.split(": ", 1)[1] for line in user.splitlines() if line.startswith("- "))
        if "## Question" in user:
            if self.good and "/power/is_charging=True" in user:
                return "I was plugged into my charger, so I could not drive."
            return "Nothing went wrong."
        return ""  # an explainer asking for phrasing keeps its template


@pytest.fixture(scope="module")
def runs(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return tmp_path_factory.mktemp("runs")


def options(runs: Path, out: Path, **kw: Any) -> EvalOptions:
    return EvalOptions(out=out, runs=runs, scenarios=(7,), first=2, progress=False, **kw)


def test_three_methods_graded_tested_and_written(runs: Path, tmp_path: Path) -> None:
    console = Console(file=io.StringIO(), width=160)
    code = eval_command(options(runs, tmp_path / "out", audit=3, write_baseline=tmp_path / "base.json"), console,
                        backend=Backend("fake:llm", FakeLLM()), judge_model=FakeLLM())
    assert code == 0
    report = json.loads((tmp_path / "out" / "report.json").read_text())
    assert report["methods"] == [HEXAR, END_TO_END, ALL_COMPONENTS] and len(report["cases"]) == 2
    assert report["summary"][END_TO_END]["root_cause"]["mean"] == 1.0
    assert report["statistics"]["applicable"] and set(report["statistics"]["metrics"]) == {
        "root_cause", "incorrect_facts", "accuracy"}
    assert report["judge"]["agreement"][HEXAR][0]["judged"] == 2
    assert "baseline_end_to_end.md" in report["prompts"]
    for name in ("results.md", "fig5_metrics.png", "fig6_modules.png", "audit.md"):
        assert (tmp_path / "out" / name).stat().st_size > 0
    text = console.file.getvalue()  # type: ignore[attr-defined]
    assert "Audit: 3 answers" in text and "End-to-end" in text


def test_a_worse_run_fails_the_gate(runs: Path, tmp_path: Path) -> None:
    base = tmp_path / "base.json"
    assert eval_command(options(runs, tmp_path / "a", write_baseline=base, figures=False),
                        Console(file=io.StringIO()), backend=Backend("fake:llm", FakeLLM())) == 0
    console = Console(file=io.StringIO(), width=200)
    code = eval_command(options(runs, tmp_path / "b", baseline=base, figures=False), console,
                        backend=Backend("fake:llm", FakeLLM(good=False)))
    assert code == 1
    text = console.file.getvalue()  # type: ignore[attr-defined]
    assert "REGRESSION" in text and "7.1.generic" in text
    report = json.loads((tmp_path / "b" / "report.json").read_text())
    assert report["regression"]["failed"] and report["regression"]["flips"]


def test_llm_none_reports_baselines_not_applicable(runs: Path, tmp_path: Path) -> None:
    code = eval_command(options(runs, tmp_path / "out", llm="none", figures=False), Console(file=io.StringIO()))
    report = json.loads((tmp_path / "out" / "report.json").read_text())
    assert code == 0 and report["methods"] == [HEXAR]
    assert set(report["not_applicable"]) == {END_TO_END, ALL_COMPONENTS}
    assert not report["statistics"]["applicable"] and "not applicable" in report["statistics"]["reason"]
    assert "n/a (needs an LLM)" in (tmp_path / "out" / "results.md").read_text()


@pytest.mark.parametrize(("kw", "message"), [
    ({"scenarios": (21,)}, "unknown scenario"),
    ({"modules": ("arms",)}, "unknown module"),
    ({"kinds": ("rude",)}, "unknown question kind"),
    ({"methods": ("oracle",)}, "unknown method"),
    ({"audit": -1}, "--audit"),
    ({"tolerance": 2.0}, "--tolerance"),
])
def test_user_errors(runs: Path, tmp_path: Path, kw: dict[str, Any], message: str) -> None:
    opts = EvalOptions(out=tmp_path / "out", runs=runs, llm="none", progress=False, **kw)
    with pytest.raises(HexarError, match=message):
        eval_command(opts, Console(file=io.StringIO()))


def test_baseline_of_another_backend_is_refused_before_running(tmp_path: Path) -> None:
    base = Path(__file__).resolve().parents[2] / "evals" / "baselines" / "none.json"
    opts = EvalOptions(out=tmp_path / "out", runs=tmp_path / "never", baseline=base, progress=False)
    with pytest.raises(HexarError, match="backend"):
        eval_command(opts, Console(file=io.StringIO()), backend=Backend("fake:llm", FakeLLM()))
    assert not (tmp_path / "never").exists()
