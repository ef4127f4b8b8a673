"""A Nav2 lifecycle node that was started but never brought up.

Every Nav2 server is a managed node (nav2_util::LifecycleNode): it starts unconfigured, prints "<name> lifecycle
node launched. Waiting on external lifecycle transitions to activate" (nav2_util lifecycle_node.cpp@kilted,
printLifecycleNodeNotification), and logs "Configuring" and "Activating" only when a lifecycle manager (or a person)
asks it to. A lifecycle manager brings up the nodes of its node_names and then logs "Managed nodes are active". A
node that announced itself before that and never logged "Configuring" was in no manager's list: it stays
unconfigured, and the servers it creates on configure (a waypoint follower's follow_waypoints action) never exist.
It is told only for a run in which no goal reached the navigator: a node no goal needed explains nothing.

A manager configures every node of its list before it activates any (LifecycleManager::startup: configure all, then
activate all): one that has begun activating ("Activating <node>") without configuring a node announced before is
past that node too. When its bring-up then failed because a server was not there (the navigator's "… action server
not available", the catalogue's bt.action_unavailable), the node it never configured is told the same way.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from hexar.events.records import LogLine
from hexar.explainers.base import Evidence
from hexar.explainers.navigation.chain import BRINGUP, NEVER_CAME_UP
from hexar.explainers.navigation.detectors import Finding

_LAUNCHED = re.compile(r"(?P<node>[\w/]+) lifecycle node launched")
_ACTIVE = "Managed nodes are active"
_ASKED = ("Configuring", "Activating")
_UNAVAILABLE = "bt.action_unavailable"  # the mined Nav2 catalogue's "… action server not available …"


def _past(logs: Sequence[LogLine]) -> list[LogLine]:
    """A manager's lines by which every node of its list had been configured: its "Managed nodes are active", or,
    where its bring-up then failed for want of a server, its first "Activating <node>"."""
    from hexar.explainers.navigation.catalogue import catalogue

    active = [ln for ln in logs if ln.msg.strip() == _ACTIVE]
    if active:
        return active
    missing = any((e := catalogue().match(ln.msg)) is not None and e.id == _UNAVAILABLE for ln in logs)
    activating = next((ln for ln in logs if "lifecycle_manager" in ln.name and ln.msg.startswith("Activating ")), None)
    return [activating] if missing and activating is not None else []


def unmanaged(logs: Sequence[LogLine]) -> Finding | None:
    """The first managed node that announced itself before a lifecycle manager had all its nodes active (or had
    begun activating them, and failed for want of a server), and was never configured."""
    active = _past(logs)
    if not active:
        return None
    for line in logs:
        m = _LAUNCHED.search(line.msg)
        if m is None or line.t > active[-1].t:
            continue
        node = (line.name or m["node"]).strip("/")
        if any(ln.name.strip("/") == node and ln.msg.strip() in _ASKED for ln in logs):
            continue
        found = Finding(BRINGUP, [Evidence.of_log(BRINGUP, line), Evidence.of_log(BRINGUP, active[-1])])
        brought = (f"brought the others up ('{_ACTIVE}')" if active[-1].msg.strip() == _ACTIVE else
                   f"configured the others and went on to activate them ('{active[-1].msg.strip()}')")
        found.notes = [f"{node} was started but never configured or activated: my lifecycle manager {brought} "
                       "without it, as when it is missing from the manager's node_names, so nothing it serves ever "
                       "existed"]
        found.facts[NEVER_CAME_UP] = 1.0
        return found
    return None
