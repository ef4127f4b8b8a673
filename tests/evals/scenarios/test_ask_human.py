from __future__ import annotations

import random
from dataclasses import replace
from pathlib import Path

import pytest

from hexar.evals.scenarios.ask_human import (
    ERR_DECLINED,
    ERR_NAVIGATION,
    ERR_NOT_CONFIRMED,
    ERR_NOT_FOUND,
    AskHumanConditions,
    random_conditions,
    run_state_machine,
    scenario_conditions,
    simulate_ask_human,
    training_executions,
)
from hexar.evals.scenarios.bag import BagBuilder, SkillResult, sec_ns
from hexar.events.contract import ASK_HUMAN_STATUS_NAME, EPISODIC_MEMORY
from hexar.events.reader import read_recording
from hexar.explainers.ask_human.variables import END_KEYS, KEYS, assignment

GOOD = AskHumanConditions(True, True, 2.5, 0.2, False, 0.1, True, True)


def _keys(cond: AskHumanConditions) -> list[str]:
    return [key for _, key, _ in run_state_machine(cond)]


def test_keys_follow_the_state_machine_order() -> None:
    rng = random.Random(5)
    for _ in range(500):
        keys = _keys(random_conditions(rng))
        assert keys[:3] == ["InitialState", "person_approached", "DetectState"]
        assert keys[-1] in END_KEYS and sum(k in END_KEYS for k in keys) == 1
        body = keys[:-1]
        assert body == sorted(body, key=KEYS.index) and len(set(body)) == len(body)


def test_full_success_writes_every_key_in_order() -> None:
    assert _keys(GOOD) == [*KEYS, "SkillSucceeded"]


@pytest.mark.parametrize(
    ("distance", "path"),
    [(0.74, "ask"), (0.75, "navigate"), (4.0, "navigate"), (4.01, "fail")],
)
def test_distance_thresholds(distance: float, path: str) -> None:
    keys = _keys(replace(GOOD, person_distance=distance))
    assert ("NavigateState" in keys) == (path == "navigate")
    assert ("AskForHelpState" in keys) == (path != "fail")
    assert keys[-1] == ("SkillFailed" if path == "fail" else "SkillSucceeded")


@pytest.mark.parametrize(
    ("change", "last_key", "value"),
    [
        ({"person_detected": False}, "person_detected", "False"),
        ({"detection_stable": False}, "detection_stable", "False"),
        ({"navigation_failure": True}, "navigation_failure", "True"),
        ({"user_accepted": False}, "user_accepted", "False"),
        ({"user_accepted": None}, "user_accepted", "None"),
        ({"user_confirmed": False}, "user_confirmed", "False"),
        ({"user_confirmed": None}, "user_confirmed", "None"),
    ],
)
def test_each_failure_ends_right_after_its_step(change: dict[str, object], last_key: str, value: str) -> None:
    steps = run_state_machine(replace(GOOD, **change))  # type: ignore[arg-type]
    assert steps[-1][1] == "SkillFailed"
    assert steps[-2][1:] == (last_key, value)


def test_noise_and_approach_error_do_not_stop_the_skill() -> None:
    steps = run_state_machine(replace(GOOD, person_std_rms=0.9, robot_nav_err=0.8))
    assert steps[-1][1] == "SkillSucceeded"
    values = {k: v for _, k, v in steps}
    assert values["person_std_rms"] == "0.9" and values["robot_nav_err"] == "0.8"


def _simulate(
    tmp_path: Path, cond: AskHumanConditions, navigate: bool = False
) -> tuple[SkillResult, list[str], list[int]]:
    b = BagBuilder()
    start = sec_ns(1_760_000_000)

    def nav(t: int) -> SkillResult:
        b.log(t + sec_ns(3), "bt_navigator", 40, "Goal failed")
        return SkillResult(t + sec_ns(14), False, "blocked")

    result = simulate_ask_human(
        b, random.Random(1), start, cond, question="Could you help me?", navigate=nav if navigate else None
    )
    log = read_recording(b.write(tmp_path / "bag"))
    records = log.statuses[EPISODIC_MEMORY]
    assert all(
        r.name == ASK_HUMAN_STATUS_NAME
        and r.values[0] == ("Module name", "skill_ask_human_for_help")
        and len(r.values) == 2
        for r in records
    )
    assert all(start < r.t <= result.end for r in records)
    return result, [r.values[1][0] for r in records], [r.t for r in records]


