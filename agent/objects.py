""""Where is the cup?", "did you drop it?", "what are you holding?": the object a fetch task picks up and puts down,
told from what its pick and place steps recorded, never from a failure nobody asked about.

The robot records no gripper state, so only the steps say where an object went: picked up and put down, picked up
and not put down since, or never got hold of. Where the recording cannot say more (a place that failed half way),
the answer says so.
"""

from __future__ import annotations

import re

from hexar.events import contract as c
from hexar.events.tasks import SkillRun, Task
from hexar.explainers.base import Evidence, Explanation
from hexar.explainers.recorded import NAV_SKILLS, place_name, step_ref

PICK, PLACE = "pick", "place"
_THE = r"(?:the |my |your |that |this )?"
_ASKED = re.compile(
    r"\bwhere(?:'s| is| are| did you (?:put|leave|drop|take)) " + _THE + r"(?P<a>[a-z]+(?: [a-z]+)?)\b|"
    r"\bdid you (?:drop|lose|spill|break|forget|leave|pick up|grab|get|bring) " + _THE + r"(?P<b>[a-z]+)\b|"
    r"\b(?:do|did) you (?:still )?(?:have|hold) " + _THE + r"(?P<c>[a-z]+)\b|"
    r"\bwhat (?:were|are|was|is) you (?P<d>holding|carrying)\b|\bwhat did you (?P<e>pick up|carry|hold)\b")
_PRONOUNS = {"it", "them", "that", "this"}
# yes-or-no questions on what became of the object, and the answer for each of its fates (None: the steps can't say)
_LEADS = (
    (re.compile(r"\bdid you (?:drop|lose|spill|break)\b"),
     {"never": "No.", "placed": "No.", "holding": None, "unknown": None}),
    (re.compile(r"\b(?:do|did) you (?:still )?(?:have|hold)\b"),
     {"never": "No.", "placed": "No.", "holding": "Yes.", "unknown": None}),
    (re.compile(r"\bdid you (?:pick up|grab|get)\b"),
     {"never": "No.", "placed": "Yes.", "holding": "Yes.", "unknown": "Yes."}),
    (re.compile(r"\bdid you bring\b"), {"never": "No.", "placed": "Yes.", "holding": "No.", "unknown": None}),
)


def objects(task: Task) -> list[str]:
    """The objects the task's pick and place steps name, in plan order."""
    out: list[str] = []
    for run in task.skills:
        obj = run.params.get("object")
        if run.skill in {PICK, PLACE} and isinstance(obj, str) and obj.strip() and obj not in out:
            out.append(obj)
    return out


def object_asked(question: str, task: Task) -> str | None:
    """The object of the task a question asks about ("where is the cup?", "did you drop it?"), else None: a
    question about anything the task did not pick up ("where is the kitchen?") is not one."""
    named = objects(task)
    m = _ASKED.search(" ".join(question.lower().split()))
    if m is None or not named:
        return None
    if m.group("d") or m.group("e"):
        return named[0] if len(named) == 1 else None
    words = next(w for w in (m.group("a"), m.group("b"), m.group("c")) if w)
    if words.split()[0] in _PRONOUNS:
        return named[0] if len(named) == 1 else None
    asked = words.split()
    for obj in named:
        said = obj.replace("_", " ").lower().split()  # whole words: "the cupboard" is no cup
        if set(said) <= set(asked) or asked[0] in said or said[-1] in asked:
            return obj
    return None


def _step(task: Task, skill: str, obj: str) -> SkillRun | None:
    return next((r for r in task.skills if r.skill == skill and r.params.get("object") == obj), None)


def step_place(task: Task, run: SkillRun) -> str:
    """' in the kitchen': where the robot was for a step, the place its last trip before it reached."""
    trips = [r for r in task.skills if r.index < run.index and r.skill in NAV_SKILLS]
    last = trips[-1] if trips else None
    if last is None or last.state != "succeeded" or not last.params.get("location"):
        return ""
    return " in " + place_name(last.params["location"])


def object_state(question: str, obj: str, task: Task, failed: Explanation | None) -> Explanation:
    """Where the object went, as far as the task's pick and place steps show; `failed` is the task's failure as
    its explainer tells it, said after what it kept the object from."""
    thing = "the " + obj.replace("_", " ")
    pick, place = _step(task, PICK, obj), _step(task, PLACE, obj)
    runs = [r for r in (pick, place) if r is not None]
    # a step that never ran shows nothing of the object: only those that did are evidence
    evidence = [Evidence(cause="planner.plan_ok", topic=c.TASK_INFO, t=r.time_of(r.state) or r.last_change,
                         item=f"step {r.index + 1}: {r.label()} {r.state}") for r in runs
                if r.time_of("running") is not None]
    text, fate = _fate(task, thing, pick, place)
    q = " ".join(question.lower().split())
    lead = next((leads[fate] for pattern, leads in _LEADS if pattern.search(q)), None)
    text = f"{lead} {text}" if lead else text
    # the task's failure kept the object from where it was to go: told after it, and "why?" goes on to it
    told = failed if failed is not None and failed.enough_information and fate != "placed" else None
    if told is not None:
        text = f"{text} {told.text}"
        evidence += told.evidence
    return Explanation(explainer="manipulation", text=text, causes=list(told.causes) if told is not None
                       else ["planner.plan_ok"], evidence=evidence,
                       fix=failed.fix if failed is not None else None,
                       counterfactual=failed.counterfactual if failed is not None else None,
                       details=list(failed.details) if failed is not None else [])


def _fate(task: Task, thing: str, pick: SkillRun | None, place: SkillRun | None) -> tuple[str, str]:
    """What the steps say became of the object, and which fate that is: never (got hold of), placed, holding
    (picked up, not put down since) or unknown (a step the recording does not see the end of, or a place that
    failed half way)."""
    if pick is None or pick.time_of("running") is None:
        why = f", because {step_ref(task.failed_skill)} failed" if task.failed_skill is not None else ""
        return f"I never picked up {thing}: {step_ref(pick) if pick else 'no step of my plan'} never started{why}.", \
            "never"
    if pick.state == "failed":
        return (f"I never got hold of {thing}: picking it up{step_place(task, pick)} failed, so I did not carry it "
                "anywhere."), "never"
    if pick.state != "succeeded":
        return f"I was still picking up {thing}{step_place(task, pick)} when my recording ends.", "unknown"
    if place is None:
        return f"I picked up {thing}{step_place(task, pick)}, and no step of my plan put it down.", "holding"
    if place.state == "succeeded":
        return f"I put {thing} down{step_place(task, place)}, after I picked it up{step_place(task, pick)}.", "placed"
    if place.state == "failed":
        return (f"I picked up {thing}{step_place(task, pick)}, but putting it down{step_place(task, place)} failed: my "
                "recording does not show whether I still hold it."), "unknown"
    if place.time_of("running") is not None:
        return f"I picked up {thing}{step_place(task, pick)} and was putting it down when my recording ends.", "unknown"
    if task.outcome == "running":  # on its way to put it down
        return f"I picked up {thing}{step_place(task, pick)} and have not put it down yet.", "holding"
    why = f": {step_ref(task.failed_skill)} failed before that" if task.failed_skill is not None else ""
    return f"I picked up {thing}{step_place(task, pick)} and never got to put it down{why}.", "holding"
