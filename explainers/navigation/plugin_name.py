"""A plugin type a node asked pluginlib for that its plugin descriptions do not declare, read against the types they
do declare.

pluginlib's ClassLoader::createUniqueInstance throws "According to the loaded plugin descriptions the class <type>
with base class type <base> does not exist. Declared types are <type> <type> …" (pluginlib class_loader_imp.hpp),
which Nav2's servers log as they fail to configure ("Failed to create global planner. Exception: …"). The declared
types name each plugin as its package's plugin description file does ("nav2_navfn_planner/NavfnPlanner", or
"nav2_navfn_planner::NavfnPlanner"): a type asked for with the other separator, or with a letter or two wrong, is
told as that, with the declared type to write instead.
"""

from __future__ import annotations

import difflib
import re

_MISSING = re.compile(r"the class (?P<cls>\S+) with base class type (?P<base>\S+) does not exist\. Declared types "
                      r"are (?P<declared>.*)", re.S)
CLOSE = 0.85  # difflib's ratio above which a declared type is the one meant, one letter or two apart


def plugin_reading(text: str) -> str:
    """For pluginlib's "does not exist. Declared types are …" in `text`, what is wrong with the type asked for,
    against the declared ones; "" when the text holds no such line, or no declared type is near."""
    m = _MISSING.search(" ".join(text.split()))
    if m is None:
        return ""
    asked = m["cls"]
    declared = [t.strip(",.") for t in m["declared"].split() if t.strip(",.") and t != "..." and t != "…"]
    for other in (asked.replace("::", "/"), asked.replace("/", "::")):
        if other != asked and other in declared:
            sep, right = ("::", "/") if "::" in asked else ("/", "::")
            return (f"the plugin type asked for, {asked}, is written with '{sep}' where its plugin description "
                    f"declares it with '{right}' ({other}): write {other} in the parameter that names it")
    # a type asked for without its package ("BaseObstaclCritic": DWB adds dwb_critics::) is read against the
    # declared types' own names
    names = {re.split(r"::|/", t)[-1] if not re.search(r"::|/", asked) else t: t for t in declared}
    near = [names[t] for t in difflib.get_close_matches(asked, list(names), n=3, cutoff=CLOSE) if _misspelt(asked, t)]
    if near:
        return (f"the plugin type asked for, {asked}, is not among the types its plugin descriptions declare; the "
                f"nearest declared one is {near[0]}, so the parameter that names it is most likely misspelt")
    if declared and m["declared"].rstrip().endswith(("...", "…")):
        return ""  # the list was cut short where it was copied: the type may be among the rest
    if declared:
        shown = ", ".join(declared[:6]) + (", …" if len(declared) > 6 else "")
        return (f"the plugin type asked for, {asked}, is not among the types its plugin descriptions declare "
                f"({shown}): the package that would declare it is not installed in this version, or the parameter "
                "names another type")
    return ""


def _misspelt(asked: str, declared: str) -> bool:
    """One or two letters apart, and not a longer name of its own ("SmacPlanner" and "SmacPlanner2D", "SmacPlanner"
    and "SmacPlannerHybrid" are different plugins: what one adds begins a word or a number of its own)."""
    short, long_ = sorted((asked, declared), key=len)
    if long_.startswith(short) and long_[len(short):][:1].isupper() | long_[len(short):][:1].isdigit():
        return False
    return _distance(asked, declared) <= 2


def _distance(a: str, b: str) -> int:
    """Levenshtein's edit distance."""
    row = list(range(len(b) + 1))
    for i, ca in enumerate(a, 1):
        prev, row[0] = row[0], i
        for j, cb in enumerate(b, 1):
            prev, row[j] = row[j], min(row[j] + 1, row[j - 1] + 1, prev + (ca != cb))
    return row[-1]
