"""The agent's nodes: intake, context, failure check, router, tools, answer, walk, content (the follow-up is in
followup_node.py)."""

from __future__ import annotations

import json
import time
from typing import TYPE_CHECKING, Any

from hexar import progress
from hexar.agent import content as answers
from hexar.agent import guard, sequence
from hexar.agent.attempts import tried
from hexar.agent.cited import asks_specific, cited
from hexar.agent.classifier import GENERIC
from hexar.agent.context import RunContext
from hexar.agent.errors import BadQuestionError
from hexar.agent.flags import flag_answer
from hexar.agent.focus import when_untold, with_pointed
from hexar.agent.followups import content_kind, intent_of, module_asked, task_ref_of
from hexar.agent.health import health
from hexar.agent.kinds import FROM_RECORDING
from hexar.agent.logs import logs
from hexar.agent.matters import matters_lead
from hexar.agent.means import means, means_lead
from hexar.agent.measure_words import why_so_long
from hexar.agent.mentions import mentioned
from hexar.agent.named_task import named_task
from hexar.agent.objects import object_asked, object_state
from hexar.agent.overview import (
    asks_fix,
    confirmed,
    helped,
    presumes_goal_not_done,
    presumes_not_done,
    recovery,
    steps_summary,
    whole_task,
    with_lead,
    yes_or_no,
)
from hexar.agent.parameters import asks_parameters
from hexar.agent.probes import finding, notable, probe, talked, with_failure
from hexar.agent.questions import EXAMPLE, check_question, quoted, small_talk_reply
from hexar.agent.state import AgentState
from hexar.agent.topic import ABOUT_ME, OFF_TOPIC, about_me, defined, off_topic, recording_words
from hexar.agent.unseen import unseen
from hexar.agent.walk import next_finding
from hexar.agent.whole import RECORDING_WIDE, lines_answer
from hexar.agent.whole import answerable as whole_answerable
from hexar.causes import BENIGN, NOTHING_WRONG
from hexar.events.tasks import WHOLE
from hexar.explainers.base import Context, Explanation
from hexar.explainers.errors import ModelError
from hexar.prompts import load
from hexar.tools.explainer_tools import explainer_of_tool, run_explainer, scope, tools_for

if TYPE_CHECKING:
    # Only a type: the one-shot path runs these nodes without importing LangGraph (agent/oneshot.py).
    from langgraph.runtime import Runtime


CONFIDENT = 0.45
SAID_BEFORE = "I have nothing more specific on that than what I just said:"
QUOTED_BEFORE = "I have nothing more specific on that than the lines I just quoted:"
KEEP_TURNS = 20  # the turns of a conversation kept in its saved state
BUILTIN = {"planner", "navigation", "ask_human_for_help", "text_to_speech", "pizza_recommender"}


def _ms(start: float) -> float:
    return round((time.perf_counter() - start) * 1000, 2)


def timings(state: AgentState, key: str, start: float) -> dict[str, float]:
    return {**state.get("timings_ms", {}), key: _ms(start)}


def intake(state: AgentState, runtime: Runtime[RunContext]) -> dict[str, Any]:
    start = time.perf_counter()
    reset: dict[str, Any] = {"timings_ms": {}, "error": "", "fallback": [], "asked": "", "object": ""}
    try:
        question = check_question(state.get("question", ""))
    except BadQuestionError as e:
        reply = small_talk_reply(state.get("question", ""))
        if reply is not None:  # "thanks", "hi": refused as a question, with a reply a conversation can say
            return {**reset, "intent": "smalltalk", "error": str(e), "answer": reply, "route": "none",
                    "timings_ms": {"intake": _ms(start)}}
        return {**reset, "intent": "invalid", "error": str(e), "answer": str(e)}
    meaning = ABOUT_ME if about_me(question) else defined(question)
    if meaning is not None:  # about HEXAR itself, or what a word of its answers means
        return {**reset, "question": question, "intent": "about", "answer": meaning, "route": "none",
                "timings_ms": {"intake": _ms(start)}}
    intent = intent_of(question, bool(state.get("explanations")))
    # the recording is read only for a question whose words name nothing a robot does
    if intent == "new" and not asks_specific(question) and off_topic(question) and \
            off_topic(question, recording_words(runtime.context.log.tasks)):
        error = (f"{quoted(question)} is not about anything I did: I can only explain what I did, from my "
                 f"recording. Ask me why I did something, {EXAMPLE}")
        return {**reset, "question": question, "intent": "offtopic", "error": error, "answer": OFF_TOPIC,
                "route": "none", "timings_ms": {"intake": _ms(start)}}
    update: dict[str, Any] = {**reset, "question": question, "intent": intent}
    if intent == "switch":
        update["task_ref"] = task_ref_of(question)
        update["used"] = []
        update["told"] = []
    elif intent == "new":
        update["used"] = []
        update["told"] = []
    update["timings_ms"] = {"intake": _ms(start)}
    return update


