"""Simulator of the ask-human-for-help skill: its state machine, the `/episodic_memory` it writes, and the
random worlds it meets (for the causal model's training data and for Table I scenarios 11-18)."""

from __future__ import annotations

import random
from collections.abc import Callable
from dataclasses import dataclass, replace

from hexar.evals.scenarios.bag import BagBuilder, SkillResult, sec_ns
from hexar.events.contract import ASK_HUMAN_STATUS_NAME, EPISODIC_MEMORY
from hexar.explainers.ask_human.variables import APPROACH_MARGIN, MAX_DISTANCE, assignment

MODULE = "skill_ask_human_for_help"
ANSWER_TIMEOUT_S = 45.0
CONFIRM_TIMEOUT_S = 30.0
NAVIGATION_TIMEOUT_S = 30.0
SEARCH_TIMEOUT_S = 10.0

ERR_NOT_FOUND = "Person not found"
ERR_NAVIGATION = "Navigation to the person failed"
ERR_DECLINED = "The person declined to help or did not answer"
ERR_NOT_CONFIRMED = "The person did not confirm completion"

Step = tuple[str, str, str]


@dataclass(frozen=True)
class AskHumanConditions:
    """The world the skill meets. `None` for an answer means nobody answered before the timeout."""

    person_detected: bool
    detection_stable: bool
    person_distance: float
    person_std_rms: float
    navigation_failure: bool
    robot_nav_err: float
    user_accepted: bool | None
    user_confirmed: bool | None


def _navigates(d: float) -> bool:
    return APPROACH_MARGIN <= d <= MAX_DISTANCE


def random_conditions(rng: random.Random) -> AskHumanConditions:
    """A broad world where each step mostly works, with every failure mode common enough to be learned."""
    detected = rng.random() < 0.85
    noisy = rng.random() < 0.18
    std = rng.uniform(0.55, 1.3) if noisy else rng.uniform(0.05, 0.48)
    # A noisy track is often lost; a steady one rarely is.
    stable = rng.random() < (0.5 if noisy else 0.95)
    band = rng.random()
    if band < 0.2:
        distance = rng.uniform(0.3, 0.74)
    else:
        distance = rng.uniform(0.75, 4.0) if band < 0.88 else rng.uniform(4.05, 7.5)
    # Longer approaches meet more obstacles.
    nav_fail = rng.random() < (0.05 if distance <= 2.0 else 0.13)
    # The goal is the detected position, so a noisy detection spoils the final approach.
    if noisy:
        nav_err = rng.uniform(0.35, 1.2)
    else:
        nav_err = rng.uniform(0.55, 1.1) if rng.random() < 0.12 else rng.uniform(0.03, 0.45)
    # People are less willing to help a robot that stops awkwardly far or close.
    p_accept = 0.75 if _navigates(distance) and nav_err > 0.5 else 0.9
    accepted: bool | None = True if rng.random() < p_accept else (False if rng.random() < 0.6 else None)
    confirmed: bool | None = True if rng.random() < 0.93 else (False if rng.random() < 0.5 else None)
    return AskHumanConditions(detected, stable, distance, std, nav_fail, nav_err, accepted, confirmed)


def _machine(cond: AskHumanConditions) -> tuple[list[Step], str]:
    """The steps and the skill's error message ("" on success)."""
    # Decide on the values as recorded, so that a recording never contradicts the transition it led to.
    std, dist, err = (
        round(cond.person_std_rms, 3),
        round(cond.person_distance, 2),
        round(cond.robot_nav_err, 2),
    )
    steps: list[Step] = [
        ("Skill started", "InitialState", "True"),
        ("No person approached yet", "person_approached", "False"),
        ("Looking for a person to ask for help", "DetectState", "True"),
    ]

    def fail(error: str) -> tuple[list[Step], str]:
        steps.append((f"Skill failed: {error}", "SkillFailed", "True"))
        return steps, error

    if not cond.person_detected:
        steps.append(("No person detected", "person_detected", "False"))
        return fail(ERR_NOT_FOUND)
    steps.append(("Person detected", "person_detected", "True"))
    steps.append((f"Spread of the person's detected position: {std} m", "person_std_rms", str(std)))
    if not cond.detection_stable:
        steps.append(
            ("Lost track of the person before the detection was stable", "detection_stable", "False")
        )
        return fail(ERR_NOT_FOUND)
    steps.append(("Detection stable", "detection_stable", "True"))
    steps.append((f"Person at {dist} m", "person_distance", str(dist)))
    if dist > MAX_DISTANCE:
        return fail(ERR_NOT_FOUND)
    if dist >= APPROACH_MARGIN:
        steps.append(("Navigating to the person", "NavigateState", "True"))
        if cond.navigation_failure:
            steps.append(("Navigation to the person failed", "navigation_failure", "True"))
            return fail(ERR_NAVIGATION)
        steps.append(("Reached the person", "navigation_failure", "False"))
        steps.append((f"Final approach error: {err} m", "robot_nav_err", str(err)))
    steps.append(("Asking the person for help", "AskForHelpState", "True"))
    if cond.user_accepted is None:
        steps.append((f"No answer within {ANSWER_TIMEOUT_S:.0f} s", "user_accepted", "None"))
        return fail(ERR_DECLINED)
    if not cond.user_accepted:
        steps.append(("The person declined to help", "user_accepted", "False"))
        return fail(ERR_DECLINED)
    steps.append(("The person agreed to help", "user_accepted", "True"))
    steps.append(("Waiting for the person to confirm", "WaitForConfirmationState", "True"))
    if cond.user_confirmed is None:
        steps.append((f"No confirmation within {CONFIRM_TIMEOUT_S:.0f} s", "user_confirmed", "None"))
        return fail(ERR_NOT_CONFIRMED)
    if not cond.user_confirmed:
        steps.append(("The person said they had not helped", "user_confirmed", "False"))
        return fail(ERR_NOT_CONFIRMED)
    steps.append(("The person confirmed", "user_confirmed", "True"))
    steps.append(("Skill succeeded", "SkillSucceeded", "True"))
    return steps, ""


