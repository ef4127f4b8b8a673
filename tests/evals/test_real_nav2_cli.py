"""`hexar eval --suite real-nav2`: the command, its report files, its baseline gate and its bad input."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from hexar.cli import main
from hexar.errors import HexarError
from hexar.evals.real_nav2 import corpus
from hexar.evals.real_nav2_cli import baseline_of, compare, read_baseline, render

BASELINE = Path(__file__).resolve().parents[2] / "evals" / "baselines" / "real_nav2_none.json"


@pytest.fixture(scope="module")
def run(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, int]:
    out = tmp_path_factory.mktemp("out")
    code = main(["eval", "--suite", "real-nav2", "--llm", "none", "--out", str(out), "--runs",
                 str(tmp_path_factory.mktemp("runs")), "--write-baseline", str(out / "baseline.json")])
    return out, code


def report_of(run: tuple[Path, int]) -> dict[str, Any]:
    data: dict[str, Any] = json.loads((run[0] / "report.json").read_text(encoding="utf-8"))
    return data


def test_the_suite_writes_json_and_a_table_per_distro(run: tuple[Path, int]) -> None:
    out, code = run
    assert code == 0
    report = report_of(run)
    assert report["suite"] == "real-nav2" and report["n"] == len(corpus())
    assert set(report["by_distro"]) == {e.distro for e in corpus()}
    md = (out / "results.md").read_text(encoding="utf-8")
    assert "### Per distro" in md and "### Per diagnosed cause" in md and "### Excerpts still wrong" in md
    for distro in report["by_distro"]:
        assert f"| {distro} | " in md


def test_same_run_passes_its_own_baseline(run: tuple[Path, int]) -> None:
    out, _ = run
    assert main(["eval", "--suite", "real-nav2", "--out", str(out / "again"), "--baseline",
                 str(out / "baseline.json")]) == 0


def test_an_excerpt_turning_wrong_is_a_regression(run: tuple[Path, int]) -> None:
    report = report_of(run)
    baseline = baseline_of(report)
    some = report["excerpts"][0]["id"]
    baseline["excerpts"][some]["verdict"] = "named"
    if report["excerpts"][0]["text"]["verdict"] == "named":
        baseline["excerpts"][some]["unsupported"] = []
        report["excerpts"][0]["text"]["unsupported"] = ["navigation.charging"]
    assert compare(report, baseline)[0].startswith(some)


def test_a_rate_drop_beyond_tolerance_is_a_regression(run: tuple[Path, int]) -> None:
    report = report_of(run)
    baseline = baseline_of(report)
    baseline["summary"]["text"]["no_unsupported_rate"] = 1.5
    assert any(w.startswith("no_unsupported_rate") for w in compare(report, baseline))


def test_excerpts_the_baseline_does_not_know_are_not_compared(run: tuple[Path, int]) -> None:
    report = report_of(run)
    baseline = baseline_of(report)
    del baseline["excerpts"][report["excerpts"][0]["id"]]
    assert compare(report, baseline) == []


def test_committed_baseline_still_passes(run: tuple[Path, int]) -> None:
    assert compare(report_of(run), read_baseline(BASELINE)) == []


def test_markdown_lists_what_is_still_wrong(run: tuple[Path, int]) -> None:
    report = report_of(run)
    wrong = [e["id"] for e in report["excerpts"] if e["text"]["verdict"] == "wrong"]
    md = render(report)
    assert all(f"`{i}`" in md for i in wrong)


@pytest.mark.parametrize("args, message", [
    (["--suite", "real-nav3"], "unknown suite 'real-nav3'"),
    # every suite is named, the module suites too (they were missing from a wrong nav suite's list)
    (["--suite", "real-nav3"], "real-nav2-blind29, real-modules, real-modules-heldout"),
    (["--suite", "real-modules-heldout99"], "use paper, real-nav2, "),
    (["--suite", "real-nav2", "--scenario", "3"], "--scenario belong to the paper's suite"),
    (["--suite", "real-nav2", "--tolerance", "2"], "--tolerance is a fraction"),
])
def test_bad_options_are_one_line_errors(args: list[str], message: str, tmp_path: Path,
                                         capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["eval", *args, "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr()
    assert message in err.out + err.err and "Traceback" not in err.out + err.err


def test_a_baseline_of_another_suite_is_refused(tmp_path: Path) -> None:
    other = tmp_path / "none.json"
    other.write_text(json.dumps({"schema": 1, "backend": "none", "methods": {}}), encoding="utf-8")
    with pytest.raises(HexarError, match="not a real-nav2 baseline"):
        read_baseline(other)
    assert main(["eval", "--suite", "real-nav2", "--out", str(tmp_path / "o"), "--baseline", str(other)]) == 2
