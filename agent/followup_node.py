"""The follow-up node: "why?" goes one level deeper on the answer just given, "what would have helped?" gives its
counterfactual or fix."""

from __future__ import annotations

import re
import time
from typing import TYPE_CHECKING, Any

from hexar.agent.cited import cited
from hexar.agent.context import RunContext
from hexar.agent.nodes import remembered, timings
from hexar.agent.overview import NOTHING_TO_CHANGE, helped
from hexar.agent.probes import failure_not_told
from hexar.agent.state import AgentState
from hexar.causes import BENIGN
from hexar.explainers.base import Explanation

if TYPE_CHECKING:
    from langgraph.runtime import Runtime


def followup(state: AgentState, runtime: Runtime[RunContext]) -> dict[str, Any]:
    """'Why?' goes one level deeper (evidence, then the causal chain); 'what would have helped?' gives the
    counterfactual or fix. Nothing is invented: past what was recorded, the robot says so."""
    start = time.perf_counter()
    exps = [Explanation.model_validate(e) for e in state.get("explanations", [])]
    depth = state.get("depth", 0)
    if state["intent"] == "helped":
        text = helped(exps, BENIGN) or ""
        failed = failure_not_told(runtime.context, state, exps)
        if failed is not None and (not text or text == NOTHING_TO_CHANGE or text.startswith("I have no fix")):
            fix = helped([failed], BENIGN)
            stepped = any(e.explainer != "planner" and e.causes and set(e.causes) <= BENIGN for e in exps)
            text = f"{NOTHING_TO_CHANGE.split(',')[0]}. As for what failed: {fix}" if stepped and fix else fix or text
    else:
        depth += 1
        if depth == 1:
            text = cited(exps)
        elif depth == 2:
            # A detail that only repeats a recorded item was heard at depth 1 (and reads as raw fields)
            heard = {ev.item for e in exps for ev in e.evidence}
            text = " ".join(_sentence(d) for e in exps for d in e.details if d not in heard)
        else:
            text = ""
        text = text or "That's everything I recorded about it; I don't have enough information to go deeper."
    turn = {"question": state["question"], "answer": text, "explainers": [e.explainer for e in exps]}
    return {"answer": text, "depth": depth, "route": "followup", "history": remembered(state, turn),
            "timings_ms": timings(state, "followup", start)}


# A count of nothing is no finding: "I tried 0 recovery manoeuvres" says what the log does not hold. Said as what
# was not recorded, so a recording of only /rosout is not taken to prove the robot never tried.
_NONE_COUNTED = re.compile(r"^I tried 0 recovery manoeuvres (\([^)]*\)) and then gave up")


def _sentence(detail: str) -> str:
    """Details are written as notes; spoken one after another each must end as a sentence."""
    detail = _NONE_COUNTED.sub(r"My log records no recovery manoeuvre \1 before I gave up", detail.strip())
    if not detail:
        return detail
    detail = detail[0].upper() + detail[1:]
    return detail if detail.endswith((".", "!", "?", '."', ".'")) else detail + "."