@pytest.mark.parametrize(
    ("change", "error"),
    [
        ({"person_detected": False}, ERR_NOT_FOUND),
        ({"detection_stable": False}, ERR_NOT_FOUND),
        ({"person_distance": 5.5}, ERR_NOT_FOUND),
        ({"navigation_failure": True}, ERR_NAVIGATION),
        ({"user_accepted": False}, ERR_DECLINED),
        ({"user_confirmed": None}, ERR_NOT_CONFIRMED),
        ({}, ""),
    ],
)
def test_simulation_writes_the_steps_and_returns_the_skill_error(
    tmp_path: Path, change: dict[str, object], error: str
) -> None:
    cond = replace(GOOD, **change)  # type: ignore[arg-type]
    result, keys, _ = _simulate(tmp_path, cond)
    assert keys == _keys(cond)
    assert result.succeeded == (error == "") and result.error_msg == error


def test_timeouts_show_in_the_timing(tmp_path: Path) -> None:
    _, keys, times = _simulate(tmp_path, replace(GOOD, user_accepted=None))
    i = keys.index("user_accepted")
    assert times[i] - times[i - 1] == sec_ns(45.0)
    _, keys, times = _simulate(tmp_path / "b", replace(GOOD, user_confirmed=None))
    i = keys.index("user_confirmed")
    assert times[i] - times[i - 1] == sec_ns(30.0)


def test_navigate_callback_decides_the_approach(tmp_path: Path) -> None:
    result, keys, times = _simulate(tmp_path, GOOD, navigate=True)
    assert not result.succeeded and result.error_msg == ERR_NAVIGATION
    assert keys[-2:] == ["navigation_failure", "SkillFailed"]
    nav_start = times[keys.index("NavigateState")]
    assert times[keys.index("navigation_failure")] > nav_start + sec_ns(14)


@pytest.mark.parametrize("seed", range(4))
def test_scenarios_keep_their_situation(seed: int) -> None:
    def run(s: int) -> dict[str, str]:
        steps = run_state_machine(scenario_conditions(s, random.Random(seed)))
        return assignment((k, v) for _, k, v in steps)

    assert run(0)["outcome"] == "success"
    assert run(0)["person_std_rms"] == "le_0.5" and run(0)["robot_nav_err"] == "le_0.5"
    assert run(11)["person_detected"] == "false"
    assert run(12)["person_distance"] == "gt_4.0"
    assert run(13)["detection_stable"] == "false"
    assert run(14)["navigation_failure"] == "true"
    assert run(15)["user_accepted"] == "false"
    assert run(16)["user_confirmed"] in {"false", "no_answer"}
    for s in (17, 18):
        assert run(s)["outcome"] == "success" and run(s)["robot_nav_err"] == "gt_0.5"
    assert run(17)["person_std_rms"] == "le_0.5" and run(18)["person_std_rms"] == "gt_0.5"
    with pytest.raises(ValueError):
        scenario_conditions(5, random.Random(seed))


def test_training_executions_are_read_from_the_records() -> None:
    rows = training_executions(1000, 7)
    assert rows == training_executions(1000, 7) and rows != training_executions(1000, 8)
    rng = random.Random(7)
    for row in rows[:50]:
        steps = run_state_machine(random_conditions(rng))
        assert row == assignment((k, v) for _, k, v in steps)
    outcomes = {r["outcome"] for r in rows}
    causes = {
        (r["detection_next"], r["navigation_next"], r["ask_next"], r["confirmation_next"]) for r in rows
    }
    assert outcomes == {"success", "failure"} and len(causes) >= 7  # every path of the state machine is seen
