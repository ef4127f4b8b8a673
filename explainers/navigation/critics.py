"""Which of DWB's critics rejected the trajectories it sampled, from DWB's own summary.

With `debug_trajectory_details`, DWB's planner logs after "No valid trajectories out of N!" one line per critic and
reason, "%.2f: %10s/%s" (navigation2 dwb_core/src/dwb_local_planner.cpp, logger DWBLocalPlanner): the share of the
sampled trajectories that critic rejected for that reason ("1.00: Oscillation/Trajectory is oscillating.",
"0.87: ObstacleFootprint/Trajectory Hits Obstacle."). A controller failure is told with them: which critic stopped
every trajectory says why no command could be computed, where "No valid trajectories" alone does not.
"""

from __future__ import annotations

import re
from collections.abc import Iterable

from hexar.events.records import LogLine

_SHARE = re.compile(r"^\s*(?P<share>[01]\.\d\d): +(?P<critic>\w+)/(?P<why>\S.*?)\.?\s*$")
SHOWN = 3


def rejected_by(lines: Iterable[LogLine]) -> str:
    """'DWB's critics rejected them: Oscillation 100 % ("Trajectory is oscillating").' from the summary lines, each
    critic and reason at the highest share logged; "" when no such line was logged."""
    best: dict[tuple[str, str], float] = {}
    for ln in lines:
        m = _SHARE.match(ln.msg)
        if m is not None:
            key = (m["critic"], m["why"])
            best[key] = max(best.get(key, 0.0), float(m["share"]))
    if not best:
        return ""
    # a critic at 0.00 rejected none of them (DWB lists it all the same)
    ranked = sorted(((k, v) for k, v in best.items() if v > 0), key=lambda kv: -kv[1])[:SHOWN]
    if not ranked:
        return ""
    said = "; ".join(f"{critic} {share:.0%} (\"{why}\")" for (critic, why), share in ranked)
    return f"DWB's critics rejected the trajectories it sampled, by share: {said}."


__all__ = ["rejected_by"]
