""""Is the arm broken?", "is it my fault?": a yes-or-no opening from where the failure's cause lies, then the failure
as its explainer tells it; a set-up problem is never told as a broken part, a person's doing never as the asker's."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.followups import content_kind
from hexar.causes import BENIGN, ORIGINS, vocabulary
from hexar.evals.scenarios.arm import simulate_arm_suite
from tests.agent.helpers import converse, real_module_run


@pytest.fixture(scope="module")
def arm(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("arm")
    simulate_arm_suite(out, only=lambda s, v: v == 1 and s in {"controllers_not_found", "nominal"})
    return out


@pytest.mark.parametrize(("question", "kind"), [
    ("is the arm broken?", "broken"), ("Are you broken?", "broken"), ("is something wrong with your wheels?", "broken"),
    ("was it a hardware problem?", "broken"), ("does the robot need a repair?", "broken"),
    ("is your gripper not working?", "broken"), ("did the arm break?", "broken"),
    ("is it my fault?", "fault"), ("did I do something wrong?", "fault"), ("whose fault was it?", "fault"),
    ("did I break it?", "fault"),
    ("why is the arm broken?", None), ("what is a fault?", None), ("what broke?", None),
    ("did you break anything?", None),
])
def test_where_a_failure_lies_is_told_apart(question: str, kind: str | None) -> None:
    assert content_kind(question) == kind


def test_every_cause_says_where_it_lies() -> None:
    known = vocabulary()
    assert {cause.origin for cause in known.values()} <= set(ORIGINS)
    assert all(known[c].origin == "none" for c in BENIGN if c in known)
    assert known["control.hardware_failure"].origin == "hardware"


def test_a_setup_problem_is_not_a_broken_arm(arm: Path) -> None:
    broken, deeper, fault = converse(arm / "armfile_controllers_not_found_1", "is the arm broken?", "why?",
                                     "is it my fault?")
    finding = "because MoveIt found no controllers for my arm's joints."
    assert str(broken["answer"]).startswith("Nothing in my recording says a part of me is broken: what went wrong "
                                            "lies in how my software is set up")
    assert str(broken["answer"]).endswith(finding)
    assert broken["causes"] == ["manipulation.controllers_not_found"]
    assert "Unable to identify any set of controllers" in str(deeper["answer"])  # "why?" goes on to the failure
    assert str(fault["answer"]).startswith("Nothing in my recording says you did anything wrong.")
    assert str(fault["answer"]).endswith(finding)


def test_a_task_that_went_well_has_nothing_broken(arm: Path) -> None:
    (said,) = converse(arm / "armfile_nominal_1", "are you broken?")
    assert str(said["answer"]).startswith("Nothing in my recording says so: your request")
    assert str(said["answer"]).endswith("went without a problem.")


def test_a_hardware_failure_is_possibly_broken_and_says_what_it_cannot_tell(tmp_path: Path) -> None:
    """A real ros2_control start whose serial device could not be opened."""
    run = real_module_run("r2c-controllers-1595-libserial-open-failed", tmp_path / "run")
    (said,) = converse(run, "is the robot broken?")
    assert str(said["answer"]).startswith("Possibly: my recording shows a device of mine failing")
    assert "control.hardware_failure" in said["causes"]  # type: ignore[operator]


@pytest.mark.parametrize(("run", "broken", "fault"), [
    ("bagfile_6_1", "what stopped me was a person's doing", "My recording shows what a person did, not who it was."),
    ("bagfile_1_1", "the mistake was my own", "No: as far as my recording shows, the mistake was my own."),
    ("bagfile_4_1", "what you asked needs more than I can do", "You did nothing wrong"),
    ("bagfile_14_1", "what stopped me was around me", "Nothing in my recording says you did anything wrong."),
    ("bagfile_8_1", "I can't tell from my recording whether a part of me is broken",
     "Nothing in my recording says you did anything wrong."),
])
def test_where_the_cause_lies_leads_the_failure(suite: Path, run: str, broken: str, fault: str) -> None:
    said, blamed = converse(suite / run, "is the robot broken?", "is it my fault?")
    (told,) = converse(suite / run, "what happened?")
    assert broken in str(said["answer"])
    assert str(blamed["answer"]).startswith(fault)
    assert said["causes"] == blamed["causes"] and said["causes"] and told["causes"][0] in said["causes"]


@pytest.mark.parametrize(("run", "lead"), [
    ("bagfile_8_1", "Yes. I reached the kitchen, but slowly and unsteadily, because I was not sure where I was"),
    ("bagfile_5_1", "Nothing in my recording says I was lost. I couldn't reach the kitchen because something blocked"),
    ("bagfile_10_1", "Nothing in my recording says so: your request"),
])
def test_did_you_get_lost_is_yes_only_where_localisation_was_the_finding(suite: Path, run: str, lead: str) -> None:
    assert content_kind("did you get lost?") == content_kind("did you know where you were?") == "lost"
    (said,) = converse(suite / run, "did you get lost?")
    assert str(said["answer"]).startswith(lead)
