"""Planner explainer: validates the plan against the skill catalogue and the request, then explains."""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar

from hexar.events import contract as c
from hexar.events.tasks import SkillRun, Task
from hexar.explainers.base import Context, Evidence, Explanation, TextModel
from hexar.explainers.phrasing import phrase
from hexar.explainers.plan_check import LOCATIONS, Finding, check_plan
from hexar.explainers.recorded import place_name, plan_words, sentence, step_words

if TYPE_CHECKING:
    from hexar.explainers.registry import Registry

_LEAD = {
    "planner.request_beyond_capabilities": "I couldn't do that because {msg}.",
    "planner.invalid_skill": "I didn't start because my plan was faulty: {msg}.",
    "planner.invalid_parameter": "I didn't start because my plan was faulty: {msg}.",
    "planner.plan_not_fulfilling_request": "I did the wrong thing because my plan did not match your request: {msg}.",
}
_FIX = {
    "planner.request_beyond_capabilities": "Ask someone with hands for this one; I can move around, talk, "
    "recommend pizzas and ask people for help.",
    "planner.invalid_skill": "Ask me again; if it happens again, the task planner needs fixing.",
    "planner.invalid_parameter": "Ask me again and name one of my places: the kitchen, the dining room or the "
    "living room.",
    "planner.plan_not_fulfilling_request": "Ask me again, saying exactly what to do and where.",
}


def _fix(cause: str, task: Task) -> str:
    """What to do about a faulty plan; a request that already named one of my places was fine, and the planner put
    another name in the plan: the request needs no change."""
    named = [p for p in LOCATIONS if p.replace("_", " ") in task.instruction.lower()]
    if cause == "planner.invalid_parameter" and named:
        return (f"Your request was fine: it named {place_name(named[0])}, one of my places, and my task planner put "
                "another name in my plan. Ask me again the same way; if it happens again, the task planner needs "
                "fixing.")
    return _FIX[cause]


_OUTCOME = {"invalid": "was rejected", "failed": "failed", "succeeded": "succeeded", "canceled": "was canceled",
            "running": "was still running when the recording ends", "waiting": "never started"}
_STEP_STATE = {"succeeded": "done", "failed": "failed", "running": "still running when the recording ends",
               "canceled": "canceled"}


def step_outcome(run: SkillRun) -> str:
    """"Step 2, to ask someone for help: failed.": one step and what became of it."""
    return f"Step {run.index + 1}, to {step_words(run, short=True)}: {_STEP_STATE.get(run.state, 'never started')}."


def _recovery_item(task: Task) -> str:
    """What to cite for a recovery task, whose instruction is empty: the first step's own words as recorded."""
    for run in task.skills:
        for value in run.params.values():
            if isinstance(value, str) and value:
                return value
    return task.skills[0].skill if task.skills else ""


def plan_of(task: Task) -> list[tuple[str, dict[str, object]]]:
    return [(run.skill, run.params) for run in task.skills]


def task_findings(task: Task) -> list[Finding]:
    if task.derived:
        return []  # a Nav2 goal seen in the recording, not a plan HEXAR's planner made: nothing to check
    return check_plan(task.instruction, plan_of(task))


class PlannerExplainer:
    """Explains task-planning problems: invalid plans, wrong plans and impossible requests."""

    name: ClassVar[str] = "planner"
    topics: ClassVar[frozenset[str]] = frozenset({c.TASK_INFO})
    description: ClassVar[str] = (
        "Task planning: how the robot turned the request into a plan of skills. Use it for questions about "
        "what the robot decided to do, a plan that was rejected, a step the robot does not have, a wrong "
        "place, doing something different from what was asked, or a request the robot cannot do at all."
    )

    def __init__(self, model: TextModel | None = None, registry: Registry | None = None) -> None:
        self.model = model
        self.registry = registry

    def explain(self, question: str, context: Context) -> Explanation:
        task = context.task
        findings = task_findings(task)
        update = task.updates[-1]
        # cite the message that holds the quoted text, not merely the latest one
        said = next((u for u in reversed(task.updates) if u.instruction == task.instruction), update)
        if not findings:
            if not task.valid:
                # The robot rejected the plan for a reason our catalogue does not know: report its own words.
                return Explanation(
                    explainer=self.name,
                    text=f"My planner rejected the plan: {task.error_msg or 'it gave no reason'}.",
                    causes=["planner.invalid_plan"],
                    evidence=[Evidence(cause="planner.invalid_plan", topic=c.TASK_INFO, t=update.t,
                                       item=task.error_msg)],
                    confidence=0.5,
                )
            # Plain words for each step ("say 'Sorry, ...'"), never the plan's call notation.
            steps = plan_words(task)
            item = task.instruction or _recovery_item(task)
            return Explanation(
                explainer=self.name,
                text=(f"My plan for \"{task.instruction}\"" if not task.is_recovery else
                      "My own recovery plan, which I made after the task before it failed,") +
                sentence(f" looks right to me: {steps}"),
                causes=["planner.plan_ok"],
                evidence=[Evidence(cause="planner.plan_ok", topic=c.TASK_INFO, t=said.t, item=item)]
                if item else [],
                details=[*(step_outcome(run) for run in task.skills), f"The task {_OUTCOME[task.outcome]}."],
            )
        causes = list(dict.fromkeys(f.cause for f in findings))
        first = findings[0]
        evidence = []
        for f in findings:
            if f.step is not None and f.step < len(update.skills):
                item = update.skills[f.step].skill
            else:
                item = task.instruction
            evidence.append(Evidence(cause=f.cause, topic=c.TASK_INFO, t=(update if item != task.instruction
                                                                         else said).t, item=item))
        if task.error_msg:
            evidence.append(Evidence(cause=first.cause, topic=c.TASK_INFO, t=update.t, item=task.error_msg))
        text = _LEAD[first.cause].format(msg=first.message)
        details = [f.message[0].upper() + f.message[1:] + "." for f in findings]
        details.append(sentence(f"My plan was to {plan_words(task)}"))
        if task.error_msg:
            details.append(f"My plan check said: \"{task.error_msg}\"")
        counterfactual = None
        if first.cause == "planner.invalid_parameter":
            counterfactual = "Had every step named a valid place and all its parameters, I would have started the task."
        elif first.cause == "planner.invalid_skill":
            counterfactual = "Had the plan used only skills I have, I would have started the task."
        grounded = Explanation(
            explainer=self.name,
            text=text,
            causes=causes,
            evidence=evidence,
            counterfactual=counterfactual,
            fix=_fix(first.cause, task),
            details=details,
        )
        facts = "\n".join([f"Request: {task.instruction}", *details])
        return phrase(self.model, "planner", question, facts, grounded)
