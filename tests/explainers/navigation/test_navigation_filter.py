from __future__ import annotations

from pathlib import Path

from hexar.events.records import INFO, WARN, LogLine
from hexar.explainers.navigation.detectors import summarise
from hexar.explainers.navigation.filter import MANY_DROPS, NOISE, filter_logs, routine_drops, tag_logs, weak_noise
from tests.explainers.navigation.scenario import recording


def _line(t: int, name: str, msg: str, level: int = INFO) -> LogLine:
    return LogLine(t, level, name, msg)


def test_keeps_nav2_and_skill_loggers_only() -> None:
    lines = [
        _line(1, "bt_navigator", "Goal succeeded"),
        _line(2, "joystick_relay", "Toggled joy_priority, current status is: True"),
        _line(3, "skill_navigate_to_zone", "Navigating to kitchen at (1.00, 2.00)"),
        _line(4, "tts_engine", "hello"),
    ]
    assert [ln.t for ln in filter_logs(lines)] == [1, 3]


def test_drops_every_noise_pattern() -> None:
    lines = [_line(i, "controller_server", f"x {pattern} y", WARN) for i, pattern in enumerate(NOISE)]
    lines.append(_line(99, "controller_server", "Failed to make progress"))
    assert [ln.msg for ln in filter_logs(lines)] == ["Failed to make progress"]


def test_drops_a_line_equal_to_the_previous_one_of_the_same_logger() -> None:
    lines = [
        _line(1, "controller_server", "Passing new path to controller."),
        _line(2, "controller_server", "Passing new path to controller."),
        _line(3, "planner_server", "Planner loop missed its desired rate of 20.0000 Hz. Current loop rate is "
              "15.0000 Hz"),
        _line(4, "controller_server", "Passing new path to controller."),
        _line(5, "controller_server", "No valid trajectories out of 360! "),
        _line(6, "controller_server", "Passing new path to controller."),
        _line(7, "bt_navigator", "Passing new path to controller."),
    ]
    assert [ln.t for ln in filter_logs(lines)] == [1, 5, 6, 7]


def test_a_simulated_recording_loses_its_noise_and_repeats(tmp_path: Path) -> None:
    log = recording(tmp_path, "joystick")
    raw = [ln for ln in log.logs if ln.name == "controller_server"]
    kept = filter_logs(log.logs)
    assert any("missed its desired rate" in ln.msg for ln in log.logs)
    assert any("Message Filter dropping message" in ln.msg for ln in log.logs)
    assert any("KeepoutFilter" in ln.msg for ln in log.logs)
    assert not any(pattern in ln.msg for ln in kept for pattern in NOISE)
    new_paths_raw = sum(ln.msg == "Passing new path to controller." for ln in raw)
    new_paths_kept = sum(ln.msg == "Passing new path to controller." for ln in kept)
    assert new_paths_kept < new_paths_raw / 5
    previous: dict[str, str] = {}
    for ln in kept:
        assert previous.get(ln.name) != ln.msg
        previous[ln.name] = ln.msg


def test_an_unknown_loggers_warnings_are_kept_its_chatter_is_not() -> None:
    lines = [
        _line(1, "my_robot_base_driver", "Motor controller 2 over temperature, limiting current", WARN),
        _line(2, "my_robot_base_driver", "publishing odometry at 50 Hz"),
        _line(3, "bt_navigator", "Goal failed"),
    ]
    assert [ln.t for ln in filter_logs(lines)] == [1, 3]


# tf2_ros MessageFilter::signalFailure's INFO line (message_filter.h:708@rolling), as amcl printed it in a real log.
DROP = ("Message Filter dropping message: frame 'rplidar_link' at time 1725246931.465 for reason 'the timestamp on "
        "the message is earlier than all the data in the transform cache'")


def _drops_kept(lines: list[LogLine], state: str | None) -> int:
    noise = weak_noise(lines)
    return len(routine_drops(noise, summarise(tag_logs(lines), [], state)))


def test_a_few_info_drops_are_evidence_only_on_a_goal_that_failed_or_stalled() -> None:
    begin = _line(1, "bt_navigator", "Begin navigating from current location (0.00, 0.00) to (1.00, 1.00)")
    drops = [_line(10 + i, "amcl", DROP) for i in range(2)]
    assert _drops_kept(drops, "failed") == 2
    assert _drops_kept([begin, *drops], None) == 2  # a goal that began and never ended
    assert _drops_kept(drops, "succeeded") == 0
    assert _drops_kept(drops, None) == 0  # no goal in the window at all (e.g. a `say` step after a trip)
    assert _drops_kept([_line(10, "amcl", DROP, WARN)], "succeeded") == 1
    many = [_line(10 + i, "amcl", DROP) for i in range(MANY_DROPS)]
    assert _drops_kept(many, "succeeded") == MANY_DROPS
