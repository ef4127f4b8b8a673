"""Spawners that never reached their controller manager, for a bring-up setting.

- Spawners that asked for a controller manager other than the one that runs: the spawner's "Could not contact
  service /<manager>/list_controllers" (controller_manager/spawner.py, its service calls) names the manager it was
  given (`--controller-manager`, or its namespace), while a controller manager under another name logged its start.
  Nothing went wrong with the controllers: no request ever reached their manager, so the finding is a bring-up
  setting, told with both names.
- Spawners that gave up before their controller manager had its robot description: since Jazzy the controller
  manager offers its services only once a description has arrived on its topic ("Waiting for data on
  'robot_description' topic to finish initialization" until then, "Received robot description from topic." when one
  does: controller_manager.cpp@kilted). A spawner that stopped waiting ("Could not contact service …") while the
  manager still waited, with the description arriving after, gave up too early: a `--controller-manager-timeout`
  shorter than the description's delay, or a description published late.
- A controller the controller manager configured ("Configuring controller: '…'") and never activated, while it
  activated others ("Activating controllers: [ … ]", controller_manager.cpp@kilted) and the start went on with no
  error: its spawner left it inactive (`--inactive`), or nothing activated it after, so it takes no goal or command.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from hexar.events.records import ERROR, LogLine
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


def gave_up(lines: list[LogLine]) -> bool:
    """A spawner could not reach its controller manager, and none got its controllers up after all."""
    return any(_ASKED.match(ln.msg) for ln in lines) and not any(
        ln.msg.startswith("Configured and activated") for ln in lines)


def other_manager(lines: list[LogLine]) -> OtherManager | None:
    asked = next(((ln, m[1]) for ln in lines if (m := _ASKED.match(ln.msg))), None)
    if asked is None or not gave_up(lines):
        return None  # a spawner that got its controllers up after all reached a manager
    started = next((ln for ln in lines if _STARTED.match(ln.msg) and ln.name.endswith("controller_manager")), None)
    if started is None:
        return None
    (spawner, wanted), running = asked, "/" + started.name.replace(".", "/")
    return OtherManager(wanted, running, spawner, started) if wanted != running else None


_WAITING = re.compile(r"^Waiting for data on 'robot_description' topic to finish initialization")
_RECEIVED = re.compile(r"^Received robot description (from topic|file)")


@dataclass(frozen=True)
class TooEarly:
    spawner: LogLine  # the last spawner that gave up
    waiting: LogLine  # the manager still waiting for its description just before
    received: LogLine  # the description that came after


def gave_up_early(lines: list[LogLine]) -> TooEarly | None:
    """Every spawner gave up while the controller manager waited for its robot description, which came after."""
    if not gave_up(lines):
        return None
    last = [ln for ln in lines if _ASKED.match(ln.msg)][-1]
    waiting = next((ln for ln in reversed(lines) if _WAITING.match(ln.msg) and ln.t <= last.t), None)
    received = next((ln for ln in lines if _RECEIVED.match(ln.msg) and ln.t > last.t), None)
    if waiting is None or received is None or any(_RECEIVED.match(ln.msg) and ln.t <= last.t for ln in lines):
        return None
    return TooEarly(last, waiting, received)


def early_answer(explainer: str, found: TooEarly, t0: int) -> Explanation:
    late = (found.received.t - found.spawner.t) / 1e9
    return Explanation(
        explainer=explainer, causes=[CAUSE], confidence=0.8,
        evidence=[Evidence.of_log(CAUSE, found.waiting), Evidence.of_log(CAUSE, found.spawner),
                  Evidence.of_log(CAUSE, found.received)],
        text=("Starting my controllers could not complete because a parameter never reached one of my nodes in "
              f"time: my robot description came to my controller manager {late:.1f} s after my spawners gave up "
              "on it, and until then the manager offered no service, so no controller was loaded."),
        fix=("Publish the robot description before the spawners start (robot_state_publisher first), or give the "
             "spawners a --controller-manager-timeout longer than the description's delay."),
        details=[f"The last spawner gave up at {(found.spawner.t - t0) / 1e9:.1f} s; the description came at "
                 f"{(found.received.t - t0) / 1e9:.1f} s."])


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


_CONFIGURING = re.compile(r"^Configuring controller: '(?P<name>[^']+)'")
_ACTIVATING = re.compile(r"^Activating controllers: \[(?P<names>[^\]]*)\]")
ACTIVATION = "control.controller_activation_failed"
SETTLED_NS = 2_000_000_000  # the start went on this long after the configure: an activation would have come


# joint_trajectory_controller's goal_received_callback on a controller that is not active: the refusal that follows
# from a controller left inactive, no error of its own
_REFUSED = re.compile(r"^Can't accept new action goals\. Controller is not running\.")


def never_activated(lines: list[LogLine]) -> LogLine | None:
    """The configure line of a controller never activated while others were, in a start with no error but that
    controller's refusal of a goal."""
    activated = {n for ln in lines if (m := _ACTIVATING.match(ln.msg)) for n in m["names"].split()}
    last = max((ln.t for ln in lines), default=0)
    errors = [ln for ln in lines if ln.level >= ERROR]
    for ln in lines:
        m = _CONFIGURING.match(ln.msg)
        if m is None or not activated or m["name"] in activated:
            continue
        refused = [r for r in lines if r.t > ln.t and _REFUSED.match(r.msg) and r.name.rsplit(".", 1)[-1] == m["name"]]
        # its refusal of a goal shows it inactive then; without one, the start must have gone on long enough
        if (refused or last - ln.t >= SETTLED_NS) and all(r in refused for r in errors):
            return ln
    return None


def inactive_answer(explainer: str, configured: LogLine) -> Explanation:
    name = m["name"] if (m := _CONFIGURING.match(configured.msg)) else "a controller"
    return Explanation(
        explainer=explainer, causes=[ACTIVATION], confidence=0.7,
        evidence=[Evidence.of_log(ACTIVATION, configured)],
        text=(f"My controller {name} was never activated: my controller manager configured it, then activated my "
              "other controllers but not it, so it took no goal or command. Its spawner left it inactive (as "
              "--inactive does), or nothing activated it afterwards."),
        fix=f"Spawn {name} without --inactive, or activate it (ros2 control switch_controllers --activate {name}).",
        details=["The controller manager's activations never named it."])
