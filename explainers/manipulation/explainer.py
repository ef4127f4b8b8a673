"""The manipulation (MoveIt 2) component explainer: move_group, planning pipelines, kinematics, the planning
scene and trajectory execution, read from /rosout through the mined MoveIt catalogue.

Causes (explainers/logcause.py decides by the earliest decisive line; symptoms such as "MoveGroupInterface::move()
failed or timeout reached" or "Plan and Execute request aborted" are never the answer when a cause precedes them):
planning_failed, ik_failed, start_state_in_collision, goal_state_invalid, no_joint_states, stale_robot_state,
execution_failed, controllers_not_found, configuration_error, nominal, and unexplained_failure (the first error no
catalogue explains, quoted with its node and time). A controller's line (a tolerance abort) is told by the control
explainer, asked through the registry; a bring-up or device line before any of them is cited first.

The state monitor's numbers decide between two causes: "Requested time R, but latest received state has time L"
with L = 0 and R a simulated time (small) means no joint state ever arrived; R a wall-clock time (an epoch) with L
a simulated time or 0, or any L older than R, means the times were mixed (stale_robot_state).

A pick or place that failed for want of reach (IK, planning, an invalid goal) after a navigation step of the same
task asks navigation about that trip: a base that stopped in the wrong place is part of the answer.
"""

from __future__ import annotations

import re
from typing import ClassVar

from hexar.events.records import LogLine, hms
from hexar.explainers.base import Context, Evidence, Explanation
from hexar.explainers.control.catalogue import catalogue as control_catalogue
from hexar.explainers.logcause import Diagnosis, ModuleCatalogue, Reading
from hexar.explainers.manipulation.catalogue import catalogue
from hexar.explainers.manipulation.wording import template
from hexar.explainers.module_explainer import ModuleExplainer, focus
from hexar.explainers.module_wording import verbatim
from hexar.explainers.recorded import NAV_SKILLS
from hexar.explainers.sim_time import with_sim_time

SKILLS = ("pick", "place", "move_arm")
REACH = frozenset({"manipulation.ik_failed", "manipulation.planning_failed", "manipulation.goal_state_invalid"})
FOUND_NONE = "manipulation.controllers_not_found"
# move_action_capability.cpp's INFO when the goal holds before any motion (the mined catalogue's id)
ALREADY_MET = "move_group.goal_constraints_are_already_satisfied_no"
# fix_start_state_collision.cpp's WARN: it found no valid state nearby and passes the request to the planner anyway
PASSED_ON = "planning_request_adapter_plugins.unable_to_find_a_valid_state"
# getActionResultString's success text for a plan-only goal and MoveGroupInterface::plan()'s end
# (move_action_capability.cpp, move_group_interface.cpp): a plan computed for a request that asked for no execution
PLANNED = frozenset({"move_group.motion_plan_was_computed_successfully",
                     "move_group_interface.planning_request_complete"})
NOT_RUN = "move_group.no_motion_plan_found_no_execution"
ENDS = frozenset({"cause", "symptom", "failed", "succeeded", "canceled"})
NAV_FINE = frozenset({"navigation.nominal", "navigation.nominal_speed"})
_TIMES = re.compile(r"Requested time (?P<req>\d+(?:\.\d+)?),? but latest received state has time "
                    r"(?P<last>\d+(?:\.\d+)?)")
WALL_CLOCK_S = 1e9  # an epoch in seconds (2001 onwards): a wall-clock time, not a simulation's
NO_STATES = "manipulation.no_joint_states"
STATE_CAUSES = frozenset({NO_STATES, "manipulation.stale_robot_state"})
# move_group_interface's ERROR and the planning scene monitor's WARN (move_group_interface.cpp:551@2.1.0,
# planning_scene_monitor.cpp:1008@2.1.0): MoveIt had no current state, for either reason; only the state
# monitor's own line before it ("Didn't receive robot state ...", with or without its times) tells which
FETCH = re.compile(r"Failed to fetch current robot state")
MONITOR = re.compile(r"Didn't received? robot state|latest received state has time")
UNTOLD = "no state monitor line says which"
# the state monitor's line without its times ("Didn't received robot state (joint angles) with recent timestamp
# within 1.000000 seconds. Check clock synchronization ..."): MoveIt's own hint points at the clocks, its numbers
# would have confirmed it
HINTED = "the state monitor's hint, without its times"


def state_monitor_cause(msg: str) -> str | None:
    """no_joint_states or stale_robot_state from the numbers of MoveIt's state-monitor line (None: no numbers)."""
    m = _TIMES.search(msg)
    if m is None:
        return None
    requested, latest = float(m["req"]), float(m["last"])
    if latest == 0.0 and requested < WALL_CLOCK_S:
        return "manipulation.no_joint_states"
    return "manipulation.stale_robot_state"


