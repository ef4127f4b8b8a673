"""The real-modules suite: the corpus parses, every excerpt becomes a recording, answers are graded from their
text, and the CLI writes its report; bad input is one ERROR line."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.cli import main
from hexar.errors import HexarError
from hexar.evals.real_modules import FILES, SUITE, Excerpt, grade, load_excerpts, parse_corpus, write_recording
from hexar.events import read_recording


def test_the_corpus_parses_with_cause_ids_of_the_vocabulary() -> None:
    excerpts = load_excerpts(SUITE)
    assert len(excerpts) >= 20
    assert {e.module for e in excerpts} <= {"manipulation", "control", "bringup", "system"}


def test_the_held_out_sets_parse_and_share_no_excerpt_or_thread_with_the_corpus() -> None:
    by_suite = {suite: load_excerpts(suite) for suite in FILES}
    assert len(by_suite["real-modules-heldout2"]) >= 24
    seen: dict[str, str] = {}
    for suite, excerpts in by_suite.items():
        for e in excerpts:
            assert e.id not in seen, f"{e.id} is in {suite} and {seen[e.id]}"
            seen[e.id] = suite
    urls = {suite: {e.url for e in excerpts} for suite, excerpts in by_suite.items()}
    assert not urls["real-modules-heldout2"] & (urls[SUITE] | urls["real-modules-heldout"])
    assert len(by_suite["real-modules-heldout3"]) >= 16
    earlier = urls[SUITE] | urls["real-modules-heldout"] | urls["real-modules-heldout2"]
    assert not urls["real-modules-heldout3"] & earlier
    assert len(by_suite["real-modules-heldout4"]) >= 15
    assert not urls["real-modules-heldout4"] & (earlier | urls["real-modules-heldout3"])
    assert len(by_suite["real-modules-heldout5"]) >= 10
    assert not urls["real-modules-heldout5"] & (earlier | urls["real-modules-heldout3"] | urls["real-modules-heldout4"])
    assert len(by_suite["real-modules-heldout6"]) >= 20
    assert not urls["real-modules-heldout6"] & (earlier | urls["real-modules-heldout3"] | urls["real-modules-heldout4"]
                                                | urls["real-modules-heldout5"])
    assert len(by_suite["real-modules-heldout7"]) >= 13
    assert not urls["real-modules-heldout7"] & (earlier | urls["real-modules-heldout3"] | urls["real-modules-heldout4"]
                                                | urls["real-modules-heldout5"] | urls["real-modules-heldout6"])
    assert len(by_suite["real-modules-heldout8"]) >= 10
    assert not urls["real-modules-heldout8"] & (earlier | urls["real-modules-heldout3"] | urls["real-modules-heldout4"]
                                                | urls["real-modules-heldout5"] | urls["real-modules-heldout6"]
                                                | urls["real-modules-heldout7"])
    assert len(by_suite["real-modules-heldout9"]) >= 5
    assert not urls["real-modules-heldout9"] & (earlier | urls["real-modules-heldout3"] | urls["real-modules-heldout4"]
                                                | urls["real-modules-heldout5"] | urls["real-modules-heldout6"]
                                                | urls["real-modules-heldout7"] | urls["real-modules-heldout8"])
    # from the tenth on, each set's sources are in no other file at all; its least size as collected
    for n, least in ((10, 10), (11, 10), (12, 4), (13, 2), (14, 1), (15, 2), (16, 7), (17, 3), (18, 10), (19, 2),
                     (20, 1), (21, 3), (22, 15), (23, 14), (24, 11), (25, 14), (26, 18),
                     (27, 17), (28, 12), (29, 14), (30, 12), (31, 10), (32, 12), (33, 6), (34, 8), (35, 11), (36, 10)):
        suite = f"real-modules-heldout{n}"
        assert len(by_suite[suite]) >= least
        assert not urls[suite] & set().union(*(u for s, u in urls.items() if s != suite))


def test_an_excerpt_becomes_a_recording_with_or_without_a_task(tmp_path: Path) -> None:
    ex = load_excerpts(SUITE)[0]
    with_task = read_recording(write_recording(ex, tmp_path / "a", True))
    without = read_recording(write_recording(ex, tmp_path / "b", False))
    assert with_task.task_updates and not without.task_updates
    assert [ln.msg for ln in with_task.logs] == [ln.msg for ln in without.logs]
    assert not any(ex.cause in u.raw for u in with_task.task_updates)  # the diagnosis is never recorded


def _ex(cause: str, outcome: str = "failed") -> Excerpt:
    return Excerpt("x", "s", "u", "unknown", "control", outcome, cause, "q", True, "[ERROR] [1.0] [a]: b")


def test_grading_named_wrong_and_honest() -> None:
    assert grade(_ex("control.tolerance_violated"), {"control.tolerance_violated"}).verdict == "named"
    wrong = grade(_ex("control.tolerance_violated"), {"manipulation.planning_failed"})
    assert wrong.verdict == "wrong" and wrong.unsupported == ("manipulation.planning_failed",)
    honest = grade(_ex("control.hardware_failure"), set(), "My controllers failed, but my control logs do not "
                                                           "show a cause I know.")
    assert honest.verdict == "honest"


def test_a_cause_told_in_more_detail_is_no_false_claim_as_in_the_navigation_grader() -> None:
    # hexar/causes.yaml: control.controller_load_failed implies control.configuration_error
    finer = grade(_ex("control.configuration_error"), {"control.controller_load_failed"})
    assert finer.unsupported == () and finer.verdict == "wrong"  # not false, but not the label either
    both = grade(_ex("control.configuration_error"), {"control.controller_load_failed", "control.configuration_error"})
    assert both.verdict == "named"
    coarser = grade(_ex("control.controller_load_failed"), {"control.configuration_error"})
    assert coarser.unsupported == ()
    other = grade(_ex("control.configuration_error"), {"control.tolerance_violated"})
    assert other.unsupported == ("control.tolerance_violated",)


def test_a_corpus_that_names_an_unknown_cause_is_refused() -> None:
    with pytest.raises(HexarError, match="unknown cause"):
        parse_corpus("- {id: a, source: s, url: u, distro: humble, module: control, outcome: failed, "
                     "cause: control.nonsense, cause_quote: q, logs_show_cause: true, lines: 'x'}")


def test_the_suite_runs_from_the_cli(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["eval", "--suite", "real-modules", "--out", str(tmp_path / "out")]) == 0
    text = (tmp_path / "out" / "results.md").read_text()
    assert "### By module" in text and "| manipulation |" in text and "| control |" in text


def test_options_of_the_paper_suite_are_one_error_line(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["eval", "--suite", "real-modules", "--first", "2"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["ERROR: --first do not apply to --suite real-modules"]
