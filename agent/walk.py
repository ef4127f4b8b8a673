""""What else happened?": the task's findings in plan order, each naming its real goal.

A navigation goal inside a skill (the approach to a person) is its own finding, named by the skill's log line
and its coordinates, never by the plan's room. What the person has already been told is skipped; when nothing
is left, the robot says so.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from hexar.agent.content import task_name
from hexar.causes import BENIGN
from hexar.events.log import EventLog
from hexar.events.tasks import SkillRun, Task
from hexar.explainers.base import Context, Explanation
from hexar.explainers.planner import task_findings
from hexar.explainers.recorded import NAV_SKILLS, join_words, place_name, step_words, trips_inside, utterances
from hexar.explainers.registry import Registry
from hexar.explainers.tts import compare


@dataclass
class Finding:
    lead: str  # names the step and its goal, e.g. "Step 1, going to the kitchen"
    explanation: Explanation
    related: list[str] = field(default_factory=list)  # sentences that say the same thing in other words

    @property
    def sentence(self) -> str:
        if not self.lead:
            return self.explanation.text
        joint = " " if self.lead.endswith(",") else ": "
        return f"{self.lead}{joint}{self.explanation.text}"


def _explain(registry: Registry, name: str, question: str, log: EventLog, task: Task,
             window: tuple[int, int]) -> Explanation | None:
    try:
        explainer = registry.get(name)
    except KeyError:
        return None
    found = explainer.explain(question, Context.for_task(log, task, registry).with_window(window))
    return found if found.enough_information else None


def _step(registry: Registry, question: str, log: EventLog, task: Task, run: SkillRun) -> list[Finding]:
    window = task.skill_window(run)
    number = f"Step {run.index + 1}"
    out: list[Finding] = []
    if run.skill in NAV_SKILLS:
        where = place_name(run.params["location"]) if run.params.get("location") else "my goal"
        lead = f"{number}, going to {where}"
    else:
        lead = f"{number}, when I tried to {step_words(run)}"
    # Every explainer registered for the skill has its say (a robot may add its own beside the built-in ones).
    for name in registry.for_module(run.skill):
        found = _explain(registry, name, question, log, task, window)
        if found is not None and all(f.explanation.text != found.text for f in out):
            out.append(Finding(lead, found))
    if run.skill == "ask_human_for_help":
        for trip in trips_inside(log, window):
            inner = (trip.t, window[1])
            found = _explain(registry, "navigation", question, log, task, inner)
            if found is None:
                continue
            lead = f"Inside step {run.index + 1}, on my approach to {trip.describe()}"
            if set(found.causes) <= BENIGN:
                # The drive itself was clean; how well the skill placed me is the skill's finding, not this one.
                figures = found.text.split(". ", 1)[1] if ". " in found.text else ""
                found = found.model_copy(update={"text": f"my navigation logs show no failures. {figures}".strip()})
                out.append(Finding(lead + ",", found))
            else:
                out.append(Finding(lead, found))
    if run.skill == "say" and not task.is_recovery:
        for u in utterances(log, window)[-1:]:
            compared = compare(task.instruction, u.text, [])
            if compared is not None and compared.causes == ["tts.utterance_mismatch"]:
                out.append(Finding(f"{number}, about what I said", compared))
    return out


def findings(registry: Registry, question: str, log: EventLog, task: Task) -> list[Finding]:
    """Everything notable about the task, in the order it happened."""
    out: list[Finding] = []
    if not task.valid or task_findings(task):
        found = _explain(registry, "planner", question, log, task, task.window())
        if found is not None:
            out.append(Finding("", found))
    for run in task.skills:
        if run.time_of("running") is not None:
            out += _step(registry, question, log, task, run)
    skipped = [r for r in task.skills if r.time_of("running") is None]
    if task.valid and skipped and task.failed_skill is not None:
        named = [f"{r.index + 1} (to {step_words(r, short=True)})" for r in skipped]
        steps = join_words(named)
        word = "Step" if len(skipped) == 1 else "Steps"
        out.append(Finding("", Explanation(
            explainer="planner", causes=["planner.plan_ok"],
            text=f"{word} {steps} never ran, because step {task.failed_skill.index + 1} had failed.")))
    return out


def told(finding: Finding, said_before: list[str], causes_told: set[str]) -> bool:
    """Already said, word for word, or a problem whose causes the person has already heard."""
    if any(finding.explanation.text in s for s in said_before):
        return True
    causes = set(finding.explanation.causes)
    return bool(causes) and not causes <= BENIGN and causes <= causes_told


def next_finding(registry: Registry, question: str, log: EventLog, task: Task, said_before: list[str],
                 causes_told: set[str]) -> Explanation:
    for finding in findings(registry, question, log, task):
        if not told(finding, said_before, causes_told):
            return finding.explanation.model_copy(update={"text": finding.sentence})
    later = [t for t in log.tasks if t.order > task.order and t.is_recovery]
    after = (f" Afterwards I ran {task_name(later[0], log)} (task {later[0].order}); ask about it with "
             f"\"what about task {later[0].order}?\".") if later else ""
    return Explanation(explainer="planner", text=f"Nothing else happened in {task_name(task, log)}: that is "
                       f"everything I recorded about it.{after}", causes=[], enough_information=True)
