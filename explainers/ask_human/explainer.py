"""The component explainer of the ask-human-for-help skill (paper section IV): counterfactuals from the causal
model on failure, templates for the non-failures (noisy detection, poor approach) on success."""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import cache
from itertools import pairwise
from typing import ClassVar

from hexar.events.contract import ASK_HUMAN_STATUS_NAME, EPISODIC_MEMORY
from hexar.events.records import StatusRecord
from hexar.explainers.ask_human.causal import CausalModel, Counterfactual, ancestors, search_counterfactual
from hexar.explainers.ask_human.variables import (
    APPROACH_ERROR_LIMIT,
    CAUSE_OF,
    DEFAULT_NOTE,
    MAX_DISTANCE,
    NOISE_LIMIT,
    TRANSITION_OF_STATE,
    WORLD,
    assignment,
    phrase,
)
from hexar.explainers.base import Context, Evidence, Explanation, TextModel
from hexar.explainers.errors import ExplainerError
from hexar.explainers.phrasing import phrase as llm_phrase
from hexar.explainers.registry import Registry

NAME = "ask_human_for_help"
_HOW_FAR = re.compile(r"\bhow (far|close|near)\b.*\b(person|people|human|someone|somebody|they|them|he|she|him|her)\b|"
                      r"\b(distance|far) (to|from) (the )?(person|human)\b")
SUCCEEDED = "ask_human.succeeded"
IN_PROGRESS = "ask_human.in_progress"
STEP_NAMES = {
    "DetectState": "looking for a person",
    "NavigateState": "going to the person",
    "AskForHelpState": "asking the person for help",
    "WaitForConfirmationState": "waiting for the person to confirm",
}


@dataclass(frozen=True)
class Step:
    record: StatusRecord
    key: str
    value: str

    def evidence(self, cause: str) -> Evidence:
        return Evidence(
            cause=cause, topic=EPISODIC_MEMORY, t=self.record.t, item=f"{self.key} = {self.value}"
        )


def last_execution(records: list[StatusRecord]) -> list[Step]:
    """The steps of the skill's last execution: from its last `InitialState` (or the window's start)."""
    steps = [
        Step(r, k, v)
        for r in records
        if r.name == ASK_HUMAN_STATUS_NAME or r.get("Module name") == "skill_ask_human_for_help"
        for k, v in r.data_items()
    ]
    starts = [i for i, s in enumerate(steps) if s.key == "InitialState"]
    return steps[starts[-1] :] if starts else steps


@cache
def shipped_model() -> CausalModel:
    """The packaged model, loaded once per process: it is read-only, and pgmpy takes a second to load it."""
    return CausalModel.load()


def chance(p: float) -> str:
    """0.82 -> "about 4 in 5": odds a person can use, with the smallest denominator that is close enough."""
    for d in range(2, 11):
        k = round(p * d)
        if abs(p - k / d) <= 0.03:
            if k == 0:
                return "almost no"
            return "almost a certain" if k == d else f"about {k} in {d}"
    return f"about {round(p * 100)} in 100"


def _likely(p: float) -> str:
    return "very likely" if p >= 0.8 else "probably"


def _cm(value: str) -> str:
    """Sub-metre values in centimetres, which read more naturally to a non-expert."""
    try:
        return f"{round(float(value) * 100)} cm"
    except ValueError:
        return value