class ManipulationExplainer(ModuleExplainer):
    """Explains what the robot's arm did (MoveIt 2)."""

    name: ClassVar[str] = "manipulation"
    skills: ClassVar[tuple[str, ...]] = SKILLS
    prefix: ClassVar[str] = "manipulation."
    module_words: ClassVar[str] = "my arm's motion"
    description: ClassVar[str] = (
        "Explains the robot's arm (MoveIt 2 motion planning and execution): why it could not pick up or put down "
        "an object or move its arm (no motion plan found, no inverse-kinematics solution, a start or goal in "
        "collision, no or out-of-date joint states, no controller for the arm, trajectory execution failures, "
        "MoveIt set-up problems), and whether an arm motion went fine. Use it for questions about grasping, "
        "picking, placing, reaching or moving the arm."
    )

    # a trajectory controller's action server that refused the goal or ended it itself (rclpy's own lines)
    action_causes: ClassVar[dict[str, str]] = {"not_ended": "manipulation.execution_failed",
                                               "refused": "manipulation.execution_failed"}
    candidates: ClassVar[str] = ("It may be MoveIt's settings (its parameters, plugins or robot description), the "
                                 "request itself, or the controllers that run my arm.")

    def catalogues(self) -> list[ModuleCatalogue]:
        return [catalogue(), control_catalogue()]

    def refine(self, readings: list[Reading]) -> list[Reading]:
        monitor = [r for r in readings if MONITOR.search(r.line.msg)]
        told = bool(monitor) or any(r.cause in STATE_CAUSES and not FETCH.search(r.line.msg) for r in readings)
        # the monitor's times where its line is worded as no mined entry reads it (no comma before "but")
        by_times = next((c for r in reversed(monitor) if r.cause is None
                         and (c := state_monitor_cause(r.line.msg)) is not None), None)
        out = []
        # the last line in which MoveIt itself says it found no controller (a left-out one carries a note)
        found_none = max((i for i, r in enumerate(readings) if r.cause == FOUND_NONE and not r.note), default=-1)
        for i, r in enumerate(readings):
            cause = state_monitor_cause(r.line.msg) if r.cause == "manipulation.stale_robot_state" else None
            if r.cause == FOUND_NONE and r.note and r.entry is not None and r.entry.cause != FOUND_NONE \
                    and found_none < i:
                # a controller left out of MoveIt's list (its settings lack a field) is why MoveIt found none for
                # the joints only where MoveIt then says so; alone, it is the set-up error its entry names
                cause = r.entry.cause
                out.append(Reading(r.line, r.entry, cause, r.catalogue))
                continue
            if r.cause == NO_STATES and FETCH.search(r.line.msg) and (not told or by_times):
                out.append(Reading(r.line, r.entry, by_times or r.cause, r.catalogue, "" if told else UNTOLD))
                continue
            if r.cause == "manipulation.stale_robot_state" and cause is None and MONITOR.search(r.line.msg):
                out.append(Reading(r.line, r.entry, r.cause, r.catalogue, HINTED))
                continue
            out.append(Reading(r.line, r.entry, cause, r.catalogue) if cause is not None else r)
        return out

    def words(self, cause: str, d: Diagnosis, what: str) -> tuple[str, str | None, list[str]]:
        if cause == NO_STATES and d.decisive is not None and d.decisive.note == UNTOLD:
            _, fix, seen = template(cause, d, what)
            return (f"I couldn't finish {what} because MoveIt had no current state of my arm: the joint states it "
                    "asked for did not reach it in time. My logs do not show what it was: none may have come at all "
                    "(nothing published them where move_group listens), or they came stamped older than it asked "
                    "for (simulated and wall-clock time mixed).",
                    f"{fix} If they are published, give every node the same use_sim_time.", seen[:1])
        if cause == "manipulation.stale_robot_state" and d.decisive is not None and d.decisive.note == HINTED:
            _, fix, seen = template(cause, d, what)
            return (f"I couldn't finish {what} because MoveIt received no state of my arm recent enough, and its "
                    "own line points at the clocks: most likely, simulated time and wall-clock time were mixed. "
                    "That line gives no times to confirm it; joint states that never arrived would read the same.",
                    fix, seen[:1])
        return template(cause, d, what)

    def reason_before(self, context: Context, d: Diagnosis) -> Diagnosis:
        """MoveIt found no controller for the goal's joints, and before the goal (at its start) its controller
        manager left one out for a field its settings lack: that line says why, and is kept as support."""
        if d.cause != FOUND_NONE or d.decisive is None or d.decisive.note:
            return d
        why = [r for r in self.readings_before(context) if r.cause == FOUND_NONE and r.note]
        if not why:
            return d
        first = d.decisive
        d.decisive = Reading(first.line, first.entry, first.cause, first.catalogue, why[-1].note)
        d.support = [why[-1], *d.support][:3]
        return d

    def explain(self, question: str, context: Context) -> Explanation:
        found = with_sim_time(super().explain(question, context), context.log, context.window[1])
        if found.causes == ["manipulation.nominal"]:
            lines = context.view(self.topics).logs()
            met = _without_motion(found, lines)
            return met if met is not found else _plan_only(found, lines)
        if found.causes == ["manipulation.start_state_in_collision"]:
            found = _passed_on(found, context.view(self.topics).logs())
        if not set(found.causes) & REACH:
            return found
        return self._with_navigation(question, context, found)

    def _with_navigation(self, question: str, context: Context, found: Explanation) -> Explanation:
        """Ask navigation about the trip that brought the base to this pick or place."""
        run = focus(context, SKILLS)
        if run is None or self.registry is None or "navigation" not in self.registry.classes:
            return found
        trips = [r for r in context.task.skills[:run.index] if r.skill in NAV_SKILLS and r.state == "succeeded"]
        if not trips:
            return found
        trip = trips[-1]
        nav = self.registry.get("navigation").explain(question, context.with_window(context.task.skill_window(trip)))
        if not nav.enough_information or set(nav.causes) <= NAV_FINE:
            return found
        return found.model_copy(update={
            "text": f"{found.text} My base had stopped where my arm could not work well: {nav.text}",
            "causes": [*found.causes, *[c for c in nav.causes if c not in found.causes]],
            "evidence": [*found.evidence, *nav.evidence],
            "details": [*found.details, "I asked my navigation explainer about the trip before it.", *nav.details],
        })


