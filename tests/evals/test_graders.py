"""The deterministic graders on hand-written answers, as a baseline's free text or HEXAR's would read."""

from __future__ import annotations

import pytest

from hexar.claims import read_claims
from hexar.evals.cases import Case, cases, scenarios
from hexar.evals.graders import Graded, Grader, Grades, Truth


def case_of(scenario: int) -> Case:
    return next(c for c in cases() if c.scenario.id == scenario)


def grade(scenario: int, text: str, causes: list[str] | None = None, explainers: list[str] | None = None) -> Grades:
    return Grader().grade(Truth.of(case_of(scenario)), Graded(text, causes, explainers))


def test_correct_answer() -> None:
    g = grade(7, "I couldn't reach the kitchen because I was plugged into my charger.")
    assert g.root_cause and not g.incorrect_facts and g.accuracy


def test_missing_cause() -> None:
    g = grade(7, "I couldn't reach the kitchen, sorry.")
    assert not g.root_cause and not g.incorrect_facts and not g.accuracy


def test_extra_false_claim_of_the_planner() -> None:
    # The paper's own example (scenario 7, all-components baseline).
    g = grade(7, "The reason I didn't bring it is that autonomous navigation was disabled while I was charging. "
                 "Additionally, my plan was incorrect as I attempted to go directly to the living room.")
    assert g.root_cause and g.incorrect_facts and not g.accuracy
    assert "claim.plan_blamed" in g.false_claims


def test_extra_false_cause_of_the_same_module() -> None:
    g = grade(5, "An obstacle blocked my path. I was also badly localised on my map.")
    assert g.root_cause and g.false_claims == ("navigation.poor_localisation",)


def test_paraphrase() -> None:
    g = grade(16, "She said she'd help, but she never got back to me to say it was done — no confirmation came.")
    assert g.root_cause and g.accuracy


@pytest.mark.parametrize("scenario", [s.id for s in scenarios() if s.id != 3])
def test_each_ground_truth_sentence_grades_correct(scenario: int) -> None:
    """The ground truth, as scenarios.yaml words it, is itself a correct explanation. (Scenario 3's sentence
    "a needed step or place is missing" also reads as a missing parameter, another planner cause.)"""
    g = grade(scenario, case_of(scenario).scenario.root_cause)
    assert g.accuracy, g


def test_denied_causes_are_not_claims() -> None:
    g = grade(7, "There was no obstacle in my path and the joystick was not engaged; I was docked on my charger.")
    assert g.root_cause and not g.incorrect_facts
    assert read_claims("I was not charging.").denied == {"navigation.charging"}


def test_inverted_phrasings() -> None:
    assert "ask_human.unstable_detection" in read_claims("I could not keep a stable detection of her.").affirmed
    assert "ask_human.unstable_detection" in read_claims("I had a stable detection of her.").denied


def test_task_failed_is_false_when_it_succeeded() -> None:
    g = grade(10, "I failed to bring the book. I drove at 0.4 m/s.")
    assert g.false_claims == ("claim.task_failed",)
    assert not grade(5, "I failed to bring the coffee because something blocked my path.").incorrect_facts


def test_nothing_went_wrong_only_about_the_whole_run() -> None:
    assert grade(8, "Nothing went wrong.").false_claims == ("claim.all_fine",)
    g = grade(19, "Nothing went wrong on the way to the kitchen, but my speech has a 20-second limit and timed out.")
    assert g.accuracy


def test_also_true_causes_are_not_false() -> None:
    g = grade(14, "I couldn't approach the person because an obstacle blocked my path.")
    assert g.root_cause and not g.incorrect_facts


def test_structured_causes_and_selection() -> None:
    g = grade(6, "My joystick held my wheels.", causes=["navigation.joystick", "planner.invalid_skill"],
              explainers=["navigation"])
    assert g.structured == {"root_cause": True, "incorrect_facts": True, "accuracy": False}
    assert g.selection is True
    assert grade(6, "x", explainers=["planner"]).selection is False
    assert grade(6, "x").selection is None and grade(6, "x").structured is None


