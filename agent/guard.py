"""Faithfulness guard: an LLM may phrase an explanation, but not change what it says."""

from __future__ import annotations

from dataclasses import dataclass

from hexar.causes import stated_causes, vocabulary


@dataclass(frozen=True)
class Verdict:
    ok: bool
    reason: str = ""


def check(text: str, causes: list[str]) -> Verdict:
    """The text must state the explanation's first cause and no cause of another module it did not find."""
    vocab = vocabulary()
    own = set(causes)
    modules = {c.split(".", 1)[0] for c in causes}
    primary = next((c for c in causes if c in vocab), None)
    if primary is not None and not vocab[primary].stated_in(text):
        return Verdict(False, f"does not state {primary}")
    foreign = sorted(c for c in stated_causes(text) - own if vocab[c].module not in modules)
    if foreign:
        return Verdict(False, f"adds {', '.join(foreign)}")
    return Verdict(True)
