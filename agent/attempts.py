""""Did you try again?", "how many times did you try?": what the robot did to get a step done before it gave up (or
got through), counted from what its modules logged while the step ran, never guessed.

What counts as another try, from the real log strings (../shared/reference/nav2_log_messages.md, the MoveIt
catalogue):
- a step of the plan started again (its /task_info history goes back to running);
- Nav2 planning a path again: planner_server's "Planning algorithm %s failed to generate a valid path to ..."
  (planner_server.cpp:348; NavFn's "%s: failed to create plan with tolerance %.2f." on the same attempt) and the
  Jazzy "%s plugin failed to plan from ...";
- a Nav2 recovery: behavior_server's "Running %s" ("Attempting %s" up to Galactic), a costmap's "Received request to
  clear entirely the ...";
- a MoveIt planning request: move_group's "Planning request received for MoveGroup action..." or "Combined planning
  and execution request received for MoveGroup action...", else one per "Unable to solve the planning problem";
- a path found invalid on the way, which the behaviour tree plans anew: "Path validation failed. Invalid pose indices:
  [...]" (nav2_behavior_tree validate_path_action.cpp:74, lyrical and main), and MPPI restarting its optimisation,
  "Soft reset triggered by trajectory validator" (nav2_mppi_controller optimizer.cpp:249, lyrical and main).
"""

from __future__ import annotations

import re
from collections import Counter
from dataclasses import dataclass

from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.events.records import LogLine, hms
from hexar.events.tasks import SkillRun, Task
from hexar.explainers.base import Evidence, Explanation
from hexar.explainers.navigation.behaviors import BEGIN
from hexar.explainers.recorded import join_words, step_ref

# Asked from the start of the question: "why did you give up so quickly?" asks for a cause, not a count of tries.
TRIED = re.compile(
    r"^(and |so |but |ok |okay )?(did|have|had) you (even |ever )?(try|tried|retry|retried|attempt(ed)?)"
    r"( it| that| this)?( again| once more| twice| a second time| more than once| another time| something else|"
    r" anything else| another way| to go around( it| them| that)?)?\W*$|"
    r"^(and |so |but |ok |okay )?how (many|often|many times) (times )?(did|have) (you|it|the robot|nav2|the planner|"
    r"moveit|[a-z_/]+) (try|tried|retry|retried|attempt(ed)?|re-?plann?(ed)?|recover(ed)?)\b|"
    r"^(and |so |but |ok |okay )?how many ([a-z]+ )?(attempts|tries|retries|re-?plans|recoveries|recovery cycles)\b|"
    r"^(and |so |but |ok |okay )?did you (just )?give up\W*$|"
    # "did any recovery behaviors run?", "which recoveries ran?"
    r"^(and |so |but )?(did|were) (any|there any|the|my|your) (nav2 )?(recover(y|ies)|recovery behaviou?rs?)"
    r"( (run|ran|triggered|executed|used|tried))?\b|"
    r"^(and |so )?(which|what) (recover(y|ies)|recovery behaviou?rs?) (ran|run|were (run|tried|triggered|executed))\b|"
    # "did the BT try any recovery behaviors after the follow_path abort?"
    r"^(and |so |but )?did (the bt|the behaviou?r tree|it|you|nav2|the robot|the navigator|bt_navigator) (try|run|"
    r"attempt|use|trigger|start) (any |a |the )?(recover(y|ies)|recovery behaviou?rs?)\b|"
    r"^(and |so |but |ok |okay )?why did (you|it|the planner|nav2) (re-?plan|replanned|re-?route)\b|"
    r"^(and |so |but |ok |okay )?(could(n't| not)? you (not )?|why (didn't|did not|couldn't|could not) you |can't you )"
    r"(just )?(go|drive|get|find a way) (a)?round (it|them|that|the obstacle)\b")
_REPLAN = (re.compile(r"^Planning algorithm \S+ failed to generate a valid path"),
           # "…: failed to create plan with tolerance …." and "…: failed to create plan, …." (nav2_navfn_planner,
           # nav2_smac_planner/src/smac_planner_2d.cpp:270@humble): one line per failed attempt
           re.compile(r": failed to create plan( with tolerance|, )"),
           # "GridBasedplugin failed to plan from" as a Jazzy robot logged it (the format has no space)
           re.compile(r"^\S+?\s?plugin failed to plan (from|calculation to|through)"))
