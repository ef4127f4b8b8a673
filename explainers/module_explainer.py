"""The shared flow of the log-reading component explainers of the arm (manipulation: MoveIt 2; control:
ros2_control): read the window's /rosout through the module's mined catalogue, decide by evidence
(explainers/logcause.py), word the finding, and ask another explainer when the decisive line is its module's.
A bring-up line (explainers/stack_causes.py) and a driver's error line that states its why in standard words (a
strerror text, a version or parameter wording: explainers/stated_causes.py) are ranked with the catalogue's lines;
with no cause, the answer quotes the first error with its node and time and names the candidates.

What each subclass gives: its name, topics and description, its skills (the plan steps it explains), the
catalogues to read with (its own first), its cause prefix, and `words(cause, ...)` -> (sentence, fix, details).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, ClassVar

from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.events.records import ERROR, WARN, LogLine
from hexar.events.tasks import SkillRun
from hexar.explainers.base import Context, Evidence, Explanation, TextModel
from hexar.explainers.bringup_answer import derived_start, driver_candidates, start_answer
from hexar.explainers.logcause import Diagnosis, ModuleCatalogue, Reading, at, diagnose, read, said
from hexar.explainers.module_wording import nav2_logger, verbatim, warned_on_the_way
from hexar.explainers.phrasing import phrase
from hexar.explainers.recorded import join_words
from hexar.explainers.shutdown import before_shutdown
from hexar.explainers.stack.actions import action_finding
from hexar.explainers.stack.bringup import PROCESS_SUFFIX
from hexar.explainers.stack.signals import ended_by, killed_by_signal
from hexar.explainers.stack_causes import (
    mixed_clocks,
    one_shot_failed,
    stack_cause,
    stack_words,
    uncaught,
)
from hexar.explainers.stated_causes import adopt, first_thrown, stated_cause, stated_words

if TYPE_CHECKING:
    from hexar.explainers.registry import Registry

MAX_FACT_LINES = 40
# Which explainer tells a cause of another module (the manipulation explainer asks control for a controller's).
OWNER = {"manipulation.": "manipulation", "control.": "control"}


def focus(context: Context, skills: tuple[str, ...]) -> SkillRun | None:
    """The step this window is about: the failed one of these skills, else the last one inside the window."""
    failed = context.task.failed_skill
    if failed is not None and failed.skill in skills:
        return failed
    inside = [r for r in inside_window(context, skills) if r.history]
    return inside[-1] if inside else None


def inside_window(context: Context, skills: tuple[str, ...]) -> list[SkillRun]:
    """The task's steps of these skills that overlap the context's window, in plan order."""
    lo, hi = context.window
    return [r for r in context.task.skills if r.skill in skills
            and context.task.skill_window(r)[0] < hi and context.task.skill_window(r)[1] > lo]


def evidence_of(cause: str, readings: list[Reading]) -> list[Evidence]:
    return [Evidence.of_log(cause, r.line) for r in readings]


class ModuleExplainer:
    """Base of the arm's log explainers (see the module docstring)."""

    name: ClassVar[str]
    topics: ClassVar[frozenset[str]] = frozenset({c.ROSOUT})
    description: ClassVar[str]
    skills: ClassVar[tuple[str, ...]]
    prefix: ClassVar[str]
    module_words: ClassVar[str]  # "my arm's motion", "my controllers"
    # catalogue entries that only report that a step failed, not why, where the why is one of several causes:
    # entry id -> the candidates, told beside the quoted line instead of one of them
    ambiguous: ClassVar[dict[str, str]] = {}
    # the candidates told when no line says why (module words only: no cause pattern reads them as a claim)
    candidates: ClassVar[str] = ""
    # what rclpy's action layer tells of a goal (explainers/stack/actions.py), by kind, as this module's cause
    action_causes: ClassVar[dict[str, str]] = {}

    def __init__(self, model: TextModel | None = None, registry: Registry | None = None) -> None:
        self.model = model
        self.registry = registry

    def catalogues(self) -> list[ModuleCatalogue]:
        raise NotImplementedError

    def applies(self, log: EventLog) -> bool:
        """Whether the recording shows this module at all: a line its catalogues tie to a cause, a symptom or a
        goal, or an arm action's status. A robot without an arm is not asked (the all-components baseline)."""
        if any(c.topic_key(s.topic) in c.ARM_STATUS_TOPICS for s in log.goal_statuses):
            return True
        cats = self.catalogues()
        return any(e is not None and e.kind != "other" for ln in log.logs for e in (cat.match(ln.msg) for cat in cats))

    def refine(self, readings: list[Reading]) -> list[Reading]:
        """A module's reading of what a line's numbers say (e.g. MoveIt's state-monitor times)."""
        return readings

    def words(self, cause: str, d: Diagnosis, what: str) -> tuple[str, str | None, list[str]]:
        raise NotImplementedError

    def decided(self, lines: list[LogLine], context: Context) -> Explanation | None:
        """What a module reads from the whole window before any goal or catalogue line, whatever they say (none by
        default); `context` gives the lines around the window (`lines_after`, `readings_before`)."""
        return None

    def reason_before(self, context: Context, d: Diagnosis) -> Diagnosis:
        """A module's reading of the lines before the goal that say why its decisive line happened."""
        return d

    def readings_before(self, context: Context) -> list[Reading]:
        """The module's catalogues' reading of the recording's lines before the window (none when it starts the
        recording)."""
        if context.window[0] <= 0:
            return []
        return read(context.view(self.topics, (0, context.window[0] - 1)).logs(), self.catalogues())

    @staticmethod
    def lines_after(context: Context) -> list[LogLine]:
        """The recording's lines after the window, up to where the stack began to shut down."""
        return before_shutdown([ln for ln in context.log.logs if ln.t > context.window[1]])

    def explain(self, question: str, context: Context) -> Explanation:
        # what a stack prints as it is stopped explains nothing before; where the stopping began is read from the
        # window's start to the recording's end (a goal aborted just after launch's ctrl-c line, printed after it
        # by its pipe, ends inside the window, while the signals launch sends come after it)
        rest = context.view(self.topics, (context.window[0], context.log.end)).logs()
        lines = [ln for ln in before_shutdown(rest) if ln.t <= context.window[1]]
        if not lines:
            return Explanation.not_enough(self.name, "The recording has no log lines for that time.")
        told = self.decided(lines, context)
        if told is not None:
            return phrase(self.model, self.name, question, self._facts(lines, told), told)
        run = focus(context, self.skills)
        step = context.task.skills[0] if len(context.task.skills) == 1 else None
        if derived_start(step) and step is not None:
            # no task, no goal: the robot's start, which completed or is still under way (a failed one is below)
            kept = {id(ln) for ln in lines}
            down = [ln for ln in context.log.logs if id(ln) not in kept and ln.t >= context.task.created]
            told = start_answer(self.name, self.prefix, step, lines, context.task.created, question, down)
            return phrase(self.model, self.name, question, self._facts(lines, told), told)
        readings = self.refine([r for r in read(lines, self.catalogues()) if not _other_module(r)])
        d = self.reason_before(context, diagnose(readings, run.state if run is not None else None))
        if d.outcome == "succeeded":
            # a goal that completed: warnings and errors on the way did not stop it (many healthy arms print some)
            d = Diagnosis("succeeded", end=d.end)
        else:
            stack = stack_cause(lines)
            if stack is not None and stack.cause == "bringup.process_died" and one_shot_failed(stack.line.msg):
                # a spawner's exit tells that its controller failed: the controller manager's lines say why
                d.symptoms = [stack, *d.symptoms][:2] if d.decisive is None else d.symptoms
                stack = None
            if stack is not None and stack.cause == "bringup.process_died" and d.decisive is None \
                    and d.unknown is not None and d.unknown.t < stack.line.t and d.unknown.level >= ERROR:
                # a process that died after an error no catalogue explains: the death is that error's consequence
                d.symptoms = [stack, *d.symptoms][:2]
            elif stack is not None and stack.cause == "bringup.process_died" and d.decisive is None \
                    and killed_by_signal(stack.line.msg) and not _crash_alone(stack.line, d, context.log.logs):
                # a crash (SIGSEGV, SIGABRT): what made the program crash is not in its death line, so the death
                # is quoted as the first error, never told as the cause
                d.unknown = stack.line
            elif stack is not None and (d.decisive is None or stack.line.t < d.decisive.line.t):
                # a cause, or a crash or kill with no warning or error before it: the death is all the lines show
                d.cause, d.decisive, d.support = stack.cause, stack, []
                d.symptoms = [r for r in d.symptoms if r.line.t >= stack.line.t][:2]
            # a driver's own error line whose why is a strerror text or a set-up wording: ranked with the rest
            before = d.end.t if d.end is not None else None
            # launch's lines ("process started", which Nav2's catalogue knows too) carry a process's exception
            own = [ln for ln in lines if not nav2_logger(ln)]
            adopt(d, stated_cause(own, self.prefix, before))
            action = action_finding(own) if d.cause is None else None
            if action is not None and (cause := self.action_causes.get(action.kind)) is not None:
                # the server refused or ended the goal itself: its own error, if any, is kept as the support
                d.cause, d.decisive = cause, Reading(action.line, None, cause, "stack", "action")
                d.support = [Reading(action.reason, None, cause, None)] if action.reason is not None else []
            if d.cause is None and d.unknown is None:
                d.unknown = first_thrown(own, before)
            died = uncaught(own, before) if d.cause is None else None
            if died is not None and (d.unknown is None or died.t <= d.unknown.t):
                if (clocks := mixed_clocks(died)) is not None:
                    d.unknown, d.candidates = died, clocks  # the exception's meaning, not the death, tells it
                else:
                    # nothing explained comes before an uncaught C++ exception: its process died there, which is
                    # what the lines show (an unexplained error before it would be the death's cause, quoted
                    # instead)
                    d.cause, d.decisive, d.support = ("bringup.process_died",
                                                      Reading(died, None, "bringup.process_died", "stack"), [])
        if d.cause is not None and not d.cause.startswith(self.prefix):
            asked = self._ask_owner(question, context, d)
            if asked is not None:
                return asked
        grounded = self._compose(context, d, readings, run)
        if grounded.causes == [f"{self.prefix}nominal"] and (seen := warned_on_the_way(lines, context.task.created)):
            # it went well, and what it warned of on the way is told as the log's words (a control loop that missed
            # its rate says why a motion was slow), never as a cause
            grounded = grounded.model_copy(update={"text": f"{grounded.text} {seen}"})
        return phrase(self.model, self.name, question, self._facts(lines, grounded), grounded)

    def _ask_owner(self, question: str, context: Context, d: Diagnosis) -> Explanation | None:
        """The decisive line is another module's (a controller's tolerance abort under a MoveIt execution):
        that module's explainer tells it, with this module's symptom kept as the first detail."""
        owner = next((name for pre, name in OWNER.items() if d.cause and d.cause.startswith(pre)), None)
        if owner is None or self.registry is None or owner not in self.registry.classes or owner == self.name:
            return None
        theirs = self.registry.get(owner).explain(question, context)
        if not theirs.enough_information or d.cause not in theirs.causes:
            return None
        symptom = next((r for r in d.symptoms), None)
        first = (f"I asked my {owner} explainer, because the decisive line was {owner}'s"
                 + (f"; my own log then said '{said(symptom.line)}'." if symptom else "."))
        return theirs.model_copy(update={"explainer": self.name, "details": [first, *theirs.details]})

    def _compose(self, context: Context, d: Diagnosis, readings: list[Reading], run: SkillRun | None
                 ) -> Explanation:
        start = context.task.created
        if d.cause is None and d.outcome == "failed":
            cause = f"{self.prefix}unexplained_failure"
            first = d.unknown
            ev = [Evidence.of_log(cause, first)] if first is not None else []
            ev += evidence_of(cause, d.symptoms)
            # the error's first line: a console's continuation lines (a C++ what(), a traceback) follow from it
            quoted = (f" The first error was {verbatim(first)} at {at(first, start)}."
                      if first is not None else self._last_said(d, start))
            # what is left open, in words no cause pattern reads as a claim: the line's own, else the module's
            maybe = (f" Its words say that {d.candidates}." if d.candidates
                     else f" {driver_candidates(run, first) or self.candidates_of(first)}")
            return Explanation(
                explainer=self.name, causes=[cause], evidence=ev, confidence=0.4,
                # a line whose words leave candidates is no line the logs say nothing of: their why is still open
                text=(f"{_upper(self._what(run))} failed, and I can't tell why for sure." if d.candidates and
                      first is not None else
                      f"{_upper(self._what(run))} failed, but my {self.name} logs do not show a cause I know.")
                + quoted + maybe,
                fix="Read that node's own log around that time; the decisive line may be at DEBUG level." if first
                else "Record /rosout at INFO level from move_group and the controller manager.",
                details=[*(f"The last line about it was '{said(r.line)}'." for r in d.symptoms[:1]),
                         *(f"That line means: {r.entry.meaning}." for r in d.symptoms[:1] if r.entry is not None),
                         f"The last line about it was '{said(d.end)}'." if d.end else
                         "No line of the catalogue names a cause."])
        if d.cause is None:
            if d.outcome == "unknown" and not any(r.entry is not None for r in readings):
                return Explanation.not_enough(
                    self.name, f"The recording does not show what {self.module_words} did then.")
            if d.outcome == "unknown":
                return Explanation.not_enough(
                    self.name, f"The recording ends before {self.module_words} finished, and shows no error.")
            cause = f"{self.prefix}nominal"
            ends = [r.line for r in readings if r.kind in {"begin", "begin_server", "succeeded", "end_server"}]
            d.decisive = None
            text, fix, details = self.words(cause, d, self._done(context, run))
            return Explanation(explainer=self.name, text=text, causes=[cause], fix=fix, details=details,
                               evidence=[Evidence.of_log(cause, ln) for ln in ends[:1] + ends[-1:]][:2])
        decisive = d.decisive
        assert decisive is not None
        if d.outcome == "unknown" and not decisive.strong and not decisive.refined:
            return self._unsure(decisive, start)
        if decisive.entry is not None and decisive.entry.id in self.ambiguous and decisive.note == "":
            return self._candidates(decisive, self.ambiguous[decisive.entry.id], start, run)
        cause = d.cause
        what = self._what(run)
        text, fix, details = (stated_words(d, what, self.prefix, start) or stack_words(cause, d, what)
                              or self.words(cause, d, what))
        ev = [Evidence.of_log(cause, decisive.line), *evidence_of(cause, d.support), *evidence_of(cause, d.symptoms)]
        if d.end is not None and all(e.t != d.end.t for e in ev):
            ev.append(Evidence.of_log(cause, d.end))
        source = decisive.entry.source if decisive.entry is not None else ""
        details = [*details, f"The decisive line, at {at(decisive.line, start)}: '{said(decisive.line)}'"
                   + (f" (its source: {source.split(' (')[0]})." if source else ".")]
        if d.symptoms:
            details.append(f"What followed it is a consequence, not the cause: '{said(d.symptoms[0].line)}'.")
        if d.outcome == "unknown":
            text = (f"The recording ends before {self.module_words} finished; on the way my logs show a problem. "
                    + text)
        return Explanation(explainer=self.name, text=text, causes=[cause], evidence=ev, fix=fix, details=details,
                           confidence=0.9 if decisive.strong else 0.6)

    def candidates_of(self, first: LogLine | None) -> str:
        """What is left open when `first`, the first error, names no cause: the module's candidates."""
        return self.candidates

    def _unsure(self, decisive: Reading, start: int) -> Explanation:
        """No line ends the goal, and the only problem line is one many healthy robots print too (a weak cause):
        quoted with its node and time, and neither a failure nor a cause is claimed."""
        line = decisive.line
        meaning = decisive.entry.meaning if decisive.entry is not None else ""
        return Explanation(
            explainer=self.name, causes=[], evidence=[Evidence.of_log("warning", line)], confidence=0.3,
            text=f"The recording ends before {self.module_words} finished. On the way, "
                 f"{verbatim(line)} at {at(line, start)}; healthy robots print it too, so my "
                 f"logs do not show whether anything went wrong.",
            details=[f"That line means: {meaning}."] if meaning else [])

    def _candidates(self, decisive: Reading, candidates: str, start: int, run: SkillRun | None) -> Explanation:
        """The decisive line reports a failed step whose reason could be one of several causes: quoted with its
        node and time and the candidates, none claimed."""
        cause = f"{self.prefix}unexplained_failure"
        line = decisive.line
        source = decisive.entry.source.split(" (")[0] if decisive.entry is not None else ""
        return Explanation(
            explainer=self.name, causes=[cause], evidence=[Evidence.of_log(cause, line)], confidence=0.4,
            text=f"{_upper(self._what(run))} failed, but my {self.name} logs do not show a cause I know: "
                 f"{verbatim(line)} at {at(line, start)} says only that a step failed. "
                 f"{candidates}",
            fix="Read the lines of that component just before it, at DEBUG level if need be: they decide which.",
            details=[f"That line's source: {source}." if source else "No line before it says why."])

    @staticmethod
    def _last_said(d: Diagnosis, start: int) -> str:
        """Where the failure was told, when no error line says why: the node and the time of the last line about
        it (its words stay in the details: they name the consequence, not the cause)."""
        last = d.symptoms[0].line if d.symptoms else d.end
        if last is None:
            return ""
        who = last.name or "a node"
        return f" The failure was told by {who} at {at(last, start)}, and no line before it says why."

    def _done(self, context: Context, run: SkillRun | None) -> str:
        """What the arm did in a window where it all went well: every pick and place in it ("did you pick up the
        cup?" about a whole fetch is not answered with its last step, the putting down)."""
        runs = [r for r in inside_window(context, ("pick", "place")) if r.state == "succeeded"]
        if len(runs) < 2:
            return self._what(run)
        objects = {r.params.get("object") for r in runs}
        if [r.skill for r in runs] == ["pick", "place"] and len(objects) == 1:
            return f"{self._what(runs[0])} and putting it down"
        return join_words(list(dict.fromkeys(self._what(r) for r in runs)))

    def _what(self, run: SkillRun | None) -> str:
        if run is None:
            return self.module_words
        if run.skill == "bring_up_controllers":
            return "starting my drivers and controllers"
        obj = run.params.get("object")
        if run.skill in {"pick", "place"} and isinstance(obj, str) and obj:
            return f"{'picking up' if run.skill == 'pick' else 'putting down'} the {obj.replace('_', ' ')}"
        return self.module_words

    @staticmethod
    def _facts(lines: list[LogLine], grounded: Explanation) -> str:
        out = ["Findings (the only causes you may state):"]
        out += [f"- {cause}" for cause in grounded.causes]
        out += [f"- {detail}" for detail in grounded.details]
        out.append(f"Template answer: {grounded.text}")
        if grounded.fix:
            out.append(f"Suggested fix: {grounded.fix}")
        out.append("Log (oldest first):")
        out += [line.render() for line in lines[-MAX_FACT_LINES:]]
        return "\n".join(out)