def context(state: AgentState, runtime: Runtime[RunContext]) -> dict[str, Any]:
    start = time.perf_counter()
    ctx = runtime.context
    ref = state.get("task_ref")
    log = ctx.log
    if ref == "previous":
        current = state.get("task_id")
        user = [t for t in log.tasks if not t.is_recovery and t.task_id != current]
        ref = user[-1].task_id if user else None
    if ref is None and state.get("intent") in {"new", "content", "else"} and \
            (named := named_task(state["question"].lower(), log)) is not None:
        ref = named.task_id  # "why did the goal to (9, 4) fail?" of a recording with several: that goal
    whole = not log.tasks and ref is None and whole_answerable(state["question"], content_kind(state["question"]), log)
    task = ctx.task(WHOLE if whole else ref)  # a recording with no task: what it holds, if that is what was asked
    candidates: list[str] = []
    for run in task.skills:
        for name in ctx.registry.for_module(run.skill):
            if name not in candidates:
                candidates.append(name)
    # a task derived from goals or start lines has no plan of the robot's to fault: HEXAR built its steps itself, so
    # "my plan looks right" would say nothing (the planner stays the fallback when no explainer serves its steps)
    if "planner" not in candidates and (not task.derived or not candidates):
        candidates.append("planner")
    update: dict[str, Any] = {"task_id": task.task_id, "task_outcome": task.outcome, "candidates": candidates}
    asked = module_asked(state["question"]) if state.get("intent") == "new" else None
    if state.get("intent") in {"new", "content"} and (obj := object_asked(state["question"], task)) is not None:
        update.update(intent="content", object=obj)  # "where is the cup?": what its steps did with it
    elif asked is not None and not answers.ran(asked, task, ctx.registry.for_module):
        update.update(intent="content", asked=asked)  # its plan never ran the module asked about
    elif whole or (state.get("intent") == "new" and asks_parameters(state["question"], log)):
        update.update(intent="content")  # "which nodes use sim time?": the recorded parameters say it
    elif state.get("intent") == "content" and task.outcome == "failed" and why_so_long(state["question"]):
        update.update(intent="new")  # "why did you wait there so long?" of a failed task: its failure says why
    return {**update, "timings_ms": timings(state, "context", start)}


def failure_check(state: AgentState, runtime: Runtime[RunContext]) -> dict[str, Any]:
    """Deterministic: a failed skill goes to its module's explainer, a bad plan to the planner. No LLM."""
    start = time.perf_counter()
    ctx = runtime.context
    task = ctx.task(state["task_id"])
    name = ctx.registry.failure_explainer(task)
    selected = [name] if name else []
    if not selected and task.is_recovery:
        # the robot's own recovery task is explained by the failure it recovers from ("why did you say sorry?")
        found = recovery(ctx.log, task, ctx.probe, state["question"])
        if found is not None:
            return {"selected": [], "explanations": [found.model_dump()], "route": "recovery", "depth": 0,
                    "used": [*state.get("used", []), found.explainer],
                    "timings_ms": timings(state, "failure_check", start)}
    return {"selected": selected, "route": "failure_check" if selected else "none",
            "timings_ms": timings(state, "failure_check", start)}