# Real baseline answers of the embedded model (one case per scenario), with the labels a person gave them.
OBSERVED = [
    (6, "The robot was unable to navigate to the kitchen due to a timeout.", False, True),
    (8, "I asked for help, found a person who agreed to help, and confirmed it. I reached the kitchen slowly and "
        "unsteadily because I was not sure where I was on my map. I said the whole message (4 words); it took 1.6 "
        "seconds, within my 20-second speech limit.", True, False),
    (9, "I asked for help, found a person who agreed, and confirmed it. I was unable to reach the kitchen because "
        "people or things kept moving into my way, so I had to stop and find new paths around them.", True, True),
    (11, "The person was unable to find a person to ask for help, so the robot navigated to the living room "
         "instead.", True, False),
    (12, "The person was not found while trying to bring coffee from the kitchen.", False, True),
    (14, "I tried to get help by asking a person for help, but my navigation failed, and I couldn't reach the "
         "person because something blocked my path.", True, False),
    (17, "You asked for help to bring me a coffee from the kitchen, but the person you asked did not respond.",
     False, True),
    (20, "The pizza recommender suggested a Margherita because they had basil, and not having pineapple also "
         "pointed to it.", True, False),
    (2, "I was unable to navigate to the kitchen_counter, as it is not a valid location specified in the plan.",
     True, False),
]


@pytest.mark.parametrize(("scenario", "text", "root", "wrong"), OBSERVED)
def test_observed_baseline_answers(scenario: int, text: str, root: bool, wrong: bool) -> None:
    g = grade(scenario, text)
    assert (g.root_cause, g.incorrect_facts) == (root, wrong), g


def test_quoting_failed_to_make_progress_claims_no_obstacle() -> None:
    # Nav2 also says it when cmd_vel never reaches the base or TF is stale: quoting it names no blocked path
    claims = read_claims("My controller said 'Failed to make progress' and made no progress for 10 s.").affirmed
    assert "navigation.blocked_path" not in claims and "navigation.no_progress" in claims


def test_a_log_line_quoted_verbatim_claims_nothing() -> None:
    # a real rplidar_ros SDK line (RESULT_OPERATION_TIMEOUT) quoted by the control explainer: the words "time out"
    # are the driver's, not a text-to-speech timeout; the same words outside the quote stay a claim
    quoted = ("Starting my drivers and controllers failed, but my control logs do not show a cause I know. The first "
              "error was “[rplidar_composition] Error, operation time out. RESULT_OPERATION_TIMEOUT!” at 1.2 s.")
    assert read_claims(quoted).affirmed == frozenset()
    assert "tts.timeout" in read_claims("My sentence was cut off: my speech timed out.").affirmed
    assert "tts.timeout" in read_claims("I said “hello” but my speech timed out.").affirmed


@pytest.mark.parametrize("text, charging", [
    ("I was docked on my charger, so I could not drive.", True),
    ("I stayed on my dock the whole time.", True),
    # a docking that failed names the dock without claiming the robot was on it (blind Nav2 set 26's answers)
    ("I didn't get onto my dock: my docking controller detected a collision ahead on its approach.", False),
    ("My docking failed: the dock I was asked to go to, kitchen_dock, is not in my list of docks.", False),
])
def test_the_dock_of_a_docking_is_no_claim_of_charging(text: str, charging: bool) -> None:
    assert ("navigation.charging" in read_claims(text).affirmed) is charging


@pytest.mark.parametrize("text, nominal", [
    # a behaviour server goal that succeeded (blind Nav2 set 28's answers) is a claim that nothing went wrong
    ("I finished my spin of 1.57 rad without any problem, in 1.7 s.", True),
    ("I finished my drive ahead without any problem, in 2.5 s.", True),
    # one that ran out of time is none
    ("My backup ran out of the time allowed for it (10.0 s) before it was done, and my logs do not show why.", False),
])
def test_a_behaviour_finished_without_a_problem_is_a_nominal_claim(text: str, nominal: bool) -> None:
    assert ("navigation.nominal" in read_claims(text).affirmed) is nominal
