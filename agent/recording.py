""""What did you record?" and "what time is it?": answered from the recording itself (its topics, their message
counts, its span), the only clock and the only data the agent has, instead of the task's finding."""

from __future__ import annotations

import re

from hexar.events.log import EventLog
from hexar.events.records import calendar_day, duration, hms
from hexar.events.tasks import Task
from hexar.explainers.base import Evidence, Explanation
from hexar.explainers.recorded import join_words

_LEAD = r"^(and |so |but |ok |okay |hey |robot )?"
CLOCK = re.compile(
    _LEAD + r"(what|which) (time|day|date) is it( (now|today|right now))?\b|"
    + _LEAD + r"what('s| is) (the )?(time|date|day)( (now|today|right now))?\W*$|"
    + _LEAD + r"what('s| is) (the date |the day )?today\b|"
    + _LEAD + r"(do|can) you (know|tell me|have) (the )?(time|date)\b")
RECORDED = re.compile(
    _LEAD + r"what (did|do|have) you (record|recorded|capture|captured|save|saved)( (there|here|in (it|this|there)))?"
            r"\W*$|"
    + _LEAD + r"what('s| is| was) (in|on) (your|the|this|that) (recording|bag|rosbag|bag file|data)\b|"
    + _LEAD + r"what (topics|data|messages) (did|do|have) you (have|record|recorded|hear|heard|get|got|save)\b|"
    + _LEAD + r"(what|which) topics\b|"
    + _LEAD + r"(what|how much|how many messages) (was|were|is|got) recorded\b|"
    + _LEAD + r"how (long|big) is (your|the|this) (recording|bag|rosbag)\b")
SHOWN = 5  # topics named, most messages first; the rest are counted
# "did any /scan get published?", "was odom updating?", "were joint_states coming in?", "did docking_server ever get
# a BatteryState message?": whether data flowed on a topic, which only the recording's topics can say
_TOPIC_WORDS = {"scan": "scan", "laser": "scan", "lidar": "scan", "odom": "odom", "odometry": "odom",
                "cmd_vel": "cmd_vel", "joint_states": "joint_states", "joint states": "joint_states", "tf": "tf",
                "tf_static": "tf_static", "clock": "clock", "imu": "imu", "battery_state": "battery_state",
                "batterystate": "battery_state", "battery state": "battery_state", "points": "points",
                "pointcloud": "points", "point cloud": "points", "image": "image", "camera": "image",
                "map": "map", "costmap": "costmap", "goal_pose": "goal_pose", "amcl_pose": "amcl_pose"}
_NAMED = r"(/[a-z0-9_/]+|" + "|".join(sorted((re.escape(w) for w in _TOPIC_WORDS), key=len, reverse=True)) + r")"
TOPIC_DATA = re.compile(
    r"\b(did|was|were|is|are|has|have|had)\b[a-z_ ]{0,40}?\b(any |the |my |a )?" + _NAMED + r"s?\b( (data|messages?|"
    r"topic))?[a-z_ ]{0,30}?\b(published|publishing|get published|arriv\w*|receiv\w*|sent|coming in|come in|updat\w*|"
    r"flowing|recorded|in the bag|reach\w*|alive)\b|"
    r"\b(anything|any messages?|any data) (on|from|in) (the )?" + _NAMED + r"\b|"
    r"\b(arriv\w*|publish\w*|come in|came in|received?|sent) (on|in|at|to) (the )?" + _NAMED + r"\b|"
    r"\bany " + _NAMED + r"( or " + _NAMED + r")?( data| messages?)? (in|on) (the |this |my )?(bag|recording)\b|"
    r"\b(ever )?(get|got|receive|received) (a |any )?" + _NAMED + r"( messages?)?\b|"
    # "did the driver publish any scans before it stopped?"
    r"\b(did|has|had) (the |my |your |a |any )?[a-z_]+ (ever )?(publish|send|output) (a |any )?" + _NAMED + r"s?\b")


_WHY = re.compile(r"^(and |so |but |ok,? )?why\b")


def clock_kind(q: str) -> str | None:
    """'clock', 'recorded' or 'topic_data' for a question (lower case, spaces collapsed) about the recording
    itself."""
    if CLOCK.search(q):
        return "clock"
    if RECORDED.search(q):
        return "recorded"
    # "why did the planner never receive the map?" asks for a cause, which the finding gives, not for a count
    return "topic_data" if TOPIC_DATA.search(q) and not _WHY.match(q) else None


def _asked_topics(q: str) -> list[str]:
    """The topic names a question asks about, as a recording names them: "/scan", or a word for one ("lidar")."""
    found: list[str] = []
    for m in re.finditer(r"(?<![a-z0-9_])" + _NAMED + r"s?(?![a-z0-9_])", q):
        word = m.group(1)
        name = word.strip("/") if word.startswith("/") else _TOPIC_WORDS[word]
        if name not in found:
            found.append(name)
    return found