def _llm_choice(ctx: RunContext, state: AgentState) -> str | None:
    """The model's pick among all explainers; a pick outside this task's candidates counts as no pick."""
    model = ctx.backend.model
    if model is None:
        return None
    descriptions = ctx.registry.descriptions()
    options = [c for c in state["candidates"] if c in descriptions]
    question = state["question"]
    chooser = getattr(model, "choose_tool", None)
    try:
        if chooser is not None:
            tools = [t for t in tools_for(ctx.registry) if explainer_of_tool(t.name) in options]
            called = chooser([{"role": "user", "content": question}], tools)
            choice = explainer_of_tool(called) if called else "none"
        else:
            # A fixed prefix (the prompt file plus every registered explainer) lets llama.cpp reuse its cache.
            extra = "".join(f"{name}: {descriptions[name].split('. ')[0]}.\n" for name in ctx.registry.names
                            if name not in BUILTIN)
            messages = [{"role": "system", "content": load("router") + extra},
                        {"role": "user", "content": f"Question: {question}"}]
            schema = {"type": "object", "properties": {"explainer": {"enum": [*ctx.registry.names, "none"]}},
                      "required": ["explainer"]}
            choice = str(json.loads(model.chat(messages, schema=schema, max_tokens=16)).get("explainer", "none"))
    except (ModelError, ValueError, AttributeError):
        return None
    return choice if choice in options else None


def router(state: AgentState, runtime: Runtime[RunContext]) -> dict[str, Any]:
    """Only when nothing failed: choose an explainer from the question (LLM or classifier), else from findings."""
    start = time.perf_counter()
    ctx = runtime.context
    # a question about the whole task names no module: the finding worth hearing, not a model's guess at one
    whole = whole_task(state["question"])
    choice = None
    if not whole and ctx.backend.model is not None:
        with progress.step(f"asking the model ({ctx.backend.name}) which of my modules this question is about"):
            choice = _llm_choice(ctx, state)
    route = "llm"
    named = module_asked(state["question"]) if choice is None and not whole else None
    if named is not None and (choice := answers.serving(named, state["candidates"])) is not None:
        route = "named"  # "did you drop anything?": the arm's to answer, however unsure the classifier is
    if choice is None:
        label, share = (GENERIC, 0.0) if whole else ctx.classifier.choose(state["question"], state["candidates"])
        choice, route = (label, "classifier") if label != GENERIC and share >= CONFIDENT else (None, "findings")
    if choice is None:
        choice = notable(ctx, state, set()) or state["candidates"][0]
    elif route != "named" and set(probe(ctx, choice, state["question"], state["task_id"]).causes) <= NOTHING_WRONG:
        # The person asks "why" about something, but the chosen module saw nothing unusual: if another module
        # of this task did, that is what the question is about (e.g. "why did you stop so awkwardly?" when
        # the drive was fine but the approach to the person was not).
        # Another module's figures of a run that went fine (its speed) are nothing unusual either: "was the arm
        # slow?" about a clean pick is the arm's to answer, not the drive's. A module the question names by what it
        # does ("who did you ask for help?") is answered by that module, whatever another one found.
        other = notable(ctx, state, {choice}, BENIGN)
        if other is not None:
            choice, route = other, "findings"
    return {"selected": [choice], "route": route, "timings_ms": timings(state, "router", start)}


def tools(state: AgentState, runtime: Runtime[RunContext]) -> dict[str, Any]:
    start = time.perf_counter()
    ctx = runtime.context
    task = ctx.task(state["task_id"])
    explanations: list[dict[str, Any]] = []
    # Past the time budget, answer from the grounded templates rather than wait on the model.
    registry = ctx.registry if ctx.budget_left() > 0 else ctx.probe
    with scope(registry, Context.for_task(ctx.log, task, registry)):
        for name in state.get("selected", []):
            # What each explainer tool runs, called directly: building LangChain tools costs a second of imports.
            explanations.append(run_explainer(name, state["question"]))
    return {"explanations": explanations, "used": [*state.get("used", []), *state.get("selected", [])],
            "depth": 0, "timings_ms": timings(state, "tools", start)}


