"""The navigation (Nav2) component explainer: log filter, situation detectors, template or LLM phrasing.

Every line is read through the Nav2 message catalogue (nav2_catalogue.json), by its text, whatever its logger.
A task whose failed step is not a navigation (a `say` after the trip) has its trips told each in its own window,
with its own /task_info outcome, never the other step's window.
Causes, each with its evidence from the recording (a cause is claimed only when lines or motion support it):
- navigation.joystick: `/joy_priority` True while the goal did not complete (plus the relay's toggle line).
- navigation.charging: `/power/is_charging` True while the goal did not complete.
- a goal that did not succeed, first cause with strong lines in diagnose.ORDER, then weak ones (a ranked chain:
  a node that never came up before the goal explains everything after it):
  bringup_failure (a params file rcl could not parse, a process that died: hexar.explainers.stack's
  bringup_findings, over the whole recording up to the goal's end), configuration_error (plugins, BT XML,
  parameters, a lifecycle transition that failed), transform_error (TF, clocks; also tf2/tf_help/message-filter
  lines of the mined stack catalogue; tf2_ros's routine INFO drops only on a goal that failed or stalled, or in
  numbers: filter.routine_drops), poor_localisation (AMCL covariance run, AMCL's own warnings), off_costmap
  (the robot's start off the map), start_in_obstacle (the start on occupied cells, a keepout zone's "Pose is in
  keepout zone", or a spin that could not turn where the planner never planned: keepout.py), goal_unreachable
  (goal outside the map or in lethal cost), docking_failure, blocked_path (DWB's obstacle critic before the
  controller gave up, or a planner that had a path to this goal and lost it even after clearing its maps, unless the
  keepout filter's first mask had just come: then the zones, told as such), collision_ahead (RPP's
  lookahead, the collision monitor, a behaviour's checker - but not a behaviour's "Collision Ahead" during the
  recoveries after no progress), controller_failure, commands_not_reaching_base (/cmd_vel commanding while
  /odom is still; never from logs alone).
- symptoms are never the cause: a planner that never found a path (unexplained_failure naming the candidates and
  what tells them apart), `Failed to make progress` alone (navigation.no_progress: the checks a person can make),
  AMCL asking for an initial pose, the collision monitor stopping for a source without data (wording.SYMPTOMS).
  Either quotes the decisive unknown ERROR/FATAL line with its node and time when there is one (chain.py). A planner
  that found no path is checked on the recorded global costmap or map when there is one (grids.py): the goal off the
  grid or on an obstacle, the robot's own position on one, or no free way between them is claimed from the grid.
- a recording with no goal line, no /task_info and no error: a background layer's warning alone (costmap, TF, AMCL)
  is quoted, never read as a cause (chain.only_warned); a transform wait that bring-up got past is no cause
  (chain.unresolved).
- navigation.poor_localisation: mean(cov[0], cov[7]) or cov[35] above 0.2 for more than 5 consecutive
  `/amcl_pose` samples, or AMCL warnings.
- navigation.collision_ahead on a goal reached late: the collision monitor held the robot.
- a waypoint reached whose waypoint follower's task then failed is that task (waypoints.py); a Nav2 server started
  but never configured is the node that never came up when no goal reached the navigator (unmanaged.py).
- a goal reached, then an abort of a server no reading here covers (SimpleActionServer's "Aborting handle"), or a
  step /task_info reports failed: told in that server's words, or as both records (afterwards.py), never "without
  any problem".
- navigation.moving_obstacles: the goal was reached after at least two transient obstacle events of the
  controller (trajectories hitting obstacles, a collision check stopping it; warnings up to a second apart are
  one event); one event, planner retries and recoveries alone are a slow run whose logs do not show what was in
  the way (reached.slow_retries).
- navigation.nominal_speed: a clean successful run asked about speed or time: configured limit (from
  `/diagnostics`, key `max_vel_x`), distance travelled and average speed from `/amcl_pose`.
- navigation.nominal: a clean successful run asked anything else: a truthful "it went fine" with figures.
- navigation.unexplained_failure: the goal failed and no detector explains it (low confidence).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar

from hexar.events import contract as c
from hexar.events.log import View
from hexar.events.records import WARN, LogLine
from hexar.explainers.base import Context, Evidence, Explanation, TextModel
from hexar.explainers.navigation import (
    afterwards,
    behaviors,
    chain,
    docking,
    goal_sent,
    grids,
    held,
    keepout,
    mapsave,
    nomap,
    reached,
    smoother,
    states,
    waypoints,
)
from hexar.explainers.navigation import detectors as d
from hexar.explainers.navigation import diagnose as g
from hexar.explainers.navigation.answers import answer as _template
from hexar.explainers.navigation.answers import unfinished, unread
from hexar.explainers.navigation.critics import rejected_by
from hexar.explainers.navigation.filter import routine_drops, tag_logs, weak_noise
from hexar.explainers.navigation.focus import inferred, place_of, skill_state, status_evidence
from hexar.explainers.navigation.unmanaged import unmanaged
from hexar.explainers.phrasing import phrase
from hexar.explainers.recorded import NAV_SKILLS
from hexar.explainers.shutdown import before_shutdown
from hexar.explainers.sim_time import with_sim_time

if TYPE_CHECKING:
    from hexar.explainers.registry import Registry

MAX_FACT_LINES = 60


class NavigationExplainer:
    """Explains what the Nav2 navigation stack did during the task's window."""

    name: ClassVar[str] = "navigation"
    topics: ClassVar[frozenset[str]] = frozenset({c.ROSOUT, c.AMCL_POSE, c.JOY_PRIORITY, c.IS_CHARGING,
                                                  c.DIAGNOSTICS, c.CMD_VEL, c.ODOM, c.MAP, c.GLOBAL_COSTMAP,
                                                  c.KEEPOUT_MASK})
    description: ClassVar[str] = (
        "Explains the robot's movement between places (Nav2 navigation): why it could not reach a location "
        "(path blocked by an obstacle, joystick/manual mode holding the base, plugged into the charger, "
        "lost or badly localised on its map), why a trip was slow or took a detour (people or objects moving "
        "in the way, replanning, recovery manoeuvres, poor localisation), and how fast it moved, how far it "
        "went and what its speed limit is. Use it for questions about driving, moving, getting somewhere, "
        "speed, or time spent travelling."
    )

    def __init__(self, model: TextModel | None = None, registry: Registry | None = None) -> None:
        self.model = model
        self.registry = registry

    def explain(self, question: str, context: Context) -> Explanation:
        task = context.task
        trips = [r for r in task.skills if r.skill in NAV_SKILLS and r.state in {"succeeded", "failed"}]
        failed = task.failed_skill
        own = failed is not None and failed.skill not in NAV_SKILLS
        if ((failed is None and len(trips) > 1) or (own and trips)) and context.window == task.window():
            # Several trips in one task, or trips before another step failed (the task's window is then that
            # step's, after the trips): explain each trip in its own window, with its own /task_info outcome,
            # and answer with the first one that was not a plain, problem-free drive.
            parts = [self._explain(question, context.with_window(task.skill_window(r))) for r in trips]
            found = next((p for p in parts if not set(p.causes) <= {d.NOMINAL, d.NOMINAL_SPEED}), parts[0])
        else:
            found = self._explain(question, context)
        return with_sim_time(found, context.log, context.window[1])

    def _explain(self, question: str, context: Context) -> Explanation:
        view = context.view(self.topics)
        window = view.window or (context.log.start, context.log.end)
        raw = before_shutdown(view.logs())
        poses = view.poses()
        if not raw and not poses:
            return Explanation.not_enough(
                self.name, "The recording has no log lines and no localisation data for that time.")
        tagged = tag_logs(raw)
        lines = [ln for ln, _ in tagged]
        state = skill_state(context)
        noise = routine_drops(weak_noise(raw), d.summarise(tagged, poses, state))
        run = d.summarise(tagged, poses, state, noise + chain.stack_notes(tagged, raw))
        flags = [f for f in (d.joystick(view, window, run, context.log.logs), d.charging(view, window, run))
                 if f is not None]
        # Lines of the stack under Nav2 (tf2's drops on a failed goal, a rejected parameter) are navigation evidence
        # too, for a goal the recording shows (not one inferred from an error line alone); and a step that
        # /task_info reports succeeded with no node warning in its window is a normal trip.
        stack = bool(run.notes) and not (inferred(context) and state == "failed")
        quiet_success = state == "succeeded" and not any(ln.level >= WARN for ln in raw)
        findings: list[d.Finding] = []
        if not lines and not poses and not flags and not stack and not quiet_success:
            # A node that never came up explains every later failure, read first; else an error none of the
            # catalogues knows is still the log's own words on what went wrong: quoted with its node and time,
            # never "nothing I read" while it is there (issue 20).
            came_up = chain.bringup(context.log.logs, None)
            if came_up is None and inferred(context):
                run.outcome = "unknown"  # a goal inferred from this error alone: no goal is shown, none failed
            # no navigation line at all: a map saver that got no map is what went wrong (a SLAM session's save)
            unsaved = None if came_up else mapsave.map_not_saved(raw)
            quoted = came_up or unsaved or chain.with_last_error(d.Finding(d.UNEXPLAINED), raw, run)
            if not quoted.notes:
                return Explanation.not_enough(self.name, unread(raw))
            findings = [quoted]
        until = run.end.t if run.end is not None else window[1]
        before = before_shutdown([ln for ln in context.log.logs if ln.t <= until])
        findings = findings or flags + self._others(question, view, run, bool(flags), before, raw,
                                                    inferred(context))
        if run.outcome == "reached" and findings and all(f.cause in {d.NOMINAL, d.NOMINAL_SPEED} for f in findings):
            # a goal reached is not a task done: a server with no reading here that failed after it, or a task
            # record that says the step failed, is told instead of "without any problem"
            where = place_of(context, lines)
            later = afterwards.aborted(run, before_shutdown(context.log.logs), where)
            if later is None and state == "failed":
                later = afterwards.task_disagrees(run, where, status_evidence(context, d.UNEXPLAINED))
            findings = [later] if later is not None else findings
        for f in findings:
            if f.cause == d.UNEXPLAINED and not f.evidence:
                f.evidence += status_evidence(context, d.UNEXPLAINED)
        if run.outcome == "unknown" and all(f.cause in {d.NOMINAL, d.NOMINAL_SPEED} for f in findings):
            # neither a navigator line nor the skill's status says how the trip ended: "I reached it" would be a
            # claim without evidence; a stack whose nodes ran without a warning is told as just that
            quiet = chain.ran_quietly(raw, [ln for ln in context.log.logs if ln.t < window[0]])
            if quiet is None:
                return Explanation.not_enough(self.name, "The recording does not show whether I reached the goal."
                                              + chain.last_warning(raw))
            return Explanation(explainer=self.name, text=quiet[0], causes=[d.NOMINAL], confidence=0.6,
                               evidence=[Evidence.of_log(d.NOMINAL, ln) for ln in quiet[1]])
        grounded = self._compose(question, context, run, findings, lines)
        if grounded.causes == [g.CONTROLLER] and (critics := rejected_by(raw)):
            # which critic stopped every trajectory says why no command could be computed (read from every line of
            # the window: DWB's summary lines carry no logger's role of navigation's)
            grounded = grounded.model_copy(update={"text": f"{grounded.text} {critics}"})
        return phrase(self.model, "navigation", question, self._facts(lines, grounded), grounded)

    def _others(self, question: str, view: View, run: d.Run, flagged: bool, before: list[LogLine],
                raw: list[LogLine], inferred: bool = False) -> list[d.Finding]:
        if flagged:
            return []
        # a spin, backup, ... that a program asked for (not a goal's recovery); the goal as it was sent
        told = behaviors.explained(behaviors.last_run(raw), raw, held.stall(view, run)) \
            if behaviors.standalone(raw) else goal_sent.framed(raw) if run.outcome != "reached" else None
        if told is not None:
            return [told]
        dock = docking.docking(raw)
        docked = docking.dock_failed(dock, raw)  # a docking that failed after (or without) the trip to its staging pose
        if docked is not None:
            return [docked]
        unsmoothed = smoother.no_time(raw) if run.outcome != "reached" else None
        if unsmoothed is not None:
            return [unsmoothed]
        if run.outcome != "reached":
            found = self._failure(view, run, before)
            if found is not None:
                found = held.speed_filtered(docking.staging(found, dock, raw), before)
            if found is not None and inferred and run.outcome == "unknown":
                # no goal, no end, no error: warnings alone do not show that anything failed (many a healthy robot
                # prints them), so they are quoted, not read as a cause
                found = chain.only_warned(found, run) or found
            if found is not None:
                return [chain.with_last_error(found, raw, run)]
        else:
            problem = waypoints.tasks_failed(raw) or reached.reached_without_pose(run) or d.poor_localisation(run) \
                or held.by_collision_monitor(run) or d.moving_obstacles(run) or reached.slow_retries(run)
            if problem is not None:
                return [problem]
        if run.outcome == "failed":
            # nothing else explains it: a costmap that refused its map's publisher, a goal sent before the stack was up
            refused = mapsave.costmap_refused_map(before) or goal_sent.rejected(raw)
            if refused is not None:
                return [refused]
            found = d.Finding(d.UNEXPLAINED, [Evidence.of_log(d.UNEXPLAINED, run.end)] if run.end else [])
            return [chain.with_last_error(found, raw, run)]
        if run.outcome == "unknown":
            # no goal end and no task status: an error line is still worth quoting rather than "I can't tell"
            found = chain.with_last_error(d.Finding(d.UNEXPLAINED), raw, run)
            if found.notes:
                return [found]
        cause = d.NOMINAL_SPEED if d.asks_about_speed(question) else d.NOMINAL
        figures = d.speed(run, view.statuses(c.DIAGNOSTICS), cause)
        return [held.slowed(run, figures) if cause == d.NOMINAL_SPEED else figures]

    @staticmethod
    def _failure(view: View, run: d.Run, before: list[LogLine]) -> d.Finding | None:
        """The first cause, in diagnose.ORDER, that the window's lines (or its motion, or a node that never came up
        before the goal ended) support: strong lines first, then weak ones. Symptoms are never the cause: a
        planner that found no path names its candidates, `Failed to make progress` alone is no_progress, and a
        behaviour's "Collision Ahead" after the controller had already stopped making progress is a recovery's
        trouble, not the reason the goal failed."""
        progress = run.first(d.PROGRESS)
        for strength in ("strong", "weak"):
            for cause in g.ORDER:
                found: d.Finding | None = None
                if cause == g.BRINGUP:
                    specific = chain.config_specific((n.line, n.entry) for n in run.notes)
                    found = chain.bringup(before, None) if strength == "strong" and not specific else None
                    if found is None and strength == "strong" and run.begin is None:
                        found = unmanaged(before)  # no goal reached the navigator, and a server never came up
                elif cause == g.COLLISION_AHEAD:
                    planned = next(iter(d.plan_failures(run)), None)
                    lines = [ln for ln in g.supporting(run.notes, cause, strength) if (progress is None
                             or ln.t <= progress.t or not ln.msg.startswith("Collision Ahead - Exiting"))
                             and not (planned is not None and ln.t > planned.t and held.SLOWED.match(ln.msg))]
                    found = d.Finding(cause, g.evidence(cause, lines)) if lines else None
                elif cause == g.POOR_LOCALISATION:
                    found = d.poor_localisation(run) if strength == "strong" else None
                elif cause == g.BLOCKED:
                    # a keepout mask that arrived between the plan and its failures is no obstacle in the way
                    found = (keepout.mask_closed_way(view, run, before) if strength == "strong" else None) \
                        or d.blocked_path(run, strength)
                elif cause == g.NOT_REACHING_BASE:
                    found = held.stall(view, run) if strength == "strong" else None
                else:
                    lines = g.supporting(run.notes, cause, strength)
                    if cause == g.TRANSFORM:
                        lines = d.after_planner_gave_up(run, chain.unresolved(lines, before))
                        lines = nomap.without_map_timeouts(lines, before)
                    elif cause == g.CONTROLLER:
                        lines = d.after_planner_gave_up(run, lines)
                    lines = states.claimable(run.notes, cause, lines, before)
                    if lines:
                        found = d.Finding(cause, g.evidence(cause, lines))
                    elif cause == g.START_IN_OBSTACLE and strength == "strong":
                        found = keepout.spin_blocked_start(run)
                if found is not None and found.cause == g.OFF_COSTMAP:
                    found = nomap.no_map_finding(found, before)
                if found is not None:
                    notes = ((n.line, n.entry) for n in run.notes)
                    if found.cause == g.CONFIGURATION and chain.never_came_up(notes, before):
                        found.facts[chain.NEVER_CAME_UP] = 1.0
                    for line in (run.first(d.PROGRESS), run.end if run.outcome == "failed" else None):
                        if line is not None and all(e.t != line.t for e in found.evidence):
                            found.evidence.append(Evidence.of_log(cause, line))
                    return found
        said = states.reported(run.notes)
        if said and said[0][1] is states.START and (
                mapped := grids.read_grids(view, run, said[0][0])) is not None and mapped.cause == g.START_IN_OBSTACLE:
            return _ended(mapped, run)  # the costmap the planner used shows the obstacle under the robot
        if said:
            # a state of the costmap or planner with no line that supports one of its causes: told as what it is
            found = d.Finding(d.UNEXPLAINED, [Evidence.of_log(d.UNEXPLAINED, ln) for ln, _ in said[:2]])
            found.facts = {states.FACT + said[0][1].key: float(len(said))}
            if said[0][1] is states.OUTSIDE and (by := states.outside_by(before)):
                found.notes.append(by)  # where I was against where the costmap lies, as the costmap logged it
            if run.end is not None and run.outcome == "failed":
                found.evidence.append(Evidence.of_log(d.UNEXPLAINED, run.end))
            return found
        plans = d.plan_failures(run)
        # a recorded keepout mask with the goal (or the robot) in a zone, else the recorded costmap and map
        mapped = (keepout.in_zone(view, run, plans[0]) or grids.read_grids(view, run, plans[0])) if plans else None
        if mapped is not None and grids.FREE_WAY not in mapped.facts:
            return _ended(mapped, run)  # the recorded grids say which of the candidates it was
        if plans:
            found = d.Finding(d.UNEXPLAINED, [Evidence.of_log(d.UNEXPLAINED, ln) for ln in plans[:2]])
            found.facts = {"plan_failures": float(d.attempts(plans))}
            if mapped is not None:
                found.facts.update(mapped.facts)
                found.notes += mapped.notes
                found.evidence += mapped.evidence
            if run.end is not None and run.outcome == "failed":
                found.evidence.append(Evidence.of_log(d.UNEXPLAINED, run.end))
            return found
        stuck = run.matching(("Failed to make progress",))
        if stuck:
            found = d.Finding(g.NO_PROGRESS, [Evidence.of_log(g.NO_PROGRESS, stuck[0])])
            if run.end is not None and run.outcome == "failed":
                found.evidence.append(Evidence.of_log(g.NO_PROGRESS, run.end))
            found.facts = {"progress_failures": float(len(stuck))}
            return found
        return None

    def _compose(self, question: str, context: Context, run: d.Run, findings: list[d.Finding],
                 lines: list[LogLine]) -> Explanation:
        place = place_of(context, lines)
        texts: list[str] = []
        fixes: list[str] = []
        details: list[str] = []
        for f in findings:
            text, fix, more = _template(f, place, run)
            texts.append(unfinished(text, place, skill_state(context) == "canceled") if run.outcome == "unknown"
                         else text)
            if fix:
                fixes.append(fix)
            details += more
        return Explanation(
            explainer=self.name,
            text=" ".join(texts[:2]),
            causes=[cause for f in findings for cause, _ in chain.with_bringup(f)],
            evidence=[e for f in findings for _, ev in chain.with_bringup(f) for e in ev],
            fix=" ".join(fixes) or None,
            details=details,
            confidence={d.UNEXPLAINED: 0.4, g.NO_PROGRESS: 0.5}.get(findings[0].cause, 0.9) if findings else 0.9,
        )

    @staticmethod
    def _facts(lines: list[LogLine], grounded: Explanation) -> str:
        shown = lines[-MAX_FACT_LINES:]
        out = ["Findings (the only causes you may state):"]
        out += [f"- {cause}" for cause in grounded.causes]
        out += [f"- {detail}" for detail in grounded.details]
        out.append(f"Template answer: {grounded.text}")
        if grounded.fix:
            out.append(f"Suggested fix: {grounded.fix}")
        out.append("Filtered navigation log (oldest first):")
        out += [line.render() for line in shown]
        return "\n".join(out)


def _ended(found: d.Finding, run: d.Run) -> d.Finding:
    """`found` with the line that ended a failed goal as evidence too."""
    if run.end is not None and run.outcome == "failed" and all(e.t != run.end.t for e in found.evidence):
        found.evidence.append(Evidence.of_log(found.cause, run.end))
    return found
