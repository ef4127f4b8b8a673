"""The discrete variables of the ask-human-for-help causal model, and how recorded steps map onto them.

Both the training data (simulated executions) and the explainer (a recording) go through `assignment`, so the
model learns from exactly what a recording can show.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

# Thresholds of the skill (reference, `/episodic_memory`). The skill records the measured values, never these
# limits, so an answer names them as configured defaults (DEFAULT_NOTE), not as facts of the recording.
DEFAULT_NOTE = "a configured default, not recorded"
MAX_DISTANCE = 4.0
APPROACH_MARGIN = 0.75
NOISE_LIMIT = 0.5
APPROACH_ERROR_LIMIT = 0.5
# Splits the navigable band so that the model can learn that longer approaches fail more often.
MID_DISTANCE = 2.0

KEYS: tuple[str, ...] = (
    "InitialState",
    "person_approached",
    "DetectState",
    "person_detected",
    "person_std_rms",
    "detection_stable",
    "person_distance",
    "NavigateState",
    "navigation_failure",
    "robot_nav_err",
    "AskForHelpState",
    "user_accepted",
    "WaitForConfirmationState",
    "user_confirmed",
)
END_KEYS: tuple[str, ...] = ("SkillSucceeded", "SkillFailed")

NONE = "none"  # the step was never reached, so the skill did not record the key
TRUE, FALSE, NO_ANSWER = "true", "false", "no_answer"

# Observable values, which a counterfactual may change (the structural nodes below follow from them).
WORLD: dict[str, tuple[str, ...]] = {
    "person_detected": (FALSE, TRUE),
    "person_std_rms": ("le_0.5", "gt_0.5", NONE),
    "detection_stable": (FALSE, TRUE, NONE),
    "person_distance": ("lt_0.75", "0.75_2.0", "2.0_4.0", "gt_4.0", NONE),
    "navigation_failure": (FALSE, TRUE, NONE),
    "robot_nav_err": ("le_0.5", "gt_0.5", NONE),
    "user_accepted": (FALSE, TRUE, NO_ANSWER, NONE),
    "user_confirmed": (FALSE, TRUE, NO_ANSWER, NONE),
}
# State-executed flags and the transitions the state machine took.
STRUCTURE: dict[str, tuple[str, ...]] = {
    "detection_next": ("failure", "navigate", "ask_for_help"),
    "navigate_executed": (FALSE, TRUE),
    "navigation_next": ("failure", "ask_for_help", NONE),
    "ask_executed": (FALSE, TRUE),
    "ask_next": ("failure", "wait_for_confirmation", NONE),
    "confirm_executed": (FALSE, TRUE),
    "confirmation_next": ("failure", "success", NONE),
    "outcome": ("failure", "success"),
}
STATES: dict[str, tuple[str, ...]] = {**WORLD, **STRUCTURE}
VARIABLES: tuple[str, ...] = tuple(STATES)
# Values on a scale, so that "the smallest change" can be measured; others differ by 1 whatever the value.
ORDINAL: frozenset[str] = frozenset({"person_std_rms", "person_distance", "robot_nav_err"})

# The transition node whose failure ends the skill, by the state it leaves.
TRANSITION_OF_STATE = {
    "DetectState": "detection_next",
    "NavigateState": "navigation_next",
    "AskForHelpState": "ask_next",
    "WaitForConfirmationState": "confirmation_next",
}
# The recorded key behind each observable variable (the evidence a cause cites).
KEY_OF: dict[str, str] = {name: name for name in WORLD}

# First-person phrases for "had X been x*" and "because X = x"; generic over variables, not per failure.
PHRASES: dict[str, dict[str, str]] = {
    "person_detected": {TRUE: "I had detected a person", FALSE: "I did not detect anybody"},
    "person_std_rms": {
        "le_0.5": "the person's detected position had been steady (spread at most 0.5 m)",
        "gt_0.5": "the person's detected position was noisy (spread above 0.5 m)",
    },
    "detection_stable": {
        TRUE: "the detection had been stable",
        FALSE: "I could not keep a stable detection of the person",
    },
    "person_distance": {
        "lt_0.75": "the person had been closer than 0.75 m",
        "0.75_2.0": "the person had been between 0.75 and 2.0 m away",
        "2.0_4.0": "the person had been between 2.0 and 4.0 m away",
        "gt_4.0": "the person was farther away than my limit for asking, 4.0 m",
    },
    "navigation_failure": {
        FALSE: "my navigation to the person had succeeded",
        TRUE: "my navigation to the person failed",
    },
    "robot_nav_err": {
        "le_0.5": "my final approach had been accurate (error at most 0.5 m)",
        "gt_0.5": "my final approach was off by more than 0.5 m",
    },
    "user_accepted": {
        TRUE: "the person had agreed to help",
        FALSE: "the person declined to help",
        NO_ANSWER: f"the person did not answer in time (I wait 45 seconds: {DEFAULT_NOTE})",
    },
    "user_confirmed": {
        TRUE: "the person had confirmed that they had helped",
        FALSE: "the person did not confirm that they had helped",
        NO_ANSWER: f"the person did not confirm in time (I wait 30 seconds: {DEFAULT_NOTE})",
    },
}

# The cause a variable's observed value stands for, when an intervention on it turns the outcome around.
CAUSE_OF: dict[tuple[str, str], str] = {
    ("person_detected", FALSE): "ask_human.nobody_detected",
    ("detection_stable", FALSE): "ask_human.unstable_detection",
    ("person_distance", "gt_4.0"): "ask_human.person_too_far",
    ("navigation_failure", TRUE): "ask_human.navigation_failed",
    ("user_accepted", FALSE): "ask_human.refused",
    ("user_accepted", NO_ANSWER): "ask_human.refused",  # the shared vocabulary: refused or did not answer
    ("user_confirmed", FALSE): "ask_human.not_confirmed",
    ("user_confirmed", NO_ANSWER): "ask_human.not_confirmed",
    ("person_std_rms", "gt_0.5"): "ask_human.noisy_detection",
    ("robot_nav_err", "gt_0.5"): "ask_human.poor_approach",
}


def _flag(value: str | None) -> str:
    if value is None:
        return NONE
    low = value.strip().lower()
    if low in {"true", "1", "yes"}:
        return TRUE
    if low in {"false", "0", "no"}:
        return FALSE
    return NO_ANSWER  # "None": nobody answered before the timeout


def _number(value: str | None) -> float | None:
    if value is None:
        return None
    try:
        return float(value)
    except ValueError:
        return None


def distance_bin(d: float | None) -> str:
    if d is None:
        return NONE
    if d < APPROACH_MARGIN:
        return "lt_0.75"
    if d <= MID_DISTANCE:
        return "0.75_2.0"
    if d <= MAX_DISTANCE:
        return "2.0_4.0"
    return "gt_4.0"


def limit_bin(x: float | None, limit: float) -> str:
    if x is None:
        return NONE
    return "gt_0.5" if x > limit else "le_0.5"


def assignment(steps: Iterable[tuple[str, str]]) -> dict[str, str]:
    """The model's variables from one execution's recorded (key, value) steps, in recording order."""
    rec: dict[str, str] = {}
    for key, value in steps:
        rec.setdefault(key, value)
    detected = _flag(rec.get("person_detected"))
    out = {
        "person_detected": TRUE if detected == TRUE else FALSE,
        "person_std_rms": limit_bin(_number(rec.get("person_std_rms")), NOISE_LIMIT),
        "detection_stable": _flag(rec.get("detection_stable")) if "detection_stable" in rec else NONE,
        "person_distance": distance_bin(_number(rec.get("person_distance"))),
        "navigation_failure": _flag(rec.get("navigation_failure")) if "navigation_failure" in rec else NONE,
        "robot_nav_err": limit_bin(_number(rec.get("robot_nav_err")), APPROACH_ERROR_LIMIT),
        "user_accepted": _flag(rec.get("user_accepted")) if "user_accepted" in rec else NONE,
        "user_confirmed": _flag(rec.get("user_confirmed")) if "user_confirmed" in rec else NONE,
    }
    for var, value in out.items():
        if value not in WORLD[var]:
            out[var] = NONE  # a recorded value this variable cannot take ("maybe") tells nothing
    navigate, ask, confirm = (
        ("NavigateState" in rec),
        ("AskForHelpState" in rec),
        ("WaitForConfirmationState" in rec),
    )
    succeeded = "SkillSucceeded" in rec
    out["detection_next"] = "navigate" if navigate else "ask_for_help" if ask else "failure"
    out["navigate_executed"] = TRUE if navigate else FALSE
    out["navigation_next"] = NONE if not navigate else "ask_for_help" if ask else "failure"
    out["ask_executed"] = TRUE if ask else FALSE
    out["ask_next"] = NONE if not ask else "wait_for_confirmation" if confirm else "failure"
    out["confirm_executed"] = TRUE if confirm else FALSE
    out["confirmation_next"] = NONE if not confirm else "success" if succeeded else "failure"
    out["outcome"] = "success" if succeeded else "failure"
    return out


def phrase(var: str, value: str) -> str:
    return PHRASES.get(var, {}).get(value, f"{var} had been {value}")


def value_gap(var: str, a: str, b: str) -> int:
    """How far apart two values are: steps on the scale for ordinal variables, else 0 or 1."""
    if a == b:
        return 0
    if var in ORDINAL and NONE not in (a, b):
        order = STATES[var]
        return abs(order.index(a) - order.index(b))
    return 1


def describe(assign: Mapping[str, str]) -> str:
    return ", ".join(f"{k}={assign[k]}" for k in WORLD if k in assign)


_LABELS = {
    "lt_0.75": "< 0.75 m",
    "0.75_2.0": "in 0.75-2.0 m",
    "2.0_4.0": "in 2.0-4.0 m",
    "gt_4.0": "> 4.0 m",
    "le_0.5": "<= 0.5 m",
    "gt_0.5": "> 0.5 m",
    TRUE: "= True",
    FALSE: "= False",
    NO_ANSWER: "= no answer",
}


def label(var: str, value: str) -> str:
    """A bin as a condition on the recorded value, e.g. `in 2.0-4.0 m`."""
    return _LABELS.get(value, f"= {value}")
