"""The text-to-speech explainer: the TTS stops an utterance at a fixed timeout (paper section IV)."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

from hexar.events.contract import SAY_EVENTS, SAY_STATUS_NAME
from hexar.events.records import StatusRecord
from hexar.explainers.base import Context, Evidence, Explanation, TextModel

if TYPE_CHECKING:
    from hexar.explainers.registry import Registry

TIMEOUT = "tts.timeout"
COMPLETED = "tts.completed"
MISMATCH = "tts.utterance_mismatch"
MATCHES = "tts.utterance_matches"
# What the original TTS uses when a robot does not record its settings.
DEFAULT_TIMEOUT_S = 20.0
DEFAULT_WPM = 150.0
MAX_TIMEOUT_S = 86_400.0
MAX_WPM = 1_000.0
ENDS = frozenset({"finished", "timed_out"})


@dataclass(frozen=True)
class Assumed:
    """Which settings the recording did not hold, so that the answer says they are defaults."""

    timeout: bool
    wpm: bool

    @property
    def any(self) -> bool:
        return self.timeout or self.wpm


def _float(record: StatusRecord, key: str) -> float | None:
    raw = record.get(key)
    try:
        return float(raw) if raw is not None else None
    except ValueError:
        return None


def _num(x: float) -> str:
    """20.0 -> "20", 38.4 -> "38.4": a person hears whole seconds without a trailing ".0"."""
    return f"{x:.1f}".removesuffix(".0")


# A question about what was said rather than how the speech went.
# "Did you say it out loud?", "did you tell me?": whether anything was said at all (then what), not whether it was
# what the request asked for.
SAID_ANYTHING = re.compile(r"^(and |so |but )?did you (actually |really |even |ever )?(say|tell|read|speak)( it| that|"
                           r" this| anything| something| me| her| him| them| anyone)*( out loud| aloud| at all)?\W*$")
# "What were you trying to say?", "say the rest": the whole text the robot was to say, and where a cut came.
WHOLE_MESSAGE = re.compile(
    r"what (were|was) you (trying|going|about|meant|supposed) to (say|tell|read)\b|"
    r"what did you (want|mean|try|intend|have) to (say|tell|read)\b|"
    r"what (was|is) the (whole|full|entire|complete) (message|text|list|story)\b|"
    r"what (was|is) the rest( of (it|the (message|text|list)))?\W*$|(say|tell|read)( me)? the rest\b|"
    r"what did(n't| you not) you (get to )?say\b|what did you (leave out|miss out|not say|never say)\b")
CONTENT_QUESTION = re.compile(
    WHOLE_MESSAGE.pattern + "|"
    r"what (exactly |actually )?did you (say|read|tell)|did you (read|say|tell)( me| her| him| them)? (the )?"
    r"(right|correct|wrong)|"
    # "did you tell Maria dinner is at eight?", "did you give her the message?": whether it was said, and what
    r"did you (actually |really |even )?(tell|give|pass on|deliver) (?!(me|us)\b)[a-z]+ (that\b|the message\b|"
    r"about\b|[a-z]+ (is|was|are|were|will)\b)|"
    r"(right|correct|wrong) (recipe|message|text|thing|story|list|news)|was (that|it) (the )?(right|correct)|"
    r"(is|was) that what i asked|"
    + SAID_ANYTHING.pattern
)
# The part of a request that names what to say: the words after the verb that asks for speech.
_SPEECH_VERB = re.compile(r"\b(read|tell|say|announce|remind|recite|repeat)\b(.*)$", re.I)
_FILLER = frozenset(
    (
        "me", "you", "him", "her", "them", "us", "it", "the", "a", "an", "to", "for", "of", "and", "or", "that",
        "this", "these", "those", "what", "is", "are", "was", "be", "on", "in", "at", "whole", "all", "some",
        "please", "could", "would", "can", "will", "my", "your", "our", "their", "his", "its", "about", "with",
        "from", "there", "here", "now", "today", "week",
    )
)


def _words(text: str, drop: frozenset[str] = frozenset()) -> list[str]:
    """Lower-case words without a plural s, so that "recipes" meets "recipe"."""
    return [w.removesuffix("s") for w in re.findall(r"[a-z0-9]+", text.lower()) if w not in drop]


def requested_topic(instruction: str) -> list[str]:
    """The words a request asks to hear about ("Read me the recipe for a lasagne" -> recipe, lasagne); empty
    when the request does not ask the robot to say something."""
    m = _SPEECH_VERB.search(instruction)
    if m is None:
        return []
    return list(dict.fromkeys(w for w in _words(m.group(2), _FILLER) if len(w) > 1))


def first_sentence(text: str, limit: int | None = 120) -> str:
    """The text up to its first sentence's end, clipped to `limit` characters (None: never clipped)."""
    sentence = re.split(r"(?<=[.!?])\s", text.strip(), maxsplit=1)[0]
    return sentence if limit is None or len(sentence) <= limit else sentence[: limit - 3].rstrip() + "..."