def answer(state: AgentState, runtime: Runtime[RunContext]) -> dict[str, Any]:
    start = time.perf_counter()
    ctx = runtime.context
    kept: list[dict[str, Any]] = []
    fallback: list[str] = []
    for raw in state.get("explanations", []):
        exp = Explanation.model_validate(raw)
        if exp.phrased_by != "template":
            verdict = guard.check(exp.text, exp.causes, state.get("task_outcome"))
            if not verdict.ok:
                fallback.append(f"{exp.explainer}: {verdict.reason}")
                exp = probe(ctx, exp.explainer, state["question"], state["task_id"])
        kept.append(exp.model_dump())
    texts = list(dict.fromkeys(e["text"] for e in kept))
    text = " ".join(texts) if texts else "I don't have enough information to say."
    question = state["question"]
    if state.get("intent") == "new" and asks_fix(question):  # "how can I fix this?": the cause, then the fix
        text = f"{text} {helped([Explanation.model_validate(e) for e in kept], BENIGN, text)}".strip()
    quoted_lines = ""
    if state.get("intent") == "new" and asks_specific(question):  # "which joint?": the lines that say it
        quoted_lines = cited([Explanation.model_validate(e) for e in kept])
        last = [t["answer"] for t in state.get("history", [])[-2:]]
        if quoted_lines and any(quoted_lines in said for said in last):
            text = f"{QUOTED_BEFORE} {quoted_lines.removeprefix('Here is what I recorded: ')}"
        else:  # the finding just heard is not told again before its lines
            text = quoted_lines if quoted_lines and text in last else f"{text} {quoted_lines}".strip()
    task = ctx.task(state["task_id"])
    if state.get("intent") == "new" and not quoted_lines:  # "why did it fail with 'Transform data too old'?"
        text = with_pointed(text, question, ctx.log, task)
    failed = state.get("route") == "failure_check"
    # what became of every step, too; and of a task done where nothing failed, when the question takes it for
    # not done ("why didn't you bring it?": I did)
    done = task.outcome == "succeeded" and not failed and presumes_not_done(question)
    if (whole_task(question) or done) and state.get("route") != "recovery":
        summary = steps_summary(task)
        if summary and done and presumes_goal_not_done(question) and all(set(e["causes"]) <= BENIGN for e in kept):
            # "why didn't you bring it?", all done and nothing wrong: a clean drive's speed is no answer; a task
            # with no plan recorded (a goal found in the logs) has no steps to say, so its explainer's words stay
            text = ""
        # a failure's cause comes first (a spoken answer keeps only its first sentences); a run where nothing
        # failed opens with every step done, which answers "did everything go ok?"
        text = (f"{text} {summary}" if failed else f"{summary} {text}".strip()) if summary else text
    meant = means_lead(question, ctx.log) if state.get("intent") == "new" else ""  # "what does exit code -8 mean?"
    lead = matters_lead(question, ctx.log, task, [Explanation.model_validate(e) for e in kept]) \
        if state.get("intent") == "new" and not meant else ""
    lead = lead or (yes_or_no(question, task.outcome) if state.get("route") != "recovery" else "")
    lead = lead or confirmed(question, {c for e in kept for c in e["causes"]}, BENIGN)
    if lead and text:
        text = with_lead(text, lead)
    elif text and not quoted_lines and not whole_task(question) and \
            text in {t["answer"] for t in state.get("history", [])[-2:]}:
        # a different question that finds nothing more specific: said as such, not as if it were news
        text = f"{SAID_BEFORE} {text}"
    text = f"{meant} {text}".strip() if meant else text
    turn = {"question": question, "answer": text, "explainers": [e["explainer"] for e in kept]}
    told = [*state.get("told", []), *(c for e in kept for c in e["causes"])]
    # lines already quoted: the next "why?" goes past them
    return {"explanations": kept, "answer": text, "fallback": fallback, "told": told,
            "history": remembered(state, turn), "timings_ms": timings(state, "answer", start),
            **({"depth": 1} if quoted_lines else {})}


def remembered(state: AgentState, turn: Any) -> list[Any]:
    """The thread's history with `turn`, its last KEEP_TURNS only: a conversation's saved state stays bounded
    however long it goes on (a follow-up reads the last answers, never the first of hundreds)."""
    return [*state.get("history", []), turn][-KEEP_TURNS:]


