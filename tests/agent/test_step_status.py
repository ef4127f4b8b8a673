""""Did the place step finish cleanly?", "how did step 2 go?": one step, named by what it does or by its number,
told by how it ended and the warnings and errors the log holds while it ran and after it."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.followups import content_kind
from hexar.evals.scenarios.arm import simulate_arm_suite
from tests.agent.helpers import converse


@pytest.fixture(scope="module")
def arm(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("arm")
    simulate_arm_suite(out, only=lambda s, v: v == 1 and s in {"nominal", "out_of_reach"})
    return out


def test_a_step_named_by_what_it_does_is_told_with_its_warnings(arm: Path) -> None:
    (place,) = converse(arm / "armfile_nominal_1",
                        "Did the place step actually finish cleanly, or is there an error hidden in the last lines?")
    text = str(place["answer"])
    assert text.startswith("Step 4 (to put down the cup) finished without error at 16:01:49 UTC, 7 s after it began.")
    assert "While it ran, my log holds 1 warning or error line: at 16:01:44, local_costmap.local_costmap (WARN)" in text
    assert text.endswith("After it, up to the recording's end, my log holds no error.")


def test_a_step_named_by_its_number_and_a_failed_one(arm: Path) -> None:
    (second,) = converse(arm / "armfile_nominal_1", "did step 2 succeed?")
    assert str(second["answer"]).startswith("Step 2 (to pick up the cup) finished without error at 16:01:34 UTC")
    (pick,) = converse(arm / "armfile_out_of_reach_1", "did the pick step work?")
    assert str(pick["answer"]).startswith("Step 2 (to pick up the cup) failed at ")


def test_a_step_the_plan_does_not_have_is_said_so(suite: Path) -> None:
    (none,) = converse(suite / "bagfile_1_1", "did the pick step finish?")
    assert str(none["answer"]).startswith("No step of my plan for this task is the one you name. Its steps were: "
                                          "step 1")


@pytest.mark.parametrize("question", ["did the place step finish?", "was the drive step ok?", "how did step 3 go?",
                                      "Did the pick step actually succeed?"])
def test_how_a_step_went_is_asked_in_many_ways(question: str) -> None:
    assert content_kind(question) == "step"


def test_why_a_step_failed_is_the_failures_question() -> None:
    assert content_kind("why did the pick step fail?") != "step"
