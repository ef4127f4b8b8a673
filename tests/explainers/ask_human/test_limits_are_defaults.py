"""The skill records measured values (distance, spread, approach error, answers), never its limits: an answer that
names a limit (4.0 m, 50 cm, 45 s, 30 s) says it is a configured default, not a value from the recording."""

from __future__ import annotations

import random
import re
from dataclasses import replace
from pathlib import Path

import pytest

from hexar.evals.scenarios.ask_human import scenario_conditions
from hexar.events.contract import EPISODIC_MEMORY
from hexar.explainers.ask_human import AskHumanForHelpExplainer
from hexar.explainers.ask_human.variables import DEFAULT_NOTE

from .helpers import context, record

LIMITS = ("4.0 m", "50 cm", "45 seconds", "30 seconds")
# Model bins in a counterfactual ("had the person been between 2.0 and 4.0 m away") are conditions, not limits.
BIN = re.compile(r"between [\d.]+ and [\d.]+ m")
CASES = {
    "too far": (12, {}, "4.0 m"),
    "no answer": (15, {"user_accepted": None}, "45 seconds"),
    "no confirmation": (16, {"user_confirmed": None}, "30 seconds"),
    "poor approach": (17, {}, "50 cm"),
    "noisy detection": (18, {}, "50 cm"),
}


@pytest.fixture(scope="module")
def explainer() -> AskHumanForHelpExplainer:
    return AskHumanForHelpExplainer()


@pytest.mark.parametrize("case", sorted(CASES))
def test_a_limit_is_said_to_be_a_default(tmp_path: Path, explainer: AskHumanForHelpExplainer, case: str) -> None:
    scenario, change, limit = CASES[case]
    log, _ = record(tmp_path, replace(scenario_conditions(scenario, random.Random(1)), **change))
    out = explainer.explain("Why?", context(log))
    said = BIN.sub("", " ".join([out.text, out.counterfactual or "", out.fix or "", *out.details]))
    assert limit in out.text, out.text  # the limit is still named: it is why the skill failed or complained
    recorded = {v for r in log.statuses[EPISODIC_MEMORY] for _, v in r.data_items()}
    for value in LIMITS:
        for m in re.finditer(re.escape(value), said):
            nearby = said[max(0, m.start() - 40):m.end() + 60]
            assert "default" in nearby or value.split()[0] in recorded, (value, nearby)
    assert DEFAULT_NOTE in out.text
    assert not re.search(r"I can ask from|I allow|I normally accept|within 45 seconds|within 30 seconds", said)