def compare(instruction: str, text: str, evidence: list[Evidence], question: str = "") -> Explanation | None:
    """Did the utterance say what the request asked for? Word overlap between the request's topic and the
    utterance: a missing topic word (e.g. the dish named) is a mismatch. None when nothing can be compared."""
    topic = requested_topic(instruction)
    if not topic or not text.strip():
        return None
    said = set(_words(text))
    missing = [w for w in topic if w not in said]
    quoted = first_sentence(text)
    yes_no = re.match(r"\W*(did|was|is|were|have|has)\b", question.lower()) is not None
    if not missing:
        return Explanation(
            explainer="text_to_speech",
            text=("Yes: " if yes_no else "") + f'I said "{quoted}", which is what you asked for ("{instruction}").',
            causes=[MATCHES], evidence=[e.model_copy(update={"cause": MATCHES}) for e in evidence],
            details=[f"Every word that names what you asked for is in what I said: {', '.join(topic)}."],
        )
    named = " or ".join(f'"{w}"' for w in missing)
    return Explanation(
        explainer="text_to_speech",
        text=("No. " if yes_no else "") + (f'What I said did not match your request: you asked "{instruction}", '
                                            f'but I said "{quoted}", which never mentions {named}.'),
        causes=[MISMATCH], evidence=[e.model_copy(update={"cause": MISMATCH}) for e in evidence],
        counterfactual=f"Had my plan given my speech a text about {' and '.join(missing)}, I would have said "
                       "what you asked for.",
        fix="The text I speak comes from my plan's say step, not from my speech itself: ask me again and "
            "name exactly what you want to hear, so that the plan carries the right text.",
        details=[f"The words of your request that name what to say: {', '.join(topic)}; missing from what I "
                 f"said: {', '.join(missing)}.", "My speech says the text it is given; it does not choose it."],
    )


def render(record: StatusRecord) -> str:
    return f"{record.message}: " + ", ".join(f"{k} = {v}" for k, v in record.data_items())


def last_utterance(records: list[StatusRecord]) -> tuple[StatusRecord | None, StatusRecord | None]:
    """The last `started` record and the end (`finished`/`timed_out`) that follows it, if any."""
    say = [r for r in records if r.name in {SAY_STATUS_NAME, ""}]
    starts = [i for i, r in enumerate(say) if r.message == "started"]
    if not starts:
        return None, None
    i = starts[-1]
    end = next((r for r in say[i + 1:] if r.message in ENDS), None)
    return say[i], end


