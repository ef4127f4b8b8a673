""""What did they say?", "why did she say no?", "where was he?", "what was her name?": the person the help skill
asked, told from what the skill recorded of them (/episodic_memory: detected, how far, agreed, confirmed), which is
never their words, their reasons, their place on the map or their name. Said so, rather than answered with the
task's finding again."""

from __future__ import annotations

import re

from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.events.records import duration, hms
from hexar.events.tasks import SkillRun, Task
from hexar.explainers.ask_human.explainer import NAME, Step, last_execution
from hexar.explainers.base import Explanation

_WHO = r"(they|she|he|the person|the human|that person|them|her|him|the man|the woman)"
_LEAD = r"^(and |so |but |ok |okay )?"
PERSON = re.compile(
    _LEAD + r"what did " + _WHO + r" (say|answer|reply|tell you|respond)\b|"
    + _LEAD + r"(what was|what's|what is) (their|her|his|the person's) (answer|reply|response)\b|"
    + _LEAD + r"why did(n't| not)? " + _WHO + r" (say no|refuse|decline|not help|help|say yes|agree|not answer|"
              r"ignore (you|me)|not confirm|confirm)\b|"
    + _LEAD + r"where (was|were|is|are) " + _WHO + r"\W*$|"
    + _LEAD + r"(what was|what's|what is|who was|who is) (her|his|their|the person's) name\b|"
    + _LEAD + r"(who|what) (was|is) (that|the) (person|human|man|woman)\b|"
    + _LEAD + r"who (helped( you)?|said (no|yes)|declined|refused|agreed|answered|replied|confirmed)\b|"
    + _LEAD + r"how many (people|persons|humans|others) did you (meet|see|detect|find|ask|talk to|speak to)\b|"
    # "who put the book on your tray?", "did somebody give it to you?", "did you pick it up yourself?"
    # not "who gave you the task?" (the request's) nor "did anyone help you?" (the ask-for-help step's)
    + _LEAD + r"who (were|was) you (talking|speaking|chatting) (to|with)\b|"
    # "did you have to wait for someone before coming back?": the help skill's wait for a person
    + r"\bdid you (have to |need to )?wait (for|on) (someone|somebody|anyone|anybody|a person|the person|them|her|"
      r"him|help)\b|"
    + _LEAD + r"who (put|gave|handed|loaded|placed|brought|made|prepared|got|fetched)\b(?!.*\b(task|request|order|job|"
              r"instruction|command|plan|errand)s?\b)|"
    + _LEAD + r"did (someone|somebody|anyone|anybody|a person|the person|they|she|he) (give|put|hand|load|place)\b|"
    + r"\bdid you (actually |really |even )?(pick|get|take|find|fetch|grab) ([a-z]+ ){0,3}?(up )?(yourself|by yourself|"
      r"on your own)\b")
# "did someone give it to you?", "did you find it yourself?": whether a person put it on my tray
_GAVE = re.compile(r"\bdid (someone|somebody|anyone|anybody|a person|the person|they|she|he) "
                   r"(give|put|hand|load|place)\b|\b(yourself|by yourself|on your own)\b")
_ACCEPTED = {"True": "they agreed to help", "False": "they declined"}
_CONFIRMED = {"True": "then confirmed that they had helped", "False": "then never confirmed that they had helped"}


def _steps(log: EventLog, task: Task) -> tuple[SkillRun | None, dict[str, Step]]:
    """The task's last ask-for-help step that started, and what its last execution recorded, by key."""
    run = next((r for r in reversed(task.skills) if r.skill == NAME and r.time_of("running") is not None), None)
    if run is None:
        return None, {}
    start, end = task.skill_window(run)
    records = [r for r in log.statuses.get(c.EPISODIC_MEMORY, []) if start <= r.t <= end]
    return run, {s.key: s for s in last_execution(records)}


def _answered(steps: dict[str, Step]) -> str:
    accepted = steps.get("user_accepted")
    if accepted is None or accepted.value not in _ACCEPTED:
        return "my recording holds no answer from them: I never got as far as asking" if "AskForHelpState" not in \
            steps else "my recording holds no answer from them"
    said = _ACCEPTED[accepted.value]
    confirmed = steps.get("user_confirmed")
    if accepted.value == "True" and confirmed is not None and confirmed.value in _CONFIRMED:
        said += f", and {_CONFIRMED[confirmed.value]}"
    return said


def person(question: str, log: EventLog, task: Task) -> Explanation:
    """What the help skill recorded of the person, for the part of them asked about."""
    from hexar.agent.followups import normalise  # it reads this module's PERSON

    q = normalise(question)
    run, steps = _steps(log, task)
    if run is None:
        text = "I asked nobody for help in this task, so my recording holds nothing of a person."
        return Explanation(explainer=NAME, text=text, causes=["planner.plan_ok"], enough_information=False)
    if not steps:
        text = f"My recording holds nothing of the person: no {c.EPISODIC_MEMORY} record of my ask for help."
        return Explanation(explainer=NAME, text=text, causes=["planner.plan_ok"], enough_information=False)
    answered = _answered(steps)
    detected = steps.get("person_detected")
    many = re.search(r"\bhow many\b", q) is not None
    if detected is None or detected.value != "True":
        text = f"{'None: ' if many else ''}I never detected anybody to ask, so my recording holds nothing of a person."
    elif many:
        text = f"One, as far as my recording shows: the person I detected and asked for help; {answered}."
    elif re.search(r"\bwait (for|on)\b", q):
        start, end = run.time_of("running"), run.last_change
        took = f" for {duration(end - start)}, from {hms(start)} to {hms(end)}" if start is not None else ""
        text = f"Yes: I waited for a person's help{took}; {answered}."
    elif re.search(r"\bname\b|^(\w+ )?who\b", q):
        text = ("My recording holds no name: I knew the person only as someone I detected and asked for help"
                f"; {answered}")
        # "who were you talking to, and what did they say?"
        text += (", and of what they said only that yes or no, not their words." if
                 re.search(r"\bwhat did (they|she|he) (say|answer|reply|tell)\b", q) else ".")
    elif _GAVE.search(q) and "AskForHelpState" in steps:
        # "did you find it yourself or did someone give it to you?": the help skill is how it came to my tray
        confirmed = steps.get("user_confirmed")
        helped = confirmed is not None and confirmed.value == "True"
        text = (f"Someone gave it to me: I asked a person for help, and {answered}; no step of my plan had me take "
                "it myself." if helped else
                f"Not as far as my recording shows: I asked a person for help, and {answered}.")
    elif re.search(r"^(\w+ )?where\b", q):
        distance = steps.get("person_distance")
        text = (f"I measured the person at {distance.value} m from me when I detected them" if distance is not None
                else "I detected the person") + (", but my recording holds no position for them on my map.")
    elif re.search(r"\bwhy\b", q):
        text = f"I can't tell why: my recording holds only that {answered}, not their reasons."
    else:
        text = f"My recording holds only their yes or no, not their words: {answered}."
    evidence = [s.evidence("planner.plan_ok") for k, s in steps.items()
                if k in {"person_detected", "person_distance", "user_accepted", "user_confirmed"}]
    return Explanation(explainer=NAME, text=text[0].upper() + text[1:], causes=["planner.plan_ok"], evidence=evidence)
