"""What the content and follow-up nodes ask the explainers (agent/nodes.py): one explainer's answer about the task,
and the task's failure beside an answer that is about something else."""

from __future__ import annotations

from hexar.agent import content as answers
from hexar.agent.context import RunContext
from hexar.agent.state import AgentState
from hexar.causes import BENIGN, NOTHING_WRONG
from hexar.events.tasks import Task
from hexar.explainers.base import Context, Explanation


def probe(ctx: RunContext, name: str, question: str, task_id: str) -> Explanation:
    task = ctx.task(task_id)
    return ctx.probe.get(name).explain(question, Context.for_task(ctx.log, task, ctx.probe))


def talked(ctx: RunContext, state: AgentState, task: Task) -> Explanation:
    """"Who did you talk to?": the person I asked for help (that explainer's answer, or the step I never got to,
    whose failure "why?" goes on to), then what I said aloud."""
    module, of = "ask_human_for_help", ctx.registry.for_module
    step = answers.started_step(module, task, of)
    if step is not None:
        asked = probe(ctx, module, state["question"], state["task_id"])
        asked = asked.model_copy(update={"text": answers.asked_someone(step, asked)})
        nothing = "Apart from that, I said nothing aloud for this task."
    elif answers.steps_of(module, task, of):
        asked = with_failure(ctx, state, answers.not_run(module, ctx.log, task, of))
        nothing = "I didn't say anything either."
    else:
        return answers.said(state["question"], ctx.log, task)
    spoken = answers.said(state["question"], ctx.log, task, nothing)
    return asked.model_copy(update={"text": f"{asked.text} {spoken.text}",
                                    "evidence": [*asked.evidence, *spoken.evidence]})


def with_failure(ctx: RunContext, state: AgentState, exp: Explanation,
                 failed: Explanation | None = None) -> Explanation:
    """"Did anyone help you?" of a task that failed before asking: the answer names the step that failed, so
    "why?" and "what would have helped?" go on to that failure (its evidence, details and fix), not to the plan.
    `failed`: the failure's explainer's answer where the caller has it already (it is not asked again)."""
    name = ctx.registry.failure_explainer(ctx.task(state["task_id"]))
    if name is None:
        return exp
    failed = failed or probe(ctx, name, state["question"], state["task_id"])
    return exp.model_copy(update={"evidence": [*exp.evidence, *failed.evidence], "fix": failed.fix,
                                  "counterfactual": failed.counterfactual,
                                  "details": [failed.text, *failed.details]})


def notable(ctx: RunContext, state: AgentState, exclude: set[str],
            benign: frozenset[str] = NOTHING_WRONG) -> str | None:
    """For a question that names no module: the first explainer (in plan order) with a notable finding."""
    for name in state.get("candidates", []):
        if name in exclude:
            continue
        found = probe(ctx, name, state["question"], state["task_id"])
        if found.enough_information and not set(found.causes) <= benign:
            return name
    return None


def finding(ctx: RunContext, state: AgentState) -> Explanation | None:
    """The failure of a task that failed, or, of one that did not, its notable finding (a node that never came up
    on a run the recording cuts short, a slow trip); None when there is neither."""
    name = ctx.registry.failure_explainer(ctx.task(state["task_id"])) or notable(ctx, state, set(), BENIGN)
    return probe(ctx, name, state["question"], state["task_id"]) if name is not None else None


def failure_not_told(ctx: RunContext, state: AgentState, exps: list[Explanation]) -> Explanation | None:
    """The task's failure or notable finding (see finding), when the answer being followed up is not about it (a
    step that went well, the tries, the steps that never ran, "nothing else happened"): "how do I fix it?" then
    means that problem."""
    failed = finding(ctx, state)
    if failed is None:
        return None
    told = {c for e in exps for c in e.causes}
    return None if not failed.causes or set(failed.causes) & told else failed
