"""What the robot says out loud: the answer's first sentence or two, in utterances that fit the TTS timeout.

At ~150 words per minute a 25-word utterance takes ~10 s, half the robot's 20 s TTS timeout. The printed answer
keeps everything; the evidence is there for "tell me more".
"""

from __future__ import annotations

import re
from collections.abc import Sequence

MAX_WORDS = 25
MAX_SENTENCES = 2
MAX_TOTAL_WORDS = 50  # about 20 s of speech: a spoken answer should be short

_NODE = re.compile(r"\[[\w/.\-]+\]\s*")  # "[controller_server] " in quoted log lines
_LEVEL = re.compile(r"\b(ERROR|WARN(ING)?|INFO|DEBUG|FATAL)\b:?\s*")
_PAREN = re.compile(r"\s*\([^)]*\)")  # figures in brackets read badly aloud; they stay in the printed answer
_ASSIGN = re.compile(r"\s*=\s*")
_SNAKE = re.compile(r"(?<=[a-z])_(?=[a-z])")
_SENTENCE = re.compile(r"(?<=[.!?])\s+(?=[A-Z0-9\"'])")
_BREAK_AFTER = (",", ":", ";")
# Words the voices say ambiguously: piper's "timeout" is heard as "time up" or "we're had the time out".
_SAY_AS = ((re.compile(r"\btimeout(s?)\b", re.I), r"time-out\1"), (re.compile(r"\bGridBased\b"), "grid-based"))
_HEADER = re.compile(r"^([^:;.]{3,60}:)\s+(.*)$", re.S)


def clean(text: str) -> str:
    """Make recorded values and log lines sayable: no node tags, levels, brackets, `=` or snake_case."""
    text = _NODE.sub("", text)
    text = _LEVEL.sub("", text)
    text = _PAREN.sub("", text)
    text = _ASSIGN.sub(" is ", text)
    text = _SNAKE.sub(" ", text)
    for pattern, say_as in _SAY_AS:
        text = pattern.sub(say_as, text)
    text = re.sub(r"\s+([.,;:!?])", r"\1", text)  # "a path to (4.2, 2.1)." lost its bracket, not its stop
    return re.sub(r"\s+", " ", text).strip()


def _first_sentence(text: str) -> str:
    parts = [s.strip() for s in _SENTENCE.split(text) if s.strip()]
    return parts[0] if parts else ""


def _sentences(text: str, items: Sequence[str] | None) -> list[str]:
    """The answer's sentences. A list of evidence ("Here is what I recorded: a; b; c") gives the first sentence
    of each item, since an item may quote a long message, and the same item once. With the evidence `items`
    at hand they are used as they are, since a quoted message may itself hold a `;`."""
    m = _HEADER.match(text)
    header, body = (m.group(1), m.group(2)) if m and ";" in m.group(2) else ("", text)
    if not header:
        units = [s.strip() for s in _SENTENCE.split(text) if s.strip()]
    else:
        raw = [clean(i) for i in items] if items else re.split(r";\s+", body)
        units = []
        for item in raw:
            first = _first_sentence(item)
            if first and first not in units:
                units.append(first)
        if units:
            units[0] = f"{header} {units[0]}"
    return units


def _chunks(sentence: str, max_words: int) -> list[str]:
    """Split a long sentence at a comma or colon where possible, else at the word limit."""
    words = sentence.split()
    out: list[str] = []
    while len(words) > max_words:
        cut = max((i + 1 for i, w in enumerate(words[:max_words]) if w.endswith(_BREAK_AFTER) and i >= 5),
                  default=max_words)
        out.append(" ".join(words[:cut]))
        words = words[cut:]
    if words:
        out.append(" ".join(words))
    return out


def _end(text: str) -> str:
    text = text.rstrip(",:; ")
    return text if text.endswith((".", "!", "?")) else f"{text}."


def spoken(answer: str, evidence: Sequence[str] | None = None, max_words: int = MAX_WORDS,
           max_sentences: int = MAX_SENTENCES, max_total: int = MAX_TOTAL_WORDS) -> list[str]:
    """The utterances to say for `answer`, each at most `max_words` words, together at most `max_total`.
    `evidence`: the recorded items an evidence answer lists, to split it where the items end."""
    out: list[str] = []
    total = 0
    for sentence in _sentences(clean(answer), evidence)[:max_sentences]:
        for chunk in _chunks(sentence, max_words):
            words = chunk.split()
            room = max_total - total
            if room <= 0:
                return out
            out.append(_end(" ".join(words[:room])))
            total += min(room, len(words))
    return out
