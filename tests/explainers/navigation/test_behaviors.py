"""Whole consoles of the real Nav2 sent one goal of a behaviour server action (blind set 28, spent), written as
recordings with rosbags, with and without a /task_info task: a spin, backup, drive or wait that a program asked for is
a task of its own, told by the behaviour server's own lines; the same lines inside a navigation goal stay that goal's
recovery."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.claims import read_claims
from hexar.evals.real_nav2 import Excerpt, blind_set, corpus, write_recording
from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events import read_recording
from hexar.events.records import INFO, WARN, LogLine
from hexar.explainers.navigation.behaviors import end_of, last_run, standalone
from hexar.explainers.recorded import step_words
from tests.explainers.navigation.test_nav2_causes import T0, _odom, _twist


def _excerpt(ident: str) -> Excerpt:
    return next(e for e in blind_set(28) if e.id == f"kilted-nav2-{ident}")


def _ask(tmp_path: Path, ident: str, task: bool, question: str = "Why did you fail?") -> dict[str, object]:
    bag = write_recording(_excerpt(ident), tmp_path / f"bag{int(task)}", task=task)
    return dict(Session(RunSettings(recording=bag, llm="none")).ask(question))


@pytest.mark.parametrize("ident, behavior, outcome", [("spin-nominal", "spin", "succeeded"),
                                                      ("backup-toward-box", "backup", "failed"),
                                                      ("drive-nominal", "drive_on_heading", "succeeded")])
def test_a_behaviour_goal_no_navigation_ran_is_one_task_of_its_own(
        tmp_path: Path, ident: str, behavior: str, outcome: str) -> None:
    # "Running spin" ... "spin completed successfully" (or "backup failed:Collision Ahead - ..."), and no navigation
    # goal anywhere in the console
    log = read_recording(write_recording(_excerpt(ident), tmp_path / "bag", task=False))
    [task] = log.tasks
    assert task.outcome == outcome
    assert [(r.skill, r.params["behavior"]) for r in task.skills] == [("run_behavior", behavior)]
    assert step_words(task.skills[0]) == {"spin": "turn in place", "backup": "back up",
                                          "drive_on_heading": "drive straight ahead"}[behavior]


@pytest.mark.parametrize("ident, words", [("spin-nominal", "I finished my spin of 1.57 rad without any problem"),
                                          ("backup-nominal", "I finished my backup without any problem"),
                                          ("wait-nominal", "I finished my wait without any problem, in 3.0 s")])
@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_behaviour_that_succeeded_is_told_as_what_it_was(tmp_path: Path, ident: str, words: str,
                                                            task: bool) -> None:
    answer = _ask(tmp_path, ident, task, "How did it go?")
    assert answer["causes"] == ["navigation.nominal"] and words in str(answer["answer"])
    assert read_claims(str(answer["answer"])).causes == {"navigation.nominal"}


@pytest.mark.parametrize("ident, cause, words", [
    # "Collision Ahead - Exiting Spin" 0.2 s into a quarter turn of a rectangular robot beside a wall
    ("spin-beside-wall", "navigation.collision_ahead", "My spin of 1.57 rad stopped at once"),
    # the collision checker's own "Costmap is not available" before the same "Collision Ahead - Exiting Spin"
    ("behavior-costmap-topic", "navigation.configuration_error", "could not check at all ('Costmap is not available')"),
    # "Current robot pose is not available." with robot_base_frame base_footprint
    ("behavior-base-frame", "navigation.transform_error", "My spin could not start"),
])
@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_behaviour_that_failed_is_told_by_its_own_lines(tmp_path: Path, ident: str, cause: str, words: str,
                                                          task: bool) -> None:
    answer = _ask(tmp_path, ident, task)
    text = str(answer["answer"])
    assert answer["causes"] == [cause] and words in text
    assert read_claims(text).causes == {cause}


@pytest.mark.parametrize("ident, figures", [("spin-time-allowance", "needs 0.78 rad/s"),
                                            ("behavior-cmd-vel", "(10.0 s)")])
def test_a_time_allowance_that_ran_out_names_what_the_console_cannot_tell_apart(
        tmp_path: Path, ident: str, figures: str) -> None:
    # "Exceeded time allowance before reaching the Spin goal" (too short an allowance) and the same for a backup
    # whose commands never reached the base: one line, two causes, neither claimed
    answer = _ask(tmp_path, ident, False)
    text = str(answer["answer"])
    assert answer["causes"] == ["navigation.unexplained_failure"] and figures in text
    assert "the allowance was too short" in text and "my base did not move as commanded" in text
    assert read_claims(text).causes <= {"navigation.unexplained_failure"}


def test_a_recovery_inside_a_navigation_goal_stays_the_goals() -> None:
    # corpus excerpts of recoveries whose goal's begin and end are not in the paste: the controller's "Failed to
    # make progress" and its follow_path action show a navigation at work
    for ident in ("neo-sim2-19-spin-collision-ahead", "nav2-1050-spins-failed-to-make-progress"):
        excerpt = next(e for e in corpus() if e.id == ident)
        raw = [LogLine(t=i, level=20, name="behavior_server", msg=line.split("]: ", 1)[-1])
               for i, line in enumerate(excerpt.lines.splitlines())]
        assert last_run(raw) is not None and not standalone(raw)


def test_each_distros_begin_and_end_lines_are_read() -> None:
    # timed_behavior.hpp@kilted's "spin failed:Collision Ahead - Exiting Spin", Humble's bare "spin failed",
    # recovery.hpp@foxy's "Attempting Spin" ... "Spin completed successfully"
    def line(msg: str) -> LogLine:
        return LogLine(t=0, level=20, name="behavior_server", msg=msg)

    assert end_of(line("spin failed:Collision Ahead - Exiting Spin")) == ("spin", "failed",
                                                                        "Collision Ahead - Exiting Spin")
    assert end_of(line("backup failed")) == ("backup", "failed", "backup failed")
    assert end_of(line("Spin completed successfully")) == ("Spin", "succeeded", "")
    assert end_of(line("Initial checks failed for spin - Current robot pose is not available.")) == (
        "spin", "failed", "Current robot pose is not available.")
    assert last_run([line("Attempting Spin"), line("Spin completed successfully")]) is not None


def _backup_that_ran_out(odom_vx: float) -> BagBuilder:
    # blind28 behavior-cmd-vel's behaviour server lines (the base listened on another topic), with /cmd_vel and
    # /odom recorded as a robot's recorder keeps them
    b = BagBuilder()
    b.log(T0, "behavior_server", INFO, "Running backup")
    for i in range(100):
        t = T0 + sec_ns(0.1 * i)
        b.raw(t, "/cmd_vel", "geometry_msgs/msg/Twist", _twist(-0.1))
        b.raw(t, "/odom", "nav_msgs/msg/Odometry", _odom(t, odom_vx * 0.1 * i, odom_vx))
    b.log(T0 + sec_ns(10), "behavior_server", WARN, "Exceeded time allowance before reaching the DriveOnHeading "
          "goal - Exiting DriveOnHeading")
    b.log(T0 + sec_ns(10), "behavior_server", WARN, "backup failed:Exceeded time allowance before reaching the "
          "DriveOnHeading goal - Exiting DriveOnHeading")
    return b


def test_a_time_allowance_that_ran_out_on_a_base_that_never_moved_is_told_with_the_recorded_motion(
        tmp_path: Path) -> None:
    still = _backup_that_ran_out(0.0).write(tmp_path / "still")
    answer = dict(Session(RunSettings(recording=still, llm="none")).ask("Why did you fail?"))
    text = str(answer["answer"])
    assert answer["causes"] == ["navigation.commands_not_reaching_base"]
    assert "my velocity commands did not reach my base" in text
    assert read_claims(text).causes == {"navigation.commands_not_reaching_base"}
    # the same lines where the odometry shows the base backing up: the console's two readings stay open
    moving = _backup_that_ran_out(-0.1).write(tmp_path / "moving")
    answer = dict(Session(RunSettings(recording=moving, llm="none")).ask("Why did you fail?"))
    assert answer["causes"] == ["navigation.unexplained_failure"]


def test_where_and_how_long_of_a_spin_derived_from_the_logs(tmp_path: Path) -> None:
    """A spin sends the robot to no place, and a goal read from the logs is nobody's request."""
    where = str(_ask(tmp_path / "1", "spin-beside-wall", False, "where are you?")["answer"])
    assert where.startswith("My last step was to turn in place, which sends me to no place on my map.")
    assert "on the way" not in where and "didn't get there" not in where
    took = str(_ask(tmp_path / "2", "spin-beside-wall", False, "how long did it take?")["answer"])
    assert took.startswith("The goal to run spin took ")
    assert "your request" not in took.lower()
