""""What errors were there?", "show me the logs", "which node failed?": the recorded log lines themselves, counted and
quoted from the recording, checked against the same recording read on its own."""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import pytest

from hexar.agent.followups import content_kind
from hexar.events import read_recording
from hexar.events.records import ERROR, WARN, clock
from tests.agent.helpers import converse, real_module_run


@pytest.mark.parametrize(("question", "kind"), [
    ("What errors were there?", "logs"), ("show me the logs", "logs"), ("any errors?", "logs"),
    ("were there any warnings?", "logs"), ("Which node failed?", "logs"), ("what was the last error?", "logs"),
    ("list the error messages", "logs"), ("what did the logs say?", "logs"), ("did you get any errors", "logs"),
    ("did you get an error?", "logs"),
    # a cause asked for stays the explainers'
    ("what was the error?", None), ("why was there an error?", None), ("what does this error mean?", None),
    ("Why did the controller fail?", None),
])
def test_log_questions_are_told_apart(question: str, kind: str | None) -> None:
    assert content_kind(question) == kind


def test_the_errors_of_a_failed_task_are_counted_by_node_and_quoted(suite: Path) -> None:
    run = suite / "bagfile_5_1"
    log = read_recording(run)
    task = log.tasks[0]
    errors = [ln for ln in log.logs if ln.level >= ERROR and task.created <= ln.t <= task.last_update]
    nodes = Counter(ln.name for ln in errors)
    assert len(errors) >= 2 and len(nodes) >= 2  # the check reads a run with errors from several nodes
    said, which, last, first, yes = converse(run, "What errors were there?", "Which node failed?",
                                             "What was the last error?", "what was the first error?", "any errors?")
    text = str(said["answer"])
    assert text.startswith(f"My log holds {len(errors)} errors while I worked on your request \"Bring me a coffee "
                           "from the kitchen\"")
    assert all(f"{node} ({n})" in text for node, n in nodes.items())
    first_line = errors[0]
    assert f'at {clock(first_line.t).split(".")[0]}, {first_line.name} "{first_line.msg}"' in text
    # the quoted lines lead the evidence; the failure's own follows, for "why?"
    cited = [(e["topic"], e["t"], e["item"]) for e in said["evidence"]]  # type: ignore[union-attr]
    assert set(cited[:3]) <= {(ln.origin, ln.t, ln.render()) for ln in errors}
    assert str(which["answer"]).endswith(f'The first, at {clock(first_line.t).split(".")[0]}, came from '
                                         f'{first_line.name}: "{first_line.msg}".')
    assert str(last["answer"]).endswith(f'from {errors[-1].name}: "{errors[-1].msg}".')
    assert str(first["answer"]).startswith("The first error while I worked on")
    assert str(first["answer"]).endswith(f'from {first_line.name}: "{first_line.msg}".')
    assert str(yes["answer"]).startswith("Yes. My log holds")
    assert said["intent"] == "content" and said["error"] == ""


def test_no_error_says_so_and_points_to_the_warnings(suite: Path) -> None:
    run = suite / "bagfile_10_1"
    log = read_recording(run)
    task = log.tasks[0]
    assert not [ln for ln in log.logs if ln.level >= ERROR and ln.t <= task.last_update]
    warnings = [ln for ln in log.logs if ln.level == WARN and task.created <= ln.t <= task.last_update]
    none, warned = converse(run, "any errors?", "what warnings were there?")
    assert str(none["answer"]).startswith('No. My log holds no error while I worked on your request "Bring me a '
                                          'coffee from the kitchen"')
    assert str(none["answer"]).endswith(f'It holds {len(warnings)} warnings: ask "what warnings were there?" for '
                                        "them.")
    assert str(warned["answer"]).startswith(f"My log holds {len(warnings)} warnings while I worked on")
    assert "(WARN)" not in str(warned["answer"])  # only warnings were asked for: no level on each


def test_an_error_at_bring_up_is_told_as_before_the_task(tmp_path: Path) -> None:
    """A real ros2_control start whose hardware failed: the error is the start's own, quoted as logged."""
    run = real_module_run("r2c-controllers-1595-libserial-open-failed", tmp_path / "run")
    (said,) = converse(run, "what errors were there?")
    assert "OpenFailed" in str(said["answer"]) and "controller_manager" in str(said["answer"])
    assert "derived from" not in str(said["answer"])


def test_a_recording_without_logs_says_it_cannot_tell(tmp_path: Path) -> None:
    from hexar.evals.scenarios.bag import BagBuilder, sec_ns

    out = tmp_path / "nolog"
    b = BagBuilder()
    for k, status in enumerate(("waiting", "Running", "failed")):
        b.task_info(sec_ns(1700000000 + k), {
            "instruction": "Bring me a coffee from the kitchen", "task_id": "t1", "task_status": "valid",
            "task_error_msg": "", "skill_sequence": [{"skill": "navigate_to_zone", "params": {"location": "kitchen"},
                                                      "status": status, "error_msg": ""}]})
    b.write(out)
    (said,) = converse(out, "show me the logs")
    assert str(said["answer"]).startswith("My recording holds no log lines (/rosout), so I can't tell which "
                                          "errors or warnings there were")


def test_why_after_the_errors_goes_on_to_the_failure(suite: Path) -> None:
    _, why, deeper = converse(suite / "bagfile_5_1", "What errors were there?", "why?", "why?")
    assert str(why["answer"]).startswith("Here is what I recorded: ")
    assert "something blocked my path" in str(deeper["answer"])


@pytest.mark.parametrize("question", ["which nodes were running?", "list the nodes", "what nodes did you have?",
                                      "show me all the processes"])
def test_which_nodes_is_its_own_question(question: str) -> None:
    assert content_kind(question) == "nodes"


def test_the_nodes_are_those_that_logged_with_their_counts_and_errors(suite: Path) -> None:
    run = suite / "bagfile_5_1"
    log = read_recording(run)
    names = Counter(ln.name for ln in log.logs)
    errors = Counter(ln.name for ln in log.logs if ln.level >= ERROR)
    (said,) = converse(run, "which nodes were running?")
    text = str(said["answer"])
    assert text.startswith(f"My log holds lines from {len(names)} nodes: ")
    top, n = names.most_common(1)[0]
    assert f"{top} ({n} lines" in text
    assert all(f"{node} ({names[node]} line" in text and f"{k} error" in text for node, k in errors.items())
    assert text.endswith("A node that never logged does not show here, and my log cannot tell whether one was still "
                         "running at the end.")


def test_any_warnings_of_one_module_is_a_question_about_the_log() -> None:
    from hexar.agent.followups import content_kind

    assert content_kind("Were there any planner warnings before bt_navigator said the goal succeeded?") == "logs"


def test_warnings_of_a_module_named_are_that_modules(tmp_path: Path) -> None:
    """"Any planner warnings before bt_navigator said the goal succeeded?": planner_server logged none (the node
    after "before" is a moment, not whose lines); the warnings there were controller_server's, and are not told
    as the planner's."""
    from tests.agent.helpers import converse, real_nav2_run

    run = real_nav2_run("kilted-nav2-goal-in-wall", tmp_path / "run")
    (planner,) = converse(run, "Were there any planner warnings before bt_navigator said the goal succeeded?")
    assert planner["answer"] == ("No. My log holds no warning from planner_server while I worked on the navigation "
                                 "goal to (6.10, 2.00) (01:36:38 to 01:36:53 UTC); the warnings there came from "
                                 "controller_server.")
