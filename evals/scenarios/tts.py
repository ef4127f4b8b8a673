"""Simulated `say` skill (scenario 19): the TTS cuts an utterance off at its timeout."""

from __future__ import annotations

import math
import random

from hexar.evals.scenarios.bag import BagBuilder, SkillResult, sec_ns
from hexar.events.contract import SAY_EVENTS, SAY_STATUS_NAME

MODULE = ("Module name", "skill_say")
TIMEOUT_ERROR = "The skill has timed out"
WARN = 1  # diagnostic_msgs/DiagnosticStatus.WARN

LONG_MESSAGES: tuple[str, ...] = (
    # 1: a message to pass on to the family
    "Hello everyone, this is a message from Anna. She asked me to tell you that her train from Barcelona "
    "has been delayed by about two hours because of works on the line near Girona, so she will not be "
    "home for dinner as planned. Please do not wait for her to eat; she will get something at the "
    "station. She also asked that somebody takes the laundry out of the machine before it starts to "
    "smell, feeds the cat around seven, and checks that the back door is locked before going to bed. She "
    "will call again as soon as the train leaves, and she sends a big hug to the children.",
    # 2: a recipe read out step by step
    "Here is the recipe for a Margherita pizza. Mix five hundred grams of flour with three hundred and "
    "twenty millilitres of warm water, seven grams of dry yeast, a spoon of olive oil and ten grams of "
    "salt. Knead the dough for ten minutes until it is smooth, cover it and let it rise for two hours. "
    "Divide it into three balls and stretch each one by hand into a thin round base. Spread crushed "
    "tomatoes on top, add torn mozzarella and a pinch of salt, then bake in the hottest oven you have "
    "for about eight minutes. Finish with fresh basil leaves and a drizzle of olive oil.",
    # 3: the day's schedule
    "Good morning. Here is your schedule for today. At nine you have a video call with the insurance "
    "company about the car. At half past ten the physiotherapist comes for your knee exercises, which "
    "take about forty minutes. Lunch is at one, and your daughter said she would join you. At three you "
    "need to take your blood pressure tablet with a glass of water. At four the pharmacy delivers your "
    "new prescription, so please stay at home. In the evening there is the football match at eight, and "
    "tomorrow the rubbish collection is early, so the bins should go out tonight.",
)
SHORT_MESSAGES: tuple[str, ...] = (
    "I have arrived in the kitchen.",
    "Here is your pizza recommendation.",
    "Sorry, I could not complete the task.",
)


def long_message(variant: int) -> str:
    """One of three long utterances (scenario 19), each long enough to outlast a 20 s TTS timeout."""
    if not 1 <= variant <= len(LONG_MESSAGES):
        raise ValueError(f"long message variant must be 1, 2 or 3, not {variant}")
    return LONG_MESSAGES[variant - 1]


def short_message(variant: int = 1) -> str:
    """A short utterance for an ordinary `say` step."""
    return SHORT_MESSAGES[(variant - 1) % len(SHORT_MESSAGES)]


def simulate_say(
    b: BagBuilder,
    rng: random.Random,
    start: int,
    text: str,
    *,
    timeout_s: float = 20.0,
    words_per_minute: float = 150.0,
) -> SkillResult:
    """Speak `text`: `finished` after its spoken length, or `timed_out` at the timeout with what was said."""
    t0 = start + sec_ns(rng.uniform(0.05, 0.2))
    settings = [("timeout_s", f"{timeout_s:g}"), ("words_per_minute", f"{words_per_minute:g}")]
    b.status(t0, SAY_EVENTS, SAY_STATUS_NAME, "started", [MODULE, ("text", text), *settings])
    words = text.split()
    # A real voice does not keep an exact rate: pauses at punctuation make it a few percent slower or faster.
    spoken = len(words) / words_per_minute * 60.0 * rng.uniform(0.97, 1.04)
    if spoken > timeout_s:
        said = words[: math.floor(len(words) * timeout_s / spoken)]
        t1 = t0 + sec_ns(timeout_s)
        b.status(t1, SAY_EVENTS, SAY_STATUS_NAME, "timed_out",
                 [MODULE, ("spoken_s", f"{timeout_s:.2f}"), ("text_said", " ".join(said))], level=WARN)
        return SkillResult(end=t1 + sec_ns(rng.uniform(0.02, 0.1)), succeeded=False, error_msg=TIMEOUT_ERROR)
    t1 = t0 + sec_ns(spoken)
    b.status(t1, SAY_EVENTS, SAY_STATUS_NAME, "finished", [MODULE, ("spoken_s", f"{spoken:.2f}")])
    return SkillResult(end=t1 + sec_ns(rng.uniform(0.02, 0.1)), succeeded=True)
