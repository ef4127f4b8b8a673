"""Is a question about the robot at all? "What is the capital of France?" and "tell me a joke" are questions, but
nothing the robot did answers them: told the task's finding instead, the person hears an answer to something they
did not ask. And "what can you do?" or "who are you?" asks what HEXAR is, which no explainer knows either.

A question is about the robot when it names the robot ("you"), something that happens to a robot (failing,
waiting, driving, a plan, a place, a person), or anything the recording itself names (its tasks' instructions, steps
and their parameters). A question made only of small words ("why?", "and then?") goes on to the dialogue, which
reads it against what was said before."""

from __future__ import annotations

import difflib
import re
from collections.abc import Iterable
from functools import cache
from importlib.resources import files

from hexar.agent.questions import _words, vocabulary
from hexar.events.tasks import Task

_WORD = re.compile(r"[a-z]+")


# Words that carry no topic: question words, pronouns, auxiliaries, prepositions, fillers.
_FUNCTION = _words("""
a an the this that these those there here it its it's i me my mine we us our he him his she her they them their what
what's why how how's when where where's who whom whose which whats hows wheres whos is are was were be been being am
do does did done doing have has had having can could would will should shall may might must isn't aren't wasn't
weren't don't doesn't didn't can't couldn't won't wouldn't shouldn't haven't hasn't to of in on at for from with
without by about into onto over under after before again not no yes so and or but if then than too very just only
also even ever never always some any all every each one ones much many more most less like as such own same other
else tell me please explain describe show say know think really actually ok okay well oh um uh hey hi hello s t d ll
ve re m
""")

# Beyond the router's examples: what people ask a home robot about its errands.
_DOMAIN = _words("""
you your you're yourself yours robot robots tiago hexar happen happened happening went go going gone come came get
got take took taking long time slow fast late early wrong right fail failed failure problem error mistake stuck stop
stopped start started finish finished done task tasks goal goals plan plans step steps job errand mission request
asked order instruction move moved moving drive drove driving turn turned spin walk path route way map place room
position location pose arm gripper hand pick picked place placed grab grasp hold holding carry carrying drop dropped
put object person people someone somebody human help helped answer said say speak speaking voice talk navigation
planner planning controller control manipulation localisation localization battery charge charging sensor sensors
camera laser lidar scan obstacle obstacles collision blocked wall door reason cause because fix change changes check
look wait waited waiting work worked held day date recorded recording
""")
# The world outside the robot: the words people ask a robot about it with are in the question vocabulary (so they
# are not gibberish), but they are a topic only where the recording names them (a robot that read the news aloud).
_WORLD = frozenset({"weather", "news"})
# "what if I had no basil?", "why not a Hawaiian?", "and without the mozzarella?": a counterfactual on what the
# robot chose, whatever it names.
_COUNTERFACTUAL = re.compile(r"\bwhat if\b|\bwhy not\b|\bwithout\b|\binstead\b")


def _stem(word: str) -> str:
    for suffix in ("ing", "ed", "es", "s", "ly"):
        if word.endswith(suffix) and len(word) - len(suffix) >= 3:
            return word[: -len(suffix)]
    return word


@cache
def _domain() -> frozenset[str]:
    words = (set(_DOMAIN) | {w for v in vocabulary() for w in _WORD.findall(v)}) - _FUNCTION - _WORLD
    return frozenset(words) | frozenset(_stem(w) for w in words)


def recording_words(tasks: Iterable[Task]) -> frozenset[str]:
    """Every word the recording's tasks name: instructions, step names, their parameters and error messages."""
    words: set[str] = set()
    for task in tasks:
        texts = [task.instruction, task.error_msg]
        for run in task.skills:
            texts += [run.skill, run.error_msg, *(str(v) for v in run.params.values())]
        for text in texts:
            words.update(_WORD.findall(text.lower().replace("_", " ")))
    return frozenset(words - _FUNCTION)


