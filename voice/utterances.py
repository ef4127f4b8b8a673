"""What the robot says out loud: the answer's first sentence or two, in utterances that fit the TTS timeout.

At ~150 words per minute a 25-word utterance takes ~10 s, half the robot's 20 s TTS timeout. The printed answer
keeps everything; the evidence is there for "tell me more".
"""

from __future__ import annotations

import re

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
_HEADER = re.compile(r"^([^:;.]{3,60}:)\s+(.*)$", re.S)


def clean(text: str) -> str:
    """Make recorded values and log lines sayable: no node tags, levels, brackets, `=` or snake_case."""
    text = _NODE.sub("", text)
    text = _LEVEL.sub("", text)
    text = _PAREN.sub("", text)
    text = _ASSIGN.sub(" is ", text)
    text = _SNAKE.sub(" ", text)
    return re.sub(r"\s+", " ", text).strip()


def _sentences(text: str) -> list[str]:
    """The answer's sentences. A list of evidence ("Here is what I recorded: a; b; c") gives the first sentence
    of each item, since an item's body may be a long quotation, and the same item only once."""
    m = _HEADER.match(text)
    header, body = (m.group(1), m.group(2)) if m and ";" in m.group(2) else ("", text)
    units: list[str] = []
    items = [i.strip() for i in re.split(r";\s+", body) if i.strip()]
    for item in items:
        sents = [s.strip() for s in _SENTENCE.split(item) if s.strip()]
        for s in sents if not header else sents[:1]:
            if s not in units:
                units.append(s)
    if header and units:
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


def spoken(answer: str, max_words: int = MAX_WORDS, max_sentences: int = MAX_SENTENCES,
           max_total: int = MAX_TOTAL_WORDS) -> list[str]:
    """The utterances to say for `answer`, each at most `max_words` words, together at most `max_total`."""
    out: list[str] = []
    total = 0
    for sentence in _sentences(clean(answer))[:max_sentences]:
        for chunk in _chunks(sentence, max_words):
            words = chunk.split()
            room = max_total - total
            if room <= 0:
                return out
            out.append(_end(" ".join(words[:room])))
            total += min(room, len(words))
    return out