_CLEAR = re.compile(r"^Received request to clear entirely the (?P<which>\w+)")
_INVALID = re.compile(r"^Path validation failed\. Invalid pose indices")
_SOFT_RESET = re.compile(r"^Soft reset triggered by trajectory validator")
_MOVEIT_REQUEST = re.compile(r"^(Combined planning and execution|Planning) request received for MoveGroup action")
_MOVEIT_FAILED = re.compile(r"(?:^|\]:? )Unable to solve the planning problem")
# any other node's own words for trying again, as a lifecycle manager, a driver or a spawner log them ("retrying in
# 1 s", "failed twice; giving up", "attempt 3 of 5"; MoveIt's "Planning attempt 1 of at most 1" is the first): quoted
# as they are, never counted as a kind of try above
_RETRIED = re.compile(r"\bretry(ing)?\b|\bretried\b|\b(trying|try) again\b|\battempt #?([2-9]|\d\d+)\b|"
                      r"\b(2nd|3rd|\d+th|second|third) attempt\b|\b(giving|gave) up\b|\bfailed (twice|\d+ times)\b|"
                      r"\bafter \d+ (attempts|tries|retries)\b",
                      re.I)
_RECOVERY_WORDS = {"spin": ("a spin", "spins"), "backup": ("a backup", "backups"), "back_up": ("a backup", "backups"),
                   "wait": ("a wait", "waits"), "drive_on_heading": ("a drive ahead", "drives ahead"),
                   "assisted_teleop": ("an assisted teleop", "assisted teleops")}


def _times(n: int) -> str:
    return {1: "once", 2: "twice"}.get(n, f"{n} times")


def _recoveries(names: list[str]) -> str:
    parts = []
    for name, k in Counter(names).items():
        one, many = _RECOVERY_WORDS.get(name, (f"a {name.replace('_', ' ')}", f"{name.replace('_', ' ')}s"))
        parts.append(one if k == 1 else f"{k} {many}")
    return f"{len(names)} recover{'y' if len(names) == 1 else 'ies'} ({join_words(parts)})"


@dataclass(frozen=True)
class _Tries:
    run: SkillRun
    said: list[str]  # each kind of try, as the robot says it
    lines: list[LogLine]


def _tags(line: LogLine) -> list[str]:
    """What kind of try a log line tells, read once: "replan<i>" per planner pattern it matches, "clear",
    "moveit" (a planning request), "moveit_failed", or "recovery:<name>"."""
    msg = line.msg.strip()
    tags = [f"replan{i}" for i, p in enumerate(_REPLAN) if p.search(msg)]
    if _CLEAR.match(msg):
        tags.append("clear")
    if _INVALID.match(msg):
        tags.append("invalid")
    if _SOFT_RESET.match(msg):
        tags.append("soft_reset")
    if _MOVEIT_REQUEST.match(msg):
        tags.append("moveit")
    if _MOVEIT_FAILED.search(line.msg):
        tags.append("moveit_failed")
    if _recovering(line) and (m := BEGIN.match(msg)):
        tags.append(f"recovery:{m['name']}")
    if not tags and _RETRIED.search(msg):
        tags.append("retried")
    return tags


