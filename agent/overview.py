"""Answers about a whole task rather than one explainer's part of it.

- "did everything go ok?", "what happened" on a task of several steps: what became of every step, then the one
  finding worth hearing (the router's pick), instead of one step's finding alone;
- a question about the robot's own recovery task ("why did you say sorry?"): the failure of the task before it,
  which is why the recovery exists;
- "how can I fix this?", "what would have helped?" asked as a first question: the cause with its fix, not the
  cause alone.
"""

from __future__ import annotations

import re
from collections.abc import Sequence, Set

from hexar.events.log import EventLog
from hexar.events.tasks import Task
from hexar.explainers.base import Context, Evidence, Explanation
from hexar.explainers.recorded import join_words, plan_words, sentence, step_ref

# Questions about the task as a whole ("what happened" asks for the whole story, not one step of it).
_WHOLE = re.compile(
    r"\b(did|has|have|was|is) (everything|it all|all|all of it|the task|the whole thing|it) (go|gone|went|going|been|"
    r"work|worked|run|ok|okay|fine|alright|all right|good|well)\b|"
    r"\bhow did (it|that|the task|everything|things|your task|the job) go\b|"
    r"\b(everything|all) (ok|okay|fine|alright|all right|good|went well)\b|"
    r"\bany (problems?|issues?|trouble)\b|\b(did|has|had) (anything|something) (go|gone) wrong\b|"
    r"^(so |and |ok |okay )?what went (well|right|ok|okay|fine)\b|"
    r"^(so |and |ok |okay )?(tell me )?what (happened|did you do|have you done)( (here|there|today|then))?\W*$|"
    r"^(so |and |ok |okay )?(did|have) you (finish(ed)?|complete(d)?|(do|done) (it|everything)|manage(d)?|"
    r"make it|made it|succeed(ed)?)"
    r"( (it|the task|your task|the job|everything|the mission|your mission|the errand|the route|the waypoints))?\W*$"
)
# A fix asked for: the same words as a "what would have helped?" follow-up (agent/followups.py).
# "Which parameter should I change?": a developer's way of asking for the fix.
SETTING_FIX = (r"(which|what) (parameters?|params?|settings?|values?|config(uration)?|files?|options?|plugins?) "
               r"(should|do|must|can|would|could) (i|we|you) (have )?(change|changed|set|tune|tuned|adjust|adjusted|"
               r"fix|fixed|edit|edited|look at|check|checked)\b")
_FIX = re.compile(
    SETTING_FIX + "|"
    r"what (would|could|might) have (helped|worked|prevented it|made a difference)|"
    r"what (could|can|should) (i|we|you) (have )?do(ne)?( differently| about it)?|"
    r"how (can|could|do|would|should) (i|we|you|one) (fix|solve|repair|avoid|prevent)|"
    r"how (can|could) (it|this|that) be (fixed|solved|avoided|prevented)|"
    r"what (should|do|can|must) (i|we) (need to |have to )?(do|change|check|look at|look into|fix)\b|"
    # a person's request as the fix: "what should I say differently?", "was there something wrong with how I asked?"
    r"what (should|could|can|do) (i|we) (say|ask|tell you) (differently|instead)\b|"
    r"how (should|could|do|can) (i|we) (ask|say|phrase|word) (it|that|this)\b|"
    r"(something|anything) wrong with (how|the way|what) (i|we) (asked|said|told)\b|"
    r"what('s| is) the (fix|solution)|how to fix|what (would|do|should) you (recommend|suggest) (i|we) (do|change)|"
    r"how (do|can|should|could) (i|we) (turn|switch|shut|take) (\w+ ){0,2}off\b|"
    r"how (do|can|should|could) (i|we) (install|add|get|build) (it|that|them|the [a-z_ ]+)\W*$|"
    r"^(\w+ )?should (i|we) (unplug|move|remove|clear|restart|reboot|turn off|switch off|change|raise|lower|"
    r"increase|decrease|set|tune)\b|"
    r"what should (i|we) (move|remove|clear|unplug|take away|get out of the way)\b|"
    r"what should (the|my|your) (\w+ ){0,2}(tolerances?|limits?|values?|thresholds?|timeouts?|settings?|"
    r"parameters?|rates?) be\b"
)
_STATE = {"succeeded": "done", "failed": "failed", "running": "still running when the recording ends",
          "canceled": "canceled", "waiting": "never started"}