def topic_data(question: str, log: EventLog, task: Task) -> Explanation:
    """How many messages the recording holds on the topics a question names (live: how many were heard), or that it
    holds none of them and which topics it does hold: whether data flowed there is for the recording to say."""
    q = " ".join(question.lower().split())
    asked = _asked_topics(q)
    held = sorted(log.topics.values(), key=lambda i: i.topic)
    said, evidence, missing = [], [], []
    for name in asked:
        last = name.rsplit("/", 1)[-1]
        on = [i for i in held if i.topic.strip("/") == name or i.topic.rsplit("/", 1)[-1] == last]
        if not on:
            missing.append(f"/{name}")
            continue
        said.append(join_words([f"{_count(i.count, 'message')} on {i.topic} ({i.type})" for i in on]))
        evidence += [Evidence(cause="planner.plan_ok", topic=i.topic, t=log.start,
                              item=f"{_count(i.count, 'message')}, {i.type}") for i in on]
    holds = "I have heard" if log.storage == "live" else "My recording holds"
    parts = [f"{holds} {join_words(said)}."] if said else []
    if missing:
        kept = join_words([i.topic for i in held][:8]) + (f" and {len(held) - 8} more" if len(held) > 8 else "")
        parts.append(f"{'It holds' if said else holds} no {join_words(missing)}: it has only {kept}, so whether "
                     f"anything was published on {join_words(missing)} it cannot tell.")
    text = " ".join(parts)
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], evidence=evidence,
                       enough_information=bool(said) and not missing)


def _heard(log: EventLog) -> str:
    return "what I have heard" if log.storage == "live" else "my recording"


def clock(question: str, log: EventLog, task: Task) -> Explanation:
    """The time of the last message recorded (the robot keeps no clock here but its recording's), with its day."""
    day = calendar_day(log.end)
    if day is None:
        text = (f"I can't tell the time: {_heard(log)} ran on a simulator's clock, which starts at zero; it read "
                f"{hms(log.end)} at the last message.")
    else:
        text = (f"I tell the time only by {_heard(log)}: its last message came at {hms(log.end)} UTC on {day}. "
                "I keep no other clock here.")
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"])


def _count(n: int, one: str) -> str:
    return f"{n:,} {one}" + ("" if n == 1 else "s")


def recorded(question: str, log: EventLog, task: Task) -> Explanation:
    """The recording's span, its topics by message count (their types in the evidence), the tasks it tells of and
    what was set aside while reading it."""
    topics = sorted(log.topics.values(), key=lambda i: (-i.count, i.topic))
    total = sum(i.count for i in topics)
    day = calendar_day(log.start)
    span = (f"{duration(log.end - log.start)}, from {hms(log.start)} to {hms(log.end)} UTC"
            + (f" on {day}" if day is not None else " on a simulator's clock"))
    kind = {"sqlite3": "a rosbag2 (sqlite3)", "mcap": "a rosbag2 (MCAP)", "rosbag1": "a ROS 1 bag"}.get(log.storage)
    live = log.storage == "live"
    # live, the counts are of every message heard, while only the latest are kept (live/log.py's limits)
    head, holds = (f"What I keep of what I have heard spans {span}.", "I have heard") if live else \
        (f"My recording is {kind or 'a recording'} of {span}.", "It holds")
    if not topics:
        return Explanation(explainer="planner", text=f"{head} {holds} no messages.", causes=["planner.plan_ok"],
                           enough_information=False)
    shown = [f"{i.count:,} on {i.topic}" for i in topics[:SHOWN]]
    rest = topics[SHOWN:]
    if rest:
        shown.append(f"{sum(i.count for i in rest):,} on {_count(len(rest), 'other topic')}")
    text = f"{head} {holds} {_count(total, 'message')} on {_count(len(topics), 'topic')}: {join_words(shown)}."
    tasks = [t for t in log.tasks if not t.is_recovery]
    if tasks:
        text += (f" It tells of {_count(len(tasks), 'task')}" + (': ask "what tasks were there?" for them.'
                                                                 if len(tasks) > 1 else "."))
    if log.warnings:
        text += f" {'Listening' if live else 'While reading it'}, I set aside: {join_words(log.warnings[:3])}"
        text += f" and {len(log.warnings) - 3} more." if len(log.warnings) > 3 else "."
    evidence = [Evidence(cause="planner.plan_ok", topic=i.topic, t=log.start, item=f"{_count(i.count, 'message')}, "
                         f"{i.type}") for i in topics]
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], evidence=evidence)
