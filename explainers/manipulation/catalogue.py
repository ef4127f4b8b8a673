"""The MoveIt 2 message catalogue (moveit_catalogue.json, mined by scripts/mine_modules.py from moveit/moveit2).

Read with the navigation catalogue's matcher (literal prefilter, patterns compiled on first need), so a line is
recognised by its text whatever its logger. Besides the messages it holds MoveIt's error-code names and the
cause each one states (a "Planner '…' failed with error code NO_IK_SOLUTION" line is an IK failure).
"""

from __future__ import annotations

from functools import cache

from hexar.explainers.logcause import ModuleCatalogue, load


@cache
def catalogue() -> ModuleCatalogue:
    return load("hexar.explainers.manipulation", "moveit_catalogue.json")