def _without_motion(found: Explanation, lines: list[LogLine]) -> Explanation:
    """A goal MoveIt ended without moving the arm, because it was already there ("Goal constraints are already
    satisfied. No need to plan or execute any motions"), in the window's `lines`: told as that, never as a motion
    made."""
    met = next((ln for ln in lines if (e := catalogue().match(ln.msg)) is not None and e.id == ALREADY_MET), None)
    if met is None:
        return found
    text = (f"I did not need to move my arm: it was already at the goal, so MoveIt had nothing to plan or execute "
            f"and ended the goal as a success ({verbatim(met)} at {hms(met.t)}).")
    return found.model_copy(update={"text": text, "evidence": [Evidence.of_log("manipulation.nominal", met),
                                                               *found.evidence]})


def _plan_only(found: Explanation, lines: list[LogLine]) -> Explanation:
    """A goal that asked MoveIt for a plan alone (RViz's "Plan", MoveGroupInterface::plan()): MoveIt computed it, and
    no line of the window shows an execution; told as a plan made, never as a motion."""
    entries = [(ln, catalogue().match(ln.msg)) for ln in lines]
    planned = next((ln for ln, e in entries if e is not None and e.id in PLANNED), None)
    ran = any(e is not None and "execut" in e.id and e.id != NOT_RUN for _, e in entries)
    if planned is None or ran:
        return found
    text = (f"I planned a motion for my arm and did not move it: the request asked MoveIt for a plan only, and it "
            f"computed one ({verbatim(planned)} at {hms(planned.t)}); no line of my log shows the plan executed.")
    return found.model_copy(update={"text": text, "evidence": [Evidence.of_log("manipulation.nominal", planned),
                                                               *found.evidence]})


def _passed_on(found: Explanation, lines: list[LogLine]) -> Explanation:
    """A start state in collision that MoveIt passed on to its planner anyway ("Passing the original planning request
    to the planner"), in the window's `lines`, with no later line that says how planning went: told as that, never as
    a planning that could not begin (the planner may still find a path)."""
    at = next((i for i in range(len(lines) - 1, -1, -1) if (e := catalogue().match(lines[i].msg)) is not None
               and e.id == PASSED_ON), None)
    if at is None or any((e := catalogue().match(ln.msg)) is not None and e.kind in ENDS for ln in lines[at + 1:]):
        return found
    line = lines[at]
    text = (f"The recording ends before my arm's motion finished. On the way, MoveIt found my start state in "
            f"collision and passed the request on to its planner anyway ({verbatim(line)} at {hms(line.t)}); no later "
            "line says how planning went, so my logs do not show whether it failed.")
    # the cause stays the one the line shows (a start state in collision), with the low confidence of an unfinished
    # story: the words claim no failure
    return found.model_copy(update={"text": text, "confidence": 0.3, "fix": None})