class TextToSpeechExplainer:
    """f_e for the `say` skill: did the utterance finish, or did the TTS timeout cut it off, and why."""

    name: ClassVar[str] = "text_to_speech"
    topics: ClassVar[frozenset[str]] = frozenset({SAY_EVENTS})
    description: ClassVar[str] = (
        "Explains what happened when the robot spoke through its text-to-speech: whether it said the whole "
        "message or stopped in the middle because the speech has a fixed time limit (20 seconds by default) "
        "and the message was too long to say within it. It reads the recorded utterance, its length, the "
        "speaking rate and the timeout. Use it for questions like 'why did you stop talking?', 'why didn't "
        "you finish the message?' or 'what did you say?'."
    )

    def __init__(self, model: TextModel | None = None, registry: Registry | None = None) -> None:
        # The paper answers this module from a template; the model is kept for the common constructor only.
        self.model = model
        self.registry = registry

    def explain(self, question: str, context: Context) -> Explanation:
        started, end = last_utterance(context.view(self.topics).statuses(SAY_EVENTS))
        if started is None:
            return Explanation.not_enough(self.name, "Nothing was said through my speech in this task.")
        if end is None:
            return Explanation.not_enough(
                self.name, "I started speaking, but the recording does not show how the utterance ended."
            )
        text = started.get("text", "") or ""
        if CONTENT_QUESTION.search(question.lower()):
            evidence = [Evidence(cause=MISMATCH, topic=SAY_EVENTS, t=started.t, item=render(started))]
            compared = compare(context.task.instruction, text, evidence, question)
            if compared is not None:
                return compared
            return Explanation(explainer=self.name, text=f'I said: "{first_sentence(text, 200)}"',
                               causes=[COMPLETED], evidence=evidence)
        words = len(text.split())
        timeout = _float(started, "timeout_s")
        wpm = _float(started, "words_per_minute")
        # a recorded "nan", "-1" or "1e308" is no setting a person could be told: treated as not recorded
        if timeout is not None and not 0 < timeout <= MAX_TIMEOUT_S:
            timeout = None
        if wpm is not None and not 1 <= wpm <= MAX_WPM:
            wpm = None
        assumed = Assumed(timeout is None, wpm is None)
        details = [render(started), render(end)]
        if timeout is None:
            details.append(f"timeout not recorded; assumed the default {_num(DEFAULT_TIMEOUT_S)} s")
        if wpm is None:
            details.append(f"speaking rate not recorded; assumed {_num(DEFAULT_WPM)} words per minute")
        timeout = timeout if timeout is not None else DEFAULT_TIMEOUT_S
        wpm = wpm if wpm is not None else DEFAULT_WPM
        needed = words / wpm * 60.0
        details.append(f"{words} words at {_num(wpm)} words per minute need about {_num(needed)} s")
        if end.message == "timed_out":
            return self._timed_out(started, end, text, words, timeout, wpm, needed, details, assumed)
        return self._finished(started, end, words, timeout, details, assumed)

    def _timed_out(
        self,
        started: StatusRecord,
        end: StatusRecord,
        text: str,
        words: int,
        timeout: float,
        wpm: float,
        needed: float,
        details: list[str],
        assumed: Assumed,
    ) -> Explanation:
        said = end.get("text_said")
        said_words = len(said.split()) if said is not None else None
        max_words = math.floor(timeout * wpm / 60.0)
        # A round timeout that would have fitted the whole message: the next multiple of 5 s above the need.
        enough = math.ceil(needed / 5.0) * 5
        if enough <= needed:
            enough += 5
        rate = f"{words} words at {'an assumed ' if assumed.wpm else ''}{_num(wpm)} words per minute"
        if assumed.timeout:
            sentence = (
                f"I stopped talking before the end of the message. The recording does not say my speech time "
                f"limit; the default is {_num(timeout)} seconds, and the message needed about {round(needed)} "
                f"seconds ({rate})."
            )
        else:
            sentence = (
                f"I stopped talking because my speech has a {_num(timeout)}-second limit and the message needed "
                f"about {round(needed)} seconds ({rate})."
            )
        if assumed.wpm:
            sentence += f" The recording does not say my speaking rate; {_num(DEFAULT_WPM)} words per minute is " \
                        "the default."
        if said_words is not None:
            sentence += f" I got through the first {said_words} of {words} words."
            details.append(f"said before the cut: {said!r}")
        details.append(f"the limit fits about {max_words} words at that rate")
        return Explanation(
            explainer=self.name,
            text=sentence,
            causes=[TIMEOUT],
            evidence=[
                Evidence(cause=TIMEOUT, topic=SAY_EVENTS, t=started.t, item=render(started)),
                Evidence(cause=TIMEOUT, topic=SAY_EVENTS, t=end.t, item=render(end)),
            ],
            counterfactual=(
                ("If the default limit applied, h" if assumed.any else "H")
                + f"ad the message been shorter than about {max_words} words, or had my speech time limit been "
                f"{enough} seconds instead of {_num(timeout)}, I would have finished it."
            ),
            fix="Ask for a shorter message, or split it into several shorter ones.",
            details=details,
        )

    def _finished(
        self,
        started: StatusRecord,
        end: StatusRecord,
        words: int,
        timeout: float,
        details: list[str],
        assumed: Assumed,
    ) -> Explanation:
        spoken = _float(end, "spoken_s")
        took = spoken if spoken is not None and math.isfinite(spoken) else (end.t - started.t) / 1e9
        if assumed.timeout:
            text = (f"I said the whole message ({words} words); it took {_num(took)} seconds. The recording does "
                    f"not say my speech time limit; the default is {_num(timeout)} seconds.")
        else:
            text = (f"I said the whole message ({words} words); it took {_num(took)} seconds, within my "
                    f"{_num(timeout)}-second speech limit.")
        return Explanation(
            explainer=self.name,
            text=text,
            causes=[COMPLETED],
            evidence=[
                Evidence(cause=COMPLETED, topic=SAY_EVENTS, t=started.t, item=render(started)),
                Evidence(cause=COMPLETED, topic=SAY_EVENTS, t=end.t, item=render(end)),
            ],
            details=details,
        )
