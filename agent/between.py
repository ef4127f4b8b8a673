""""How long after the FATAL from spawner_arm_controller did spawner-4 exit?", "why is there a 15 second gap between
'Mission started' and 'Navigating...'?", "how long from launch until diff_drive_controller was activated?": the time
between two moments a developer names by their lines, and what the log holds in between.

Each end is found as agent/focus.py finds the lines a question points at (a quote, an identifier, a node's name, the
phrase's own words), with two words of the stack's own: "launch" is the log's first line, "the goal" the task's
start; "the FATAL", "the error" prefer a line of that level. Where either end cannot be found, nothing is said
(the question goes on to the other answers), never a guessed moment."""

from __future__ import annotations

import re
from itertools import pairwise

from hexar.agent.focus import ranked_lines
from hexar.events.log import EventLog
from hexar.events.records import ERROR, FATAL, WARN, LogLine, duration, hms
from hexar.events.tasks import Task
from hexar.explainers.base import Evidence, Explanation
from hexar.explainers.shutdown import CTRL_C

_ASKED = re.compile(
    r"\bhow (long|many seconds|much time) (did it take |was it |passed )?(after|before) (?P<a>.+?) (did|was|were|"
    r"does|is|until|till) (?P<b>.+)|"
    r"\bhow (long|many seconds|much time) (did (it|the \w+|\w+) take |was it |passed )?(from|between) (?P<a2>.+?) "
    r"(until|till|to|and) (?P<b2>.+)|"
    r"\b(gap|delay|pause|wait|silence|time|minutes?|seconds?) (between|from) (?P<a3>.+?) (and|to|until|till) "
    r"(?P<b3>.+)")
# "which came first, the global_costmap TF timeout or the AMCL warning?", "did the timeout come before the warning?"
_ORDER = re.compile(r"\b(which|what) (came|happened|was logged|showed up|appeared|was) first,? (?P<a>.+?),? or "
                    r"(?P<b>.+)|^(and |so )?did (?P<a2>.+?) (come|happen|appear|show up) (before|after) (?P<b2>.+)")
# ("did the launch fail": the error it failed with)
_LEVELS = ((re.compile(r"\bfatal\b"), FATAL), (re.compile(r"\b(errors?|fail(ed|s|ure)?|crash(ed)?)\b"), ERROR),
           (re.compile(r"\bwarn(ing)?s?\b"), WARN))
# launch's start (not "the launch fail", a moment of its own)
_LAUNCH = re.compile(r"^(the )?(launch|start(up)?|bring-?up|the beginning|the first line)"
                     r"( (started|began|was started))?\W*$")
# "the goal was sent", "the navigate_to_pose goal was accepted": the task's start
_GOAL = re.compile(r"^(the |my |a )?([a-z0-9_/]+ )?goal (was |got |is )?(sent|came|arrived?|received|started|accepted|"
                   r"began)\b|^(the )?(task|goal) (start(ed)?)\b")
# "Nav2 was active and ready for goals", "all the nodes were up": the lifecycle managers' "Managed nodes are active"
_READY = re.compile(r"^(the )?(nav2|navigation|(the )?(nav2 |navigation )?stack|everything|(all )?(the )?(nav2 |"
                    r"lifecycle )?nodes)( (stack|servers?))? (was |were |is |are |had |has |became |become |came |"
                    r"got |been )*(fully )?(active|ready|up|activated|brought up)\b")
# "how long after arm_controller was activated did the goal arrive?": "was" belongs to the first moment's words when
# a "did" or "until" splits the question later
_SPLIT = re.compile(r"\bhow (long|many seconds|much time) (did it take |was it |passed )?(after|before) (?P<a>.+) "
                    r"(did|does|until|till) (?P<b>.+)")
_INTERRUPT = re.compile(r"\bctrl.?c\b|\bsigint\b|\bthe interrupt\b")
MAX_BETWEEN = 3


def gap_said(ns: int) -> str:
    """A time between two lines as said: "300 ms", "5.6 s", "1 min 56 s"."""
    if ns < 500_000_000:
        return f"{max(ns, 0) / 1e6:.0f} ms"
    return f"{ns / 1e9:.1f} s" if ns < 60_000_000_000 else duration(ns)


