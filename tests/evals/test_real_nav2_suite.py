"""Grading of the real-nav2 suite: cause named, unsupported causes, honest "not enough information" apart from
wrong; and a run of HEXAR (no LLM) over real excerpts written as recordings."""

from __future__ import annotations

import pytest

from hexar.agent.backends import resolve
from hexar.claims import read_claims
from hexar.evals.real_nav2 import Excerpt, corpus
from hexar.evals.real_nav2_suite import QUESTIONS, grade, run_suite, summarise


def excerpt(cause: str, outcome: str = "failed", shown: bool = True) -> Excerpt:
    return Excerpt(id="x", source="s", url="https://x", distro="humble", outcome=outcome, cause=cause,
                   cause_quote="q", logs_show_cause=shown, lines="[ERROR] [controller_server]: Failed to make progress")


def graded(cause: str, answer: str, outcome: str = "failed") -> tuple[str, tuple[str, ...]]:
    g = grade(excerpt(cause, outcome), read_claims(answer).affirmed, answer)
    return g.verdict, g.unsupported


def test_the_diagnosed_cause_in_words_is_named() -> None:
    assert graded("navigation.poor_localisation",
                  "I couldn't reach my goal because I was not sure where I was on my map.") == ("named", ())


def test_blaming_an_obstacle_for_an_undiagnosed_no_progress_is_wrong() -> None:
    # HEXAR's answer on hsr-project/hsr_ros2_doc#14 before issue 9: "Failed to make progress" read as a blockage.
    verdict, bad = graded("navigation.no_progress",
                          "I couldn't reach my goal because something blocked my path and I found no other way "
                          "around it.")
    assert verdict == "wrong" and bad == ("navigation.blocked_path",)


@pytest.mark.parametrize("answer", [
    "My navigation to my goal failed, but my navigation logs do not show why.",
    "I don't have enough information to say. Nothing from my navigation system was recorded then.",
    "I don't have enough information to say. My navigation logged only lines I do not read as a goal or a cause then, "
    "such as this one from amcl: 'Message Filter dropping message: frame 'nav_lidar_link' at time 27.260 for reason "
    "'discarding message because the queue is full''.",
])
def test_saying_the_logs_do_not_show_why_is_honest_not_wrong(answer: str) -> None:
    assert graded("navigation.transform_error", answer) == ("honest", ())


NEVER_CAME_UP = ("I couldn't reach my goal because my navigation stack was misconfigured, so a node of it never "
                 "came up (a configuration error: a plugin, behaviour tree or lifecycle node failed).")


@pytest.mark.parametrize("label", ["navigation.bringup_failure", "navigation.configuration_error"])
def test_a_node_that_never_came_up_for_its_configuration_is_either_label(label: str) -> None:
    # bringup_failure implies configuration_error ("misconfigured or not brought up"): under either label the
    # answer that states both is named, neither id is unsupported
    assert graded(label, NEVER_CAME_UP) == ("named", ())


def test_a_bringup_failure_alone_under_a_configuration_label_is_no_false_claim() -> None:
    verdict, bad = graded("navigation.configuration_error",
                          "I couldn't reach my goal because a node of my navigation never came up: the process of "
                          "amcl died (exit code -11); nothing in my logs says why it died.")
    assert verdict == "honest" and bad == ()


def test_a_detail_of_an_honest_label_is_still_unsupported() -> None:
    # commands_not_reaching_base implies no_progress, but "nothing says why" is no cause to tell in more detail
    verdict, bad = graded("navigation.no_progress", "I couldn't reach my goal because my velocity commands never "
                          "reached my base: odometry showed no motion.")
    assert verdict == "wrong" and bad == ("navigation.commands_not_reaching_base",)


def test_an_answer_that_says_nothing_is_wrong() -> None:
    assert graded("navigation.transform_error", "")[0] == "wrong"


def test_saying_all_went_fine_of_a_failed_run_is_unsupported() -> None:
    verdict, bad = graded("navigation.transform_error", "Nothing went wrong.")
    assert verdict == "wrong" and bad == ("claim.all_fine",)


def test_saying_a_finished_run_failed_is_unsupported() -> None:
    verdict, bad = graded("navigation.nominal", "I failed to reach the kitchen.", outcome="succeeded")
    assert verdict == "wrong" and bad == ("claim.task_failed",)


def test_structured_causes_are_graded_the_same_way() -> None:
    ex = excerpt("navigation.transform_error")
    assert grade(ex, ["navigation.transform_error"]).verdict == "named"
    assert grade(ex, ["navigation.no_progress"]).verdict == "honest"
    assert grade(ex, ["navigation.blocked_path"]).unsupported == ("navigation.blocked_path",)


@pytest.fixture(scope="module")
def report(tmp_path_factory: pytest.TempPathFactory) -> dict[str, object]:
    chosen = [e for e in corpus() if e.id in {"nav2-3230-tb3-off-costmap", "nav2-3413-bt-port-not-in-manifest",
                                                "hsr-14-failed-to-make-progress"}]
    return run_suite(resolve("none"), tmp_path_factory.mktemp("runs"), excerpts=chosen)


def test_a_run_grades_every_excerpt_and_counts_add_up(report: dict[str, object]) -> None:
    excerpts = report["excerpts"]
    assert isinstance(excerpts, list) and [e["id"] for e in excerpts] == [
        "nav2-3230-tb3-off-costmap", "nav2-3413-bt-port-not-in-manifest", "hsr-14-failed-to-make-progress"]
    assert [e["with_task"] for e in excerpts] == [True, False, True]
    assert all(e["question"] == QUESTIONS["failed"] for e in excerpts)
    s = report["summary"]
    assert isinstance(s, dict)
    text = s["text"]
    assert s["n"] == 3 and s["n_shown"] == 2  # hsr-14's thread found no cause: never counted for "named"
    verdicts = [e["text"]["verdict"] for e in excerpts]
    assert text["honest"] == verdicts.count("honest") and text["wrong"] == verdicts.count("wrong")
    assert set(report["by_distro"]) == {"galactic", "humble", "foxy"}  # type: ignore[arg-type]


def test_summaries_group_by_distro_and_cause(report: dict[str, object]) -> None:
    by_cause = report["by_cause"]
    assert isinstance(by_cause, dict)
    assert set(by_cause) == {"navigation.off_costmap", "navigation.configuration_error", "navigation.no_progress"}
    assert summarise([]) == {}
