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


def clock_kind(q: str) -> str | None:
    """'clock' or 'recorded' for a question (lower case, spaces collapsed) about the recording itself."""
    if CLOCK.search(q):
        return "clock"
    return "recorded" if RECORDED.search(q) else None


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