# "how long was the robot stuck before the first planning error?": from the goal's start to the moment named
_BEFORE_ONE = re.compile(r"\bhow (long|many seconds|much time) (was|were|did|had) (?!.*\b(after|between|from)\b)"
                         r"[^?]*? (before|until|till) (?P<b>[^?]+)")


_QUOTED = re.compile(r"\"[^\"]+\"|“[^”]+”|(?<!\w)'[^']+'(?!\w)")


def _unquoted(q: str) -> str:
    """The question with each quoted line as one word: a line's own words ("Time between points 0 and 1 …") ask
    nothing."""
    return _QUOTED.sub("\x00", q)


def before_one(q: str) -> bool:
    """"How long was it stuck before the first planning error?": one moment named, the goal's start the other."""
    return _BEFORE_ONE.search(_unquoted(q)) is not None


def between_asked(q: str) -> bool:
    """The question (lower case) asks for the time between two moments it names, or which came first."""
    q = _unquoted(q)
    return _ASKED.search(q) is not None or _ORDER.search(q) is not None or _BEFORE_ONE.search(q) is not None


def spans_two(q: str) -> bool:
    """"How long did it take from launch until diff_drive_controller was activated?": a span between two moments
    named, not the task's own time (which "how long did it take?" alone asks)."""
    m = _ASKED.search(_unquoted(q))
    return m is not None and m.group("a2") is not None


def _ends(question: str) -> tuple[str, str] | None:
    # a quoted line is one moment, whatever words it holds ("between "ready to take commands" and ...")
    quotes = _QUOTED.findall(question)
    q = _QUOTED.sub(lambda m: f"\x00{quotes.index(m.group(0))}\x00", question)
    ends = _split_ends(q)
    if ends is None:
        return None
    a, b = (re.sub("\x00(\\d+)\x00", lambda m: quotes[int(m.group(1))], e) for e in ends)
    return a, b


def _split_ends(q: str) -> tuple[str, str] | None:
    m = _ASKED.search(q)
    if m is None:
        o = _ORDER.search(q)
        return None if o is None else ((o.group("a") or o.group("a2")).strip(" ?.!,"),
                                       (o.group("b") or o.group("b2")).strip(" ?.!,"))
    a = m.group("a") or m.group("a2") or m.group("a3")
    b = m.group("b") or m.group("b2") or m.group("b3")
    split = _SPLIT.search(q) if m.group("a") else None
    if split is not None:
        a, b = split.group("a"), split.group("b")
    return a.strip(" ?.!,"), b.strip(" ?.!,")


def moment(phrase: str, log: EventLog, task: Task) -> LogLine | int | None:
    """The first line (or, for the goal's start, the time) a phrase names ("the ctrl-c", "'Reached the goal!'")."""
    return _end(phrase, log, task, None)


def _end(phrase: str, log: EventLog, task: Task, after: int | None,
         first: LogLine | int | None = None) -> LogLine | int | None:
    """The line (or, for the goal's start, the time) a phrase names; for the second end, the first such line at or
    after the first end (`first`), never that line itself."""
    if _LAUNCH.match(phrase) and log.logs:
        return log.logs[0]
    # a line's own words, whole ("goal accepted"): that line, before any reading of them
    said = next((ln for ln in log.logs if ln.msg.strip().rstrip(".!").lower() == phrase.strip("\"'“”")
                 and (after is None or (ln.t >= after and ln is not first))), None)
    if said is not None:
        return said
    if _GOAL.match(phrase):
        return task.created
    if _READY.match(phrase) and (ready := _ready(log, task)) is not None:
        return ready
    if _INTERRUPT.search(phrase):  # launch's own line for Ctrl-C (explainers/shutdown.py)
        stop = next((ln for ln in log.logs if CTRL_C.match(ln.msg) and (after is None or ln.t >= after)), None)
        if stop is not None:
            return stop
    level = next((lv for pattern, lv in _LEVELS if pattern.search(phrase)), None)
    # one word of its own names a line only with its level ("the controller error")
    found = ranked_lines(phrase, log, None, by_words=True, least=1 if level is not None else 2, slack=0)
    if level is not None:
        found = [ln for ln in found if ln.level >= level] or found
    if after is not None:
        found = [ln for ln in found if ln.t >= after and ln is not first]
        if not found and level is None:
            # the second end is looked for after the first: one word of its own names a line there ("the result
            # coming back" after "Goal accepted": the first line on that names a result)
            found = [ln for ln in ranked_lines(phrase, log, None, by_words=True, least=1, slack=0)
                     if ln.t >= after and ln is not first]
    if not found:
        return None
    # "both controllers being active", "all nodes up": the last of the lines it names
    last = re.search(r"\b(both|all|every|last|each)\b", phrase) is not None
    return (max if last else min)(found, key=lambda ln: ln.t)


