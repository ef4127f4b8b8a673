from __future__ import annotations

import random
import re
from dataclasses import replace
from pathlib import Path
from typing import Any, ClassVar

import pytest

from hexar.evals.scenarios.ask_human import scenario_conditions
from hexar.evals.scenarios.bag import BagBuilder, SkillResult, sec_ns
from hexar.events.contract import EPISODIC_MEMORY, ROSOUT
from hexar.explainers.ask_human import AskHumanForHelpExplainer
from hexar.explainers.base import Context, Evidence, Explanation, TextModel
from hexar.explainers.registry import Registry

from .helpers import context, record

EXPECTED = {
    11: ("ask_human.nobody_detected", {"person_detected = False"}),
    12: ("ask_human.person_too_far", {"person_distance"}),
    13: ("ask_human.unstable_detection", {"detection_stable = False"}),
    14: ("ask_human.navigation_failed", {"navigation_failure = True"}),
    15: ("ask_human.refused", {"user_accepted = False"}),
    16: ("ask_human.not_confirmed", {"user_confirmed"}),
    17: ("ask_human.poor_approach", {"robot_nav_err"}),
    18: ("ask_human.noisy_detection", {"person_std_rms"}),
}


@pytest.fixture(scope="module")
def explainer() -> AskHumanForHelpExplainer:
    return AskHumanForHelpExplainer()


def _recorded(ctx: Context) -> set[tuple[str, int, str]]:
    return {
        (EPISODIC_MEMORY, r.t, f"{k} = {v}")
        for r in ctx.log.statuses[EPISODIC_MEMORY]
        for k, v in r.data_items()
    }


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize("scenario", sorted(EXPECTED))
def test_each_scenario_gets_its_cause_with_recorded_evidence(
    tmp_path: Path, explainer: AskHumanForHelpExplainer, scenario: int, seed: int
) -> None:
    log, _ = record(tmp_path, scenario_conditions(scenario, random.Random(seed)), seed)
    ctx = context(log)
    out = explainer.explain("What happened?", ctx)
    cause, shown = EXPECTED[scenario]
    assert out.causes == [cause]
    assert out.enough_information
    recorded = _recorded(ctx)
    assert out.evidence and all((e.topic, e.t, e.item) in recorded for e in out.evidence)
    assert all(e.cause == cause for e in out.evidence)
    items = [e.item for e in out.evidence]
    assert all(any(item.startswith(s) for item in items) for s in shown)
    if scenario <= 16:
        assert "SkillFailed = True" in items
        assert out.counterfactual is not None and "had" in out.counterfactual
        assert " If " in out.text  # the counterfactual, said plainly


def test_too_far_counterfactual_is_a_distance_within_4m(
    tmp_path: Path, explainer: AskHumanForHelpExplainer
) -> None:
    cond = replace(scenario_conditions(12, random.Random(3)), person_distance=5.0)
    out = explainer.explain("Why didn't you ask the person in the room?", context(record(tmp_path, cond)[0]))
    assert out.causes == ["ask_human.person_too_far"]
    assert "5.0 m" in out.text and "4.0 m" in out.text
    assert "between 2.0 and 4.0 m" in out.text  # the nearest distance bin that makes success most probable
    assert out.counterfactual is not None
    # said plainly, with odds a person can use and no model notation
    assert "between 2.0 and 4.0 m" in out.counterfactual and "P(" not in out.counterfactual
    m = re.search(r"about (\d+) in (\d+) chance", out.counterfactual)
    assert m is not None and 0.5 < int(m.group(1)) / int(m.group(2)) <= 1.0, out.counterfactual


def test_no_answer_counts_as_refusal(tmp_path: Path, explainer: AskHumanForHelpExplainer) -> None:
    cond = replace(scenario_conditions(15, random.Random(0)), user_accepted=None)
    out = explainer.explain("What happened?", context(record(tmp_path, cond)[0]))
    assert out.causes == ["ask_human.refused"]
    assert "did not answer" in out.text
    assert any(e.item == "user_accepted = None" for e in out.evidence)


def test_normal_run_is_a_plain_success(tmp_path: Path, explainer: AskHumanForHelpExplainer) -> None:
    out = explainer.explain(
        "What happened?", context(record(tmp_path, scenario_conditions(0, random.Random(0)))[0])
    )
    assert out.causes == ["ask_human.succeeded"]
    assert out.counterfactual is None and "went as planned" in out.text


def test_no_episodic_records_is_not_enough(tmp_path: Path, explainer: AskHumanForHelpExplainer) -> None:
    log, _ = record(tmp_path, scenario_conditions(11, random.Random(0)), episodic=False)
    out = explainer.explain("What happened?", context(log))
    assert not out.enough_information and out.causes == [] and out.evidence == []


