"""A map that never reached the node that reads it: map_saver's save, or a costmap's static layer.

A map that could not be saved: nav2_map_server's map_saver got no map on its topic in time.

map_saver (`ros2 run nav2_map_server map_saver_cli`, or its save_map service) waits `save_map_timeout` for one
map on its topic, then gives up: "Failed to save the map: timeout" on Foxy (map_saver.cpp:191@foxy-devel, the
timeout in milliseconds, 2000 by default), "Failed to spin map subscription" from Galactic on
(map_saver.cpp:213@humble, in seconds, 2.0 by default). From Galactic on it subscribes transient local
(`map_subscribe_transient_local`, true by default), which a map published volatile (gmapping's) never matches:
rclcpp then warns of the publisher's incompatible QoS. A SLAM node that publishes its map only every few seconds
outlasts the default timeout. Both are the map saver's settings against the map's publisher; that no node
published the map at all is the other reading, which the lines alone cannot rule out.

A costmap that refused its map: the static layer subscribes transient local too (its own
`map_subscribe_transient_local`, true by default from Foxy on, static_layer.cpp:125@foxy-devel), and rclcpp logs the
incompatible-QoS warning under the subscribing node's name, so "[global_costmap.global_costmap] New publisher
discovered on topic '/map', offering incompatible QoS" is that costmap refusing that publisher (a map bridged from
ROS 1, or published volatile). Unless its static layer then says a map came ("StaticLayer: Resizing costmap to …",
or "… static layer to …", INFO, when a map came that changed the size; "StaticLayer: Received a … map", DEBUG, for
every map; static_layer.cpp:203, :218 and :188@humble),
the costmap planned without the map.
"""

from __future__ import annotations

import re

from hexar.events.records import LogLine
from hexar.explainers.base import Evidence
from hexar.explainers.navigation import detectors as d
from hexar.explainers.navigation import diagnose as g
from hexar.explainers.navigation.nomap import MAP_QOS, map_came_after, policy_words

SAVER = "map_saver"
TIMED_OUT = ("Failed to save the map: timeout", "Failed to spin map subscription")
FACT = "map_not_saved"  # a configuration finding's fact: 1.0 with the QoS mismatch logged, 0.0 without
# rclcpp's warning on the subscription's side (subscription_base.cpp:373@rolling), the policy at its end
_QOS = re.compile(r"^New publisher discovered on topic '[^']*', offering incompatible QoS\..*: \w+_QOS_POLICY$")
REFUSED = "costmap_refused_map"  # a configuration finding's fact; notes: the costmap's node, its warning
_TOPIC = re.compile(r"topic '([^']*)'")


def map_not_saved(lines: list[LogLine]) -> d.Finding | None:
    """map_saver's own give-up in `lines`, with its QoS warning before it when logged; None when it did not."""
    saver = [ln for ln in lines if ln.name == SAVER]
    failed = next((ln for ln in saver if ln.msg.strip() in TIMED_OUT), None)
    if failed is None:
        return None
    qos = next((ln for ln in saver if ln.t <= failed.t and _QOS.match(ln.msg.strip())), None)
    found = d.Finding(g.CONFIGURATION, [Evidence.of_log(g.CONFIGURATION, ln) for ln in (qos, failed) if ln])
    found.facts[FACT] = 1.0 if qos is not None else 0.0
    if qos is not None:
        found.notes.append(policy_words(qos.msg))
    found.notes.append(failed.msg.strip())
    return found


def costmap_refused_map(lines: list[LogLine]) -> d.Finding | None:
    """A costmap whose subscription refused the map's publisher, in `lines`, and no word of its static layer after
    that that a map came; None when there is none."""
    for ln in lines:
        if "costmap" not in ln.name or not MAP_QOS.match(ln.msg.strip()):
            continue
        if map_came_after(ln, lines):
            continue
        found = d.Finding(g.CONFIGURATION, [Evidence.of_log(g.CONFIGURATION, ln)])
        found.facts[REFUSED] = 1.0
        found.notes += [ln.name, ln.msg.strip()]
        return found
    return None


def template(f: d.Finding) -> tuple[str, str | None, list[str]] | None:
    """The answer of a map_not_saved or costmap_refused_map finding, or None for any other finding."""
    if REFUSED in f.facts:
        node, said = f.notes[:2]
        costmap = node.split(".")[0].replace("_", " ")
        topic = m.group(1) if (m := _TOPIC.search(said)) else "map"
        return (f"My {costmap} never got my map: its subscription to {topic} did not match what the map's publisher "
                f"offers (the {policy_words(said)} of their QoS), so no map reached it: “[{node}] {said}”. That is a "
                "configuration problem, and without the map my navigation could not work.",
                "Make the two sides match: publish the map transient local (a map bridged from ROS 1 or published "
                "volatile is not), or set the static layer's `map_subscribe_transient_local: false` in that "
                "costmap's parameters (under its static layer's name, e.g. `static_layer.map_subscribe_transient_"
                "local`).",
                [])
    if FACT not in f.facts:
        return None
    said = f.notes[-1]
    foxy = said == TIMED_OUT[0]
    if f.facts[FACT]:
        return (f"I couldn't save my map: map_saver got no map (“[{SAVER}] {said}”) because its subscription did not "
                f"match what the map's publisher offers (the {f.notes[0]} of their QoS). That is a configuration "
                "problem of the map saver.",
                "Subscribe the way the map is published: for a map published volatile (gmapping's), run map_saver "
                "with `--ros-args -p map_subscribe_transient_local:=false`, or publish the map transient local.",
                [])
    # the parameter and the line are named in quotes and the fix only: "time out" is a text-to-speech claim's word
    waits = "2000 ms by default on Foxy" if foxy else "2 s by default"
    value = "10000" if foxy else "10.0"
    return (f"I couldn't save my map: map_saver waits a short while for a map on its topic ({waits}) and got none: "
            f"“[{SAVER}] {said}”. Most likely a configuration problem: a SLAM node publishes its map only every few "
            "seconds, less often than map_saver waits. Otherwise nothing published a map on that topic.",
            f"Give map_saver more time (`--ros-args -p save_map_timeout:={value}`), and check that the map topic it "
            "reads is published (`ros2 topic hz /map`).",
            [])