_WHY = re.compile(r"\b(why|how come|what for|reason|sorry|apologi[sz]e)\b")


def asks_why(question: str) -> bool:
    """A question about why the robot did something, or what happened ("what was your plan?" is not one)."""
    q = question.strip().lower()
    return _WHY.search(q) is not None or whole_task(q)


# A question that takes the task for not done ("why didn't you bring it?"): of a task that was done, the answer
# first says it was.
_NOT_DONE = re.compile(
    r"\bwhy (didn't|did not|couldn't|could not|haven't|have not|hasn't|has not|wasn't|was not) "
    r"(you|it|that|the task)\b|"
    r"\bwhy did (you|it|that|the task) (fail|not work)\b|\bhow come (you|it) (didn't|did not|couldn't|could not)\b"
)


# Of those, the ones about the task's own goal ("why didn't you bring me the apple?", not "why didn't you take the
# shorter way?"): of a task done with nothing wrong anywhere, every step done is the whole answer.
_GOAL_NOT_DONE = re.compile(
    r"\bwhy (didn't|did not|couldn't|could not|haven't|have not|hasn't|has not) (you|it) (bring|fetch|get|give|"
    r"deliver|hand|pass)\b|"
    # "why didn't you finish?", not "why didn't you finish telling me the recipe?" (the speech's own answer)
    r"\bwhy (didn't|did not|couldn't|could not|haven't|have not|hasn't|has not) (you|it) (do|finish|complete|"
    r"manage)( (it|that|the task|your task|the job|everything|what i asked))?\W*$|"
    r"\bwhy did (you|it|that|the task) (fail|not work)\b|\bwhy (didn't|did not) (it|that|the task) work\b|"
    r"\bhow come (you|it) (didn't|did not|couldn't|could not) (bring|fetch|get|give|deliver|do|finish|work)\b"
)


# "Why didn't you suggest a Hawaiian?" asks why one option and not another: it takes the choice as made, not the
# task as undone, so it is answered by the choice alone.
_OTHER_CHOICE = re.compile(r"\bwhy (didn't|did not) you (suggest|recommend|choose|propose|offer|go with|opt for|"
                           r"pick (a|an|another|the other|something))\b")


# "Did you make it?", "were you able to do it?": a yes-or-no question about the task's outcome, answered "Yes." or
# "No." before the explanation. Only verbs that say done or failed whatever the task was: "did you bring the
# coffee?" names an object the task may not have had, so it gets no yes or no.
_LEAD = r"^(?:(?:so|and|ok|okay|hey|well|um|uh|robot|tiago|hexar)\W+)*"
_SUBJECT = r"(?:you|it|the task|the robot|tiago|everything)"
_YES_NO = re.compile(
    _LEAD + r"(?:did|didn't|did not|have|haven't|have not|has|hasn't|has not|could|couldn't|could not) "
    + _SUBJECT + r" (?:(?:actually|really|even|ever|finally|successfully) )?(?:(?:manage|managed) to )?"
    r"(?P<verb>reach(?:ed)? (?:the|your|my|its) (?:goal|destination|target)|get there|got there|make it|made it|"
    # "did you finish?" asks about the task; "did you finish the sentence?" about one thing the task did
    r"succeed(?:ed)?|(?:finish(?:ed)?|complete(?:d)?)(?= (?:it|that|the task|the job|your task|everything|in time)\b"
    r"|\W*$)|arrive(?:d)?|do it|done it|do that|done that|"
    r"fail(?:ed)?|give up|given up|gave up|get stuck|got stuck)\b|"
    + _LEAD + r"(?:were|was|weren't|wasn't) " + _SUBJECT
    + r" (?P<state>successful|a success|able to do it|a failure|unsuccessful)\b|"
    + _LEAD + r"(?:did|has|had) (?:anything|something) (?P<wrong>go|gone) wrong\b"
)
_FAILING = ("fail", "give up", "given up", "gave up", "get stuck", "got stuck", "a failure", "unsuccessful")
_DONE = {"succeeded": True, "failed": False, "canceled": False, "invalid": False, "waiting": False}


