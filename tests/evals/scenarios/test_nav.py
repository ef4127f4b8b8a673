from __future__ import annotations

import itertools
import re
from pathlib import Path

import pytest

from hexar.evals.scenarios.bag import TYPESTORE, BagBuilder
from hexar.evals.scenarios.nav import NavSituation
from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.explainers.navigation import NavigationExplainer
from tests.explainers.navigation.scenario import ALL, context, recording, simulate

# Verbatim Nav2 Humble / tf2 / twist_mux format strings (shared/reference), as patterns.
_NUM = r"-?\d+\.\d+"
VERBATIM = [re.compile(p) for p in (
    rf"Begin navigating from current location \({_NUM}, {_NUM}\) to \({_NUM}, {_NUM}\)",
    r"Goal succeeded", r"Goal failed", r"Received a goal, begin computing control effort\.",
    r"Passing new path to controller\.", r"Reached the goal!", r"Failed to make progress",
    r"Controller patience exceeded", r"No valid trajectories out of 360! ",
    r"\[(follow_path|compute_path_to_pose|navigate_to_pose)\] \[ActionServer\] Aborting handle\.",
    r"GridBased: failed to create plan with tolerance 0\.50\.",
    rf"Planning algorithm GridBased failed to generate a valid path to \({_NUM}, {_NUM}\)",
    r"Received request to clear entirely the (global|local)_costmap",
    r"Running (spin|wait|backup)", r"Turning 1\.57 for spin behavior\.",
    r"(spin|wait|backup) completed successfully", r"(spin|backup) failed",
    r"Collision Ahead - Exiting DriveOnHeading",
    r"Exceeded time allowance before reaching the (Spin|DriveOnHeading) goal - Exiting (Spin|DriveOnHeading)",
    r"Control loop missed its desired rate of 20\.0000Hz",
    rf"Planner loop missed its desired rate of 20\.0000 Hz\. Current loop rate is {_NUM} Hz",
    rf"Costmap2DROS: Map update loop missed its desired rate of 5\.0000Hz\.\.\. "
    rf"the loop actually took {_NUM} seconds",
    rf"Message Filter dropping message: frame 'base_laser_link' at time {_NUM} for reason 'the timestamp on "
    r"the message is earlier than all the data in the transform cache'",
    r"(KeepoutFilter|SpeedFilter): New costmap filter info arrived from /\w+ topic\. "
    r"Updating old filter info\.",
    r'(KeepoutFilter|SpeedFilter): Subscribing to "/\w+" topic for filter mask\.\.\.',
    r"(KeepoutFilter|SpeedFilter): New filter mask arrived from /\w+ topic\. Updating old filter mask\.",
    rf"SpeedFilter: Using absolute speed_limit = {_NUM} \+ filter_mask_data \* {_NUM}",
    r"Toggled joy_priority, current status is: True",
)]
CAUSE_WORDS = re.compile(r"block|joystick|charg|obstacle|people|locali", re.I)


def _content(b: BagBuilder) -> list[tuple[int, str, bytes]]:
    return [(t, topic, bytes(TYPESTORE.serialize_cdr(msg, msgtype))) for t, topic, msgtype, msg in
            sorted(b.messages, key=lambda m: (m[0], m[1]))]


@pytest.mark.parametrize("situation", ALL)
def test_nav2_lines_are_verbatim_and_skill_lines_name_no_cause(
    situation: NavSituation, tmp_path: Path
) -> None:
    log = recording(tmp_path, situation)
    for line in log.logs:
        if line.name.startswith("skill_"):
            assert not CAUSE_WORDS.search(line.msg), line.msg
        else:
            assert any(p.fullmatch(line.msg) for p in VERBATIM), line.render()


def test_same_seed_same_bag_content() -> None:
    for situation in ("blocked", "moving_obstacles"):
        assert _content(simulate(situation, 7)[0]) == _content(simulate(situation, 7)[0])


@pytest.mark.parametrize("situation", ALL)
def test_other_seeds_change_timings_not_the_situation(situation: NavSituation, tmp_path: Path) -> None:
    ends = set()
    for seed in (2, 3):
        _, result = simulate(situation, seed)
        ends.add(result.end)
        log = recording(tmp_path, situation, seed)
        causes = NavigationExplainer().explain("What happened?", context(log)).causes
        assert len(causes) == 1 and causes[0].endswith(situation.replace("blocked", "blocked_path"))
    assert len(ends) == 2


@pytest.mark.parametrize(("situation", "succeeded"), [
    ("nominal", True), ("moving_obstacles", True), ("poor_localisation", True),
    ("blocked", False), ("joystick", False), ("charging", False),
])
def test_outcomes_and_realistic_timing(situation: NavSituation, succeeded: bool, tmp_path: Path) -> None:
    _, result = simulate(situation, 5)
    assert result.succeeded is succeeded
    assert (result.error_msg == "") is succeeded
    log = recording(tmp_path, situation, 5)
    nav = [ln for ln in log.logs if ln.name == "bt_navigator"]
    assert nav[0].msg.startswith("Begin navigating") and nav[-1].msg in {"Goal succeeded",
                                                                          "[navigate_to_pose] [ActionServer] "
                                                                          "Aborting handle."}
    run_loggers = {"bt_navigator", "controller_server", "planner_server", "behavior_server",
                   "skill_navigate_to_zone"}
    assert all(ln.t <= result.end for ln in log.logs if ln.name in run_loggers)
    if situation in ("joystick", "charging"):
        moving = {(round(p.x, 3), round(p.y, 3)) for p in log.poses}
        assert len(moving) == 1, "the base never moves"
        fails = [ln.t for ln in log.logs if ln.msg == "Failed to make progress"]
        assert fails and (fails[0] - nav[0].t) / 1e9 >= 10.0
        assert all(s.value == (situation == "joystick") for s in log.flags[c.JOY_PRIORITY])
        assert len(log.flags[c.JOY_PRIORITY]) == 1
    if situation == "nominal":
        assert 0.3 < _average_speed(log) < 1.0


def _average_speed(log: EventLog) -> float:
    poses = log.poses
    dist = sum(((b.x - a.x) ** 2 + (b.y - a.y) ** 2) ** 0.5 for a, b in itertools.pairwise(poses))
    begin = next(ln.t for ln in log.logs if ln.msg.startswith("Begin navigating"))
    end = next(ln.t for ln in log.logs if ln.msg == "Goal succeeded")
    return dist / ((end - begin) / 1e9)
