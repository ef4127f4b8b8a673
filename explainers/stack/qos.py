"""A publisher and a subscription on one topic whose QoS do not match, so no message goes from one to the other
(stable API).

    qos_line(lines) -> LogLine | None
    qos_words(line) -> tuple[str, str]

rclcpp and rclpy log both ends of such a pair when discovery finds it, each on its own node's logger:
"New publisher discovered on topic '%s', offering incompatible QoS. No messages will be received from it. Last
incompatible policy: %s" on the subscription's node (rclcpp subscription_base.cpp, rclpy event_handler.py; "will be
sent to it" before Jazzy), and "New subscription discovered on topic '%s', requesting incompatible QoS. No messages
will be sent to it. …" on the publisher's. The policy is printed as its name ("RELIABILITY") or, up to Humble, as
rmw's enum name ("RELIABILITY_QOS_POLICY").
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from hexar.events.records import WARN, LogLine

_QOS = re.compile(r"New (?P<found>publisher|subscription) discovered on topic '(?P<topic>[^']*)', "
                  r"(?:offering|requesting) incompatible QoS\..*?Last incompatible policy: (?P<policy>[A-Z_]+)", re.S)

_FIX = {
    "RELIABILITY": "A best-effort publisher (the sensor-data QoS most drivers use) cannot serve a reliable "
                   "subscription: subscribe best effort (rclcpp::SensorDataQoS(), rclpy's qos_profile_sensor_data), "
                   "or publish reliable.",
    "DURABILITY": "A volatile publisher cannot serve a transient-local subscription (one that wants the last "
                  "message kept, as a map's does): publish transient local, or subscribe volatile.",
    "DEADLINE": "The subscription asks for a deadline the publisher does not offer: offer at least that deadline "
                "on the publisher, or drop it from the subscription.",
    "LIVELINESS": "The subscription asks for a liveliness kind or lease the publisher does not offer: make the "
                  "publisher's at least as strict, or relax the subscription's.",
}


def qos_line(lines: Sequence[LogLine]) -> LogLine | None:
    """The first QoS mismatch line, preferring the subscription's end (its node is the one that gets nothing);
    None when there is none."""
    found = [ln for ln in lines if ln.level >= WARN and _QOS.search(ln.msg)]
    return next((ln for ln in found if "New publisher" in ln.msg), found[0] if found else None)


def qos_words(line: LogLine) -> tuple[str, str]:
    """(what happened, the fix), for a person, from a line `qos_line` found."""
    m = _QOS.search(line.msg)
    if m is None:
        return ("a publisher and a subscription on one topic asked for QoS settings that do not match",
                "Give the publisher and the subscription compatible QoS settings.")
    policy = m["policy"].removesuffix("_QOS_POLICY")
    node = line.name or "a node"
    if m["found"] == "publisher":
        whose = f"{node}'s subscription to '{m['topic']}' gets no message from a publisher"
    else:
        whose = f"{node}'s publisher on '{m['topic']}' sends nothing to a subscription"
    return (f"{whose} whose QoS settings do not match its own (the {policy.lower()} policy), so no message went "
            "between them",
            _FIX.get(policy, "Give the publisher and the subscription compatible settings of that policy "
                             "(`ros2 topic info -v` prints both ends' QoS)."))
