""""What does this line mean?": from the catalogues mined from the stack's sources and the explainers' own readings,
on real consoles written as recordings; a line none of them reads is said to have no meaning there, never a guess."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.followups import content_kind
from tests.agent.helpers import converse, real_module_run, real_nav2_run


def test_an_exceptions_meaning_on_a_recording_with_no_task(tmp_path: Path) -> None:
    run = real_module_run("r2c-demos-pr755-example9-gazebo-without-clock-bridge-time-sources-crash", tmp_path / "run")
    (means,) = converse(run, "what does can't compare times with different time sources mean here?")
    text = str(means["answer"])
    assert text.startswith("That line (gazebo-1, 22:13:20: \"terminate called after throwing an instance of "
                           "'std::runtime_error' what(): can't compare times with different time sources")
    assert "means: two times from different clocks met, which rclcpp does not allow" in text


def test_a_nav2_lines_meaning_from_its_catalogue(tmp_path: Path) -> None:
    run = real_nav2_run("kilted-nav2-through-doorway-blocked", tmp_path / "run")
    (means,) = converse(run, "what does the 'Failed to create plan with tolerance' line mean?")
    assert str(means["answer"]).endswith("means: NavFn found no path (NoValidPathCouldBeFound).")


def test_why_a_line_came_adds_what_its_node_logged_just_before(tmp_path: Path) -> None:
    """A forklift's MPC node capped its speed; the two lines it logged just before say why (a sharp turn)."""
    run = real_nav2_run("forklift-mpc-humble-p5-sparse-90-turn-speed-limited-succeeded", tmp_path / "run")
    (why,) = converse(run, "why did P5 cap max_v from 0.45 down to 0.08?")
    assert "Just before it, the same node logged: " in str(why["answer"])
    assert '"P5 trajectory curvature 5.854 exceeds allowed 0.511 from min turning radius 1.957 m"' in str(why["answer"])


@pytest.mark.parametrize(("question", "kind"), [
    ("what does the 'Failed to make progress' line mean?", "means"),
    ("What does 'Error occurred while doing error handling' mean here?", "means"),
    ("what does that mean?", None),  # of the answer just given, not of a line
    ("what does this error mean?", None),
])
def test_what_a_line_means_is_its_own_question(question: str, kind: str | None) -> None:
    assert content_kind(question) == kind


def test_two_questions_in_one_are_answered_by_the_finding(tmp_path: Path) -> None:
    """"What does X mean here? Did controller_server die?": the finding (controller_server died) answers both;
    a meaning alone would leave the second unanswered."""
    question = "What does \"Behavior Tree action client timed out waiting\" mean here? Did controller_server die?"
    assert content_kind(question) is None
    run = real_nav2_run("kilted-nav2-amcl-controller-killed", tmp_path / "run")
    (both,) = converse(run, question)
    assert str(both["answer"]).startswith("I couldn't reach the goal at (10.00, 4.00) because the process of "
                                          "controller_server died (exit code -9)")
