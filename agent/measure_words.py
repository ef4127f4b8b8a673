"""How people ask for a measure of what the robot did ("how far did you drive?", "how long did it take?", "when
did you get there?"), each kind by the ways it is asked; agent/measures.py answers them."""

from __future__ import annotations

import re
from typing import Literal

Measure = Literal["far", "fast", "start", "long", "when"]

# A person's or an obstacle's distance: no trip of mine measures it (the help skill measures a person's).
_NO_TRIP = (r"(person|people|human|man|woman|guy|lady|someone|somebody|helper|user|owner|kid|child|collision|"
            r"obstacle|obstruction|object|thing|wall)\b")
# Per kind, the ways people ask it (lower case, spaces collapsed); the first kind that matches wins.
_ASKED: tuple[tuple[Measure, tuple[str, ...]], ...] = (
    ("far", (r"\bhow far (did|have|had|do) (you|it|the robot|the base|i) (go|drive|travel|move|come|get|walk|roll)\b",
             r"\bhow (much|many (meters|metres)) did you (drive|travel|move|go)\b",
             r"\bwhat distance did you\b",
             # "how far away was the kitchen?": the way I drove there (a person's distance is the help skill's)
             r"^(and |so |ok |okay )?how far (away )?(is|was) (it|that|(the|your) (?!" + _NO_TRIP + r")[a-z ]+)\b",
             r"^(and |so |ok |okay )?how far (away )?(from|to) (the )?[a-z ]+ (is|was|were) (it|you)\b")),
    # average speeds from the same positions: a person asks it of a trip that felt slow
    ("fast", (r"^(and |so |ok |okay )?how (fast|quickly|quick) (were|did|was|are) (you|it|the robot)\b",
              r"^(and |so |ok |okay )?(what('s| was| is)|how fast (was|is)) (your|the robot's|its) "
              r"(average |top |max(imum)? )?(speed|velocity)\b(?! limit)",
              r"^(and |so |ok |okay )?at what speed (were|did) you\b")),
    ("start", (r"^(and |so |ok |okay )?where did you (start|begin|set off|come)( from)?\b",
               r"^(and |so |ok |okay )?where were you (before|at the start|at first|when (you|i) (started|began|"
               r"asked))\b",
               r"^(and |so |ok |okay )?where (was|were) (your|the) start(ing)? (point|position|place)\b")),
    # "how long did the pick take?": every step's time is in the answer, the one asked about among them
    ("long", (r"^(and |so |ok |okay )?how long (did|had) (it|that|this|you|(the|your) [a-z]+( up| down)?) "
              r"(take|need|spend|drive|be)\b",
              r"^(and |so )?how long were you (gone|away|driving|out|busy|on it)\b",
              r"^(and |so )?how much time did (it|you|that) (take|need|spend)\b",
              r"^(and |so )?how long was (the|your|that) (trip|drive|errand|task)\b",
              # "how long did you wait?": every step's time is in the answer, the one asked about among them
              r"^(and |so |ok |okay )?how long did you (wait|stand|stay|sit|talk|speak|drive|search|look|try)\b",
              r"^(and |so )?(which|what) (step|part|leg)( of (the|your|my) [a-z]+)? (took|was) (the )?(longest|slowest|"
              r"quickest|shortest)\b",
              r"^(and |so )?(which|what)( one)? of (the|your|my)( [a-z0-9]+)? (steps|parts|legs|goals|waypoints|trips) "
              r"(took|was) (the )?(longest|slowest|quickest|shortest)\b",
              # "how long did each step take?", "how long were you in the kitchen?", "what were you waiting for?",
              # "how long did you keep trying?", "and for how long?"
              r"^(and |so |ok |okay )?how long did ([a-z]+ )?(each|every|all the|the) (steps?|parts?|legs?|skills?)"
              r"( each)? take\b|^(and |so )?how long did [a-z]+ and [a-z]+ (each )?take\b",
              r"^(and |so )?how long were you (in|at) (the )?[a-z_]+( room)?\W*$",
              r"\bwhy did you (spend|stay|wait|stand) (so much longer|so long|that long|longer)\b",
              r"(^(and |so )?|, )(what|who) were you waiting (for|on)\b",
              # "why did it take you so long in the dining room?": the time at a place, step by step
              r"^(and |so |but )?why did it take (you )?(so|that) long (in|at) (the )?[a-z_]+",
              # "why did you stand around in the living room for so long?", "why were you in the dining room for
              # almost a minute?": where the time went, step by step
              r"^(and |so |but )?why (were|did) you ([a-z_']+ ){1,8}(for )?(so long|that long|such a long time|ages|"
              r"(almost |nearly |about |over |more than )?(a|one|two|three|\d+) (minutes?|min))\b",
              r"^(and |so |but )?what took (you|it|the robot) so long\b",
              # "why did it take you more than a minute to bring it?", "what were you doing in the kitchen so long?"
              # ("why did it take you so long?" asks the explainers why it was slow)
              r"^(and |so |but )?why did it take (you |me |the robot )?(almost |nearly |about |over |more than |"
              r"a whole |a full )?(a|one|two|three|\d+) (minutes?|min)\b",
              r"^(and |so |but )?what were you doing\b[^?]*\b(so long|that long|such a long time|ages)\b",
              # "how quickly did the goal fail after it was sent?": the task's and its steps' times
              r"^(and |so )?how (quickly|fast|soon) did (it|that|the( [a-z_]+){1,2}) (fail|abort|end|finish|"
              r"succeed|give up|get rejected|come back)\b",
              r"^(and |so )?how long did (you|it|the robot|the planner) (keep|kept) (trying|going|waiting|looking|"
              r"searching|driving)\b|\bfor how long\W*$",
              r"^(and |so )?how long did (it|the planner|moveit|the robot) (try|plan|wait|search|look)\b",
              # "how long did the whole errand take?", "how long did the follow_joint_trajectory goal take?"
              r"^(and |so |ok |okay )?how long did (the |your |my |this |that )?([a-z_]+ ){1,3}(take|last)\b",
              # "how long did the spin run before it aborted?", "... and how long did it run?", "how long was the
              # goal pending?": the task's and each step's times (after launch: 'when', against the log's start)
              r"\bhow long (did|was|were|had|after (the|my|your) (goal|request|task)) "
              r"(?!.*\bafter (the |my )?(launch|start|starting|bring-?up|startup)\b)")),
    ("when", (r"^(and |so |ok |okay )?(when|at what time|what time) did you (start|begin|set off|leave|go|get|arrive|"
              r"reach|finish|stop|end|come back|return|drive|head|give up|fail|quit|abort)\b",
              r"^(and |so |ok |okay )?(when|at what time|what time) did (it|the robot|the (goal|navigation|spin|"
              r"backup|motion|arm)) (start|begin|set off|leave|get|arrive|reach)\b",
              r"^(and |so |ok |okay )?(when|at what time|what time) did (it|that|this|the task|the step|things|the "
              r"(goal|navigation|motion|move|pick|trajectory|plan|arm|robot)) "
              r"(fail|go wrong|break|abort|stop|end|finish)\b",
              # the day a developer replays a run from: answered with its date
              r"^(and |so |ok |okay )?when (did|does) (it|this|that|all (this|that)) (happen|take place|start|begin)\b",
              r"^(and |so |ok |okay )?when was (it|this|that)( recorded)?\W*$",
              r"^(and |so |ok |okay )?when was (this|the|that) (recording|run) (made|recorded|taken)\b",
              r"^(and |so |ok |okay )?(what|which) (day|date) (was|is) (it|this|that)\b",
              r"^(and |so |ok |okay )?on what (day|date)\b",
              # "how many seconds after launch did the goal fail?": when, against the recording's start
              r"^(and |so )?how (long|many seconds|many minutes|much time) after (the |my )?(launch|start|starting|"
              r"bring-?up|startup)\b")),
)
_KINDS = tuple((kind, re.compile("|".join(ways))) for kind, ways in _ASKED)


def why_so_long(question: str) -> bool:
    """"Why did you wait there so long?": a time asked about with why (of a failed task, its failure answers it)."""
    q = " ".join(question.lower().split())
    return re.match(r"(and |so |but )?(why|what took|(what|who) were you waiting)\b", q) is not None and \
        measure_kind(q) == "long"


def measure_kind(q: str) -> Measure | None:
    """'far', 'long' or 'when' for a question (lower case, spaces collapsed) about distance or time."""
    for kind, pattern in _KINDS:
        if pattern.search(q):
            return kind
    return None