# a name in the stack's spelling ("cmd_vel", "/scan"): a developer's question about the software ("TwistStamped" only
# where the recording holds it: "NewYork" is spelt so too)
_STACK_NAME = re.compile(r"\b[a-z][a-z0-9]*_[a-z0-9_]+\b|(?<![\w/])/[a-z]\w*")
_CAMEL = re.compile(r"\b[A-Z][a-z0-9]+[A-Z]\w*\b")


def off_topic(question: str, recorded: frozenset[str] = frozenset()) -> bool:
    """True for a question with words of its own that name nothing of the robot, its work or its recording."""
    q = question.lower()
    content = [w for w in _WORD.findall(q.replace("'", "")) if w not in _FUNCTION]
    if not content or _COUNTERFACTUAL.search(q) or _STACK_NAME.search(question) or \
            any(m.group(0).lower() in recorded for m in _CAMEL.finditer(question)):
        return False
    return not any(_topical(w) or w in recorded or _stem(w) in recorded for w in content)


@cache
def _topical(word: str) -> bool:
    """A word of the robot's domain, or one slip away from one ("cofee", a recogniser's "navigashun")."""
    domain = _domain()
    if word in _WORLD:  # not even by a slip ("weather" is one letter from "water")
        return False
    if word in domain or _stem(word) in domain:
        return True
    return len(word) >= 4 and bool(difflib.get_close_matches(word, domain, n=1, cutoff=0.8))


# "who are you?", "what can you do?": a question about HEXAR itself, answered by what it does.
_ABOUT_ME = re.compile(
    r"^(?:(?:and|so|ok|okay|hey|robot|tiago)\W+)*(?:"
    r"who are you|what are you|what is your name|what's your name|who (?:made|built|created|programmed|wrote) you|"
    r"what (?:can|do) you do|what (?:else )?can i ask(?: you)?(?: about)?|what (?:can|do) you (?:explain|answer)|"
    r"how do (?:i|you) use (?:you|this)|help(?: me)?"
    r")\W*$")

ABOUT_ME = ("I'm HEXAR: I explain what this robot did, from what it recorded, and I never act on anything myself. "
            "Ask me why I did something (\"Why didn't you bring me the coffee?\"), what happened, how long it took, "
            "where I went, whether I tried again, which errors I logged, what came next, or what to change so it "
            "goes better next time.")
OFF_TOPIC = ("I can only explain what I did, from what I recorded, and that question is not about it. "
             "Ask me why I did something.")


def about_me(question: str) -> bool:
    return bool(_ABOUT_ME.match(" ".join(question.lower().split())))


# "What is a costmap?", "what does AMCL mean?": a word of the answers, defined from agent/data/glossary.yaml.
_DEFINE = re.compile(
    r"^(?:(?:and|so|ok|okay|sorry|but)\W+)*(?:"
    r"what(?:'s|s| is| are| was)(?: an?| the| your| my| this| that)? (?P<a>[a-z0-9_ ]+?)|"
    r"what (?:does|do) (?:(?:an?|the|your|my|this|that) )?(?P<b>[a-z0-9_ ]+?) (?:mean|stand for|do)|"
    r"(?:explain|define)(?: an?| the| what)? (?P<c>[a-z0-9_ ]+?)(?: is| means)?)\W*$")


@cache
def _glossary() -> dict[str, str]:
    import yaml

    raw = yaml.safe_load((files("hexar.agent") / "data" / "glossary.yaml").read_text(encoding="utf-8"))
    return {said.lower(): " ".join(str(entry["means"]).split()) for entry in raw.values() for said in entry["say"]}


def defined(question: str) -> str | None:
    """What a term of the answers means ("what is a costmap?"), or None for any other question."""
    m = _DEFINE.match(" ".join(question.lower().replace("-", " ").split()))
    if m is None:
        return None
    term = next(t for t in (m.group("a"), m.group("b"), m.group("c")) if t)
    return _glossary().get(term.strip())
