"""Builds a one-task navigation recording with the simulator and reads it back, for the navigation tests."""

from __future__ import annotations

import random
from pathlib import Path
from typing import Any

from hexar.evals.scenarios.bag import BagBuilder, SkillResult, sec_ns
from hexar.evals.scenarios.nav import NavSituation, simulate_navigation, simulate_robot_state
from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.events.reader import read_recording
from hexar.explainers.base import Context, Evidence
from hexar.explainers.navigation.detectors import flag_item, pose_item, status_item
from tests.events.helpers import task_msg

T0 = 1_700_000_000_000_000_000
ALL: tuple[NavSituation, ...] = ("nominal", "blocked", "joystick", "charging", "poor_localisation",
                                 "moving_obstacles")


def _task(status: str, error: str = "", label: str = "kitchen") -> dict[str, Any]:
    return task_msg("Zq3J9kLm0pQr7sT1", f"bring me a coffee from the {label}",
                    [("navigate_to_zone", {"location": label}, status, error)])


def simulate(situation: NavSituation, seed: int = 1) -> tuple[BagBuilder, SkillResult]:
    b, rng = BagBuilder(), random.Random(seed)
    created = T0 + sec_ns(3.0)
    b.task_info(created, _task("waiting"))
    b.task_info(created + sec_ns(0.2), _task("Running"))
    result = simulate_navigation(b, rng, created + sec_ns(0.4), (0.0, 0.0), (4.0, 2.0), situation)
    simulate_robot_state(b, rng, T0, result.end + sec_ns(5.0), joystick=situation == "joystick",
                         charging=situation == "charging")
    b.task_info(result.end, _task("succeeded" if result.succeeded else "failed", result.error_msg))
    return b, result


def recording(tmp: Path, situation: NavSituation, seed: int = 1) -> EventLog:
    b, _ = simulate(situation, seed)
    return read_recording(b.write(tmp / f"{situation}_{seed}"))


def context(log: EventLog) -> Context:
    return Context.for_task(log, log.task())


def recorded(log: EventLog, e: Evidence) -> bool:
    """Whether an evidence item is in the recording, at its time, with that text."""
    if e.topic == c.ROSOUT:
        return any(line.t == e.t and line.render() == e.item for line in log.logs)
    if e.topic == c.AMCL_POSE:
        return any(p.t == e.t and pose_item(p) == e.item for p in log.poses)
    if e.topic in (c.JOY_PRIORITY, c.IS_CHARGING):
        return any(s.t == e.t and flag_item(s) == e.item for s in log.flags.get(e.topic, []))
    if e.topic == c.DIAGNOSTICS:
        return any(r.t == e.t and any(status_item(r, k) == e.item for k, _ in r.values)
                   for r in log.statuses.get(e.topic, []))
    return False