def run_state_machine(cond: AskHumanConditions) -> list[Step]:
    """(message, key, str(value)) for each step the state machine records, in order; pure and
    deterministic."""
    return _machine(cond)[0]


def _delay(rng: random.Random, key: str, value: str, cond: AskHumanConditions) -> float:
    """Seconds from the previous step to this one."""
    if key == "person_detected":
        return rng.uniform(1.5, 5.0) if value == "True" else SEARCH_TIMEOUT_S + rng.uniform(0.0, 0.3)
    if key == "person_std_rms":
        return rng.uniform(0.5, 1.5)
    if key == "detection_stable":
        return rng.uniform(1.5, 3.0) if value == "True" else rng.uniform(0.5, 2.0)
    if key == "navigation_failure":
        if value == "True":
            return rng.uniform(0.5, 1.0) * NAVIGATION_TIMEOUT_S
        return min(NAVIGATION_TIMEOUT_S - 1.0, cond.person_distance / 0.4 + rng.uniform(2.0, 5.0))
    if key == "user_accepted":
        return {"True": rng.uniform(3.0, 15.0), "False": rng.uniform(3.0, 10.0)}.get(value, ANSWER_TIMEOUT_S)
    if key == "user_confirmed":
        return {"True": rng.uniform(5.0, 25.0), "False": rng.uniform(5.0, 20.0)}.get(value, CONFIRM_TIMEOUT_S)
    return rng.uniform(0.05, 0.3)


def simulate_ask_human(
    b: BagBuilder,
    rng: random.Random,
    start: int,
    cond: AskHumanConditions,
    *,
    question: str,
    navigate: Callable[[int], SkillResult] | None = None,
) -> SkillResult:
    """Write one execution to `/episodic_memory`, step by step, from `start`; `navigate(t)` (if given) writes
    the Nav2 run to the person and its result decides `navigation_failure`."""
    steps, _ = _machine(cond)
    t, i = start, 0
    while i < len(steps):
        message, key, value = steps[i]
        if key == "navigation_failure" and navigate is not None:
            result = navigate(t)
            if result.succeeded == cond.navigation_failure:
                cond = replace(cond, navigation_failure=not result.succeeded)
                # Only the steps after the navigation change; the prefix is the same.
                steps = _machine(cond)[0]
                message, key, value = steps[i]
            t = max(t, result.end) + sec_ns(rng.uniform(0.05, 0.2))
        else:
            t += sec_ns(_delay(rng, key, value, cond))
        if key == "AskForHelpState":
            message = f"Asking the person for help: {question}"
        level = 2 if key == "SkillFailed" else 0
        b.status(
            t, EPISODIC_MEMORY, ASK_HUMAN_STATUS_NAME, message, [("Module name", MODULE), (key, value)], level
        )
        i += 1
    error = _machine(cond)[1]
    return SkillResult(t + sec_ns(rng.uniform(0.05, 0.2)), error == "", error)


def scenario_conditions(scenario: int, rng: random.Random) -> AskHumanConditions:
    """The world of Table I scenario 11..18, or 0 for a run where nothing goes wrong (the other scenarios'
    plans ask for help too); values vary with `rng`, the situation does not."""
    base = AskHumanConditions(
        person_detected=True,
        detection_stable=True,
        person_distance=rng.uniform(1.0, 3.6),
        person_std_rms=rng.uniform(0.08, 0.35),
        navigation_failure=False,
        robot_nav_err=rng.uniform(0.05, 0.3),
        user_accepted=True,
        user_confirmed=True,
    )
    if scenario == 0:
        return base
    if scenario == 11:
        return replace(base, person_detected=False)
    if scenario == 12:
        return replace(base, person_distance=rng.uniform(4.3, 7.0))
    if scenario == 13:
        return replace(base, detection_stable=False)
    if scenario == 14:
        return replace(base, navigation_failure=True, person_distance=rng.uniform(1.2, 3.8))
    if scenario == 15:
        return replace(base, user_accepted=False)
    if scenario == 16:
        return replace(base, user_confirmed=rng.choice([False, None]))
    if scenario == 17:
        return replace(base, robot_nav_err=rng.uniform(0.6, 1.2))
    if scenario == 18:
        # The variance tolerance was raised for this run, so a noisy detection still counts as stable.
        return replace(base, person_std_rms=rng.uniform(0.6, 1.2), robot_nav_err=rng.uniform(0.55, 1.0))
    raise ValueError(f"scenario {scenario} is not an ask-human-for-help scenario (0 or 11..18)")


def training_executions(n: int, seed: int) -> list[dict[str, str]]:
    """`n` simulated executions as the causal model's variable assignments, read off the recorded steps."""
    rng = random.Random(seed)
    rows = []
    for _ in range(n):
        steps = run_state_machine(random_conditions(rng))
        rows.append(assignment((key, value) for _, key, value in steps))
    return rows
