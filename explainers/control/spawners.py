"""Spawners that asked for a controller manager other than the one that runs: the spawner's "Could not contact
service /<manager>/list_controllers" (controller_manager/spawner.py, its service calls) names the manager it was
given (`--controller-manager`, or its namespace), while a controller manager under another name logged its start.
Nothing went wrong with the controllers: no request ever reached their manager, so the finding is a bring-up
setting, told with both names."""

from __future__ import annotations

import re
from dataclasses import dataclass

from hexar.events.records import LogLine
from hexar.explainers.base import Evidence, Explanation

CAUSE = "bringup.configuration_error"
_ASKED = re.compile(r"^Could not contact service (/[\w/]*?)/(?:list_controllers|list_controller_types|"
                    r"load_controller|configure_controller|switch_controller|unload_controller)\b")
# the controller manager's own start (controller_manager.cpp): its logger is its node's name, namespace included
# with dots (rclcpp), so it tells the name the spawners should have asked for
_STARTED = re.compile(r"^(?:Resource Manager has been successfully initialized|Subscribing to '.*' topic for robot "
                      r"description|update rate is \d+ Hz)")


@dataclass(frozen=True)
class OtherManager:
    asked: str
    running: str
    spawner: LogLine
    manager: LogLine


def other_manager(lines: list[LogLine]) -> OtherManager | None:
    asked = next(((ln, m[1]) for ln in lines if (m := _ASKED.match(ln.msg))), None)
    if asked is None or any(ln.msg.startswith("Configured and activated") for ln in lines):
        return None  # a spawner that got its controllers up after all reached a manager
    started = next((ln for ln in lines if _STARTED.match(ln.msg) and ln.name.endswith("controller_manager")), None)
    if started is None:
        return None
    (spawner, wanted), running = asked, "/" + started.name.replace(".", "/")
    return OtherManager(wanted, running, spawner, started) if wanted != running else None


def answer(explainer: str, found: OtherManager) -> Explanation:
    return Explanation(
        explainer=explainer, causes=[CAUSE], confidence=0.8,
        evidence=[Evidence.of_log(CAUSE, found.manager), Evidence.of_log(CAUSE, found.spawner)],
        text=(f"Starting my controllers could not complete because my spawners asked for a controller manager "
              f"that does not exist, {found.asked}, while mine ran as {found.running}: the setting that names it "
              "never reached my spawners, so no controller was loaded."),
        fix=(f"Start the spawners with --controller-manager {found.running} (or in the controller manager's "
             "namespace)."),
        details=[f"My controller manager started as {found.running}; the spawners kept calling "
                 f"{found.asked}'s services, which nothing offers."])
