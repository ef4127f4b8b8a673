"""The map a costmap never got: the static layer's warning, and a QoS mismatch on the map's topic beside it.

Nav2's planner then times out on a costmap that is never current and the robot seems off its map; the cause is the
map that never came, not stale transforms or a goal off the map.
"""

from __future__ import annotations

import re

from hexar.events.records import LogLine
from hexar.explainers.navigation.detectors import Finding

# nav2_costmap_2d's static layer (static_layer.cpp:410@humble) while no /map has come: the costmap keeps its default
# size and is never current, so the planner's "Costmap timed out waiting for update" (planner_server.cpp@jazzy) is
# that missing map, not stale transforms.
NO_MAP = "Can't update static costmap layer, no map received"
# the static layer's words once a map came (static_layer.cpp:188 DEBUG, :203 INFO, :218 INFO @humble)
MAP_CAME = ("StaticLayer: Received a ", "StaticLayer: Resizing costmap to ", "StaticLayer: Resizing static layer to ")
COSTMAP_TIMEOUT = "Costmap timed out waiting for update"
# rclcpp's subscription_base.cpp:373@rolling: the map's publisher and the costmap's subscription do not match
MAP_QOS = re.compile(r"^New publisher discovered on topic '/?(\w+/)*map', offering incompatible QoS")


def map_never_came(seen: list[LogLine]) -> list[LogLine]:
    """The lines that say the costmap got no map: the static layer's, and a QoS mismatch on the map's topic beside
    it; none unless the static layer said so (a mismatch alone may be any subscriber's), and none when that layer
    then said a map came (its warning stops once it has one)."""
    gone = [ln for ln in seen if NO_MAP in ln.msg or MAP_QOS.match(ln.msg)]
    last: dict[str, LogLine] = {}  # each costmap's last warning: it warns until a map comes
    for ln in gone:
        if NO_MAP in ln.msg and (ln.name not in last or ln.t >= last[ln.name].t):
            last[ln.name] = ln
    return gone if any(not map_came_after(ln, seen) for ln in last.values()) else []


def map_came_after(line: LogLine, lines: list[LogLine]) -> bool:
    """Whether the static layer of `line`'s node said, at or after it, that a map came."""
    return any(r.name == line.name and r.t >= line.t and r.msg.startswith(MAP_CAME) for r in lines)


NO_MAP_FACT = "no_map"  # an off_costmap finding's fact: the costmap never got its map (notes: the QoS policy, if said)


def no_map_finding(found: Finding, seen: list[LogLine]) -> Finding:
    """`found` (off_costmap) marked with the map that never came, and the QoS policy that kept it away if logged."""
    gone = map_never_came(seen)
    if gone:
        found.facts[NO_MAP_FACT] = 1.0
        policy = next((policy_words(ln.msg) for ln in gone if MAP_QOS.match(ln.msg)), "")
        if policy:
            found.notes.append(policy)
    return found


def policy_words(warning: str) -> str:
    """The policy at the end of rclcpp's incompatible-QoS warning, in words ("DURABILITY_QOS_POLICY": durability)."""
    return warning.rsplit(":", 1)[-1].strip().removesuffix("_QOS_POLICY").replace("_", " ").lower()


def without_map_timeouts(lines: list[LogLine], seen: list[LogLine]) -> list[LogLine]:
    """`lines` less the costmap timeouts that a map that never came explains."""
    if not map_never_came(seen):
        return lines
    return [ln for ln in lines if COSTMAP_TIMEOUT not in ln.msg]
