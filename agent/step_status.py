""""Did the place step finish cleanly?", "how did step 2 go?": one step of the plan, named by what it does or by its
number, told by how it ended and what the log holds while it ran and after it (an error "hidden in the last
lines")."""

from __future__ import annotations

import re

from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.events.records import WARN, LogLine, duration, hms
from hexar.events.tasks import SkillRun, Task
from hexar.explainers.base import Evidence, Explanation
from hexar.explainers.recorded import NAV_SKILLS, step_ref
from hexar.explainers.shutdown import before_shutdown

# how it went, not why it failed ("why did the pick step fail?" is the failure's own question)
_ASKED = re.compile(
    r"\b(did|has|had) (the |that |your |my )?(?P<word>[a-z_]+) (step|skill)( (actually|really|ever))? (finish|succeed|"
    r"complete|work|go through|run|end|fail)|"
    r"\b(was|is) (the |that |your |my )?(?P<word2>[a-z_]+) (step|skill) (ok|okay|fine|clean|successful|a success|done|"
    r"finished|complete)\b|"
    r"\bhow did (the |that |your |my )?(?P<word3>[a-z_]+) (step|skill) go\b|"
    r"\b(did|has|had) step (?P<n>\d+)( (actually|really|ever))? (finish|succeed|complete|work|go through|run|end|fail)|"
    r"\bhow did step (?P<n2>\d+) go\b")
# the words people use for a skill of the plan
_SAID = {"drive": NAV_SKILLS, "driving": NAV_SKILLS, "navigation": NAV_SKILLS, "nav": NAV_SKILLS, "move": NAV_SKILLS,
         "speech": ("say",), "speak": ("say",), "help": ("ask_human_for_help",), "arm": ("move_arm",),
         "trajectory": ("follow_joint_trajectory",), "grasp": ("pick",),
         "gripper": ("command_gripper",), "bringup": ("bring_up_controllers",),
         "start": ("bring_up_controllers",)}
MAX_QUOTED = 3


def step_asked(q: str) -> bool:
    """The question (lower case) asks how one named step of the plan went (not why it failed)."""
    return _ASKED.search(q) is not None and re.match(r"(and |so |but )?(why|how come)\b", q) is None


def _runs(q: str, task: Task) -> list[SkillRun]:
    m = _ASKED.search(q)
    if m is None:
        return []
    n = m.group("n") or m.group("n2")
    if n is not None:
        return [r for r in task.skills if r.index + 1 == int(n)]
    word = m.group("word") or m.group("word2") or m.group("word3") or ""
    skills = _SAID.get(word, ())
    return [r for r in task.skills if r.skill in skills or word in r.skill.split("_") or word == r.skill]


def _quoted(lines: list[LogLine]) -> str:
    return "; ".join(f"at {hms(ln.t)}, {ln.name or 'a node'} ({ln.level_name}) "
                     f"\"{' '.join(ln.msg.split())[:160]}\"" for ln in lines[:MAX_QUOTED])


def step_status(question: str, log: EventLog, task: Task) -> Explanation:
    q = " ".join(question.lower().split())
    runs = _runs(q, task)
    if not runs:
        steps = "; ".join(step_ref(r) for r in task.skills) or "none"
        text = f"No step of my plan for this task is the one you name. Its steps were: {steps}."
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], enough_information=False)
    run = runs[-1]
    start, end = task.skill_window(run)
    state = run.state
    if state == "running":
        told = f"{step_ref(run)} had not ended when the recording ends, {duration(log.end - start)} after it began"
    elif run.time_of("running") is None and state in {"waiting", ""}:
        told = f"{step_ref(run)} never started"
    else:
        ended = {"succeeded": "finished without error", "failed": "failed"}.get(state, state)
        told = f"{step_ref(run)} {ended} at {hms(end)} UTC, {duration(end - start)} after it began"
        if state == "failed" and run.error_msg:
            told += f" ({run.error_msg})"
    during = [ln for ln in log.logs if start <= ln.t <= end and ln.level >= WARN]
    # what a stack prints as it is stopped (a traceback at Ctrl-C) is no error of the step
    up = {id(ln) for ln in before_shutdown(log.logs)}
    after = [ln for ln in log.logs if ln.t > end and ln.level > WARN and id(ln) in up] if state != "running" else []
    text = told[0].upper() + told[1:] + "."
    text += (f" While it ran, my log holds {len(during)} warning or error line{'s' if len(during) > 1 else ''}: "
             f"{_quoted(during)}." if during else " My log holds no warning or error while it ran.")
    if state != "running":
        text += (f" After it, up to the recording's end (or the stack's shutdown), my log holds {len(after)} error "
                 f"line{'s' if len(after) > 1 else ''}: {_quoted(after)}." if after else
                 " After it, up to the recording's end, my log holds no error.")
    evidence = [Evidence(cause="planner.plan_ok", topic=c.TASK_INFO, t=end, item=f"step {run.index + 1}: {run.label()} "
                                                                                 f"{state}")]
    evidence += [Evidence.of_log("planner.plan_ok", ln) for ln in [*during, *after][:MAX_QUOTED]]
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], evidence=evidence)


__all__ = ["step_asked", "step_status"]
