"""use_sim_time as the nodes announced it (/parameter_events): the evidence for or against a clock finding.

A finding that simulated and wall-clock time were mixed (MoveIt's out-of-date joint states, a transform
extrapolated into the future) rests on numbers in a log line; the parameters say which nodes ran on which clock.
Where some nodes had use_sim_time true and others false, those are named, as evidence. Where every node that
announced it agreed, the mix is not between them, which the finding says too: a node that announced nothing, or
another machine's clock. A recording without /parameter_events changes nothing.
"""

from __future__ import annotations

from collections import defaultdict

from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.explainers.base import Evidence, Explanation

SIM_TIME = "use_sim_time"
# the findings that say simulated and wall-clock time were (or may have been) mixed
CLOCK_CAUSES = frozenset({"manipulation.stale_robot_state", "manipulation.no_joint_states",
                          "navigation.transform_error"})
_SHOWN = 4


def _names(nodes: list[str]) -> str:
    shown = ", ".join(nodes[:_SHOWN])
    return shown + (f" and {len(nodes) - _SHOWN} more" if len(nodes) > _SHOWN else "")


def with_sim_time(found: Explanation, log: EventLog, until: int) -> Explanation:
    """`found` with what the nodes' use_sim_time says of its clock finding, when it has one and the recording holds
    the parameter."""
    if not set(found.causes) & CLOCK_CAUSES:
        return found
    held = [p for (_, name), p in log.settings(until).items() if name == SIM_TIME and isinstance(p.value, bool)]
    if not held:
        return found
    on: dict[bool, list[str]] = defaultdict(list)
    for p in sorted(held, key=lambda p: p.node):
        on[bool(p.value)].append(p.node)
    cause = found.causes[0]
    if len(on) == 2:
        note = (f"My nodes' parameters show the mix: use_sim_time was true on {_names(on[True])} but false on "
                f"{_names(on[False])}.")
        # the odd ones out first: a single node off the others' clock is the one to look at
        few = bool(len(on[True]) < len(on[False]))
        evidence = [Evidence(cause=cause, topic=c.PARAMETER_EVENTS, t=p.t, item=f"{p.node}: {SIM_TIME} = {p.said}")
                    for p in sorted(held, key=lambda p: (p.value is not few, p.node))]
        return found.model_copy(update={"text": f"{found.text} {note}", "evidence": [*found.evidence, *evidence]})
    ((flag, nodes),) = on.items()
    note = (f"use_sim_time was {'true' if flag else 'false'} on all {len(nodes)} of my nodes that announced it "
            f"({_names(nodes)}), so the clocks did not differ between them: look for a node that announced no "
            "parameters, or another machine's clock.")
    return found.model_copy(update={"details": [*found.details, note]})
