"""Findings that carry their own words: the answer, the fix and who said the lines they quote. The readings of a
docking (docking.py), of a behaviour server's goal (behaviors.py) and of a goal as it was sent (goal_sent.py) know
what to say better than any shared template; wording.template gives their words back as they are."""

from __future__ import annotations

from hexar.events.records import LogLine
from hexar.explainers.base import Evidence
from hexar.explainers.navigation.detectors import Finding

FACT = "worded"  # a finding's fact: notes[0] is its answer, notes[1] its fix ("" for none), notes[2] who spoke


def finding(cause: str, lines: list[LogLine], text: str, fix: str | None, speaker: str,
            more: list[Evidence] | None = None) -> Finding:
    """A finding of `cause` quoting `lines` (after `more` evidence), answered with `text` and `fix`; `speaker` said
    the lines ("The docking server")."""
    return Finding(cause, [*(more or []), *(Evidence.of_log(cause, ln) for ln in lines)], {FACT: 1.0},
                   [text, fix or "", speaker])


def answer(f: Finding) -> tuple[str, str | None, list[str]] | None:
    """(answer, fix, details) of a worded finding, the last line it quotes as its detail; None for any other."""
    if FACT not in f.facts:
        return None
    text, fix, speaker = f.notes[:3]
    return text, fix or None, [f"{speaker} said: {e.item}" for e in f.evidence[-1:]]