def test_only_the_last_execution_in_the_window_counts(
    tmp_path: Path, explainer: AskHumanForHelpExplainer
) -> None:
    log, _ = record(tmp_path, scenario_conditions(15, random.Random(0)))
    ctx = context(log)
    first = min(r.t for r in log.statuses[EPISODIC_MEMORY])
    # A window that starts after InitialState still explains the partial execution it sees.
    out = explainer.explain("What happened?", ctx.with_window((first + 1, ctx.window[1])))
    assert out.causes == ["ask_human.refused"]


class _BlockedPath:
    """A stand-in navigation explainer with the real interface: it reports the /rosout lines of its window."""

    name: ClassVar[str] = "navigation"
    topics: ClassVar[frozenset[str]] = frozenset({ROSOUT})
    description: ClassVar[str] = "navigation"
    windows: ClassVar[list[tuple[int, int]]] = []

    def __init__(self, model: TextModel | None = None, registry: Registry | None = None) -> None:
        pass

    def explain(self, question: str, context: Context) -> Explanation:
        _BlockedPath.windows.append(context.window)
        lines = context.view(self.topics).logs()
        return Explanation(
            explainer="navigation",
            text="An obstacle blocked my path.",
            causes=["navigation.blocked_path"],
            evidence=[Evidence.of_log("navigation.blocked_path", line) for line in lines],
        )


def _nav(b: BagBuilder, t: int) -> SkillResult:
    b.log(t + sec_ns(4), "controller_server", 40, "Failed to make progress")
    return SkillResult(t + sec_ns(12), False, "Navigation failed")


def test_navigation_failure_asks_the_navigation_explainer(
    tmp_path: Path, explainer: AskHumanForHelpExplainer
) -> None:
    cond = scenario_conditions(14, random.Random(0))
    log, _ = record(tmp_path, cond, navigate=_nav)
    alone = explainer.explain("Why didn't you go up to the person?", context(log))
    assert alone.causes == ["ask_human.navigation_failed"]
    without_nav = Registry({"ask_human_for_help": AskHumanForHelpExplainer}, {})
    assert explainer.explain("?", context(log, without_nav)).causes == ["ask_human.navigation_failed"]
    registry = Registry({"ask_human_for_help": AskHumanForHelpExplainer, "navigation": _BlockedPath}, {})
    out = explainer.explain("Why didn't you go up to the person?", context(log, registry))
    assert out.causes == ["ask_human.navigation_failed", "navigation.blocked_path"]
    assert any(e.topic == ROSOUT and "Failed to make progress" in e.item for e in out.evidence)
    steps = {k: r.t for r in log.statuses[EPISODIC_MEMORY] for k, _ in r.data_items()}
    assert _BlockedPath.windows[-1] == (steps["NavigateState"], steps["navigation_failure"])


class _Echo:
    name = "echo"

    def chat(self, messages: Any, *, schema: Any = None, max_tokens: int = 160) -> str:
        return "PHRASED: " + str(messages[-1]["content"]).splitlines()[1]


def test_a_model_phrases_the_grounded_finding(tmp_path: Path) -> None:
    log, _ = record(tmp_path, scenario_conditions(16, random.Random(0)))
    out = AskHumanForHelpExplainer(model=_Echo()).explain("Why did you wait there so long?", context(log))
    assert out.phrased_by == "echo" and out.text.startswith("PHRASED: I could not get help:")
    assert out.causes == ["ask_human.not_confirmed"]


@pytest.mark.parametrize(("scenario", "distance"), [(15, 1.35), (0, 3.2), (12, 5.0)])
def test_how_far_the_person_was_is_the_measured_distance(tmp_path: Path, explainer: AskHumanForHelpExplainer,
                                                         scenario: int, distance: float) -> None:
    """"How far away was the person?" leads with the recorded person_distance and my limit, then the finding; a
    distance that is the cause ("too far") is said once, in the finding."""
    cond = replace(scenario_conditions(scenario, random.Random(0)), person_distance=distance)
    ctx = context(record(tmp_path, cond)[0])
    out = explainer.explain("How far away was the person?", ctx)
    plain = explainer.explain("What happened?", ctx)
    if distance > 4.0:
        assert out.text == plain.text and out.text.count("I measured") == 1
        return
    assert out.text == (f"I measured the person at {distance:.2f} m, within my limit for asking (4.0 m, a configured "
                        f"default, not recorded). {plain.text}")
    assert out.causes == plain.causes
    assert any(e.item.startswith("person_distance = ") for e in out.evidence)