def _direct(state: AgentState, exp: Explanation, key: str, start: float) -> dict[str, Any]:
    """An answer made without the router and tools: it becomes the explanation that follow-ups go deeper on."""
    turn = {"question": state["question"], "answer": exp.text, "explainers": [exp.explainer]}
    return {"explanations": [exp.model_dump()], "answer": exp.text, "route": "followup", "depth": 0,
            "selected": [], "told": [*state.get("told", []), *exp.causes],
            "history": remembered(state, turn), "timings_ms": timings(state, key, start)}


def walk(state: AgentState, runtime: Runtime[RunContext]) -> dict[str, Any]:
    """'What else happened?': the next finding of the task, in plan order, that the person has not heard."""
    start = time.perf_counter()
    ctx = runtime.context
    task = ctx.task(state["task_id"])
    said_before = [t["answer"] for t in state.get("history", [])]
    exp = next_finding(ctx.probe, state["question"], ctx.log, task, said_before, set(state.get("told", [])))
    return _direct(state, exp, "walk", start)


def content(state: AgentState, runtime: Runtime[RunContext]) -> dict[str, Any]:
    """Where I went and why, where I am, how far and how long, what I said: answered from the recording, not from
    a failure."""
    start = time.perf_counter()
    ctx = runtime.context
    task = ctx.task(state["task_id"])
    kind = content_kind(state["question"])
    if task.task_id == WHOLE and kind not in RECORDING_WIDE and not asks_parameters(state["question"], ctx.log):
        exp = lines_answer(state["question"], ctx.log, task)
    elif state.get("object"):
        name = ctx.registry.failure_explainer(task)
        failed = probe(ctx, name, state["question"], state["task_id"]) if name else None
        exp = object_state(state["question"], state["object"], task, failed)
    elif state.get("asked"):
        exp = with_failure(ctx, state, answers.not_run(state["asked"], ctx.log, task, ctx.registry.for_module))
    elif kind in {"act", "next", "stop"}:
        exp = answers.read_only(kind, ctx.log, task)
    elif kind in {"learn", "feel"}:  # "why?" goes on to the failure; what keeps it from happening again is said
        exp = with_failure(ctx, state, answers.read_only(kind, ctx.log, task))
        if kind == "learn" and exp.fix:
            exp = exp.model_copy(update={"text": f"{exp.text} To keep it from happening again: {exp.fix[0].lower()}"
                                                  f"{exp.fix[1:]}"})
    elif kind == "means" and task.task_id != WHOLE:  # a line the finding rests on means what the finding says
        exp = means(state["question"], ctx.log, task, finding(ctx, state)) or \
            FROM_RECORDING[kind](state["question"], ctx.log, task)
    elif kind in FROM_RECORDING:
        exp = FROM_RECORDING[kind](state["question"], ctx.log, task)
    elif kind == "talked":
        exp = talked(ctx, state, task)
    elif kind == "tried":
        exp = with_failure(ctx, state, tried(state["question"], ctx.log, task))
    elif kind == "after":
        nxt = sequence.next_task(ctx.log, task)
        why = recovery(ctx.log, nxt, ctx.probe, "why did you do that?") if nxt is not None else None
        exp = sequence.after(ctx.log, task, why)
    elif kind == "flag":
        exp = flag_answer(ctx, state, task)
    elif kind in {"broken", "fault", "lost"}:
        exp = health(ctx, state, task, kind)
    elif kind in {"contact", "blocked"}:
        exp = unseen(ctx, state, task, kind)
    elif kind == "mentions" or asks_parameters(state["question"], ctx.log):
        exp = mentioned(ctx, state, task)
    elif kind in {"doing", "logs"}:  # "why?" after them goes on to the failure
        asked = sequence.doing(ctx.log, task) if kind == "doing" else logs(state["question"], ctx.log, task)
        exp = with_failure(ctx, state, asked)
    else:
        exp = answers.said(state["question"], ctx.log, task)
    return _direct(state, when_untold(exp, state["question"], ctx.log, task), "content", start)
