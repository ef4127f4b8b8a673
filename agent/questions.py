"""Is this a question HEXAR can take? Empty, gibberish and statements are refused with a reason."""

from __future__ import annotations

import re
from functools import cache

from hexar.agent.classifier import examples
from hexar.agent.errors import BadQuestionError

_QUESTION_START = re.compile(
    r"^(and |but |so |ok |okay |hey |robot |please )*(why|what|how|when|where|who|which|did|do|does|was|were|is|"
    r"are|can|could|would|will|should|have|has|had|tell|explain|describe|show|say|give)\b"
)
_COMMON = (
    "a an the i you we he she it they me my your our us him her them this that these those there here to of in on "
    "at for from with without by about into over after before again not no yes so and or but if then than too very "
    "just only also still even ever never always why what how when where who which did do does done was were is "
    "are be been being can could would will should shall may might must have has had get got go went gone come "
    "came take took make made say said tell told know think want need like see saw look find found give gave keep "
    "kept let put stop stopped start started try tried work worked happen happened wrong right long slow slowly "
    "fast quickly way thing things something anything nothing everything someone anyone nobody person people "
    "robot task room kitchen dining living bring brought fetch coffee book message maria pizza recipe help "
    "helped ask asked approach move moved moving drive driving talk talking speak speaking finish finished "
    "middle first second last other else more much many time times minute minutes second seconds fix problem "
    "that's don't didn't doesn't wasn't weren't isn't aren't can't couldn't won't wouldn't i'm you're it's"
)


@cache
def vocabulary() -> frozenset[str]:
    words = set(_COMMON.split())
    for qs in examples().values():
        for q in qs:
            words.update(re.findall(r"[a-z']+", q.lower()))
    return frozenset(words)


def check_question(question: str) -> str:
    """The question, trimmed; raises BadQuestionError with a one-line reason otherwise."""
    q = question.strip()
    if not q:
        raise BadQuestionError("empty question: ask me why I did something, e.g. \"What happened?\"")
    words = re.findall(r"[a-z']+", q.lower())
    if not words:
        raise BadQuestionError(f"I can't read {q!r} as a question: ask me why I did something")
    known = sum(1 for w in words if w in vocabulary())
    if known / len(words) < 0.4:
        raise BadQuestionError(f"I don't understand {q!r}: ask me why I did something, e.g. \"What happened?\"")
    if not q.endswith("?") and not _QUESTION_START.match(q.lower()):
        raise BadQuestionError(f"{q!r} is not a question: ask me why I did something, e.g. \"Why did you stop?\"")
    return q
