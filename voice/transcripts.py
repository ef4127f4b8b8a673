"""What a recogniser heard, made fit for the agent: stop words, contractions, misheard short follow-ups."""

from __future__ import annotations

import difflib
import re

_STOP = re.compile(
    r"^(?:(?:ok|okay|well|alright|all right|no|great|good)\s+)*"
    r"(?:stop(?: talking| listening)?|that's all|that is all|that's it|thanks?(?: you)?(?: very much| so much| a lot)?"
    r"|bye|goodbye|good bye|quit|exit|enough|nothing else)"
    r"(?:\s+(?:thanks?(?: you)?|that's all|bye|goodbye|robot|tiago|hexar))*$"
)
_THANKS = re.compile(r"\bthank")
_CONTRACTIONS = ((re.compile(r"\b(would|could|should|might|must)'ve\b", re.I), r"\1 have"),
                 (re.compile(r"\b(would|could|should|might|must) of\b", re.I), r"\1 have"))
# The short follow-ups the agent answers from the thread. A one-line follow-up has no context for a
# recogniser to lean on, so tiny.en often mishears it ("what would have helped" -> "what would've been held").
FOLLOW_UPS = ("why", "why is that", "why was that", "tell me more", "what would have helped",
              "what could have helped", "what could i have done", "how do you know", "what do you mean",
              "what else", "anything else", "what happened", "go on", "explain that")
# "why" said alone has no context either, and whisper writes it as another short word: "Right." most of all.
# Alone, none of these is a question to the robot, so each is taken as the "why?" it was.
MISHEARD_WHY = frozenset({"right", "white", "wide", "wise", "why'd", "y", "wine", "while"})
_MAX_REPAIR_WORDS = 6
_MIN_RATIO = 0.8


def normalise(transcript: str) -> str:
    """Lower case, no punctuation but apostrophes."""
    return re.sub(r"\s+", " ", re.sub(r"[^\w' ]+", " ", transcript.lower())).strip()


def is_stop(transcript: str) -> bool:
    return bool(_STOP.match(normalise(transcript)))


def is_thanks(transcript: str) -> bool:
    return bool(_THANKS.search(normalise(transcript)))


def repair(transcript: str) -> str:
    """The question to put to the agent: contractions spelled out, and a short utterance that sounds almost
    like a known follow-up replaced by it. Longer questions pass as heard: the agent's router copes."""
    text = transcript.strip()
    for pattern, repl in _CONTRACTIONS:
        text = pattern.sub(repl, text)
    norm = normalise(text)
    if norm in MISHEARD_WHY:
        return "why?"
    if not norm or len(norm.split()) > _MAX_REPAIR_WORDS or norm in FOLLOW_UPS:
        return text
    best = max(FOLLOW_UPS, key=lambda f: difflib.SequenceMatcher(None, norm, f).ratio())
    return f"{best}?" if difflib.SequenceMatcher(None, norm, best).ratio() >= _MIN_RATIO else text