def _upper(text: str) -> str:
    return text[:1].upper() + text[1:]


def _other_module(r: Reading) -> bool:
    """A Nav2 line (by its text or its logger's Nav2 role) is navigation's to explain, never an unknown error
    of the arm."""
    if r.catalogue is not None:
        return False
    from hexar.explainers.navigation.catalogue import catalogue as nav2

    cat = nav2()
    return cat.role(r.line.name) is not None or cat.match(r.line.msg) is not None


# ros2_control_node runs the hardware interfaces' drivers in its own process: its crash is most often a driver's (a
# device that is not there, a plugin given wrong parameters), which its death line does not show
_RUNS_DRIVERS = ("ros2_control_node", "controller_manager")


def _crash_alone(died: LogLine, d: Diagnosis, lines: Sequence[LogLine]) -> bool:
    """A process a signal ended (a kill, a segfault: explainers/stack/signals.py) with no warning or error before it
    but launch's, and not a crash of the process that runs the drivers: nothing else the lines show can be what went
    wrong."""
    signal = ended_by(died.msg)
    if PROCESS_SUFFIX.sub("", died.name or "") in _RUNS_DRIVERS and (signal is None or signal.name != "SIGKILL"):
        return False  # a driver's crash has its cause in the driver; a kill comes from outside the process
    # what followed the death (spawners that could no longer reach the controller manager) is its consequence
    return signal is not None and d.unknown is None and not any(r.line.t < died.t for r in d.symptoms) and not any(
        ln.level >= WARN and ln.t <= died.t and ln is not died and not PROCESS_SUFFIX.search(ln.name or "")
        for ln in lines)