def yes_or_no(question: str, outcome: str) -> str:
    """ "Yes." or "No." for a yes-or-no question about whether the task was done (or failed), from its recorded
    outcome; "" for any other question, and for a task still running when the recording ends."""
    m = _YES_NO.search(question.strip().lower())
    done = _DONE.get(outcome)
    if m is None or done is None or _EITHER.search(question.lower()):
        return ""
    failing = m.group("wrong") is not None or (m.group("verb") or m.group("state") or "").startswith(_FAILING)
    return "Yes." if done != failing else "No."


# "are the timeouts harmless or do I need to fix something?": two things asked, which no bare yes or no answers ("or
# not" still asks one)
_EITHER = re.compile(r"\bor\b(?! (not|no|nah)\b)")
# "Were you charging?", "was your path blocked?": a yes-or-no question about one condition the explainers name.
_ASKS_YES_NO = re.compile(_LEAD + r"(?:was|were|wasn't|weren't|is|are|isn't|aren't|did|didn't|do|does|had|has|have|"
                          r"hadn't|hasn't|could|couldn't)\b")


_GOOD = re.compile(r"\b(good|fine|ok|okay|alright|all right|accurate|correct|right|healthy|stable|working|reliable|"
                   r"precise)\W*$")


def confirmed(question: str, causes: Set[str], benign: Set[str]) -> str:
    """"Yes." for a yes-or-no question about a cause the answer states ("were you charging?" when I was), "No." for
    one about a problem where the answer found nothing wrong; "" otherwise: where another problem was found, the
    answer says which, with no yes or no that no explainer decided (both may have held)."""
    from hexar.causes import vocabulary
    from hexar.claims import read_claims

    q = " ".join(question.strip().lower().split())
    if _ASKS_YES_NO.match(q) is None or _EITHER.search(q):
        return ""
    claims = read_claims(q)
    asked = {c for c in claims.affirmed | claims.denied if not c.startswith("claim.")} - set(benign)
    if len(asked) != 1 or not causes:
        return ""
    vocab = vocabulary()
    stated = set(causes) | {i for c in causes if c in vocab for i in vocab[c].implies}
    # "was localization good?" names the cause (poor localisation) but asks whether it went well: the answer flips
    good = _GOOD.search(q) is not None
    if asked <= stated:
        return "No." if good else "Yes."
    return ("Yes." if good else "No.") if set(causes) <= set(benign) else ""


def with_lead(text: str, lead: str) -> str:
    """`text` opened by `lead` ("Yes." or "No."): a model's own "Yes," or "No." is kept where it agrees with the
    recorded outcome and replaced where it does not ("No pizza was recorded" opens with no answer word)."""
    said = re.match(r"(?i)(yes|no)[,.!]\s*", text)
    if said is not None and said.group(1).lower() == lead.rstrip(".").lower():
        return text
    rest = text[said.end():] if said is not None else text
    return f"{lead} {rest[:1].upper()}{rest[1:]}"


def presumes_not_done(question: str) -> bool:
    q = question.strip().lower()
    return _NOT_DONE.search(q) is not None and _OTHER_CHOICE.search(q) is None


