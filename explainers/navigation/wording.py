"""Answers for the causes read from Nav2's own words: (sentence, fix, details), each fix fitting its cause.

The sentences avoid the phrasings of other causes in hexar/causes.yaml (e.g. a goal outside the map is not
worded as "no valid path", which names an obstacle on the way), so the graders and the guard read exactly the
cause that was found.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable

from hexar.claims import read_claims
from hexar.events import contract as c
from hexar.events.records import LogLine
from hexar.explainers.navigation import diagnose as g
from hexar.explainers.navigation import grids, keepout, mapsave, smoother, states, waypoints, worded
from hexar.explainers.navigation.detectors import CLOCK_DOUBT, REACH_DOUBT, Finding, Run
from hexar.explainers.navigation.nomap import NO_MAP, NO_MAP_FACT
from hexar.explainers.navigation.plugin_name import plugin_reading
from hexar.explainers.stack.bringup import AGAIN, LAUNCH_ANY


def quote(line: LogLine | None) -> str:
    return f"'{line.msg.strip()}'" if line is not None else ""


# Lines that say what stopped the robot without saying why (each with its readings, from its source), told when no
# catalogued line names a cause; never a cause themselves. Keyed by Nav2 catalogue id.
SYMPTOMS = {
    # amcl_node.cpp:926@humble (WARN): printed until a pose is set, and when the one set cannot be used
    "amcl.set_initial_pose": (
        "AMCL kept saying it cannot publish a pose until an initial pose is set, which happens when no initial pose "
        "was given, or when one was given but AMCL could not use it (its laser scans or the odometry transforms not "
        "arriving in time)"),
    # collision_monitor_node.cpp:619@jazzy (WARN): a source with no valid data stops the robot, no object seen
    "cmon.invalid_source": (
        "my collision monitor held me still because one of its sensor sources gave no valid data (none published "
        "yet, none recent enough, or none it could bring into my base frame); my logs do not say which"),
    # speed_filter.cpp@kilted (INFO): the speed filter's zones are in force from its mask on; the limit it sets in a
    # zone is never logged
    "costmap.speed_mask": (
        "a speed filter was in force (its mask of speed zones had arrived), and a zone of it can hold me below the "
        "progress my controller must make; my logs do not show the limit it set"),
}


def symptoms(f: Finding) -> str:
    """The SYMPTOMS sentences a finding carries, as one sentence tail ("" when none)."""
    said = [n for n in f.notes if n in SYMPTOMS.values()]
    return "; ".join(said)


def quotable(msg: str, own: Iterable[str] = ()) -> bool:
    """Whether a log line can be quoted inside an answer's sentence: it must not read as a cause other than `own`
    (a behaviour-tree file named "..._w_replanning_and_recovery.xml" is no replanning; "detected collision" in an
    unknown error is no finding). A line that does is told by its node and time, and quoted in the details only."""
    return not read_claims(msg).causes - set(own)


def _said(f: Finding) -> str:
    """The first supporting line, quoted, with its logger."""
    ev = next((e for e in f.evidence if e.topic in c.LOG_SOURCES), None)
    return f"{ev.item}" if ev is not None else ""


PROGRESS_RADIUS_M = 0.5  # Nav2's SimpleProgressChecker default required_movement_radius


def stalled_seconds(run: Run) -> float | None:
    """How long the robot had stayed within the progress checker's radius when it gave up, from `/amcl_pose`:
    None when the recording holds no pose before the first `Failed to make progress`."""
    line = run.first(("Failed to make progress",))
    if line is None:
        return None
    before = [p for p in run.poses if p.t <= line.t]
    if not before:
        return None
    last = before[-1]
    moved = [p for p in before if math.hypot(p.x - last.x, p.y - last.y) > PROGRESS_RADIUS_M]
    since = moved[-1].t if moved else before[0].t
    return (line.t - since) / 1e9


def _progress_seconds(run: Run) -> str:
    stalled = stalled_seconds(run)
    if stalled is not None and stalled >= 1:
        # measured from the recorded poses; the allowance itself is a parameter the recording does not hold
        return (f"{stalled:.0f} s (my recorded position stayed within {PROGRESS_RADIUS_M} m for that long; "
                "Nav2's movement time allowance is 10 s by default)")
    return "longer than its movement time allowance (10 s by default)"


def _held(seconds: float) -> str:
    return " for less than a second" if seconds < 1 else f" for {seconds:.0f} s"


# The planner's lines that put the goal on lethal cells (NavFn's and Theta*'s GoalOccupied, Smac's "Goal is occupied")
GOAL_OCCUPIED = re.compile(r"Goal Coordinates of ?\(.*\) was in lethal cost|Goal was in lethal cost|"
                           r"[Gg]oal is occupied|[Gg]oal is in lethal space")


# What tells apart the causes of a planner that found no path (each needs its own line to be claimed).
PLAN_CANDIDATES = ("the goal may lie inside an obstacle or outside my map, my own start pose may sit on occupied "
                   "cells, my position estimate may be wrong, or something may stand in the way")
PLAN_CHECKS = ("What tells them apart: a planner line naming the start or the goal (e.g. 'Start occupied', 'Goal "
               "Coordinates ... outside bounds'), AMCL's covariance and warnings, and the global costmap around my "
               "start and the goal.")


def _slow(f: Finding, place: str) -> tuple[str, str | None, list[str]]:
    """A goal reached late after failures and recoveries: what went wrong on the way, and that the logs do not say
    what held the robot up (reached.slow_retries)."""
    stuck, plans = int(f.facts.get("progress_failures", 0)), int(f.facts.get("plan_failures", 0))
    what = []
    if stuck:
        what.append("my controller made no progress for a while ('Failed to make progress')"
                    + (f" {stuck} times" if stuck > 1 else ""))
    gave_up = int(f.facts.get("controller_gave_up", 0))
    if f.facts.get("collision_warned"):  # reached.slow_retries: its first note quotes the controller's warning
        what.append(f"my controller's collision check stopped me ({f.notes[0]})"
                    + (f" and it gave up {gave_up} time{'s' if gave_up > 1 else ''}" if gave_up else ""))
    if plans:
        what.append(f"my planner could not compute a route {plans} time{'s' if plans > 1 else ''}")
    done = f.notes[-1] if f.notes else "I retried"  # reached.slow_retries: "I cleared my costmaps and ran my ..."
    head = (f"I reached {place}, but it took longer because I got stuck on the way: {', and '.join(what)}"
            if what else f"I reached {place}, but it took longer")
    return (f"{head}; {done} before it worked. I can't tell what was in the way from my logs alone.",
            None, ["Failures and recoveries alone do not show what held me up."])


def _honest(f: Finding) -> str:
    """The decisive error quoted (chain.quote_last_error), as the end of a sentence."""
    return next((n for n in f.notes if n.startswith("the last error")), "")


def _bringup(f: Finding, place: str) -> tuple[str, str | None, list[str]]:
    what = f.notes[0] if f.notes else "a node of my navigation never came up"
    # a process that died may have died mid-goal: said as what launch reported, not as a node that never came up
    head = f"I couldn't reach {place} because " if what.startswith("the process of ") else \
        f"I couldn't reach {place} because my nodes never came up: " if what.startswith(LAUNCH_ANY) else \
        f"I couldn't reach {place} because of a bring-up failure: " if what.startswith(AGAIN) else \
        f"I couldn't reach {place} because a node of my navigation never came up: "
    return (f"{head}{what.rstrip('.')}.",
            "Fix the error quoted from the failing node (its parameters file, its configure step, or why its "
            "process died) and restart the navigation until the lifecycle manager reports 'Managed nodes are "
            "active'.",
            [f"Also: {n}." for n in f.notes[1:]] + [f"The decisive line: {_said(f)}"])


def _symptom(f: Finding, place: str, run: Run) -> tuple[str, str | None, list[str]] | None:
    """Answers for what a failure produced when no line says what caused it: candidates, and the last error."""
    last = _honest(f)
    warned = next((n for n in f.notes if n.startswith("the last warning")), "")
    if warned and run.outcome == "unknown":
        return (f"The recording does not show whether my navigation to {place} ended or anything went wrong: "
                f"{warned}, and a warning alone does not say that a goal failed.",
                "If a goal did fail, record its end (bt_navigator's 'Goal failed' or the action status) with the "
                "lines before it.", [])
    seen_stop = symptoms(f)
    if f.cause == g.NO_PROGRESS and last:
        also = f" Also, {seen_stop}." if seen_stop else ""
        return (f"My navigation to {place} gave up because my controller made no progress for "
                f"{_progress_seconds(run)}. I can't tell what caused it for sure, but {last}.{also}",
                "Check that error first; then that cmd_vel reaches the base and that TF is fresh.",
                ["Nav2's progress checker gave up; no catalogued line names a cause."])
    if f.cause != "navigation.unexplained_failure":
        return None
    if "reached" in f.facts:
        return _slow(f, place)
    state = states.of_finding(f.facts)
    if state is not None:
        verb = "failed" if run.outcome == "failed" else "did not finish"
        tail = f" {last[0].upper()}{last[1:]}." if last else ""
        by = next((n for n in f.notes if n.startswith(states.OUTSIDE_BY)), "")
        tail = f" {by}{tail}" if by else tail  # the facts that tell the candidates apart, as the costmap logged them
        return states.sentence(state, place, verb) + tail, state.checks, [f"Nav2 said: {_said(f)}"]
    if "plan_failures" in f.facts:
        tail = f" {last[0].upper()}{last[1:]}." if last else ""
        n = int(f.facts["plan_failures"])
        head = f"I couldn't reach {place}: my planner could not compute a route to it ({n} time{'s' * (n != 1)})"
        if free := grids.free_way(f):
            return (f"{head}, and it was not for want of a way: {free}.{tail}",
                    "Check the planner plugin's parameters (its time and iteration limits, footprint and "
                    "motion model) against this start and goal.", [f"Nav2 said: {_said(f)}"])
        # a goal still running when the recording ends is told as unfinished by the explainer (_unfinished)
        return (f"{head}, and I can't tell why from my logs alone: {PLAN_CANDIDATES}.{tail}",
                PLAN_CHECKS, [f"Nav2 said: {_said(f)}"])
    if last and run.outcome == "unknown":
        return (f"The recording does not show whether my navigation to {place} finished. I can't tell what went "
                f"wrong for sure, but {last}.",
                "Start from that error: it is the last one any node printed in the recording.", [])
    if last:
        verb = "failed" if run.outcome == "failed" else "did not finish"
        return (f"My navigation to {place} {verb}. I can't tell what caused it for sure, but {last}.",
                "Start from that error: it is the last one any node printed before the goal ended.",
                [f"The last navigation message was {quote(run.end)}."] if run.end else [])
    return None


def _waypoint_tasks(f: Finding) -> tuple[str, str | None, list[str]]:
    """Trips that reached their waypoints, and the task at some of them that failed (explainers/navigation/
    waypoints.py)."""
    n = int(f.facts[waypoints.FACT])
    reached, which = ("my waypoints", f"at {n} of them") if n > 1 else ("my waypoint", "there")
    said = _said(f)
    topic = next((x.removeprefix(waypoints.TOPIC_NOTE) for x in f.notes if x.startswith(waypoints.TOPIC_NOTE)), "")
    if f.cause == g.CONFIGURATION and topic:
        return (f"I reached {reached}, but the task {which} failed: taking a photo there needs an image from "
                f"{topic}, and none came, so that task was misconfigured or my camera was not running. My "
                f"waypoint follower said: {said}",
                f"Point the photo task's image_topic at a topic the camera publishes (ros2 topic list), or start the "
                f"camera; ros2 topic hz {topic} shows whether images come.", [])
    return (f"I reached {reached}, but the task {which} failed, and my logs do not show why. The last error "
            f"before it: {said}",
            "Read the waypoint task executor plugin's own lines before the failure, and its parameters.", [])


def _keepout(f: Finding, place: str) -> tuple[str, str | None, list[str]] | None:
    """Keepout zones and a start the robot could not leave (explainers/navigation/keepout.py)."""
    said = _said(f)
    if keepout.MASK_FACT in f.facts:
        return (f"I couldn't reach {place}: my planner had a path, then my keepout filter received its zones and from "
                "then on it found no way to the goal. That was no obstacle coming into my way: a keepout zone covers "
                "the goal or closes the way to it, and my logs do not show which.",
                "Check the keepout filter mask against the goal and the way to it (a goal inside a zone can never be "
                "reached; leave a gap in the zones where the robot must pass).", [f"Nav2 said: {said}"])
    if f.cause == g.START_IN_OBSTACLE and any(keepout.IN_ZONE in e.item for e in f.evidence):
        return (f"I couldn't reach {place} because my own start position was on occupied cells of my costmap: I "
                "stood inside a keepout zone, as my keepout filter said, and could not drive out of it.",
                "Drive the robot out of the zone by hand, or take the zone off its place in the filter mask; check "
                "that the mask is drawn on the same map as the robot's.", [f"Nav2 said: {said}"])
    if keepout.SPIN_FACT in f.facts:
        return (f"I couldn't reach {place} because my own start position was on occupied cells of my costmap: my "
                "planner could not start a plan from where I stood, and a spin in place there could not even turn. "
                "My logs do not show what put me there: an obstacle or a keepout zone under me, or a wrong position "
                "estimate.",
                "Check where the robot is on the map (its pose estimate) and what the global costmap shows under it "
                "(an obstacle, a keepout zone of a filter mask, inflation).", [f"Nav2 said: {said}"])
    return None


def template(f: Finding, place: str, run: Run) -> tuple[str, str | None, list[str]] | None:
    said = _said(f)
    seen = [f"Nav2 said: {said}"] if said else []
    if f.cause == g.BRINGUP:
        return _bringup(f, place)
    if (mapped := grids.template(f, place)) is not None:
        return mapped
    if (unsaved := mapsave.template(f)) is not None:
        return unsaved
    if (told := worded.answer(f)) is not None:  # a docking's, a behaviour's, a goal as sent: their own words
        return told
    if (smoothed := smoother.template(f, place)) is not None:
        return smoothed
    if waypoints.FACT in f.facts:
        return _waypoint_tasks(f)
    if (zoned := _keepout(f, place)) is not None:
        return zoned
    if f.cause == g.START_IN_OBSTACLE:
        return (f"I couldn't reach {place} because my own start position was on occupied cells of my costmap, so "
                "no plan could start from it.",
                "Check where the robot is on the map (its pose estimate), and clear or re-inflate the costmap "
                "around it; if it really stands in an obstacle's inflation, drive it out by hand.",
                seen)
    symptom = _symptom(f, place, run)
    if symptom is not None:
        return symptom
    if f.cause == g.GOAL_UNREACHABLE and any(GOAL_OCCUPIED.search(e.item) for e in f.evidence):
        return (f"I couldn't reach {place} because my planner found the goal itself on occupied cells (lethal cost), "
                "so no plan could end there. My logs do not show what occupies it: a wall or an obstacle at the goal, "
                "an obstacle seen earlier and still marked there, or the inflation around obstacles.",
                "Pick a goal on free space of the map, or check the global costmap around it (clear it if what "
                "was marked there has gone).", seen)
    if f.cause == g.GOAL_UNREACHABLE:
        return (f"I couldn't reach {place} because the goal itself cannot be reached: it lies outside my map or "
                "inside an obstacle, so planning to it always fails.",
                "The goal is outside the map / in an obstacle: pick a reachable goal on free space of the map.",
                seen)
    if f.cause == g.OFF_COSTMAP and NO_MAP_FACT in f.facts:
        qos = (f", because its subscription did not match what the map's publisher offers (the {f.notes[0]} of their "
               "QoS)") if f.notes else ""
        return (f"I couldn't reach {place} because my own position was outside my global costmap: the costmap never "
                f"received its map ('{NO_MAP}'){qos}, so it kept a default size that does not hold where I am.",
                "Make the map reach the costmap: map_server or SLAM must publish /map, with the durability the "
                "static layer subscribes with (transient local unless map_subscribe_transient_local is false).",
                seen)
    if f.cause == g.OFF_COSTMAP:
        return (f"I couldn't reach {place} because my own position was off my costmap, "
                "so I may not be localized.",
                "Set the initial pose (e.g. '2D Pose Estimate' in RViz) so that the robot is on the map, and "
                "check the map -> odom transform.",
                [*seen, "Nav2 plans from the robot's position; a start outside the map makes every plan fail."])
    if f.cause == g.TRANSFORM and REACH_DOUBT in f.facts:
        return (f"Nav2 logged {place} as reached, but I can't be sure I got there: on the line before, my controller "
                f"said {f.notes[0]}, so it judged the goal without knowing where I was on my plan. That is a transform "
                "(TF) error: a transform it needs was missing or stale.",
                "Check where the robot really is, and that localisation keeps publishing map -> odom (its scans "
                "must reach it with timestamps the transforms cover).",
                seen)
    if f.cause == g.TRANSFORM and CLOCK_DOUBT in f.facts:
        # the critic's word is the costmap's, and mistimed scans put obstacles where nothing stands
        return (f"I couldn't reach {place}: my controller found that every trajectory would hit an obstacle in my "
                f"costmap, and gave up. That may not have been a real obstacle: {f.notes[0]}, a sign that the "
                "clocks of my computers disagree (a clock skew), and readings placed with the wrong transform mark "
                "obstacles where nothing stands. My logs alone do not tell which it was.",
                "Check that every computer of the robot keeps the same time (chrony or NTP on each), then look at "
                "what the local costmap shows around the robot.",
                seen)
    if f.cause == g.TRANSFORM and f.notes:
        return (f"I couldn't reach {place} because of a transform (TF) error: {f.notes[0]}.",
                "Check that whatever publishes that transform runs (for map -> odom: localisation, which waits for "
                "an initial pose) before the navigation starts, or give the costmap a longer "
                "initial_transform_timeout.",
                seen)
    if f.cause == g.TRANSFORM:
        return (f"I couldn't reach {place} because of a transform (TF) or clock error: the transforms my "
                "navigation needs were missing, stale or stamped at the wrong time.",
                "Check the TF tree (ros2 run tf2_tools view_frames), that every node uses the same clock "
                "(use_sim_time everywhere or nowhere) and that odometry and localisation publish their transforms.",
                seen)
    if f.cause == g.CONFIGURATION and f.notes:
        # a node asked to configure again was up already: the stack was brought up twice, not a node that stayed down
        came = ":" if f.notes[0].startswith(AGAIN) else " and a node of it never came up:"
        return (f"I couldn't reach {place} because my navigation stack was misconfigured{came} "
                f"{f.notes[0].rstrip('.')}.",
                "Fix the error quoted from that node (often its parameters or plugins) and restart the navigation "
                "until the lifecycle manager reports 'Managed nodes are active'.",
                [f"Also: {n}." for n in f.notes[1:]] + seen)
    plugin = next((r for e in f.evidence if (r := plugin_reading(e.item or ""))), "")
    if f.cause == g.CONFIGURATION and plugin:
        return (f"I couldn't reach {place} because my navigation stack was misconfigured, so a node of it never "
                f"came up: {plugin}.",
                "Name the plugin in that node's parameters exactly as its plugin description declares it, and "
                "restart the navigation until the lifecycle manager reports 'Managed nodes are active'.",
                seen)
    if f.cause == g.CONFIGURATION and f.facts.get("never_came_up"):
        return (f"I couldn't reach {place} because my navigation stack was misconfigured, so a node of it never "
                "came up (a configuration error: a plugin, behaviour tree or lifecycle node failed).",
                "Fix the configuration error quoted in the log (plugin names, behaviour-tree XML, parameters) and "
                "restart the navigation until the lifecycle manager reports 'Managed nodes are active'.",
                seen)
    if f.cause == g.CONFIGURATION:
        what = f"my logs say: {said}" if said and quotable(said, (g.CONFIGURATION, g.BRINGUP)) else \
            "a plugin, behaviour tree or lifecycle node failed"
        return (f"I couldn't reach {place} because my navigation stack was misconfigured or not fully brought "
                f"up (a configuration error: {what}).",
                "Fix the configuration error quoted in the log (plugin names, behaviour-tree XML, parameters) and "
                "check that the lifecycle manager reports 'Managed nodes are active'.",
                seen)
    if f.cause == g.COLLISION_AHEAD and run.outcome == "reached":
        held = _held(f.facts["held_s"]) if "held_s" in f.facts else ""
        return (f"It took me longer to reach {place} because my collision monitor stopped me{held}: something "
                "was inside its stop zone, so it detected a collision ahead and held me until the way was clear.",
                "Look at what entered the collision monitor's stop polygon (or at the polygon's size, if "
                "nothing was there).",
                seen)
    if f.cause == g.COLLISION_AHEAD and "detected collision ahead" in said:
        # the controller checks its costmap, not the world: the line says the check fired, not what was there
        return (f"I couldn't reach {place} because my controller's collision check stopped me: it detected a "
                "collision ahead on my path and would not drive on. My logs do not say what it saw there: a real "
                "object, or cost marked in my costmap where nothing stands (my footprint or its inflation).",
                "Look at what is on the path just ahead; if nothing is there, check the robot's footprint and the "
                "costmap's inflation, which can make a free path look blocked to the controller.",
                seen)
    if f.cause == g.COLLISION_AHEAD:
        return (f"I couldn't reach {place} because my collision checking stopped me: it detected a collision "
                "ahead and would not let me move on.",
                "Look at what is close to the robot (or its footprint and collision-monitor polygons, if nothing "
                "is there).",
                seen)
    if f.cause == g.CONTROLLER:
        return (f"I couldn't reach {place} because my controller failed to compute velocity commands "
                "to follow the path.",
                "Check the controller's parameters and the local costmap around the robot (footprint, inflation, "
                "critics).",
                seen)
    if f.cause == g.DOCKING:
        return ("My docking failed: the docking server could not complete the docking.",
                "Check the docking server's log: that its detector sees the target, that the staging pose is "
                "reachable and that the contacts mate.",
                seen)
    if f.cause == g.NOT_REACHING_BASE:
        facts = f.facts
        return (f"I couldn't reach {place} because my velocity commands never reached my base: the "
                f"controller commanded up to {facts.get('max_cmd', 0.0):.2f} for {facts.get('seconds', 0.0):.0f} s "
                "while my odometry showed no motion.",
                "Check that cmd_vel reaches the base: the topic remapping, the velocity smoother's output and the "
                "base driver.",
                ["/cmd_vel carried motion commands while /odom stayed still."])
    if f.cause == g.NO_PROGRESS and symptoms(f):
        return (f"My navigation to {place} gave up because my controller made no progress for "
                f"{_progress_seconds(run)}, and nothing in my logs says why for sure: {symptoms(f)}.",
                "Check the data sources and transforms the line points to, then that cmd_vel reaches the base.",
                ["Nav2's progress checker gave up; no catalogued line names a cause."])
    if f.cause == g.NO_PROGRESS:
        return (f"My navigation to {place} gave up because my controller made no progress for "
                f"{_progress_seconds(run)}; nothing in my logs says why.",
                "Checks a person can make: that cmd_vel reaches the base (record /cmd_vel and /odom), that TF is "
                "fresh, that the controller is tuned for this robot, and whether something stood in the way.",
                ["The only failure Nav2 logged was its progress checker giving up; no line names a cause."])
    return None
