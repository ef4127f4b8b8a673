""""Which planner did you use?", "what controller plugin was loaded?": the plugins the robot's stacks said they loaded
at start-up, read from the log lines that say so (Nav2's planner, controller and behavior servers, MoveIt's OMPL
pipeline), never guessed from a failure. A recording that starts after those lines says it cannot tell."""

from __future__ import annotations

import re

from hexar.agent.content import task_name
from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.events.records import LogLine
from hexar.events.tasks import Task
from hexar.explainers.base import Evidence, Explanation
from hexar.explainers.recorded import join_words

_LEAD = r"^(and |so |but |ok |okay )?"
_KIND = r"(global |local |path |motion |arm |navigation )?(planners?|controllers?|plugins?|behaviou?rs?|smoothers?|" \
        r"goal checkers?|progress checkers?|planning (algorithms?|plugins?|pipelines?)|algorithms?)( plugins?)?"
PLUGINS = re.compile(
    _LEAD + r"(which|what) " + _KIND + r" (did|do|does|were|was|is|are) (you|it|nav2|moveit|the robot|loaded|in use)"
    r"( (use|using|used|load|loaded|running|run|configured|have|had))?\b|"
    # "which controller plugin did controller_server load?"
    + _LEAD + r"(which|what) " + _KIND + r" (did|does|do) [a-z_/]+ (use|using|load|loaded|run|configure|create|have)\b|"
    # a bare "which controller?" after a failure asks which one failed (agent/cited.py), not which was loaded
    + _LEAD + r"(which|what) [a-z ]*plugins?\W*$")

# Real start-up lines (navigation2 nav2_planner/src/planner_server.cpp, nav2_controller/src/controller_server.cpp,
# nav2_smoother/src/nav2_smoother.cpp, nav2_behaviors/src/behavior_server.cpp, humble to kilted; MoveIt 2's
# ompl_interface model_based_planning_context.cpp): what each loaded, named by the role said in the answer.
_LOADED = (
    ("planner", "my global planner", re.compile(r"^Created global planner plugin (?P<name>\S+) of type (?P<type>\S+)")),
    ("controller", "my controller", re.compile(r"^Created controller : (?P<name>\S+) of type (?P<type>\S+)")),
    ("checker", "my goal checker", re.compile(r"^Created goal checker : (?P<name>\S+) of type (?P<type>\S+)")),
    ("checker", "my progress checker",
     re.compile(r"^Created progress_checker : (?P<name>\S+) of type (?P<type>\S+)")),
    ("smoother", "my path smoother", re.compile(r"^Created smoother : (?P<name>\S+) of type (?P<type>\S+)")),
    ("behavior", "my recovery behaviours",
     re.compile(r"^Creating behavior plugin (?P<name>\S+) of type (?P<type>\S+)")),
    ("planner", "my arm's motion planner",
     re.compile(r"^Planner configuration '(?P<name>[^']+)' will use planner '(?P<type>[^']+)'")),
)
_ASKED = (("planner", r"\bplann(er|ers|ing)\b|\balgorithms?\b"), ("controller", r"\bcontrollers?\b"),
          ("smoother", r"\bsmoothers?\b"), ("behavior", r"\bbehaviou?rs?\b"), ("checker", r"\bcheckers?\b"))


def _found(log: EventLog) -> dict[str, list[tuple[LogLine, str, str]]]:
    """Per role said in the answer: each distinct plugin the log says was loaded (its line, name, type)."""
    found: dict[str, list[tuple[LogLine, str, str]]] = {}
    for ln in log.logs:
        for _, role, pattern in _LOADED:
            m = pattern.match(ln.msg)
            if m is not None and all(n != m["name"] for _, n, _ in found.get(role, [])):
                found.setdefault(role, []).append((ln, m["name"], m["type"]))
    return found


def plugins(question: str, log: EventLog, task: Task) -> Explanation:
    """The plugins of the kind asked for (all of them for "which plugins?"), as the log's start-up lines name them."""
    q = " ".join(question.lower().split())
    kinds = {kind for kind, words in _ASKED if re.search(words, q)} or {kind for kind, _, _ in _LOADED}
    roles = list(dict.fromkeys(role for kind, role, _ in _LOADED if kind in kinds))
    found = _found(log)
    said = []
    for role in roles:
        loaded = found.get(role, [])
        if loaded:
            said.append(f"{role} {join_words([f'{name} ({kind})' for _, name, kind in loaded])}")
    asked = join_words([r.removeprefix("my ") for r in roles]) if len(roles) < 4 else "plugins"
    if not said:
        text = (f"I can't tell: my log holds no line naming my {asked} for {task_name(task, log)}. Nav2 and MoveIt "
                f"name them when they start (\"Created controller : ... of type ...\"), and my recording ({c.ROSOUT}) "
                "holds no such line; it may have begun after they started.")
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], enough_information=False)
    text = f"My log names what I loaded: {'; '.join(said)}."
    evidence = [Evidence(cause="planner.plan_ok", topic=ln.origin, t=ln.t, item=ln.render())
                for role in roles for ln, _, _ in found.get(role, [])[:3]]
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], evidence=evidence)