def presumes_goal_not_done(question: str) -> bool:
    return _GOAL_NOT_DONE.search(question.strip().lower()) is not None


def whole_task(question: str) -> bool:
    return _WHOLE.search(question.strip().lower()) is not None


def asks_fix(question: str) -> bool:
    return _FIX.search(question.strip().lower()) is not None


NOTHING_TO_CHANGE = "Nothing went wrong there, so I have nothing to suggest changing."


def helped(exps: Sequence[Explanation], benign: Set[str], said: str = "") -> str:
    """What would have helped, as the explainers found it: their counterfactuals and fixes (less what `said`
    already holds), or why there is none."""
    parts = [p for e in exps for p in (e.counterfactual, e.fix) if p and _new(p, said)]
    if parts:
        return " ".join(dict.fromkeys(parts))
    if any(e.counterfactual or e.fix for e in exps):
        return ""  # all of it was said already
    if exps and not all(e.enough_information for e in exps):
        return ("The recording does not show what went wrong, so I can't say what would have helped: it holds "
                "too little about this task.")
    if exps and all(set(e.causes) <= benign for e in exps):
        return NOTHING_TO_CHANGE
    return "I have no fix or change to suggest: what I recorded does not show what would have helped."


def _new(part: str, said: str) -> bool:
    """Whether a counterfactual or fix adds to what was said (the cause's text often holds its counterfactual,
    without the odds that the counterfactual adds in brackets)."""
    return part.split(" (")[0].rstrip(".") not in said


def steps_summary(task: Task) -> str:
    """Every step of a task of several steps and what became of it, in one sentence ("" for one step)."""
    runs = list(task.skills)
    if len(runs) < 2:
        return ""
    if all(r.state == "succeeded" for r in runs):
        every = "both steps" if len(runs) == 2 else f"all {len(runs)} steps"
        return sentence(f"I did {every} of my plan: {plan_words(task)}")
    done = [r for r in runs if r.state == "succeeded"]
    ended = [f"{step_ref(r)} {_STATE[r.state]}" for r in runs
             if r.state in {"failed", "running", "canceled"}]
    never = [str(r.index + 1) for r in runs if r.state not in _STATE or r.state == "waiting"]
    if never:
        ended.append(f"step {never[0]} never started" if len(never) == 1 else
                     f"steps {join_words(never)} never started")
    lead = f"I did {len(done)} of the {len(runs)} steps of my plan" if done else \
        f"I did none of the {len(runs)} steps of my plan"
    return sentence(f"{lead}: {'; '.join(ended)}")


def previous_task(log: EventLog, task: Task) -> Task | None:
    """The task a recovery task recovers from: the last task the person asked for before it."""
    before = [t for t in log.tasks if t.order < task.order and not t.is_recovery]
    return before[-1] if before else None


def recovery(log: EventLog, task: Task, registry: object, question: str) -> Explanation | None:
    """Why the robot did its own recovery task: the failure of the task before it, as its explainer says it."""
    from hexar.explainers.registry import Registry

    if not task.is_recovery or not isinstance(registry, Registry) or not asks_why(question):
        return None
    prev = previous_task(log, task)
    if prev is None:
        return None
    name = registry.failure_explainer(prev)
    if name is None:
        return None
    cause = registry.get(name).explain(question, Context.for_task(log, prev, registry))
    did = plan_words(task)
    text = (f"I did my own recovery task ({did}) because my task before it, \"{prev.instruction}\", "
            f"{'was rejected' if prev.outcome == 'invalid' else 'failed'}: {cause.text}")
    item = prev.instruction or prev.task_id
    evidence = [*cause.evidence, Evidence(cause=cause.causes[0] if cause.causes else "planner.plan_ok",
                                          topic="/task_info", t=task.created, item=f"recovery task after: {item}")]
    return cause.model_copy(update={"text": text, "evidence": evidence,
                                    "details": [sentence(f"My recovery plan was to {did}"), *cause.details]})
