from __future__ import annotations

from pathlib import Path

import pytest

from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events import read_recording
from hexar.events.errors import NoTaskError
from tests.events.helpers import T0, task_msg, two_skill_task


def test_lifecycle_is_case_insensitive_and_tracks_history(tmp_path: Path) -> None:
    b = BagBuilder()
    two_skill_task(b, T0, "task-a", fail_second=False)
    task = read_recording(b.write(tmp_path / "run")).task()
    assert task.outcome == "succeeded"  # "SUCCEEDED" and "Running" compare case-insensitively
    nav, say = task.skills
    assert [ch.status.lower() for ch in nav.history] == ["waiting", "running", "succeeded"]
    assert nav.time_of("running") == T0 + sec_ns(1)
    assert task.window() == (T0, T0 + sec_ns(15))
    assert say.label() == "say(input='hello')"


def test_invalid_plan(tmp_path: Path) -> None:
    b = BagBuilder()
    b.task_info(T0, task_msg("bad", "bring me a coffee", [("navigate_to_room", {"location": "kitchen"}, "waiting", "")],
                             valid=False, error="Skill navigate_to_room is not a valid skill."))
    task = read_recording(b.write(tmp_path / "run")).task()
    assert task.outcome == "invalid" and not task.valid
    assert task.error_msg == "Skill navigate_to_room is not a valid skill."


def test_several_tasks_latest_user_task_is_default(tmp_path: Path) -> None:
    b = BagBuilder()
    two_skill_task(b, T0, "first-task", fail_second=False)
    two_skill_task(b, T0 + sec_ns(60), "second-task", fail_second=True)
    recovery = [("say", {"input": "Sorry"}, "succeeded", "")]
    b.task_info(T0 + sec_ns(90), task_msg("recovery", "", recovery))
    log = read_recording(b.write(tmp_path / "run"))
    assert [t.task_id for t in log.tasks] == ["first-task", "second-task", "recovery"]
    assert log.task().task_id == "second-task"  # the recovery task is the robot's own, not the request
    assert log.task("first").task_id == "first-task"
    assert log.task("3").is_recovery
    assert log.task("first-t").task_id == "first-task"
    with pytest.raises(NoTaskError, match="no task 'zzz'"):
        log.task("zzz")


def test_window_of_first_skill_failure_starts_at_creation(tmp_path: Path) -> None:
    b = BagBuilder()
    nav = ("navigate_to_zone", {"location": "kitchen"})
    b.task_info(T0, task_msg("t", "go", [(*nav, "waiting", "")]))
    b.task_info(T0 + sec_ns(1), task_msg("t", "go", [(*nav, "Running", "")]))
    b.task_info(T0 + sec_ns(40), task_msg("t", "go", [(*nav, "failed", "The skill has been aborted")]))
    task = read_recording(b.write(tmp_path / "run")).task()
    assert task.window() == (T0, T0 + sec_ns(40))


def test_view_restricts_topics_and_time(tmp_path: Path) -> None:
    from hexar.events import contract as c

    b = BagBuilder()
    for i in range(10):
        b.log(T0 + sec_ns(i), "planner_server", 30, f"line {i}")
    b.flag(T0 - sec_ns(100), c.JOY_PRIORITY, True)
    log = read_recording(b.write(tmp_path / "run"))
    view = log.view({c.ROSOUT, c.JOY_PRIORITY}, (T0 + sec_ns(2), T0 + sec_ns(4)))
    assert [r.msg for r in view.logs()] == ["line 2", "line 3", "line 4"]
    latched = view.flag_at(c.JOY_PRIORITY, T0 + sec_ns(3))
    assert latched is not None and latched.value is True
    with pytest.raises(KeyError):
        view.poses()
