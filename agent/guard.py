"""Faithfulness guard: an LLM may phrase an explanation, but not change what it says."""

from __future__ import annotations

from dataclasses import dataclass

from hexar.causes import BENIGN, vocabulary
from hexar.claims import ALL_FINE, PLAN_BLAMED, TASK_FAILED, read_claims

# A recommendation explained by its ingredients went fine too: the guard lets its phrasing say so.
BENIGN_CAUSES = BENIGN | {"pizza.ingredients"}


@dataclass(frozen=True)
class Verdict:
    ok: bool
    reason: str = ""


def check(text: str, causes: list[str], task_outcome: str | None = None) -> Verdict:
    """The text must affirm the explanation's first cause, affirm no cause the explainer did not find, and
    not contradict how the task ended (call a success a failure, say all was fine when something failed, or blame a
    plan the planner did not fault)."""
    vocab = vocabulary()
    claims = read_claims(text)
    own = set(causes) | {implied for c in causes if c in vocab for implied in vocab[c].implies}
    modules = {c.split(".", 1)[0] for c in causes}
    primary = next((c for c in causes if c in vocab), None)
    if primary is not None and primary not in claims.causes:
        return Verdict(False, f"does not state {primary}")
    foreign = sorted(claims.causes - own)
    if foreign:
        return Verdict(False, f"adds {', '.join(foreign)}")
    if task_outcome == "succeeded" and TASK_FAILED in claims.generic:
        return Verdict(False, "says the task failed, but it succeeded")
    if ALL_FINE in claims.generic and not own <= BENIGN_CAUSES:
        return Verdict(False, "says nothing went wrong, but something did")
    if PLAN_BLAMED in claims.generic and "planner" not in modules:
        return Verdict(False, "blames the plan, which the planner did not fault")
    return Verdict(True)
