"""The held-out real-Nav2 excerpts (evals/data/real_nav2/heldout.yaml): they load from the installed data package,
share no thread with the tuning corpus, every one becomes a rosbag2 recording HEXAR reads back line for line, and
`hexar eval --suite real-nav2-heldout` reports on them. Their accuracy is measured, never pinned here."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from hexar.cli import main
from hexar.errors import HexarError
from hexar.evals.real_nav2 import (
    DISTROS,
    NAV_CAUSES,
    Excerpt,
    corpus,
    heldout,
    write_recording,
)
from hexar.evals.real_nav2_cli import read_baseline
from hexar.events import contract as c
from hexar.events import read_recording
from hexar.events.console import parse_console, stamped

BASELINE = Path(__file__).resolve().parents[2] / "evals" / "baselines" / "real_nav2_none.json"


def test_heldout_loads_and_shares_no_thread_with_the_corpus() -> None:
    held = heldout()
    assert len(held) >= 15
    assert {e.distro for e in held} <= set(DISTROS) and {e.cause for e in held} <= NAV_CAUSES
    assert not {e.url for e in held} & {e.url for e in corpus()}
    assert not {e.id for e in held} & {e.id for e in corpus()}
    for e in held:
        assert e.url.startswith("https://") and e.cause_quote.strip() and "\n" not in e.cause_quote.strip(), e.id


@pytest.mark.parametrize("excerpt", heldout(), ids=lambda e: e.id)
def test_every_heldout_excerpt_becomes_a_readable_recording(excerpt: Excerpt, tmp_path: Path) -> None:
    expected = stamped(parse_console(excerpt.lines))
    assert expected, excerpt.id
    for task in (True, False):
        log = read_recording(write_recording(excerpt, tmp_path / f"bag-{task}", task=task))
        lines = log.view(frozenset({c.ROSOUT})).logs()
        assert [line.msg for line in lines] == [r.msg for r in expected]
        assert [line.name for line in lines] == [r.name for r in expected]
        assert bool(log.task_updates) is task


def test_the_heldout_suite_reports_every_excerpt(tmp_path: Path) -> None:
    out = tmp_path / "out"
    assert main(["eval", "--suite", "real-nav2-heldout", "--llm", "none", "--out", str(out)]) == 0
    report = json.loads((out / "report.json").read_text(encoding="utf-8"))
    assert report["suite"] == "real-nav2-heldout" and report["data"] == "heldout.yaml"
    assert report["n"] == len(heldout()) and [e["id"] for e in report["excerpts"]] == [e.id for e in heldout()]
    md = (out / "results.md").read_text(encoding="utf-8")
    assert md.startswith("# hexar eval --suite real-nav2-heldout") and "evals/data/real_nav2/heldout.yaml" in md


def test_a_corpus_baseline_is_refused_for_the_heldout_suite() -> None:
    with pytest.raises(HexarError, match="not a real-nav2-heldout baseline"):
        read_baseline(BASELINE, "real-nav2-heldout")
