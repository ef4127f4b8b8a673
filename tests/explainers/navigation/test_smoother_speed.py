"""Whole consoles of the real Nav2 with the smoother server and a speed filter (blind set 27, spent), written as
recordings with rosbags: a path smoother allowed no time at all is set up wrongly, while one whose real limit ran out
is quoted, never claimed; a controller that made no progress while a speed filter was in force names the filter
among what the logs leave open, and claims nothing more."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.claims import read_claims
from hexar.evals.real_nav2 import Excerpt, blind_set, write_recording


def _excerpt(ident: str) -> Excerpt:
    return next(e for e in blind_set(27) if e.id == f"kilted-nav2-{ident}")


def _ask(tmp_path: Path, excerpt: Excerpt, task: bool) -> dict[str, object]:
    bag = write_recording(excerpt, tmp_path / f"bag{int(task)}", task=task)
    return dict(Session(RunSettings(recording=bag, llm="none")).ask("Why did you fail?"))


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_smoother_allowed_no_time_is_set_up_wrongly(tmp_path: Path, task: bool) -> None:
    # "Smoothing time exceeded allowed duration of -0.00." then "Smoothing time exceed allowed duration" and the
    # behaviour tree's "Goal failed error_code:0 error_msg:''": SmoothPath's max_smoothing_duration was 0.00001 s
    answer = _ask(tmp_path, _excerpt("smoother-time-short"), task)
    assert answer["causes"] == ["navigation.configuration_error"]
    assert "allowed no time at all" in str(answer["answer"])


def test_a_smoother_whose_real_limit_ran_out_is_quoted_not_claimed(tmp_path: Path) -> None:
    # the same console had the limit been 3 s: a long path or a busy computer as much as a setting
    excerpt = _excerpt("smoother-time-short")
    lines = excerpt.lines.replace("allowed duration of -0.00.", "allowed duration of 3.00.")
    answer = _ask(tmp_path, dataclasses.replace(excerpt, lines=lines), False)
    text = str(answer["answer"])
    assert answer["causes"] != ["navigation.configuration_error"] and "Smoothing time exceed" in text


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_no_progress_under_a_speed_filter_names_the_filter_and_claims_nothing_more(tmp_path: Path, task: bool) -> None:
    # "SpeedFilter: Received filter mask from /speed_filter_mask topic." at bring-up, then five "Failed to make
    # progress": a 5 % zone across the doorway; no line says what limit the filter set
    answer = _ask(tmp_path, _excerpt("speed-zone-crawl"), task)
    text = str(answer["answer"])
    assert answer["causes"] == ["navigation.no_progress"] and "a speed filter was in force" in text
    assert read_claims(text).causes == {"navigation.no_progress"}


def test_no_progress_without_a_speed_filters_mask_names_no_filter(tmp_path: Path) -> None:
    excerpt = _excerpt("speed-zone-crawl")
    lines = "\n".join(ln for ln in excerpt.lines.splitlines() if "filter mask" not in ln)
    answer = _ask(tmp_path, dataclasses.replace(excerpt, lines=lines), False)
    assert "speed filter" not in str(answer["answer"])
