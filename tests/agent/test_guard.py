"""The faithfulness guard on phrasings a small model really produced here (and obvious corruptions of them)."""

from __future__ import annotations

import pytest

from hexar.agent.guard import check


@pytest.mark.parametrize(("text", "causes", "outcome", "ok"), [
    # kept: faithful rewrites by Qwen2.5-1.5B
    ("I couldn't reach the kitchen because I was plugged into my charger.", ["navigation.charging"], "failed", True),
    ("The person declined to help.", ["ask_human.refused"], "failed", True),
    ("I stopped so awkwardly because the person's position varied by 114 cm, more than the 50 cm I normally accept.",
     ["ask_human.noisy_detection"], "succeeded", True),
    # rejected: a success told as a failure (a real 1.5B output for scenario 10)
    ("I couldn't reach the kitchen because nothing went wrong on the way to the kitchen: I travelled 6.0 m in 13 s.",
     ["navigation.nominal_speed"], "succeeded", False),
    # rejected: the cause is missing or denied, or another module's cause is added
    ("The power was still on.", ["navigation.charging"], "failed", False),
    ("There was no obstacle in my path, so I waited.", ["navigation.blocked_path"], "failed", False),
    ("I was plugged into my charger and the joystick held my wheels.", ["navigation.charging"], "failed", False),
    ("I was plugged into my charger because my plan was wrong.", ["navigation.charging"], "failed", False),
    ("Nothing went wrong, the person just declined.", ["ask_human.refused"], "failed", False),
    # kept: a start and an arm motion that went fine, said as such (the bring-up answer's own words)
    ("Starting my drivers and controllers went fine: nothing went wrong, and my controllers came up without any "
     "problem.", ["control.nominal"], "succeeded", True),
    ("Nothing went wrong: I moved my arm to the shelf without any problem.", ["manipulation.nominal"], "succeeded",
     True),
    # rejected: "nothing went wrong" about an arm whose controllers failed
    ("Nothing went wrong, but my arm controllers could not run because a controller was set up wrongly.",
     ["control.configuration_error"], "failed", False),
])
def test_guard(text: str, causes: list[str], outcome: str, ok: bool) -> None:
    assert check(text, causes, outcome).ok is ok, check(text, causes, outcome)