class AskHumanForHelpExplainer:
    """f_e over `/episodic_memory`: why asking a person for help failed, or what went poorly when it
    worked."""

    name: ClassVar[str] = NAME
    topics: ClassVar[frozenset[str]] = frozenset({EPISODIC_MEMORY})
    description: ClassVar[str] = (
        "Explains the ask_human_for_help skill: the robot looks for a person, checks that the detection "
        "is stable and that the person is within 4 m, drives up to them, asks its question, and waits for "
        "them to agree and then to confirm that they helped. Use it for questions about not finding anybody, "
        "a person too far away, losing track of someone, failing to reach the person, a person who refused "
        "or did not answer or confirm, an awkward or poor approach, an uncertain (noisy) person detection, "
        "or why asking for help took long. It answers with the cause and what would have made the skill "
        "succeed."
    )

    def __init__(self, model: TextModel | None = None, registry: Registry | None = None) -> None:
        self.model = model
        self.registry = registry
        self._causal: CausalModel | None = None

    @property
    def causal(self) -> CausalModel:
        # Reading the shipped tables is cheap (queries run with NumPy, not pgmpy); still, only when asked.
        if self._causal is None:
            self._causal = shipped_model()
        return self._causal

    def explain(self, question: str, context: Context) -> Explanation:
        records = context.view(self.topics).statuses(EPISODIC_MEMORY)
        steps = last_execution(records)
        if not steps:
            return Explanation.not_enough(
                NAME,
                f"I have no record of asking anybody for help in that time ({EPISODIC_MEMORY} is empty).",
            )
        keys = [s.key for s in steps]
        if "SkillFailed" in keys and not any(k in TRANSITION_OF_STATE for k in keys):
            return Explanation.not_enough(
                NAME, "The recording shows that asking for help failed, but not in which step.")
        if "SkillFailed" in keys:
            found = self._failure(steps)
            found = self._with_navigation(question, context, steps, found)
        elif "SkillSucceeded" in keys:
            found = self._success(steps)
        else:
            found = self._in_progress(steps)
        found = found.model_copy(update={"details": [*found.details, *self._timing(steps)]})
        found = self._distance_asked(question, steps, found)
        facts = "\n".join([found.text, found.counterfactual or "", *found.details]).strip()
        return llm_phrase(self.model, NAME, question, facts, found)

    def _failure(self, steps: list[Step]) -> Explanation:
        observed = assignment((s.key, s.value) for s in steps)
        by_key = {s.key: s for s in steps}
        state = [s.key for s in steps if s.key in TRANSITION_OF_STATE][-1]
        transition = TRANSITION_OF_STATE[state]
        cf = search_counterfactual(self.causal, observed, transition)
        blamed = self._blamed(cf, observed, transition)
        cause_of = {v: CAUSE_OF.get((v, observed[v]), "ask_human.failed") for v in blamed}
        causes = list(dict.fromkeys(cause_of.values())) or ["ask_human.failed"]
        evidence = [by_key[v].evidence(cause_of[v]) for v in blamed if v in by_key]
        failed = by_key["SkillFailed"]
        evidence.append(failed.evidence(causes[0]))
        because = " and ".join(self._observed(v, by_key[v].value, observed[v]) for v in blamed if v in by_key)
        text = f"I could not get help: {because or 'the step of ' + STEP_NAMES[state] + ' failed'}."
        # The error string is left out on purpose: "Person not found" also ends unstable and too-far
        # detections, and would name the wrong cause.
        details = [f"The skill failed while {STEP_NAMES[state]}."]
        counterfactual = None
        if cf is not None:
            had = " and ".join(phrase(v, new) for v, _, new in cf.changes)
            if cf.flips:
                text += f" If {had}, I would {_likely(cf.p_success)} have got the help I needed."
            odds = chance(cf.p_success)
            counterfactual = (
                f"If {had}, I would {_likely(cf.p_success)} have got the help I needed ({odds} chance)."
                if cf.flips
                else f"Even if {had}, getting help would still not have been likely ({odds} chance)."
            )
            found = "the smallest one that makes success most likely" if cf.flips else "none makes success likely"
            details.append(
                f"I checked {cf.tried} possible change{'' if cf.tried == 1 else 's'} against what I learned from "
                f"{self.causal.meta.get('executions')} simulated runs of this skill; {found}: {had} "
                f"({odds} chance of success)."
            )
        return Explanation(
            explainer=NAME,
            text=text,
            causes=causes,
            evidence=evidence,
            counterfactual=counterfactual,
            details=details,
            fix=self._fix(causes[0]),
        )

    @staticmethod
    def _distance_asked(question: str, steps: list[Step], found: Explanation) -> Explanation:
        """"How far away was the person?": the distance I measured comes first, when the answer does not already
        give it (as the cause, "too far")."""
        measured = [s for s in steps if s.key == "person_distance"]
        if _HOW_FAR.search(question.lower()) is None or not measured or "I measured" in found.text:
            return found
        raw = measured[-1].value
        try:
            metres = float(raw)
        except ValueError:
            return found
        limit = "within" if metres <= MAX_DISTANCE else "beyond"
        lead = (f"I measured the person at {metres:.2f} m, {limit} my limit for asking ({MAX_DISTANCE} m, "
                f"{DEFAULT_NOTE}).")
        evidence = [*found.evidence, measured[-1].evidence(found.causes[0] if found.causes else SUCCEEDED)]
        return found.model_copy(update={"text": f"{lead} {found.text}", "evidence": evidence})

    @staticmethod
    def _observed(var: str, raw: str, value: str) -> str:
        said = phrase(var, value)
        if var == "person_distance" and value == "gt_4.0":
            return f"{said} (I measured {raw} m; the limit is {DEFAULT_NOTE})"
        if var == "person_distance":
            return f"{said} (I measured {raw} m)"
        return said

    @staticmethod
    def _blamed(cf: Counterfactual | None, observed: dict[str, str], transition: str) -> list[str]:
        """The variables the counterfactual changed; without one, the transition's causes that were bad."""
        if cf is not None and cf.flips:
            return [v for v, _, _ in cf.changes]
        return [v for v in WORLD if v in ancestors(transition) and (v, observed[v]) in CAUSE_OF][:1]

    @staticmethod
    def _fix(cause: str) -> str | None:
        return {
            "ask_human.nobody_detected": "Ask for help where people usually are, or try again later.",
            "ask_human.person_too_far": "Move closer to the person (within 4 m, my default limit) before asking.",
            "ask_human.unstable_detection": "Wait until the person stays in view long enough to be tracked.",
            "ask_human.navigation_failed": "Clear the way to the person.",
            "ask_human.refused": "Ask someone else, or ask again later.",
            "ask_human.not_confirmed": "Tell the robot when you have helped.",
        }.get(cause)

    def _success(self, steps: list[Step]) -> Explanation:
        observed = assignment((s.key, s.value) for s in steps)
        by_key = {s.key: s for s in steps}
        noisy = observed["person_std_rms"] == "gt_0.5"
        poor = observed["robot_nav_err"] == "gt_0.5"
        if not noisy and not poor:
            done = by_key["SkillSucceeded"]
            evidence = [done.evidence(SUCCEEDED)]
            if "user_confirmed" in by_key:
                evidence.insert(0, by_key["user_confirmed"].evidence(SUCCEEDED))
            return Explanation(
                explainer=NAME,
                text="Asking for help went as planned: I found a person, they agreed to help and "
                "confirmed it.",
                causes=[SUCCEEDED],
                evidence=evidence,
                details=["Nothing went wrong in the ask-for-help skill."],
            )
        # Consult the model: how likely a poor approach is with a steady detection, everything else as it was.
        kept = {"navigation_failure": "false"}
        p_steady = self.causal.probability("robot_nav_err", "gt_0.5", {"person_std_rms": "le_0.5"}, kept)
        p_noisy = self.causal.probability("robot_nav_err", "gt_0.5", {"person_std_rms": "gt_0.5"}, kept)
        if noisy:
            cause = "ask_human.noisy_detection"
            std = by_key["person_std_rms"]
            evidence = [std.evidence(cause)]
            text = (
                "I got help, but my detection of the person was uncertain: their position varied by "
                f"{_cm(std.value)}, more than my limit of {_cm(str(NOISE_LIMIT))} ({DEFAULT_NOTE})"
            )
            if poor:
                evidence.append(by_key["robot_nav_err"].evidence(cause))
                text += (
                    ", so the place I drove to beside them was "
                    f"{_cm(by_key['robot_nav_err'].value)} from where it should have been"
                )
            text += "."
            counterfactual = (
                f"Had the person's position varied by less than my default limit of {_cm(str(NOISE_LIMIT))} "
                f"(it varied by "
                f"{_cm(std.value)}), a poor approach would have had {chance(p_steady)} chance instead of "
                f"{chance(p_noisy)}."
            )
            return Explanation(
                explainer=NAME,
                text=text,
                causes=[cause],
                evidence=evidence,
                counterfactual=counterfactual,
                details=[
                    "The skill tolerated the noisy detection and went on; the goal it drove to was the noisy "
                    "position of the person."
                ],
                fix="Let the person stand still in view so the detection settles before approaching.",
            )
        cause = "ask_human.poor_approach"
        err = by_key["robot_nav_err"]
        spread = by_key.get("person_std_rms")
        known = (f"I knew where the person was to within {_cm(spread.value)}" if spread is not None
                 else "My detection of the person was not noisy")
        text = (
            f"I got help, but my approach to the person was poor: I stopped {_cm(err.value)} away from "
            f"where I should have, more than my limit of {_cm(str(APPROACH_ERROR_LIMIT))} ({DEFAULT_NOTE}), "
            "although I had located them well."
        )
        return Explanation(
            explainer=NAME,
            text=text,
            causes=[cause],
            evidence=[err.evidence(cause)],
            counterfactual=(
                f"{known}, and then a poor approach has only {chance(p_steady)} chance: it came from my "
                "navigation's final approach, so a better final approach would have put me in the right place."
            ),
            fix="Give me a little more room around the person, or have my navigation's final approach (its "
            "goal tolerance) checked.",
            details=[
                "The person's position was known precisely, so the error comes from navigation, "
                "not perception."
            ],
        )

    def _in_progress(self, steps: list[Step]) -> Explanation:
        last = steps[-1]
        return Explanation(
            explainer=NAME,
            text=f"I was still asking for help; the last thing I recorded was: {last.record.message}.",
            causes=[IN_PROGRESS],
            evidence=[last.evidence(IN_PROGRESS)],
            confidence=0.5,
        )

    def _with_navigation(
        self, question: str, context: Context, steps: list[Step], found: Explanation
    ) -> Explanation:
        """The navigation explainer says why the approach failed; our part stands without it."""
        if "ask_human.navigation_failed" not in found.causes or context.registry is None:
            return found
        by_key = {s.key: s for s in steps}
        window = (by_key["NavigateState"].record.t, by_key["navigation_failure"].record.t)
        try:
            nav = context.registry.get("navigation").explain(question, context.with_window(window))
        except (ExplainerError, KeyError):
            return found
        if not nav.enough_information:
            return found
        return found.model_copy(
            update={
                "text": f"{found.text} {nav.text}",
                "causes": [*found.causes, *(c for c in nav.causes if c not in found.causes)],
                "evidence": [*found.evidence, *nav.evidence],
                "details": [*found.details, f"Navigation: {nav.text}", *nav.details],
                "fix": nav.fix or found.fix,
            }
        )

    @staticmethod
    def _timing(steps: list[Step]) -> list[str]:
        """Where the time went, for "why did it take so long?"."""
        if len(steps) < 2:
            return []
        gaps = [(b.record.t - a.record.t, b) for a, b in pairwise(steps)]
        longest, step = max(gaps, key=lambda g: g[0])
        total = (steps[-1].record.t - steps[0].record.t) / 1e9
        return [
            f"The skill ran for {total:.1f} s; the longest step was {longest / 1e9:.1f} s until "
            f"'{step.record.message}'."
        ]