def _ready(log: EventLog, task: Task) -> LogLine | None:
    """The lifecycle managers' last "Managed nodes are active" before the goal's start, else their first."""
    from hexar.agent.all_up import active_lines

    done = active_lines(log)
    before = [ln for ln in done if ln.t <= task.created]
    return before[-1] if before else (done[0] if done else None)


def moment_said(end: LogLine | int, limit: int = 100) -> str:
    """A moment as said: "the goal's start at 07:05:50", or a line's node and words with its time."""
    if isinstance(end, int):
        return f"the goal's start at {hms(end)}"
    return f"{end.name or 'a node'}'s \"{' '.join(end.msg.split())[:limit]}\" at {hms(end.t)}"


def between(question: str, log: EventLog, task: Task) -> Explanation | None:
    """The time between the two moments the question names and the lines logged in between; None where either
    cannot be found in the log."""
    q = " ".join(question.lower().split())
    ends = _ends(q)
    if ends is None and (one := _BEFORE_ONE.search(q)) is not None:
        ends = ("the goal started", one.group("b").strip(" ?.!,"))
    if ends is None:
        return None
    if _ASKED.search(q) is None and _BEFORE_ONE.search(q) is None:
        return _order(ends, log, task)
    first = _end(ends[0], log, task, None)
    if first is None:
        return None
    t0 = first if isinstance(first, int) else first.t
    second = _end(ends[1], log, task, t0, first)
    if second is None:
        return None
    t1 = second if isinstance(second, int) else second.t
    text = f"{gap_said(t1 - t0)} passed from {moment_said(first)} to {moment_said(second)}."
    inside = [ln for ln in log.logs if t0 < ln.t < t1 and ln is not first and ln is not second]
    if not inside:
        text += " My log holds no line in between, so it does not say what took that time."
    else:
        notable = sorted(inside, key=lambda ln: (-ln.level, ln.t))[:MAX_BETWEEN]
        said = "; ".join(f"at {hms(ln.t)}, {ln.name or 'a node'}: \"{' '.join(ln.msg.split())[:100]}\""
                         for ln in sorted(notable, key=lambda ln: ln.t))
        text += (f" In between, my log holds {len(inside)} line{'s' if len(inside) > 1 else ''}"
                 f"{', among them' if len(inside) > len(notable) else ''}: {said}.")
        text += _silence([t0, *(ln.t for ln in inside), t1])
    lines = [e for e in (first, second) if not isinstance(e, int)]
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                       evidence=[Evidence.of_log("planner.plan_ok", ln) for ln in lines])


def _silence(times: list[int]) -> str:
    """Where most of a span passed with no line logged ("why a 4 minute gap between ..."), that stretch."""
    gaps = [(b - a, a, b) for a, b in pairwise(times)]
    gap, a, b = max(gaps)
    if gap < 1_000_000_000 or 2 * gap < times[-1] - times[0]:
        return ""
    return (f" {gap_said(gap)} of it passed with no line logged at all ({hms(a)} to {hms(b)}): no node reported "
            "waiting, a warning or an error then, so my log does not say what that time went to.")


def _order(ends: tuple[str, str], log: EventLog, task: Task) -> Explanation | None:
    """Which of two moments the question names came first, and how long before the other."""
    a, b = (_end(phrase, log, task, None) for phrase in ends)
    if a is None or b is None or a is b:
        return None
    ta, tb = (e if isinstance(e, int) else e.t for e in (a, b))
    (early, t0), (late, t1) = sorted([(a, ta), (b, tb)], key=lambda x: x[1])
    text = (f"First came {moment_said(early)}; {moment_said(late)} came {gap_said(t1 - t0)} later."
            if t1 > t0 else f"They came at the same moment: {moment_said(a)}, and {moment_said(b)}.")
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                       evidence=[Evidence.of_log("planner.plan_ok", e) for e in (early, late)
                                 if not isinstance(e, int)])


__all__ = ["before_one", "between", "between_asked", "gap_said", "moment", "moment_said", "spans_two"]