def _tries(log: EventLog, task: Task, run: SkillRun) -> _Tries:
    start, end = task.skill_window(run)
    if run.state == "running" and log.logs:
        end = max(end, log.logs[-1].t)  # still under way: every line since it started
    tagged = [(ln, tags) for ln in log.logs if start <= ln.t <= end and (tags := _tags(ln))]
    counts = Counter(tag for _, tags in tagged for tag in tags)
    starts = sum(1 for h in run.history if h.status.strip().lower() == "running")
    # one failed attempt may be logged by more than one of the patterns: the most any of them counts
    replans = max(counts[f"replan{i}"] for i in range(len(_REPLAN)))
    recoveries = [tag.removeprefix("recovery:") for _, tags in tagged for tag in tags if tag.startswith("recovery:")]
    moveit = counts["moveit"] or counts["moveit_failed"]
    said: list[str] = []
    if starts > 1:
        said.append(f"I started it {_times(starts)}")
    if replans:
        said.append(f"my planner failed to find a path {_times(replans)}")
    if recoveries:
        said.append(f"I ran {_recoveries(recoveries)}")
    if counts["clear"]:
        said.append(f"I cleared my costmaps {_times(counts['clear'])}")
    if counts["invalid"]:
        said.append(f"my path was found to cross an obstacle in my costmap {_times(counts['invalid'])}, so I "
                    "planned a new one")
    if counts["soft_reset"]:
        said.append(f"my controller started its trajectory optimisation over {_times(counts['soft_reset'])}")
    if moveit > 1:
        said.append(f"I asked my motion planner for a plan {_times(moveit)}")
    retried = [ln for ln, tags in tagged if "retried" in tags]
    if retried:
        quoted = "; ".join(f"{hms(ln.t)}, {ln.name or 'a node'}: \"{' '.join(ln.msg.split())[:140]}\""
                           for ln in retried[:3])
        said.append(f"my log tells of trying again ({quoted})")
    # a failed MoveIt plan is told by its request's line, not shown twice
    shown = [ln for ln, tags in tagged if tags != ["moveit_failed"]]
    return _Tries(run, said, shown)


def _recovering(line: LogLine) -> bool:
    return line.name.endswith(("behavior_server", "recoveries_server"))


def _evidence(tries: list[_Tries], task: Task) -> list[Evidence]:
    out = [Evidence(cause="planner.plan_ok", topic=c.TASK_INFO, t=h.t,
                    item=f"step {t.run.index + 1}: {t.run.label()} {h.status.strip().lower()}")
           for t in tries for h in t.run.history if h.status.strip().lower() in {"running", "failed", "succeeded"}]
    out += [Evidence(cause="planner.plan_ok", topic=ln.origin, t=ln.t, item=ln.render())
            for t in tries for ln in t.lines[:6]]
    return out or [Evidence(cause="planner.plan_ok", topic=c.TASK_INFO, t=task.created, item=task.instruction)]


def tried(question: str, log: EventLog, task: Task) -> Explanation:
    """For a failed task, the tries at the step that failed; otherwise every step that needed more than one."""
    yes_no = re.match(r"^(and |so |but )?(did|have|had) you\b", " ".join(question.lower().split())) is not None
    started = [r for r in task.skills if r.time_of("running") is not None]
    failed = task.failed_skill
    runs = [failed] if failed is not None else started
    tries = [_tries(log, task, run) for run in runs]
    retried = [t for t in tries if t.said]
    if not started:
        text = "none of my plan's steps started, so there was nothing to try again."
        lead = "No: " if yes_no else ""
    elif retried:
        parts = []
        for t in retried:
            ending = ("but none of it got it done, so the step failed" if t.run.state == "failed" else
                      "and the step went through in the end" if t.run.state == "succeeded" else
                      "and the step was still going when the recording ends")
            parts.append(f"for {step_ref(t.run)}, {join_words(t.said)}, {ending}")
        text = "; ".join(parts) + "."
        lead = "Yes. "
    elif failed is not None:
        text = f"my recording shows one try at {step_ref(failed)}: it failed, and I did not start it again after that."
        lead = "No. "
    elif all(r.state != "running" for r in started):
        text = "every step of my plan that started went through at the first try."
        lead = "I didn't need to: "
    else:
        going = [r for r in started if r.state == "running"][-1]
        text = (f"my recording shows no second try at any step: {step_ref(going)} was still going when the "
                "recording ends.")
        lead = "No. "
    if re.search(r"\brecover", question.lower()) and not any(
            said.startswith(("I ran ", "I cleared ")) for t in tries for said in t.said):
        # asked about recoveries alone: that none ran is the answer, before the tries
        text = ("no recovery shows in my log: my behavior server never logged running one (spin, backup, wait) "
                "and no costmap was cleared; " + text[0].lower() + text[1:])
        lead = ""
    if not yes_no and lead in {"Yes. ", "No. "}:
        lead = ""
    said = lead + (text[0].upper() + text[1:] if lead.endswith(". ") else text)
    return Explanation(explainer="planner", text=said[0].upper() + said[1:], causes=["planner.plan_ok"],
                       evidence=_evidence(retried or tries, task))
